# SPDX-License-Identifier: GPL-3.0-or-later
# The platy study's figures from committed tables (make -C pipelines platy-figures,
# validate/platy-8000.md): pipelines/join-rows.sh joins the per-platyness summaries into one
# table (the header once, the rows sorted by eta, a mismatched header refused), the paper's
# values table names only columns the summary has, and, where gnuplot is installed, the four
# figures are drawn from a copy of validate/platy-8000 without a missing column.  No tool
# runs: a second or two, in the optimised build only.
. "$TOP/tests/tools/lib.sh"

if [ "${BIN#*build-san}" != "$BIN" ]; then
	echo "SKIP platy figures (left to the optimised build)"
	exit 0
fi
join() { sh "$TOP/pipelines/join-rows.sh" "$@"; }
cols() { sh "$TOP/pipelines/cols.sh" "$@"; }

# two platynesses' summaries given out of order, the first with a metadata line
printf '## made by a test\n# eta\trows\tqp\tqp_sd\n0.8\t101\t0.69\t0.015\n' >summary-eta0.8.tsv
printf '# eta\trows\tqp\tqp_sd\n0\t101\t0.31\t0.02\n0.33\t101\t0.46\t0.02\n' >summary-eta0.tsv
expect_ok "join-rows.sh of two summaries" join summary-eta0.8.tsv summary-eta0.tsv
expect_num "one header line" "$(grep -c '^# ' ok.out)" == 1
expect_num "the first file's metadata line kept, once" "$(grep -c '^## made by a test$' ok.out)" == 1
expect_num "every row kept" "$(rows ok.out | wc -l)" == 3
[ "$(rows ok.out | cut -f 1 | tr '\n' ' ')" = "0 0.33 0.8 " ] && pass "rows sorted by eta" ||
    fail "rows sorted by eta" "$(rows ok.out | cut -f 1 | tr '\n' ' ')"
[ "$(cols ok.out eta qp | sed -n 3p)" = "$(printf '0.8\t0.69')" ] && pass "a row keeps its values" ||
    fail "a row keeps its values" "$(cols ok.out eta qp | sed -n 3p)"
printf '# eta\trows\tqp\n0.5\t101\t0.55\n' >other.tsv
expect_error "a summary with other columns is refused" 2 '^join-rows.sh: other.tsv: header differs from summary-eta0.8.tsv' \
    join summary-eta0.8.tsv other.tsv
expect_error "a missing summary is refused" 2 '^join-rows.sh: nosuch.tsv: cannot read' join summary-eta0.8.tsv nosuch.tsv

# the paper's table: only columns the study's summary has, so that the figures compare like with like
v=$TOP/validate/platy-8000
sm=$(ls "$v"/summary-eta*.tsv | head -n 1)
missing=
for c in $(grep -m 1 '^# ' "$v/paper.tsv" | sed 's/^# //'); do
	cols "$sm" "$c" >/dev/null 2>&1 || missing="$missing $c"
done
[ -z "$missing" ] && pass "paper.tsv's columns are the summary's" || fail "paper.tsv's columns are the summary's" "not in $sm:$missing"

if command -v gnuplot >/dev/null 2>&1; then
	mkdir -p v
	cp "$v"/*.tsv v/
	if make --no-print-directory -C "$TOP/pipelines" PLATY_VALIDATE="$PWD/v" OUT="$PWD/out" platy-figures >make.out 2>make.err; then
		pass "make -C pipelines platy-figures"
	else
		fail "make -C pipelines platy-figures" "$(tail -n 5 make.err)"
	fi
	for f in fig5-8 fig11-14 fig17 fig20-22; do
		if head -c 8 "v/$f.png" 2>/dev/null | od -c | grep -q 'P   N   G'; then pass "$f.png is a PNG"; else fail "$f.png is a PNG" "not written"; fi
	done
	grep -q 'cols.sh:' make.err && fail "the figures find every column" "$(grep 'cols.sh:' make.err | head -n 3)" ||
	    pass "the figures find every column"
	expect_num "the summary of the figures: a row per platyness" "$(rows out/platy-validate/summary.tsv | wc -l)" == "$(ls v/summary-eta*.tsv | wc -l)"
fi
