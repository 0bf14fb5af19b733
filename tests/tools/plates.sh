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
if grep -q '^columns id x y z r E nu rho side qw qx qy qz$' dense0.pack && head -n 1 dense0.pack | grep -q '^qusgm-pack 2$' &&
    [ "$(awk 'f && NF == 13 { n++ } $1 == "end" { f = 1 } END { print n }' dense0.pack)" = 200 ]; then
	pass "densify writes the shape columns back"
else
	fail "densify writes the shape columns back" "$(grep -E '^(qusgm-pack|columns)' dense0.pack)"
fi
expect_ok "frictionalize takes shape columns with every side 0" frictionalize -o fr0.pack dense0.pack
expect_ok "loadtest takes shape columns with every side 0" loadtest -n 2 -o lt0.pack fr0.pack
