# SPDX-License-Identifier: GPL-3.0-or-later
# packinfo's bulk keys on a real pack (the small pack of the loading tests: 200 grains,
# densify --stress 4e6): the walls order the grains next to them, so the box away from them
# is denser and better connected than the whole box; --bulk-margin 0 is the box itself; a
# margin too large for the box leaves the bulk keys out; bad margins are usage errors.  Then
# the rattlers of that pack frictionalized: the rule of 2 contacts, not 4.  The closed-form
# cases are the unit test's (test_measure.c).  About a second.
. "$TOP/tests/tools/lib.sh"

small_pack dense "densify makes the dense pack"
packinfo dense.pack >d.info 2>d.err || fail "packinfo reads the dense pack" "$(cat d.err)"

# --- the wall effect ------------------------------------------------------------------------
expect_num "bulk porosity below the box's (the looser layer at the walls left out)" \
    "$(info_value d.info bulk_porosity)" "<" "$(info_value d.info porosity)"
expect_num "bulk coordination above the box's" "$(info_value d.info bulk_coordination)" ">" "$(info_value d.info coordination)"
expect_num "bulk porosity a porosity" "$(info_value d.info bulk_porosity)" ">" 0.3
expect_num "the default margin is one mean grain diameter, 2 r_mean" \
    "$(rel "$(info_value d.info bulk_margin)" "$(awk 'BEGIN { printf "%.17g", 2 * '"$(info_value d.info r_mean)"' }')")" "<" 1e-12
expect_num "some grains are in the bulk" "$(info_value d.info bulk_grains)" ">" 10
expect_num "... and not all" "$(info_value d.info bulk_grains)" "<" "$(info_value d.info grains)"
# the keys next to porosity and coordination, in this order
awk '{ print $1 }' d.info | sed -n 5,10p | tr '\n' ' ' >order
if [ "$(cat order)" = "porosity bulk_porosity coordination bulk_coordination bulk_grains bulk_margin " ]; then
	pass "bulk keys next to porosity and coordination"
else
	fail "bulk keys next to porosity and coordination" "$(cat order)"
fi

# --- margin 0: the box ------------------------------------------------------------------------
packinfo --bulk-margin 0 dense.pack >m0.info 2>/dev/null
expect_num "--bulk-margin 0: bulk_porosity = porosity" \
    "$(rel "$(info_value m0.info bulk_porosity)" "$(info_value m0.info porosity)")" "<=" 1e-12
expect_num "--bulk-margin 0: bulk_coordination = coordination" \
    "$(info_value m0.info bulk_coordination)" "==" "$(info_value m0.info coordination)"
expect_num "--bulk-margin 0: every grain" "$(info_value m0.info bulk_grains)" "==" "$(info_value m0.info grains)"
expect_num "--bulk-margin 0: bulk_margin 0" "$(info_value m0.info bulk_margin)" "==" 0
# a larger margin leaves a smaller, denser core
packinfo --bulk-margin "$(awk 'BEGIN { printf "%.17g", 2 * '"$(info_value d.info bulk_margin)"' }')" dense.pack >m2.info 2>/dev/null
expect_num "two diameters: fewer grains in the bulk" "$(info_value m2.info bulk_grains)" "<" "$(info_value d.info bulk_grains)"
expect_num "two diameters: still below the box porosity" "$(info_value m2.info bulk_porosity)" "<" "$(info_value d.info porosity)"

# --- --tsv: the same numbers ------------------------------------------------------------------
packinfo --tsv dense.pack >d.tsv 2>/dev/null
hdr=$(head -n 1 d.tsv | cut -f 5-14)
if [ "$hdr" = "$(printf 'porosity\tbulk_porosity\thydrate_grains\thydrate_volume_fraction\thydrate_saturation\tporosity_hydrate_as_pore\tcoordination\tbulk_coordination\tbulk_grains\tbulk_margin[m]')" ]; then
	pass "--tsv: the bulk columns next to porosity and coordination, the hydrate columns after the porosities"
else
	fail "--tsv: the bulk columns next to porosity and coordination" "$hdr"
fi
expect_num "--tsv: bulk_porosity as in the key/value output" "$(sed -n 2p d.tsv | cut -f 6)" "==" "$(info_value d.info bulk_porosity)"
expect_num "--tsv: bulk_margin as in the key/value output" "$(sed -n 2p d.tsv | cut -f 14)" "==" "$(info_value d.info bulk_margin)"

