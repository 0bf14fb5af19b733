# SPDX-License-Identifier: GPL-3.0-or-later
# The frictionless paper's Fig. 3: the three principal stresses against their strains through a
# polyaxial loading (solid) and unloading (dashed) cycle; hysteresis shows as different curves.
# gnuplot -e "out='f.png'; cols='pipelines/cols.sh'; run='DIR'" share/plot/polyaxial.gp
set terminal pngcairo size 800,600 noenhanced font ",10"
set output out
set datafile separator "\t"
set grid
set key top left
set xlabel "strain (from the reference box)"
set ylabel "stress (MPa)"
src = "< sh ".cols." ".run."/curve.tsv seg eps_xx eps_yy eps_zz sig_xx sig_yy sig_zz"
plot for [a=1:3] src using (column(a+1)):($1 <= 1 ? column(a+4)/1e6 : 1/0) with lines lc a lw 1.5 title "sig_".word("xx yy zz", a)." loading", \
     for [a=1:3] src using (column(a+1)):($1 == 2 ? column(a+4)/1e6 : 1/0) with lines lc a dt 2 lw 1.5 title "sig_".word("xx yy zz", a)." unloading"
