# SPDX-License-Identifier: GPL-3.0-or-later
# plates: what the tools do with packs of spheroplates (the shape columns side qw qx qy qz of
# share/doc/pack-format.md).  The sphere physics (densify, frictionalize, loadtest) refuses a
# pack with any side > 0 in one line, through pack_require_spheres, and takes one whose shape
# columns are all side 0 as the spheres it is.
. "$TOP/tests/tools/lib.sh"

# to_shapes: a version-1 pack on stdin as version 2 with the shape columns, every grain a
# sphere (side 0, q = 1); with ID and SIDE, grain ID gets that side.
to_shapes() {
	awk -v id="${1-}" -v side="${2-}" '
	NR == 1 { print "qusgm-pack 2"; next }
	$1 == "grains" && !h { n = $2 }
	$1 == "end" && !h { print "boundary walls walls walls"; print "columns id x y z r E nu rho side qw qx qy qz"; print; h = 1; next }
	h && n > 0 { print $0, ($1 == id ? side : 0), 1, 0, 0, 0; n--; next }
	{ print }'
}

# --- the sphere tools refuse plates ---
small_pack dense
to_shapes 17 1e-5 <dense.pack >plate17.pack
for t in densify frictionalize loadtest; do
	expect_error "$t refuses a plate" 1 "^$t: plate17\\.pack: grain 17 is a spheroplate \\(side > 0\\); $t handles spheres only\$" \
	    $t plate17.pack
done
expect_error "densify names stdin" 1 '^densify: <stdin>: grain 17 is a spheroplate \(side > 0\); densify handles spheres only$' \
    densify <plate17.pack
expect_error "loadtest names stdin" 1 '^loadtest: <stdin>: grain 17 is a spheroplate' loadtest - <plate17.pack
# the first plate in the file is named, not the first grain
to_shapes 40 2e-6 <dense.pack | awk '$1 == 120 && NF == 13 { $9 = 3e-6 } { print }' >plate40.pack
expect_error "the first plate is named" 1 'grain 40 is a spheroplate' frictionalize plate40.pack
# with -o: nothing written
expect_refused "no output" "nothing.pack nothing.tsv" "densify -o refuses a plate" 1 'spheroplate' \
    densify -o nothing.pack --log nothing.tsv plate17.pack

# --- shape columns with every side 0: spheres, taken and kept ---
to_shapes <loose.pack >loose0.pack
expect_ok "densify takes shape columns with every side 0" densify --stress 4e6 -o dense0.pack loose0.pack
# the same grains as densify of the plain pack, and the shape columns written back
awk 'f && NF { print $1, $2, $3, $4, $5, $6, $7, $8 } $1 == "end" { f = 1 }' dense.pack | head -n 200 >plain.grains
awk 'f && NF { print $1, $2, $3, $4, $5, $6, $7, $8 } $1 == "end" { f = 1 }' dense0.pack | head -n 200 >shape.grains
expect_same "densify: shape columns with side 0 give the spheres' result" plain.grains shape.grains
if grep -q '^columns id x y z r E nu rho shape side qw qx qy qz$' dense0.pack && head -n 1 dense0.pack | grep -q '^qusgm-pack 2$' &&
    [ "$(awk 'f && NF == 14 && $9 == "sphere" { n++ } $1 == "end" { f = 1 } END { print n }' dense0.pack)" = 200 ]; then
	pass "densify writes the shape columns back"
else
	fail "densify writes the shape columns back" "$(grep -E '^(qusgm-pack|columns)' dense0.pack)"
fi
expect_ok "frictionalize takes shape columns with every side 0" frictionalize -o fr0.pack dense0.pack
expect_ok "loadtest takes shape columns with every side 0" loadtest -n 2 -o lt0.pack fr0.pack

# --- packinfo: the shape report of a plate pack ---
# pack-format.md's example: normals z, -y and x (<n n> = I/3, so S = 0), platyness under the
# corner reading (R = r + L/sqrt(2)); the same without the meta line is read as edge
cat >three.pack <<'EOF2'
qusgm-pack 2
meta plate-radius corner
units SI
box 0 0 0 1e-3 1e-3 1e-3
boundary walls walls walls
walls 7e12 0.495 0.3
friction 0.3
grains 3
contacts 0
columns id x y z r E nu rho side qw qx qy qz
end
1 2e-4 2e-4 2e-4 2e-5 7e10 0.2 2420 1e-4 1 0 0 0
2 5e-4 5e-4 5e-4 2e-5 7e10 0.2 2420 1e-4 0.7071067811865476 0.7071067811865476 0 0
3 8e-4 8e-4 8e-4 2e-5 7e10 0.2 2420 1e-4 0.5 0.5 0.5 0.5
EOF2
expect_ok "packinfo: a plate pack" packinfo three.pack
mv ok.out three.info
expect_num "packinfo: plates" "$(info_value three.info plates)" == 3
expect_num "packinfo: corner platyness (0.7795187907884575)" "$(rel "$(info_value three.info platyness)" 0.7795187907884575)" '<' 1e-15
expect_num "packinfo: corner aspect ratio 1/(1 - eta)" "$(rel "$(info_value three.info aspect_ratio)" 4.535533905932738)" '<' 1e-15
expect_num "packinfo: normals z, -y, x: nematic order 0" "$(awk -v v="$(info_value three.info nematic_order)" 'BEGIN { print v < 0 ? -v : v }')" '<' 1e-15
# packing fraction: 3 (2 r L^2 + 2 pi r^2 L + 4/3 pi r^3) / 1e-9
want=$(awk 'BEGIN { r = 2e-5; L = 1e-4; pi = atan2(0, -1); printf "%.17g", 3 * (2 * r * L * L + 2 * pi * r * r * L + 4 / 3 * pi * r * r * r) / 1e-9 }')
expect_num "packinfo: packing fraction with the plate volume" "$(rel "$(info_value three.info packing_fraction)" "$want")" '<' 1e-14
# the interaction keys are the plates' own (measure_plates); what is defined for spheres only
# (rattlers by the 4-contact rule, overlap over the radius, the sphere fabric, the bulk keys)
# is left out
expect_num "packinfo: three plates apart, coordination 0" "$(info_value three.info coordination)" == 0
if grep -Eq '^(rattlers|under4|overlap_max|fabric_xx|bulk_porosity|bulk_margin) ' three.info; then
	fail "packinfo: no sphere-only keys for plates" "$(grep -E '^(rattlers|under4|overlap_max|fabric_xx|bulk_porosity|bulk_margin) ' three.info)"
