# SPDX-License-Identifier: GPL-3.0-or-later
# The hydrate study's small form end to end (make -C pipelines SMALL=1 s-fig5: 1000 grains of
# quartz and hydrate densified to 21 MPa, dissociated along the paper's two series, a
# three-axis probe after each), then the paper's finding from its summary table: K and G fall
# with the dissociation.  What a 1000-grain pack shows for every pack tried is checked, not one
# pack's draw: five packs (seeds 1, 2, 3 with the DEM step before 2026-12, seed 1 with three
# versions after) all have K falling point by point along dS (p_ex 1 MPa), every K of the
# p_ex series below the undissociated pack's, and G at the end of
# the dS series below half the undissociated pack's.  K at p_ex 1 MPa without dissociation
# is within the probe's scatter of the undissociated K (below).  G at small dS is not: it moved by up to
# 2.5x between neighbouring points, rose above the undissociated pack's at dS -0.01 for seed
# 2 and fell below its dS -0.02 value for seed 1.  A probe whose pack lost its rigidity along
# an axis writes nan for K or G, and its other modulus is then no measurement (194 MPa for
# G at dS -0.05 beside a nan K, against 57 MPa at -0.04): such a point is skipped, and up to
# two of the eleven are allowed (the packs tried had 0 to 2).
# About 30 s in the optimised build with two cores; left out of the sanitizer build.
. "$TOP/tests/tools/lib.sh"

if [ "${BIN#*build-san}" != "$BIN" ]; then
	echo "SKIP hydrate study (left to the optimised build)"
	exit 0
fi
o=$PWD/out
if make --no-print-directory -j2 -C "$TOP/pipelines" SMALL=1 BIN="$BIN" OUT="$o" s-fig5 >make.out 2>make.err; then
	pass "make -C pipelines SMALL=1 s-fig5"
else
	fail "make -C pipelines SMALL=1 s-fig5" "$(tail -n 5 make.err)"
fi
sm=$o/s-fig5/summary.tsv
for f in "$sm" "$o/s-fig5/report.md" "$o/s-fig5/commands.txt"; do
	if [ -s "$f" ]; then pass "wrote ${f#$o/}"; else fail "wrote ${f#$o/}" "missing or empty"; fi
done
val() { sh "$TOP/pipelines/cols.sh" "$sm" run "$2" | awk -v r="$1" '$1 == r { print $2 }'; }
S=$(val hyd-d0-p0 S)
expect_num "the dense pack's S near the paper's 0.215 (0.18-0.25)" "$S" ">" 0.18
expect_num "... below 0.25" "$S" "<" 0.25
expect_num "the dense pack at about 21 MPa" "$(rel "$(val hyd-d0-p0 sigma_after)" 21e6)" "<" 0.02
# probed RUN: the probe gave both moduli
probed() { [ "$(val "$1" K)" != nan ] && [ "$(val "$1" G)" != nan ]; }
failed=0
for r in $(awk -F'\t' 'NR > 1 { print $1 }' "$sm"); do probed "$r" || failed=$((failed + 1)); done
expect_num "probes without both moduli: at most 2 of the study's points" "$failed" "<=" 2
prev=$(val hyd-d0-p1 K)
lastG=
for k in 1 2 3 4 5; do
	probed hyd-d$k-p1 || continue
	cur=$(val hyd-d$k-p1 K)
	expect_num "p_ex 1 MPa: K at dS -0.0$k below the last probed point before it" "$cur" "<" "$prev"
	prev=$cur
	lastG=$(val hyd-d$k-p1 G)
done
# dS -0.01 at p_ex 3 MPa against 0: the pore pressure takes effective stress (6.5 % of it in
# the pack of 2026-12-06's densify: 12.64 against 13.51 MPa after the dissociation), but
# K ~ sigma'^(1/3) makes that 2.2 % of K, below what a 1000-grain probe resolves (its fits'
# relative residuals 2.2-4.6 %; that pack's K came out 3 % above, the four packs before had
# it below).  Checked are the effective stress, and K within 5 % as at p_ex 1 MPa below.
expect_num "dS -0.01: the effective stress after it at p_ex 3 MPa below p_ex 0" \
    "$(val hyd-d1-p3 sigma_after)" "<" "$(val hyd-d1-p0 sigma_after)"
expect_num "dS -0.01: K at p_ex 3 MPa within 5 % of p_ex 0" "$(rel "$(val hyd-d1-p3 K)" "$(val hyd-d1-p0 K)")" "<" 0.05
for p in 0 0.5 1 2 3; do
	probed hyd-d1-p$p || continue
	expect_num "dS -0.01, p_ex $p MPa: K below the undissociated pack's" "$(val hyd-d1-p$p K)" "<" "$(val hyd-d0-p0 K)"
done
expect_num "p_ex 1 MPa: G at the last probed dS below half the undissociated pack's" "$lastG" "<" \
    "$(awk -v g="$(val hyd-d0-p0 G)" 'BEGIN { print g / 2 }')"
# p_ex 1 MPa alone takes 1 of the 21 MPa: K ~ sigma'^(1/3) predicts K 1.6 % lower, which a
# 1000-grain probe does not resolve (rounding alone, in a build whose preconditioner's blocks
# were in closed form, tried on 2026-12-04 and not kept, moved the undissociated K from 887
# to 852 MPa, and K at p_ex 1 MPa came out 0.9 % above it): checked is that it stays within
# 5 % of it, as a pore pressure applied ten times over (K 20 % lower) would not.
expect_num "p_ex 1 MPa alone: K within 5 % of the undissociated pack's" "$(rel "$(val hyd-d0-p1 K)" "$(val hyd-d0-p0 K)")" "<" 0.05
grep -q '^| hyd-d5-p1 | ' "$o/s-fig5/report.md" && pass "report.md has the runs' rows" || fail "report.md has the runs' rows" "$(head -c 300 "$o/s-fig5/report.md")"
grep -q 'per 0.01 of -dS | -[0-9]' "$o/s-fig5/report.md" && pass "report.md gives the fall per 0.01 of dS" ||
    fail "report.md gives the fall per 0.01 of dS" "$(grep 'per 0.01' "$o/s-fig5/report.md")"
