# SPDX-License-Identifier: GPL-3.0-or-later
# The platy-particle paper's figures from the platy study (pipelines/Makefile): the velocity
# profiles (its Fig. 6), tau_w/sigma_w against gamma (Fig. 5), and against the platyness eta the
# shear strength q/p with eq. 28's harmonic sum (Figs. 7, 22), the packing fraction (Fig. 8),
# a_m (Fig. 11), Z and chi (Fig. 12), a_n (Fig. 14), a_ln and a_lt (Fig. 17), a_fn and a_ft
# (Fig. 20) and K_s (Fig. 21), each the mean over the steady state with its standard deviation;
# beside a_m the 3D nematic measures, beside a_ft and eq. 28 the direct tangential terms
# (share/doc/tables.md), chi over the free grains.
# gnuplot -e "out='platy.png'; cols='pipelines/cols.sh'; summary='S'; runs='DIR...'; from=G" share/plot/platy.gp
set terminal pngcairo size 1600,900 noenhanced font ",9"
set output out
set datafile separator "\t"
set grid
set key font ",8"
src(f, c) = "< sh ".cols." ".f." ".c
sum(c) = src(summary, c)
set multiplot layout 3,4
set title "velocity profiles (Fig. 6)"
set xlabel "<v_x> / v_w"
set ylabel "y / y_w"
set key top left
plot for [r in runs] src(r."/profile.tsv", "vx_over_vw y_over_yw") using 1:2 with linespoints pt 7 ps 0.5 title r[strstrt(r, "platy-eta") + 9:]
set title "tau_w / sigma_w (Fig. 5)"
set xlabel "gamma"
set ylabel "tau_w / sigma_w"
set arrow 1 from first from, graph 0 to first from, graph 1 nohead dt 4 lc rgb "gray30"
plot for [r in runs] src(r."/shear.tsv", "gamma tau_sigma") using 1:2 with lines title r[strstrt(r, "platy-eta") + 9:]
unset arrow 1
set xlabel "platyness eta"
set xrange [-0.05:0.85]
set key top left
set title "shear strength (Figs. 7, 22)"
set ylabel "q / p"
plot sum("eta qp qp_sd") using 1:2:3 with yerrorlines pt 7 title "measured", \
     sum("eta qp_harmonic qp_harmonic_sd") using 1:2:3 with yerrorlines pt 9 title "eq. 28", \
     sum("eta qp_harmonic_direct qp_harmonic_direct_sd") using 1:2:3 with yerrorlines pt 5 title "eq. 28, direct tangential terms"
set title "packing fraction (Fig. 8)"
set ylabel "phi"
plot sum("eta phi phi_sd") using 1:2:3 with yerrorlines pt 7 notitle
set title "particle orientations (Fig. 11)"
set ylabel "a_m"
plot sum("eta a_m a_m_sd") using 1:2:3 with yerrorlines pt 7 title "a_m (xy)", \
     sum("eta M1_M3 M1_M3_sd") using 1:2:3 with yerrorlines pt 9 title "M1 - M3 (3D)", \
     sum("eta nematic_S nematic_S_sd") using 1:2:3 with yerrorlines pt 5 title "S"
set title "coordination (Fig. 12a)"
set ylabel "Z"
plot sum("eta Z Z_sd") using 1:2:3 with yerrorlines pt 7 notitle
set title "floating particles (Fig. 12b)"
set ylabel "chi"
plot sum("eta floating_fraction_free floating_fraction_free_sd") using 1:2:3 with yerrorlines pt 7 notitle
set title "interaction orientations (Fig. 14)"
set ylabel "a_n"
plot sum("eta a_n a_n_sd") using 1:2:3 with yerrorlines pt 7 notitle
set title "branch lengths (Fig. 17)"
set ylabel "anisotropy"
plot sum("eta a_ln a_ln_sd") using 1:2:3 with yerrorlines pt 7 title "a_ln", \
     sum("eta a_lt a_lt_sd") using 1:2:3 with yerrorlines pt 9 title "a_lt"
set title "interaction forces (Fig. 20)"
plot sum("eta a_fn a_fn_sd") using 1:2:3 with yerrorlines pt 7 title "a_fn", \
     sum("eta a_ft a_ft_sd") using 1:2:3 with yerrorlines pt 9 title "a_ft (eq. 27)", \
     sum("eta a_ft_direct a_ft_direct_sd") using 1:2:3 with yerrorlines pt 5 title "a_ft direct"
set title "sliding interactions (Fig. 21)"
set ylabel "K_s"
plot sum("eta K_s K_s_sd") using 1:2:3 with yerrorlines pt 7 notitle
set title "directions (Figs. 11, 14, 20)"
set ylabel "degrees"
plot sum("eta theta_m") using 1:2 with linespoints pt 7 title "theta_m", \
     sum("eta theta_n") using 1:2 with linespoints pt 9 title "theta_n", \
     sum("eta theta_fn") using 1:2 with linespoints pt 5 title "theta_fn", \
     sum("eta theta_sigma") using 1:2 with linespoints pt 4 title "theta_sigma"
unset multiplot
