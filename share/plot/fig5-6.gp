# SPDX-License-Identifier: GPL-3.0-or-later
# The frictional paper's Figs. 5-6: deviatoric stress (axial - mean lateral) against the axial
# strain of the uniaxial test (measured from the test's start), and K and G against sigma_c
# (each with its standard error as a bar, moduli(1)) with each pack's own effective-medium K
# and G (physics.md §13; dashed: rough, dotted: smooth).
# gnuplot -e "out='f.png'; cols='pipelines/cols.sh'; runs='dir1 dir2'" share/plot/fig5-6.gp
set terminal pngcairo size 1500,480 noenhanced font ",10"
set output out
set datafile separator "\t"
set grid
set key top left font ",8"
n = words(runs)
label(i) = system("basename ".word(runs, i))
src(i, f, c) = "< sh ".cols." ".word(runs, i)."/".f." ".c
set multiplot layout 1,3
set xlabel "axial strain of the test"
set ylabel "sigma_d = sig_zz - sig_lat (MPa)"
set title "Fig. 5: deviatoric stress"
plot for [i=1:n] src(i, "curve.tsv", "eps_zz sig_zz sig_lat")." | awk -F '\t' -v OFS='\t' 'NR == 1 { e0 = $1 } { print $1 - e0, $2 - $3 }'" \
     using 1:($2/1e6) with lines lc i lw 1.5 title label(i)
set xlabel "confining stress sigma_c (MPa)"
set ylabel "K (GPa)"
set title "Fig. 6: bulk modulus"
plot for [i=1:n] src(i, "moduli.tsv", "sigma_c K K_se") using ($1/1e6):($2/1e9):($3/1e9) with yerrorlines lc i pt 7 ps 0.5 title label(i), \
     for [i=1:n] src(i, "moduli.tsv", "sigma_c K_emt") using ($1/1e6):($2/1e9) with lines lc i dt 2 notitle
set ylabel "G (GPa)"
set title "Fig. 6: shear modulus"
plot for [i=1:n] src(i, "moduli.tsv", "sigma_c G G_se") using ($1/1e6):($2/1e9):($3/1e9) with yerrorlines lc i pt 7 ps 0.5 title label(i), \
     for [i=1:n] src(i, "moduli.tsv", "sigma_c G_emt_rough") using ($1/1e6):($2/1e9) with lines lc i dt 2 notitle, \
     for [i=1:n] src(i, "moduli.tsv", "sigma_c G_emt_smooth") using ($1/1e6):($2/1e9) with lines lc i dt 3 notitle
unset multiplot