# --- no inner box: the bulk keys left out (nan in --tsv) ---------------------------------------
packinfo --bulk-margin 1 dense.pack >big.info 2>big.err
if [ $? -eq 0 ] && [ ! -s big.err ] && ! grep -q '^bulk_' big.info && grep -q '^porosity ' big.info; then
	pass "a margin larger than the box: no bulk keys, nothing on stderr"
else
	fail "a margin larger than the box: no bulk keys, nothing on stderr" "$(grep '^bulk_' big.info | tr '\n' ' ') $(cat big.err)"
fi
packinfo --tsv --bulk-margin 1 dense.pack >big.tsv 2>/dev/null
if [ "$(sed -n 2p big.tsv | cut -f 6,12-14)" = "$(printf 'nan\tnan\tnan\tnan')" ]; then
	pass "--tsv, no inner box: the bulk columns nan"
else
	fail "--tsv, no inner box: the bulk columns nan" "$(sed -n 2p big.tsv | cut -f 5-14)"
fi

# --- rattlers: 4 contacts without friction, 2 with ----------------------------------------------
# the dense pack's contact lines carry P0 alone: frictionless, whatever its mu
expect_num "dense pack: the frictionless rattler rule, 4 contacts" "$(info_value d.info rattler_min_contacts)" "==" 4
frictionalize -o fr.pack dense.pack 2>/dev/null
packinfo fr.pack >fr.info 2>/dev/null
expect_num "frictional pack: the rattler rule of 2 contacts" "$(info_value fr.info rattler_min_contacts)" "==" 2
# the same positions with the tangential forces taken out of the lines: the rule of 4
awk '/^end$/ { on = 1; print; next } on && NF == 7 { $4 = $5 = $6 = $7 = 0 } { print }' fr.pack >fr0.pack
packinfo fr0.pack >fr0.info 2>/dev/null
expect_num "... its Q0 and M0 set to 0: the rule of 4" "$(info_value fr0.info rattler_min_contacts)" "==" 4
u4=$(info_value fr.info under4)
if [ "${u4:-0}" -gt 0 ]; then
	# grains with 2 or 3 contacts, held by friction: the pack is in balance (residual <= 1e-4,
	# frictionalize.sh) with them carrying load, so they are no rattlers here
	expect_num "frictional pack: fewer rattlers than grains under 4 contacts" "$(info_value fr.info rattlers)" "<" "$u4"
	expect_num "... which the rule of 4 would all call rattlers" "$(info_value fr0.info rattlers)" ">=" "$u4"
	expect_num "... and the frictional pack is in balance with them" "$(info_value fr.info residual)" "<=" 1e-4
else
	echo "SKIP frictional rattlers: this build's frictional pack has no grain under 4 contacts"
fi
expect_num "frictional pack: the bulk denser than the box too" "$(info_value fr.info bulk_porosity)" "<" "$(info_value fr.info porosity)"

# --- residual_median: the median over the grains of the ratio that residual is the largest of
# four grains in a row, each pressed 2e-6 into the next: the two inner ones balanced (0), the
# two at the ends pushed out by their one contact (1), so the median is (0 + 1) / 2
printf 'qusgm-pack 1\nunits SI\nbox 0 0 0 1e-3 1e-3 1e-3\nwalls 7e12 0.495 0.3\nfriction 0.3\ngrains 4\ncontacts 0\nend\n' >row.pack
for g in 1 2 3 4; do
	awk -v g="$g" 'BEGIN { printf "%d %.17g 5e-4 5e-4 1e-4 7e10 0.2 2420\n", g, 2e-4 + (g - 1) * 1.98e-4 }' >>row.pack
done
packinfo row.pack >row.info 2>/dev/null
expect_num "a row of four grains: residual 1 (the end grains)" "$(rel "$(info_value row.info residual)" 1)" "<" 1e-9
expect_num "... residual_median 0.5, half of them balanced" "$(rel "$(info_value row.info residual_median)" 0.5)" "<" 1e-9
expect_num "frictional pack: residual_median at most residual" "$(info_value fr.info residual_median)" "<=" "$(info_value fr.info residual)"
expect_num "... and above 0" "$(info_value fr.info residual_median)" ">" 0

# --- hydrate (issue 20): the phase column's keys ---------------------------------------------
# a dense pack whose smallest grains held 15 % of the grain volume as hydrate (densify grows
# grains, the small hydrate ones among them, so the fraction is no longer 0.15)
packgen -n 200 --seed 5 --material quartz --hydrate-volume 0.15 2>/dev/null | densify --stress 4e6 -o hy.pack 2>/dev/null
packinfo hy.pack >hy.info 2>hy.err || fail "packinfo reads the hydrate pack" "$(cat hy.err)"
# the pack's own numbers: V_h, V_mineral (sum r^3, times 4/3 pi) and the box
awk '$1 == "box" { V = ($5 - $2) * ($6 - $3) * ($7 - $4) } /^end$/ { on = 1; next }
    on && NF == 9 { v = $5 * $5 * $5; if ($9 == 1) { h += v; n++ } else m += v }
    END { c = 4 / 3 * 3.141592653589793; h *= c; m *= c
	printf "%d %.17g %.17g %.17g %.17g\n", n, h / (h + m), h / (V - m), 1 - m / V, 1 - (h + m) / V }' hy.pack >hy.want