else
	pass "packinfo: no sphere-only keys for plates"
fi
if grep -q '^platyness_min ' three.info; then fail "packinfo: monodisperse plates, no platyness_min" "$(grep platyness three.info)"; else pass "packinfo: monodisperse plates, no platyness_min"; fi
sed '/^meta plate-radius/d' three.pack >three-edge.pack
packinfo three-edge.pack >three-edge.info 2>/dev/null
expect_num "packinfo: edge platyness by default (5/7)" "$(rel "$(info_value three-edge.info platyness)" 0.7142857142857143)" '<' 1e-15
sed 's/^meta plate-radius corner$/meta plate-radius edge/' three.pack >three-edge2.pack
packinfo three-edge2.pack >three-edge2.info 2>/dev/null
expect_same "packinfo: meta plate-radius edge is the default" three-edge.info three-edge2.info
sed 's/^meta plate-radius corner$/meta plate-radius Edge/' three.pack >bad-conv.pack
expect_error "packinfo: an unknown plate-radius" 1 "^packinfo: bad-conv\\.pack: meta plate-radius 'Edge' is neither 'edge' nor 'corner'\$" \
    packinfo bad-conv.pack
# every normal along z, then along x (q = (1, 1, 1, 1)/2 turns z to x): S = 1, director z, x
sed '13s/0.7071067811865476 0.7071067811865476 0 0$/1 0 0 0/;14s/0.5 0.5 0.5 0.5$/1 0 0 0/' three.pack >alignz.pack
packinfo alignz.pack >alignz.info 2>/dev/null
expect_num "packinfo: normals along z: nematic order 1" "$(rel "$(info_value alignz.info nematic_order)" 1)" '<' 1e-15
if [ "$(info_value alignz.info director_x)" = 0 ] && [ "$(info_value alignz.info director_y)" = 0 ] && [ "$(info_value alignz.info director_z)" = 1 ]; then
	pass "packinfo: normals along z: director (0, 0, 1)"
else
	fail "packinfo: normals along z: director (0, 0, 1)" "$(grep director alignz.info | tr '\n' ' ')"
fi
sed '12s/1 0 0 0$/0.5 0.5 0.5 0.5/;13s/0.7071067811865476 0.7071067811865476 0 0$/-0.5 -0.5 -0.5 -0.5/' three.pack >alignx.pack
packinfo alignx.pack >alignx.info 2>/dev/null
expect_num "packinfo: normals along x (q and -q): nematic order 1" "$(rel "$(info_value alignx.info nematic_order)" 1)" '<' 1e-15
expect_num "packinfo: normals along x: director_x 1" "$(rel "$(info_value alignx.info director_x)" 1)" '<' 1e-15
# polydisperse: a sphere among the plates gives platyness min 0 and aspect ratio min 1
sed '14s/ 1e-4 0.5 0.5 0.5 0.5$/ 0 1 0 0 0/' three.pack >poly.pack
packinfo poly.pack >poly.info 2>/dev/null
if [ "$(info_value poly.info plates)" = 2 ] && [ "$(info_value poly.info platyness_min)" = 0 ] &&
    [ "$(info_value poly.info aspect_ratio_min)" = 1 ] && [ -n "$(info_value poly.info platyness_max)" ]; then
	pass "packinfo: a sphere among plates: 2 plates, platyness min 0, aspect ratio min 1"
else
	fail "packinfo: a sphere among plates" "$(grep -E '^(plates|platyness|aspect)' poly.info | tr '\n' ' ')"
fi
# --tsv: the plate columns; one kind per table
expect_ok "packinfo --tsv: a plate pack" packinfo --tsv three.pack
if head -n 1 ok.out | grep -q "	plates	" && head -n 1 ok.out | grep -q "	nematic_order	"; then pass "packinfo --tsv: plate columns"; else fail "packinfo --tsv: plate columns" "$(head -n 1 ok.out)"; fi
cat three.pack dense.pack >mixed.pack
expect_error "packinfo --tsv: plates then spheres" 1 '^packinfo: mixed\.pack: --tsv: pack 2 has spheres only, the first spheroplates: one table holds one kind of pack$' \
    packinfo --tsv mixed.pack
expect_ok "packinfo: plates then spheres, key-value" packinfo mixed.pack
# shape columns with every side 0: the sphere report, byte for byte
packinfo dense.pack >dense.info 2>/dev/null
to_shapes <dense.pack >dense0.pack
packinfo dense0.pack >dense0.info 2>/dev/null
expect_same "packinfo: shape columns with every side 0 give the sphere report" dense.info dense0.info
