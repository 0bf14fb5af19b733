# SPDX-License-Identifier: GPL-3.0-or-later
# The smallest study end to end, as a user runs it: make -C pipelines SMALL=1 fig4 (the
# frictional paper's Fig. 4 on a 300-grain pack) into this test's directory, then the trends
# the paper reports, read back from the tables the study wrote: phase (b) ends with a
# saturated sliding ratio after G has fallen from its first value, and in the uniaxial test
# that follows the moduli grow with sigma_c.  Also: a rerun has nothing to do, and a failing
# stage leaves no target behind.
. "$TOP/tests/tools/lib.sh"

# The optimised build's: the study's make rules and scripts, whose tools the sanitizer build
# runs in their own tests (17 s of CPU there to run them again).
if [ "${BIN#*build-san}" != "$BIN" ]; then
	echo "SKIP pipelines (the study's rules and scripts: the optimised build's)"
	exit 0
fi
o=$PWD/out
cols() { sh "$TOP/pipelines/cols.sh" "$@"; }
if make --no-print-directory -C "$TOP/pipelines" SMALL=1 BIN="$BIN" OUT="$o" fig4 >make.out 2>make.err; then
	pass "make -C pipelines SMALL=1 fig4"
else
	fail "make -C pipelines SMALL=1 fig4" "$(tail -n 5 make.err)"
fi
r=$o/runs/g2740-s4-mu0.3
for f in $o/packs/g2740.s4.pack.gz $r/fric.pack.gz $r/fric.tsv $r/curve.tsv $r/moduli.tsv $o/fig4/report.md $o/fig4/commands.txt $o/fig4/report.html $o/fig4/pack.html; do
	if [ -s "$f" ]; then pass "wrote ${f#$o/}"; else fail "wrote ${f#$o/}" "missing or empty"; fi
done
if command -v gnuplot >/dev/null 2>&1; then
	if head -c 8 "$o/fig4/fig4.png" 2>/dev/null | od -c | grep -q 'P   N   G'; then pass "fig4.png is a PNG"; else fail "fig4.png is a PNG" "not written"; fi
	if head -c 8 "$o/fig4/pack.png" 2>/dev/null | od -c | grep -q 'P   N   G'; then pass "the picture of the pack, pack.png, is a PNG"; else fail "the picture of the pack, pack.png, is a PNG" "not written"; fi
	grep -q '^!\[pack\](pack.png)$' "$o/fig4/report.md" && pass "report.md shows the pack" || fail "report.md shows the pack" "no pack.png line"
fi
grep -q '<a href="pack.html">' "$o/fig4/report.html" && grep -q '<td>g2740-s4-mu0.3</td>' "$o/fig4/report.html" &&
    pass "report.html links the pack's 3D view and has the run's rows" ||
    fail "report.html links the pack's 3D view and has the run's rows" "$(head -c 300 "$o/fig4/report.html")"
grep -q 'frictionalize --mu 0.3' "$o/fig4/commands.txt" && pass "commands.txt holds the frictionalize command" ||
    fail "commands.txt holds the frictionalize command" "$(head -c 300 "$o/fig4/commands.txt")"

# phase (b) (the study runs frictionalize --until shear): G falls from its first increment (the
# paper's overshoot), passes its minimum, and the run stops just after: the minimum lies
# inside the run, above its first increment and below its last
g1=$(cols "$r/fric.tsv" G | sed -n 2p)
gmin=$(cols "$r/fric.tsv" G | awk 'NR > 1 && (m == "" || $1 < m) { m = $1 } END { print m }')
gn=$(cols "$r/fric.tsv" G | tail -n 1)
expect_num "phase (b): G falls from its first increment" "$gmin" "<" "$g1"
expect_num "phase (b): G has passed its minimum when the run stops" "$gn" ">" "$gmin"
sl=$(cols "$r/fric.tsv" sliding_ratio | tail -n 1)
expect_num "phase (b): sliding ratio well above zero" "$sl" ">" 0.02
s0=$(cols "$r/fric.tsv" sigma_c | tail -n 1)
expect_num "phase (b) ends between 6 and 14 MPa (the paper: about 9 MPa)" "$s0" ">" 6e6
expect_num "phase (b) ends below 14 MPa" "$s0" "<" 14e6
# the test: K and G of the last window above those of the first (they grow as sigma_c^(1/3..1/2))
for m in K G; do
	a=$(cols "$r/moduli.tsv" $m | head -n 1)
	b=$(cols "$r/moduli.tsv" $m | tail -n 1)
	expect_num "uniaxial test: $m grows with sigma_c" "$b" ">" "$a"
done
s=$(cols "$r/curve.tsv" sigma_c | tail -n 1)
expect_num "uniaxial test reached --to-stress 20e6" "$s" ">=" 20e6
grep -q '^| g2740-s4-mu0.3 | ' "$o/fig4/report.md" && pass "report.md has the run's rows" || fail "report.md has the run's rows" "$(cat "$o/fig4/report.md")"

# nothing to redo
make --no-print-directory -C "$TOP/pipelines" SMALL=1 BIN="$BIN" OUT="$o" -q fig4-data && pass "a rerun is up to date" ||
    fail "a rerun is up to date" "make -q says the study's data are out of date"

# a stage that fails leaves no target: a loadtest that cannot run (no such binary dir)
rm -f "$r/curve.tsv" "$r/moduli.tsv"
mkdir -p fakebin
for t in packgen densify frictionalize moduli packinfo; do ln -sf "$BIN/$t" fakebin/$t; done
printf '#!/bin/sh\necho "row"\nexit 1\n' >fakebin/loadtest
chmod +x fakebin/loadtest
if make --no-print-directory -C "$TOP/pipelines" SMALL=1 BIN="$PWD/fakebin" OUT="$o" fig4-data >fail.out 2>fail.err; then
	fail "a failing loadtest fails the study" "make exited 0"
else
	pass "a failing loadtest fails the study"
fi
if [ -e "$r/curve.tsv" ] || [ -e "$r/curve.tsv.tmp" ]; then fail "no half-written curve.tsv" "$(ls "$r")"; else pass "no half-written curve.tsv"; fi