read -r wn wf ws wph wpo <hy.want
expect_num "hydrate: hydrate_grains, the tagged grains" "$(info_value hy.info hydrate_grains)" == "$wn"
# 1e-12: the sums differ only in their order (200 terms, a few 1e-16 each) and S's
# denominator V_box - V_mineral cancels about half of V_box
expect_num "hydrate: hydrate_volume_fraction V_h / V_grains (rel)" "$(rel "$(info_value hy.info hydrate_volume_fraction)" "$wf")" "<" 1e-12
expect_num "hydrate: hydrate_saturation V_h / (V_box - V_mineral) (rel)" "$(rel "$(info_value hy.info hydrate_saturation)" "$ws")" "<" 1e-12
expect_num "hydrate: porosity_hydrate_as_pore 1 - V_mineral / V_box (rel)" "$(rel "$(info_value hy.info porosity_hydrate_as_pore)" "$wph")" "<" 1e-12
expect_num "hydrate: porosity 1 - V_grains / V_box (rel)" "$(rel "$(info_value hy.info porosity)" "$wpo")" "<" 1e-12
# S = F (1 - n) / (n (1 - F)) with n the porosity the hydrate counted as pore space
expect_num "hydrate: S = F (1 - n) / (n (1 - F))" "$(rel "$(info_value hy.info hydrate_saturation)" \
    "$(awk -v f="$(info_value hy.info hydrate_volume_fraction)" -v n="$(info_value hy.info porosity_hydrate_as_pore)" 'BEGIN { printf "%.17g", f * (1 - n) / (n * (1 - f)) }')")" "<" 1e-12
awk '{ print $1 }' hy.info | sed -n 5,10p | tr '\n' ' ' >order
if [ "$(cat order)" = "porosity bulk_porosity hydrate_grains hydrate_volume_fraction hydrate_saturation porosity_hydrate_as_pore " ]; then
	pass "hydrate: the keys right after the porosities"
else
	fail "hydrate: the keys right after the porosities" "$(cat order)"
fi
# a pack without the column: no hydrate keys (the key/value output as before); with --tsv
# over both kinds one header and rows of its width, nan for the pack without the column
if grep -q '^hydrate_\|^porosity_hydrate' d.info; then fail "no phase column: no hydrate keys" "$(grep hydrate d.info)"; else pass "no phase column: no hydrate keys"; fi
packinfo --tsv dense.pack hy.pack dense.pack >mix.tsv 2>/dev/null
expect_num "--tsv over packs with and without the phase column: one field count" "$(awk -F '\t' '{ print NF }' mix.tsv | sort -u | wc -l)" == 1
expect_num "--tsv: 3 rows" "$(rows mix.tsv | wc -l)" == 3
# the last column names each row's input, standard input as <stdin> (issue 59: rows of many
# files could not be told apart)
if [ "$(head -n 1 mix.tsv | awk -F '\t' '{ print $NF }')" = file ] &&
    [ "$(rows mix.tsv | awk -F '\t' '{ printf "%s ", $NF }')" = "dense.pack hy.pack dense.pack " ] &&
    [ "$(packinfo --tsv <dense.pack | grep -v '^#' | awk -F '\t' '{ print $NF }')" = "<stdin>" ]; then
	pass "--tsv: the last column, file, names each row's input (<stdin> for standard input)"
else
	fail "--tsv: the last column, file, names each row's input" "$(rows mix.tsv | awk -F '\t' '{ print $NF }' | tr '\n' ' ')"
fi
if [ "$(rows mix.tsv | sed -n 1p | cut -f 7-10)" = "$(printf 'nan\tnan\tnan\tnan')" ] &&
    [ "$(rows mix.tsv | sed -n 2p | cut -f 7)" = "$wn" ]; then
	pass "--tsv: hydrate columns nan without the column, the count with it"
else
	fail "--tsv: hydrate columns nan without the column, the count with it" "$(rows mix.tsv | cut -f 7-10 | tr '\n' ' ')"
