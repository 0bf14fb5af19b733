# SPDX-License-Identifier: GPL-3.0-or-later
# history: the one rule for which grain a contact line's Q0 acts on (pack_contact_q0_on).
# A line may name its pair 'i j' or 'j i' (pack-format.md); Q0 is the force on the first
# grain named.  A frictional pack and its twin with every grain-grain line reversed
# ('j i ... -Q0 ...', the same pack by the spec) must give the same packinfo and loadtest
# output.  Before the rule lived in one accessor, packinfo read the twin's Q0 on the wrong
# grain: residual 2.1e-5 -> 0.93 on this pack, and sig_lw and loadtest's row 0 changed.
. "$TOP/tests/tools/lib.sh"

packgen -n 200 --seed 3 2>/dev/null | densify --stress 4e6 2>/dev/null |
	frictionalize --max-inc 12 --window 3 --window-overlap 0 --allow-limit >fr.pack 2>/dev/null
G=$(awk '$1 == "grains" { print $2 }' fr.pack)
awk -v G="$G" '
/^end$/ { print; e = NR; next }
e && NR > e + G && $2 ~ /^[0-9]+$/ {
	printf "%s %s %s %.17g %.17g %.17g %s\n", $2, $1, $3, -$4, -$5, -$6, $7; next }
{ print }' fr.pack >twin.pack
nrev=$(awk -v G="$G" '/^end$/ { e = NR; next } e && NR > e + G && $2 ~ /^[0-9]+$/' fr.pack | wc -l)
expect_num "the twin reverses the grain-grain history lines" "$nrev" ">" 300
if cmp -s fr.pack twin.pack; then fail "the twin differs from the pack" "identical files"; else pass "the twin differs from the pack"; fi

packinfo fr.pack >a.info
packinfo twin.pack >b.info
expect_same "packinfo: a pack and its reversed twin agree" a.info b.info
expect_num "packinfo: the pack balances its history (residual)" "$(info_value a.info residual)" "<" 1e-3
# the last column, file, names each input: the rest agree
packinfo --tsv fr.pack | awk -F '\t' 'BEGIN { OFS = "\t" } { NF--; print }' >a.tsv
packinfo --tsv twin.pack | awk -F '\t' 'BEGIN { OFS = "\t" } { NF--; print }' >b.tsv
expect_same "packinfo --tsv: a pack and its reversed twin agree" a.tsv b.tsv
loadtest --path uniaxial --steps 2 fr.pack >a.curve 2>/dev/null
loadtest --path uniaxial --steps 2 twin.pack >b.curve 2>/dev/null
# the header's ## lines name the input file; the rows must agree
grep -v '^##' a.curve >a.rows
grep -v '^##' b.curve >b.rows
expect_same "loadtest: a pack and its reversed twin give the same rows" a.rows b.rows
expect_num "loadtest wrote rows" "$(rows a.curve | wc -l)" ">=" 3
