# SPDX-License-Identifier: GPL-3.0-or-later
# K and G against confining stress from a moduli table (moduli(1)).
# gnuplot -e "in='moduli.tsv'; out='moduli.png'" share/plot/moduli.gp
if (!exists("in")) in = 'moduli.tsv'
if (!exists("out")) out = 'moduli.png'
set terminal pngcairo size 800,560 noenhanced font ",11"
set output out
set datafile separator "\t"
set datafile commentschars "#"
set xlabel "confining stress sigma_c (MPa)"
set ylabel "modulus (GPa)"
set key top left
set grid
plot in using ($5/1e6):($7/1e9) with linespoints pt 7 ps 0.6 title "K", \
     in using ($5/1e6):($8/1e9) with linespoints pt 5 ps 0.6 title "G"