fi
expect_num "--tsv: hydrate_saturation as in the key/value output" "$(rows mix.tsv | sed -n 2p | cut -f 9)" == "$(info_value hy.info hydrate_saturation)"
# the column with every grain mineral: 0 hydrate, S 0, both porosities the same
awk '/^end$/ { on = 1; print; next } on && NF == 9 { $9 = 0 } { print }' hy.pack >min.pack
packinfo min.pack >min.info 2>/dev/null
expect_num "phase column, no hydrate: hydrate_grains 0" "$(info_value min.info hydrate_grains)" == 0
expect_num "phase column, no hydrate: S 0" "$(info_value min.info hydrate_saturation)" == 0
expect_num "phase column, no hydrate: porosity_hydrate_as_pore = porosity" "$(rel "$(info_value min.info porosity_hydrate_as_pore)" "$(info_value min.info porosity)")" "<" 1e-15

# --- the glued column: the descriptors of the free grains (issue 44) -------------------------
# Three spheres of the plate engine's law, A (id 1) touching B (id 2) along x and B touching C
# (id 3) along y, A glued to ylo.  Over every grain: Z = 2 * 2 / 3, floating A and C (2/3),
# normals along x and y: a_n 0.  Over the free grains B and C: the ends on them are 1 (A-B) + 2
# (B-C) over 2 grains, Z 1.5; C floats (1/2); the one free pair along y: a_n 2 at 90 degrees.
cat >gl.pack <<'EOF2'
qusgm-pack 2
meta contact-law linear
units SI
box 0 0 0 1 1 1
boundary walls walls walls
walls 7000000000000 0.495 0.3
friction 0.3
grains 3
contacts 0
columns id x y z r E nu rho side qw qx qy qz glued
end
1 0.3 0.5 0.5 0.1 70000000000 0.2 2420 0 1 0 0 0 ylo
2 0.49 0.5 0.5 0.1 70000000000 0.2 2420 0 1 0 0 0 -
3 0.49 0.69 0.5 0.1 70000000000 0.2 2420 0 1 0 0 0 -
EOF2
packinfo gl.pack >gl.info 2>gl.err
expect_num "glued: 1 grain" "$(info_value gl.info glued)" == 1
expect_num "glued: coordination over all 4/3" "$(rel "$(info_value gl.info coordination)" 1.3333333333333333)" "<" 1e-15
expect_num "glued: coordination_free 3/2" "$(info_value gl.info coordination_free)" == 1.5
expect_num "glued: floating_fraction over all 2/3" "$(rel "$(info_value gl.info floating_fraction)" 0.6666666666666666)" "<" 1e-15
expect_num "glued: floating_fraction_free 1/2" "$(info_value gl.info floating_fraction_free)" == 0.5
expect_num "glued: a_n of the free pair along y, 2" "$(info_value gl.info a_n)" == 2
expect_num "glued: theta_n 90" "$(info_value gl.info theta_n)" == 90
awk '/^columns/ { sub(/ glued$/, "") } /^end$/ { on = 1; print; next } on { NF = NF - 1 } { print }' gl.pack >gl0.pack
packinfo gl0.pack >gl0.info 2>/dev/null
expect_num "no glued column: every grain free, coordination_free = coordination" "$(info_value gl0.info coordination_free)" == "$(info_value gl0.info coordination)"
expect_num "no glued column: a_n of both pairs, x and y, 0" "$(info_value gl0.info a_n)" == 0

# --- usage -----------------------------------------------------------------------------------
expect_error "--bulk-margin negative" 2 '^packinfo: --bulk-margin: must be >= 0' packinfo --bulk-margin -1e-4 dense.pack
expect_error "--bulk-margin nan" 2 "^packinfo: --bulk-margin: 'nan' is not a finite number" packinfo --bulk-margin nan dense.pack
expect_error "--bulk-margin not a number" 2 "^packinfo: --bulk-margin: '2d' is not a finite number" packinfo --bulk-margin 2d dense.pack
# -o over an input is refused before any work (packinfo -o X X replaced the pack by its
# report), as is -o in a directory that is not there
cp dense.pack in.pack
expect_error "-o the input" 2 "^packinfo: -o 'in.pack' is an input: write to another file" packinfo -o in.pack in.pack
expect_same "-o the input: the input untouched" in.pack dense.pack
expect_error "-o the second input" 2 "^packinfo: -o './in.pack' is an input" packinfo -o ./in.pack dense.pack in.pack
expect_refused "nothing written" nothing.info "-o in a missing directory" 2 "^packinfo: -o: cannot write in directory 'no-such-dir': No such file or directory" \
    packinfo -o no-such-dir/nothing.info dense.pack
expect_help_version packinfo --bulk-margin --tsv
