# SPDX-License-Identifier: GPL-3.0-or-later
# The frictionless paper's Fig. 5 (pipelines/Makefile, s-fig5): K and G of the hydrate-bearing
# pack after dissociation, from the study's summary table (pipelines/hydrate.sh).  Left: against
# the excess pore pressure at dS = -0.01; right: against the fall of the hydrate saturation -dS
# at p_ex = 1 MPa.  Dashed: the pack before any dissociation.
# gnuplot -e "out='f.png'; cols='pipelines/cols.sh'; summary='out/s-fig5/summary.tsv'" share/plot/hydrate.gp
set terminal pngcairo size 1200,520 noenhanced font ",10"
set output out
set datafile separator "\t"
set grid
set key top right font ",9"
# the two series, each in the order of its axis (rows are dS pex K G fit_rel K_se G_se, the
# standard errors drawn as bars); a probe that rearranged (fit_rel above 0.5: its K and G are
# not moduli, pipelines/report.sh) is left out
tab = "< sh ".cols." ".summary." dS pex K G fit_rel K_se G_se | awk '$5 + 0 <= 0.5'"
srcA = tab." | awk '$1 + 0 == -0.01' | sort -g -k2,2"
srcB = tab." | awk '$2 + 0 == 1e6' | sort -g -r -k1,1"
K0 = real(system("sh ".cols." ".summary." run K | awk '$1 == \"hyd-d0-p0\" { print $2 / 1e9 }'"))
G0 = real(system("sh ".cols." ".summary." run G | awk '$1 == \"hyd-d0-p0\" { print $2 / 1e9 }'"))
set ylabel "modulus (GPa)"
set yrange [0:*]
set multiplot layout 1,2
set title "dS = -0.01"
set xlabel "excess pore pressure p_ex (MPa)"
plot srcA using ($2/1e6):($3/1e9):($6/1e9) with yerrorlines lc 1 pt 7 title "K", \
     srcA using ($2/1e6):($4/1e9):($7/1e9) with yerrorlines lc 2 pt 5 title "G", \
     K0 with lines lc 1 dt 2 title "K before", G0 with lines lc 2 dt 2 title "G before"
set title "p_ex = 1 MPa"
set xlabel "fall of the hydrate saturation -dS"
plot srcB using (-$1):($3/1e9):($6/1e9) with yerrorlines lc 1 pt 7 title "K", \
     srcB using (-$1):($4/1e9):($7/1e9) with yerrorlines lc 2 pt 5 title "G", \
     K0 with lines lc 1 dt 2 title "K before", G0 with lines lc 2 dt 2 title "G before"
unset multiplot
