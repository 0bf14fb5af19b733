# SPDX-License-Identifier: GPL-3.0-or-later
# The frictional paper's Fig. 4: G and the sliding ratio against sigma_c during phase (b)
# (frictionalize's log, one point per increment) and the uniaxial test that follows (moduli
# per window with its standard error as a bar, sliding ratio per increment), against the volume-averaged sigma_c (the stress
# the moduli are fitted to); the dash-dot line marks the end of phase (b), the gray band the
# paper's saturated sliding ratio (0.09-0.11).  The sliding ratio is the paper-comparable count
# (contacts committed at their Coulomb limit); the trial slip ratio (DEM codes' slip fraction)
# is drawn thin for comparison (share/doc/friction.md).
# gnuplot -e "out='fig4.png'; cols='pipelines/cols.sh'; run='DIR'" share/plot/fig4.gp
set terminal pngcairo size 1200,520 noenhanced font ",10"
set output out
set datafile separator "\t"
set grid
set key top right font ",9"
src(f, c) = "< sh ".cols." ".run."/".f." ".c
lw = "sig_lw_xx sig_lw_yy sig_lw_zz"
stats src("fric.tsv", lw) using (($1+$2+$3)/3e6) nooutput
set arrow 1 from first STATS_max, graph 0 to first STATS_max, graph 1 nohead dt 4 lc rgb "gray30"
set xlabel "volume-averaged confining stress sigma_c (MPa)"
set multiplot layout 1,2
set ylabel "G (GPa)"
set title "shear modulus"
plot src("fric.tsv", lw." G") using (($1+$2+$3)/3e6):($4/1e9) with linespoints pt 6 ps 0.6 title "(1) phase (b), per increment", \
     src("moduli.tsv", "sigma_c G G_se") using ($1/1e6):($2/1e9):($3/1e9) with yerrorlines pt 7 ps 0.6 title "(2) uniaxial test, per 1e-3 strain"
set ylabel "sliding ratio"
set title "ratio of sliding contacts"
set key center right
set yrange [0:*]
set object 1 rect from graph 0, first 0.09 to graph 1, first 0.11 fc rgb "gray85" fs solid 0.6 noborder behind
plot src("fric.tsv", lw." sliding_ratio") using (($1+$2+$3)/3e6):4 with linespoints pt 6 ps 0.6 title "(1) phase (b): sliding ratio", \
     src("curve.tsv", lw." sliding_ratio") using (($1+$2+$3)/3e6):4 with linespoints pt 7 ps 0.4 title "(2) uniaxial test: sliding ratio", \
     src("fric.tsv", lw." trial_slip_ratio") using (($1+$2+$3)/3e6):4 with lines lw 1 dt 2 lc rgb "gray40" title "trial slip ratio (DEM slip fraction)", \
     src("curve.tsv", lw." trial_slip_ratio") using (($1+$2+$3)/3e6):4 with lines lw 1 dt 2 lc rgb "gray40" notitle, \
     1/0 with boxes fc rgb "gray85" fs solid 0.6 title "paper, saturated: 0.09-0.11"
unset multiplot
