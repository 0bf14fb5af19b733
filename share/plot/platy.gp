# SPDX-License-Identifier: GPL-3.0-or-later
# The platy-particle paper's figures from the platy study (pipelines/Makefile): the velocity
# profiles (its Fig. 6), tau_w/sigma_w against gamma (Fig. 5), and against the platyness eta the
# shear strength q/p with eq. 28's harmonic sum (Figs. 7, 22), the packing fraction (Fig. 8),
# a_m (Fig. 11), Z and chi (Fig. 12), a_n (Fig. 14), a_ln and a_lt (Fig. 17), a_fn and a_ft
# (Fig. 20), K_s (Fig. 21) and the principal directions (the figures' insets), each the mean
# over the steady state with its standard deviation; beside a_m the 3D nematic measures,
# beside a_ft and eq. 28 the direct tangential terms (share/doc/tables.md), chi over the free
# grains.  With paper=FILE (validate/platy-8000/paper.tsv: the paper's values, its columns
# named as the summary's) the paper's values are drawn beside the run's as black open markers.
#
#   gnuplot -e "out='platy.png'; cols='pipelines/cols.sh'; summary='S'; runpat='R/platy-eta%s/%s'; etas='0 0.8'; from=G
#     [; paper='P'] [; panels='qp phi'; layout='1,2'; size='1200,450'; heading='T']" share/plot/platy.gp
#
# summary: pipelines/platy.sh's table, a row per platyness; runpat: where a platyness's
# shear.tsv and profile.tsv are, a sprintf pattern of the platyness and the file name; from:
# where the steady-state window starts.  panels (default all twelve, on a 3 x 4 layout):
# profile tau qp phi am Z chi an branch forces Ks angles.
if (!exists("panels")) panels = "profile tau qp phi am Z chi an branch forces Ks angles"
if (!exists("layout")) layout = "3,4"
if (!exists("size")) size = "1600,900"
if (!exists("heading")) heading = ""
havepaper = exists("paper") && paper ne ""
set terminal pngcairo size @size noenhanced font ",9"
set output out
set datafile separator "\t"
set grid
set key font ",8"
src(f, c) = "< sh ".cols." ".f." ".c
sum(c) = src(summary, "eta ".c." ".c."_sd")
runf(e, f, c) = src(sprintf(runpat, e, f), c)
# the paper's column c against eta; without a paper table a row of nan, which draws nothing
pap(c) = havepaper ? src(paper, "eta ".c) : "< printf 'nan\\tnan\\n'"
ptitle(t) = havepaper ? "paper: ".t : ""
known = " profile tau qp phi am Z chi an branch forces Ks angles "
do for [p in panels] {
	if (!strstrt(known, " ".p." ")) {
		exit error "platy.gp: no panel '".p."' (".known.")"
	}
}
set multiplot layout @layout title heading
do for [p in panels] {
	set xlabel "platyness eta"
	set xrange [-0.05:0.85]
	set autoscale y
	set key top left maxrows auto
	# room above and below the extreme points, which autoscaling puts on the border
	set offsets 0, 0, graph 0.06, graph 0.06
	unset arrow
	unset label
	if (p eq "profile") {
		set title "velocity profiles (Fig. 6)"
		set xlabel "<v_x> / v_w"
		set ylabel "y / y_w"
		set xrange [-0.05:1.05]
		set yrange [0:1]
		plot for [e in etas] runf(e, "profile.tsv", "vx_over_vw y_over_yw") using 1:2 with linespoints pt 7 ps 0.5 title "eta ".e, \
		     x with lines dt 2 lc rgb "gray50" title "uniform shear"
	}
	if (p eq "tau") {
		set title "tau_w / sigma_w (Fig. 5)"
		set xlabel "gamma"
		set ylabel "tau_w / sigma_w"
		set autoscale x
		set arrow 1 from first from, graph 0 to first from, graph 1 nohead dt 4 lc rgb "gray30"
		plot for [e in etas] runf(e, "shear.tsv", "gamma tau_sigma") using 1:2 with lines title "eta ".e
	}
	if (p eq "qp") {
		set title "shear strength (Figs. 7, 22)"
		set ylabel "q / p"
		plot sum("qp") using 1:2:3 with yerrorlines pt 7 lc 1 title "q/p", \
		     sum("qp_harmonic") using 1:2:3 with yerrorlines pt 9 lc 2 title "eq. 28", \
		     sum("qp_harmonic_direct") using 1:2:3 with yerrorlines pt 5 lc 3 title "eq. 28, direct tangential terms", \
		     pap("qp") using 1:2 with points pt 6 ps 1.8 lc rgb "black" title ptitle("q/p")
	}
	if (p eq "phi") {
		set title "packing fraction (Fig. 8)"
		set ylabel "phi"
		# the paper gives no values, only where the maximum is (Sec. III B)
		if (havepaper) {
			set arrow 2 from first 0.3, graph 0 to first 0.3, graph 1 nohead dt 2 lc rgb "black"
			set label 2 "paper: maximum near eta 0.3" at first 0.28, graph 0.05 rotate by 90 font ",8"
		}
		plot sum("phi") using 1:2:3 with yerrorlines pt 7 lc 1 title "phi"
	}
	if (p eq "am") {
		set title "particle orientations (Fig. 11)"
		set ylabel "a_m"
		plot sum("a_m") using 1:2:3 with yerrorlines pt 7 lc 1 title "a_m (xy)", \
		     sum("M1_M3") using 1:2:3 with yerrorlines pt 9 lc 2 title "M1 - M3 (3D)", \
		     sum("nematic_S") using 1:2:3 with yerrorlines pt 5 lc 3 title "S", \
		     pap("a_m") using 1:2 with points pt 6 ps 1.8 lc rgb "black" title ptitle("a_m")
	}
	if (p eq "Z") {
		set title "coordination (Fig. 12a)"
		set ylabel "Z"
		plot sum("Z") using 1:2:3 with yerrorlines pt 7 lc 1 title "Z (free grains)", \
		     pap("Z") using 1:2 with points pt 6 ps 1.8 lc rgb "black" title ptitle("Z")
	}
	if (p eq "chi") {
		set title "floating particles (Fig. 12b)"
		set ylabel "chi"
		set key top right
		plot sum("floating_fraction_free") using 1:2:3 with yerrorlines pt 7 lc 1 title "chi (free grains)", \
		     pap("floating_fraction_free") using 1:2 with points pt 6 ps 1.8 lc rgb "black" title ptitle("chi")
	}
	if (p eq "an") {
		set title "interaction orientations (Fig. 14)"
		set ylabel "a_n"
		plot sum("a_n") using 1:2:3 with yerrorlines pt 7 lc 1 title "a_n", \
		     pap("a_n") using 1:2 with points pt 6 ps 1.8 lc rgb "black" title ptitle("a_n")
	}
	if (p eq "branch") {
		set title "branch lengths (Fig. 17)"
		set ylabel "anisotropy"
		set key bottom left
		plot sum("a_ln") using 1:2:3 with yerrorlines pt 7 lc 1 title "a_ln", \
		     sum("a_lt") using 1:2:3 with yerrorlines pt 9 lc 2 title "a_lt", \
		     pap("a_ln") using 1:2 with points pt 6 ps 1.8 lc rgb "black" title ptitle("a_ln"), \
		     pap("a_lt") using 1:2 with points pt 8 ps 1.8 lc rgb "black" title ptitle("a_lt")
	}
	if (p eq "forces") {
		set title "interaction forces (Fig. 20)"
		set ylabel "anisotropy"
		plot sum("a_fn") using 1:2:3 with yerrorlines pt 7 lc 1 title "a_fn", \
		     sum("a_ft") using 1:2:3 with yerrorlines pt 9 lc 2 title "a_ft (eq. 27)", \
		     sum("a_ft_direct") using 1:2:3 with yerrorlines pt 5 lc 3 title "a_ft direct", \
		     pap("a_fn") using 1:2 with points pt 6 ps 1.8 lc rgb "black" title ptitle("a_fn"), \
		     pap("a_ft") using 1:2 with points pt 8 ps 1.8 lc rgb "black" title ptitle("a_ft")
	}
	if (p eq "Ks") {
		set title "sliding interactions (Fig. 21)"
		set ylabel "K_s"
		plot sum("K_s") using 1:2:3 with yerrorlines pt 7 lc 1 title "K_s", \
		     pap("K_s") using 1:2 with points pt 6 ps 1.8 lc rgb "black" title ptitle("K_s")
	}
	if (p eq "angles") {
		set title "principal directions (Figs. 11, 14, 17, 20: insets)"
		set ylabel "degrees"
		# the run's directions in one column of the key, the paper's in the other, below the points
		set key bottom left maxrows 5
		set offsets 0, 0, graph 0.06, graph 0.5
		plot sum("theta_m") using 1:2:3 with yerrorlines pt 7 lc 1 title "theta_m", \
		     sum("theta_n") using 1:2:3 with yerrorlines pt 9 lc 2 title "theta_n", \
		     sum("theta_ln") using 1:2:3 with yerrorlines pt 11 lc 3 title "theta_ln", \
		     sum("theta_fn") using 1:2:3 with yerrorlines pt 5 lc 4 title "theta_fn", \
		     sum("theta_sigma") using 1:2:3 with yerrorlines pt 13 lc 5 title "theta_sigma", \
		     pap("theta_m") using 1:2 with points pt 6 ps 1.8 lc rgb "black" title ptitle("theta_m"), \
		     pap("theta_n") using 1:2 with points pt 8 ps 1.8 lc rgb "black" title ptitle("theta_n"), \
		     pap("theta_ln") using 1:2 with points pt 10 ps 1.8 lc rgb "black" title ptitle("theta_ln"), \
		     pap("theta_fn") using 1:2 with points pt 4 ps 1.8 lc rgb "black" title ptitle("theta_fn")
	}
}
unset multiplot
