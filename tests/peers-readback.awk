# peers-readback.awk: a LIGGGHTS state put back into a copy of the qusgm pack it started from,
# so that packinfo judges it by qusgm's definitions (make bench-peers, tests/bench-peers.sh).
#
# usage: awk -v box="XLO YLO ZLO XHI YHI ZHI" -v note=TEXT -f peers-readback.awk \
#            ATOMS PAIRS WALLS PACK >STATE.pack
#
# ATOMS: a LIGGGHTS custom dump 'id x y z'; PAIRS: a local dump of compute pair/gran/local
# 'id force_normal force_tangential' (id1 id2 periodic, 3 + 3 values); WALLS: one of compute
# wall/gran/local 'id force_normal force_tangential' (mesh, triangle, atom, 3 + 3), the meshes
# in the order xlo xhi ylo yhi zlo zhi.  PACK: the qusgm pack (uncompressed) whose grains the
# LIGGGHTS atoms are (packexport --lammps-data numbers the atoms by the grain ids).
#
# The pack keeps its header (less the last increment's sliding-ratio records), radii and
# moduli; it gets the box, the centres and, as its contact lines, LIGGGHTS's contacts: P0 the
# normal force, Q0 the tangential force on the first grain (pair/gran/local gives the force
# on the first atom of a pair, wall/gran/local the force on the atom), M0 0 (no torsion in
# LIGGGHTS's Hertz-Mindlin).  packinfo then takes the normal forces from the overlaps with
# qusgm's Hertz law and the tangential ones from these lines.  Arithmetic only: no physics.
function abs(v) { return v < 0 ? -v : v }
BEGIN { split("xlo xhi ylo yhi zlo zhi", wall, " "); nf = 0 }
FNR == 1 { nf++; body = 0 }
nf <= 3 && /^ITEM: (ATOMS|ENTRIES)/ { body = 1; next }
nf <= 3 && !body { next }
nf == 1 { x[$1] = $2; y[$1] = $3; z[$1] = $4; next }
nf == 2 {
	if ($4 == 0 && $5 == 0 && $6 == 0 && $7 == 0 && $8 == 0 && $9 == 0)
		next
	nc++
	line[nc] = sprintf("%d %d %.17g %.17g %.17g %.17g 0", $1, $2, sqrt($4 * $4 + $5 * $5 + $6 * $6), $7, $8, $9)
	next
}
nf == 3 {
	# a grain on two triangles of one mesh would be two entries: add them
	k = $3 " " wall[$1 + 1]
	if (!(k in wn)) { order[++nw] = k; wn[k] = 0 }
	wn[k] += sqrt($4 * $4 + $5 * $5 + $6 * $6)
	wt1[k] += $7; wt2[k] += $8; wt3[k] += $9
	next
}
# the pack
FNR == 1 { print; next }
!hdr && $1 == "history" { print; next }
!hdr && !noted { print "history " note; noted = 1 }
!hdr && $1 == "box" { print "box " box; next }
!hdr && $1 == "meta" && ($2 == "sliding_ratio" || $2 == "trial_slip_ratio") { next }
!hdr && $1 == "grains" { ng = $2 }
!hdr && $1 == "contacts" { print "contacts " nc + nw; next }
!hdr && $1 == "end" { hdr = 1; print; next }
!hdr { print; next }
gi < ng {
	gi++
	if (!($1 in x)) { print "peers-readback: grain " $1 " not in the atoms dump" >"/dev/stderr"; bad = 1; exit 1 }
	$2 = x[$1]; $3 = y[$1]; $4 = z[$1]
	print
	if (gi == ng) {
		for (c = 1; c <= nc; c++) print line[c]
		for (c = 1; c <= nw; c++) {
			k = order[c]
			printf "%s %.17g %.17g %.17g %.17g 0\n", k, wn[k], wt1[k], wt2[k], wt3[k]
		}
	}
	next
}
END { if (!bad && gi != ng) { print "peers-readback: the pack has " gi " of " ng " grains" >"/dev/stderr"; exit 1 } }
