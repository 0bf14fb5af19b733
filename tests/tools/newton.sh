# SPDX-License-Identifier: GPL-3.0-or-later
# Newton's method (--method newton) against L-BFGS on the same frictionless increments: six
# uniaxial 1e-4 steps and three isotropic ones of the 200-grain dense pack with --mu 0, once
# per method from the same start.  Both stop at the residual 1e-4 (each grain's unbalanced
# force at most 1e-4 of its largest contact force); the wall stress sums the wall contacts'
# forces, each of which moves by about that fraction of itself between two states that both
# meet it, so the two methods' stresses may differ by a few 1e-4 relative and no more: the
# check allows 5e-4 (measured: below 1e-5).  The contacts (coordination) must be the same.
# Then the same with friction, and the refusal of the paper's rule.  A few seconds in all.
. "$TOP/tests/tools/lib.sh"

# columns: 6-8 sig, 15 coordination, 18 iterations, 19 residual
# The comparison needs a path with one equilibrium: where contacts open as the stress rises
# (a rearrangement), each minimiser may come to rest in another state, which is no fault of
# either.  The 200-grain packs of seeds 1-7 rearrange in these increments under both methods
# for two seeds with densify before 2026-12-05 (3 and 6) and three after (1, 2 and 5, the
# other tests' seed), so this test takes seed 4, which does not under either.
packgen -n 200 --seed 4 -o loose.pack 2>/dev/null
expect_ok "densify makes the dense pack" densify --stress 4e6 -o dense.pack loose.pack

for path in uniaxial isotropic; do
	steps=6
	[ "$path" = isotropic ] && steps=3
	for m in lbfgs newton; do
		loadtest --path "$path" --mu 0 --steps "$steps" --method "$m" -o "$m.$path.pack" dense.pack >"$m.$path.tsv" 2>"$m.$path.err"
		rc=$?
		if [ "$rc" -eq 0 ] && [ ! -s "$m.$path.err" ]; then pass "$path, --method $m: exit 0"; else fail "$path, --method $m: exit 0" "exit $rc: $(head -c 300 "$m.$path.err")"; fi
	done
	rows "newton.$path.tsv" >n.rows
	rows "lbfgs.$path.tsv" >l.rows
	expect_num "$path: newton wrote every row" "$(wc -l <n.rows)" "==" "$((steps + 1))"
	paste n.rows l.rows | awk -F '\t' '
	    { for (a = 6; a <= 8; a++) { d = $a - $(a + 22); if (d < 0) d = -d; r = d / $(a + 22); if (r > worst) worst = r }
	      if ($15 != $(15 + 22)) bad = "row " NR ": coordination " $15 " (newton) vs " $(15 + 22) " (lbfgs)"
	      if (NR > 1 && !($19 <= 1e-4 && $18 > 0)) bad = "row " NR ": newton residual " $19 " after " $18 " iterations" }
	    END { printf "%.3g\n", worst; if (bad) { print bad > "/dev/stderr"; exit 1 } }' >worst 2>why &&
	    pass "$path: newton converged to the residual with lbfgs's contacts" || fail "$path: newton converged to the residual with lbfgs's contacts" "$(cat why)"
	expect_num "$path: newton's wall stresses are lbfgs's to 5e-4" "$(head -n 1 worst)" "<=" 5e-4
	# fewer iterations is the point of the method, not a timing: a count
	n_it=$(rows "newton.$path.tsv" | awk -F '\t' 'NR > 1 { s += $18 } END { print s }')
	l_it=$(rows "lbfgs.$path.tsv" | awk -F '\t' 'NR > 1 { s += $18 } END { print s }')
	expect_num "$path: newton takes fewer iterations than lbfgs" "$n_it" "<" "$l_it"
done

# friction (the return map's consistent tangent): six uniaxial increments of the frictional
# pack, newton against lbfgs from the same start.  The same 5e-4 on the wall stresses
# (measured: 1e-6); a contact whose overlap or trial force lies within the residual's
# slack of a switch may touch (or slide) in one state and not in the other, so the
# coordination may differ by one contact in the 200 grains (0.01) and the sliding ratio by
# three of the 640 contacts (0.005; measured: at most two).
frictionalize -o fr.pack dense.pack 2>/dev/null
for m in lbfgs newton; do
	loadtest --steps 6 --method "$m" -o "$m.fr.pack" fr.pack >"$m.fr.tsv" 2>"$m.fr.err"
	rc=$?
	if [ "$rc" -eq 0 ] && [ ! -s "$m.fr.err" ]; then pass "friction, --method $m: exit 0"; else fail "friction, --method $m: exit 0" "exit $rc: $(head -c 300 "$m.fr.err")"; fi
done
rows newton.fr.tsv >n.rows
rows lbfgs.fr.tsv >l.rows
expect_num "friction: newton wrote every row" "$(wc -l <n.rows)" "==" 7
paste n.rows l.rows | awk -F '\t' '
    { for (a = 6; a <= 8; a++) { d = $a - $(a + 22); if (d < 0) d = -d; r = d / $(a + 22); if (r > worst) worst = r }
      d = $15 - $(15 + 22); if (d < 0) d = -d; if (d > 0.0100001) bad = "row " NR ": coordination " $15 " (newton) vs " $(15 + 22) " (lbfgs)"
      d = $16 - $(16 + 22); if (d < 0) d = -d; if (d > 0.005) bad = "row " NR ": sliding ratio " $16 " (newton) vs " $(16 + 22) " (lbfgs)"
      if (NR > 1 && !($19 <= 1e-4 && $18 > 0)) bad = "row " NR ": newton residual " $19 " after " $18 " iterations" }
    END { printf "%.3g\n", worst; if (bad) { print bad > "/dev/stderr"; exit 1 } }' >worst 2>why &&
    pass "friction: newton converged to the residual with lbfgs's contacts and sliding" || fail "friction: newton converged to the residual with lbfgs's contacts and sliding" "$(cat why)"
expect_num "friction: newton's wall stresses are lbfgs's to 5e-4" "$(head -n 1 worst)" "<=" 5e-4
n_it=$(rows newton.fr.tsv | awk -F '\t' 'NR > 1 { s += $18 } END { print s }')
l_it=$(rows lbfgs.fr.tsv | awk -F '\t' 'NR > 1 { s += $18 } END { print s }')
expect_num "friction: newton takes fewer iterations than lbfgs" "$n_it" "<" "$l_it"

# the paper's sliding rule has no potential, so no Hessian: refused up front, nothing on
# stdout, no -o file
expect_error "loadtest --method newton --rule paper" 1 "^loadtest: newton needs the return map's Hessian" loadtest --steps 2 --method newton --rule paper -o bad.pack fr.pack
if [ -e bad.pack ]; then fail "no -o pack after the refusal" "bad.pack exists"; else pass "no -o pack after the refusal"; fi
expect_error "frictionalize --method newton --rule paper" 1 "^frictionalize: newton needs the return map's Hessian" frictionalize --method newton --rule paper dense.pack
expect_ok "frictionalize --method newton" frictionalize --method newton -o frn.pack dense.pack
