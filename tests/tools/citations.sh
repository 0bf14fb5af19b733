# SPDX-License-Identifier: GPL-3.0-or-later
# citations: every document, section of physics.md and paper equation that code, tests, man
# pages and documents cite exists in the tree (tests/citations.pl says what is looked for).
# The checker runs on the tree, then on files with citations that exist, which it must accept,
# and with one bad citation of each kind, which it must report.
. "$TOP/tests/tools/lib.sh"

if perl "$TOP/tests/citations.pl" "$TOP" >cit.out 2>&1; then
	pass "every citation in the tree resolves"
else
	fail "every citation in the tree resolves" "$(head -c 800 cit.out)"
fi

# One file citing a citation of every kind that exists, checked against the tree.
cat >good.c <<'EOT'
/* physics.md §2-5, physics.md §8, §13, physics.md section 11, F (6)-(7b), F (13)-(18),
 * S (4)-(5), P eqs. 2-5, P eq. A2, F §3.2, S section 4.2, P §II B, F Fig. 4, F App. A,
 * share/doc/library.md, library.md, "How to add a law" */
EOT
if perl "$TOP/tests/citations.pl" "$TOP" good.c >good.out 2>&1; then
	pass "citations of every kind that exist are accepted"
else
	fail "citations of every kind that exist are accepted" "$(head -c 600 good.out)"
fi

# rejected NAME REGEX LINE: a file holding LINE fails the checker, which names the citation.
rejected() {
	printf '%s\n' "$3" >bad.c
	if perl "$TOP/tests/citations.pl" "$TOP" "$PWD/bad.c" >bad.out 2>&1; then
		fail "rejects $1" "accepted '$3'"
	elif ! grep -Eq "bad\.c:1: .*$2" bad.out; then
		fail "rejects $1" "$(head -c 400 bad.out)"
	else
		pass "rejects $1"
	fi
}
rejected "a missing physics.md section" "physics.md §31" "/* physics.md §30-31 */"
rejected "an equation the index does not list" "F \(19\)" "/* F (18)-(19) */"
rejected "a P equation the index does not list" "P eq. 29" "/* P eqs. 27-29 */"
rejected "an undefined paper key" "paper Q" "/* Q §2.1 */"
rejected "a missing document" "nowhere.md" "/* see share/doc/nowhere.md */"
rejected "a missing bare document" "style.md" "/* style.md 13 */"
rejected "a missing heading" "How to fly" "/* library.md, \"How to fly\" */"
rejected "a path outside the tree" "outside the tree" "/* ../shared/design/physics.md */"
