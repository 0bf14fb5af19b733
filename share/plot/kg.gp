# SPDX-License-Identifier: GPL-3.0-or-later
# K and G against confining stress for several simulations (pipelines/Makefile): for each run
# directory, phase (b) from fric.tsv when it exists (open points, one per increment) and the
# uniaxial test from moduli.tsv (lines, one point per fitted window, with its standard error
# as a bar: the scatter of the window's increments about Hooke's law), both against the
# volume-averaged sigma_c, the stress their moduli are fitted to; emt=1 adds each run's
# effective-medium K and G (rough and smooth contacts, physics.md §13) as dashed and dotted lines.
# gnuplot -e "out='k.png'; cols='pipelines/cols.sh'; runs='dir1 dir2'" share/plot/kg.gp
if (!exists("emt")) emt = 0
set terminal pngcairo size 1200,520 noenhanced font ",10"
set output out
set datafile separator "\t"
set grid
set key top left font ",9"
set xlabel "volume-averaged confining stress sigma_c (MPa)"
n = words(runs)
label(i) = system("basename ".word(runs, i))
src(i, f, c) = "< sh ".cols." ".word(runs, i)."/".f." ".c." 2>/dev/null || true"
fric(i, c) = system("test -f ".word(runs, i)."/fric.tsv && echo 1 || echo 0") eq "1" ? src(i, "fric.tsv", c) : "< true"
set multiplot layout 1,2
do for [m in "K G"] {
	set ylabel m." (GPa)"
	set title m
	if (emt) {
		if (m eq "K") {
			plot for [i=1:n] src(i, "moduli.tsv", "sigma_c K K_se") using ($1/1e6):($2/1e9):($3/1e9) with yerrorlines lc i pt 7 ps 0.6 title label(i), \
			     for [i=1:n] src(i, "moduli.tsv", "sigma_c K_emt") using ($1/1e6):($2/1e9) with lines lc i dt 2 title "EMT ".label(i)
		} else {
			plot for [i=1:n] src(i, "moduli.tsv", "sigma_c G G_se") using ($1/1e6):($2/1e9):($3/1e9) with yerrorlines lc i pt 7 ps 0.6 title label(i), \
			     for [i=1:n] src(i, "moduli.tsv", "sigma_c G_emt_rough") using ($1/1e6):($2/1e9) with lines lc i dt 2 title "EMT rough ".label(i), \
			     for [i=1:n] src(i, "moduli.tsv", "sigma_c G_emt_smooth") using ($1/1e6):($2/1e9) with lines lc i dt 3 title "EMT smooth ".label(i)
		}
	} else {
		plot for [i=1:n] fric(i, "sig_lw_xx sig_lw_yy sig_lw_zz ".m) using (($1+$2+$3)/3e6):($4/1e9) with points lc i pt 6 ps 0.5 notitle, \
		     for [i=1:n] src(i, "moduli.tsv", "sigma_c ".m." ".m."_se") using ($1/1e6):($2/1e9):($3/1e9) with yerrorlines lc i pt 7 ps 0.6 title label(i)
	}
}
unset multiplot
