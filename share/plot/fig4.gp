# The frictional paper's Fig. 4: G and the sliding ratio against sigma_c during phase (b)
# (frictionalize's log, one point per increment) and the uniaxial test that follows (moduli
# per window, sliding ratio per increment); the dash-dot line marks the end of phase (b).
# gnuplot -e "out='fig4.png'; cols='pipelines/cols.sh'; run='DIR'" share/plot/fig4.gp
set terminal pngcairo size 1200,520 noenhanced font ",10"
set output out
set datafile separator "\t"
set grid
set key top right font ",9"
src(f, c) = "< sh ".cols." ".run."/".f." ".c
stats src("fric.tsv", "sigma_c") using ($1/1e6) nooutput
set arrow 1 from first STATS_max, graph 0 to first STATS_max, graph 1 nohead dt 4 lc rgb "gray30"
set xlabel "confining stress sigma_c (MPa)"
set multiplot layout 1,2
set ylabel "G (GPa)"
set title "shear modulus"
plot src("fric.tsv", "sigma_c G") using ($1/1e6):($2/1e9) with linespoints pt 6 ps 0.6 title "(1) phase (b), per increment", \
     src("moduli.tsv", "sigma_c G") using ($1/1e6):($2/1e9) with linespoints pt 7 ps 0.6 title "(2) uniaxial test, per 1e-3 strain"
set ylabel "sliding ratio"
set title "ratio of sliding contacts"
set key bottom right
plot src("fric.tsv", "sigma_c sliding_ratio") using ($1/1e6):2 with linespoints pt 6 ps 0.6 title "(1) phase (b)", \
     src("curve.tsv", "sigma_c sliding_ratio") using ($1/1e6):2 with linespoints pt 7 ps 0.4 title "(2) uniaxial test"
unset multiplot
