# SPDX-License-Identifier: GPL-3.0-or-later
# pack.gp: the force-network picture of packpic.sh (which makes the two tables and calls it);
# with segs (spheroplates: x y dx dy colour, x0 z0 x1 z1 the box in x and y), the plates' traces.
# discs: id x z section-radius colour; x0 z0 x1 z1 the box (m); lines: x z dx dz class (1-8, the width in half points).
set terminal pngcairo size 900,900 noenhanced font ",10"
set output out
set datafile separator "\t"
set size ratio -1
set title ttl
set xlabel "x (mm)"
set ylabel "z (mm)"
set cblabel colour
set palette defined (0 "#3b4cc0", 1 "#dddddd", 2 "#b40426")
set style fill solid 0.85 border lc rgb "#666666"
unset key
# the box's walls (x0 z0 x1 z1, m)
set object 1 rect from x0*1e3, z0*1e3 to x1*1e3, z1*1e3 fs empty border lc rgb "#444444" lw 1.5 front
set xrange [x0*1e3:x1*1e3]
set yrange [z0*1e3:z1*1e3]
if (exists("segs")) {
	set xlabel "x (um)"
	set ylabel "y (um)"
	set object 1 rect from x0*1e6, z0*1e6 to x1*1e6, z1*1e6 fs empty border lc rgb "#444444" lw 1.5 front
	set xrange [x0*1e6:x1*1e6]
	set yrange [z0*1e6:z1*1e6]
	plot segs using ($1*1e6):($2*1e6):($3*1e6):($4*1e6):5 with vectors nohead lw 3 lc palette
	exit
}
plot discs using ($2*1e3):($3*1e3):($4*1e3):5 with circles lc palette, \
     for [k=1:8] lines using ($5 == k ? $1*1e3 : NaN):($2*1e3):($3*1e3):($4*1e3) with vectors nohead lw 0.5*k lc rgb "black"
