# SPDX-License-Identifier: GPL-3.0-or-later
# K and G against confining stress from a moduli table (moduli(1)), each with its standard
# error as a bar (K_se, G_se: the scatter of the interval's increments about Hooke's law).
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
# a column's position by its name in the header, the unit in brackets ignored (with --emt the
# standard errors come after the five effective-medium columns); 0 when absent
col(name) = system(sprintf("awk -F '\t' '/^# / { sub(/^# /, \"\"); for (i = 1; i <= NF; i++) { c = $i; sub(/\\[.*\\]$/, \"\", c); if (c == \"%s\") r = i } exit } END { print r + 0 }' '%s'", name, in)) + 0
cs = col("sigma_c"); cK = col("K"); cG = col("G"); cKse = col("K_se"); cGse = col("G_se")
if (cs * cK * cG * cKse * cGse == 0) {
	print sprintf("moduli.gp: %s: no sigma_c, K, G, K_se or G_se column (not a table of moduli(1))", in)
	exit status 1
}
plot in using (column(cs)/1e6):(column(cK)/1e9):(column(cKse)/1e9) with yerrorlines pt 7 ps 0.6 title "K", \
     in using (column(cs)/1e6):(column(cG)/1e9):(column(cGse)/1e9) with yerrorlines pt 5 ps 0.6 title "G"
