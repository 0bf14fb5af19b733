# SPDX-License-Identifier: GPL-3.0-or-later
# manpages: every tool has a man page that describes every long option its --help prints (in
# its OPTIONS, or in qusgm-solver(7) where its page points there) and lists no option --help
# does not know, --help and --version succeed, the pages render without warnings, every
# cross-reference names a page of the tree, qusgm-tables(5) is share/doc/tables.md converted,
# and make install installs every section.
. "$TOP/tests/tools/lib.sh"
# The optimised build's: the pages and the tools' --help and --version texts are the same
# from either build (11 s of CPU in the sanitizer build to read them again).  The sanitizer
# build runs each tool's --help once (version.sh runs its --version).
if [ "${BIN#*build-san}" != "$BIN" ]; then
	for t in "$BIN"/*; do
		n=$(basename "$t")
		if "$t" --help >help.out 2>help.err && [ -s help.out ] && [ ! -s help.err ]; then
			pass "$n --help runs under the sanitizers"
		else
			fail "$n --help runs under the sanitizers" "$(head -c 300 help.err)"
		fi
	done
	exit 0
fi

# The checker: groff (all warnings) if present, else mandoc -T lint, else none.
if command -v groff >/dev/null 2>&1; then
	checker=groff
elif command -v mandoc >/dev/null 2>&1; then
	checker=mandoc
else
	checker=none
fi

# render PAGE: the page as plain text (hyphens as '-'), for finding option names.
render() {
	case $checker in
	groff) groff -mandoc -Tascii -P-cbou "$1" 2>/dev/null ;;
	mandoc) mandoc -Tascii "$1" 2>/dev/null | sed 's/.\x08//g' ;;
	*) sed 's/\\-/-/g; s/Fl -/--/g; s/Fl /-/g' "$1" ;;
	esac
}

# lint NAME PAGE: renders with no warning at all.
lint() {
	case $checker in
	groff)
		groff -mandoc -Tutf8 -ww -z "$2" >lint.out 2>&1
		rc=$?
		;;
	mandoc)
		mandoc -T lint -W warning "$2" >lint.out 2>&1
		rc=$?
		;;
	*)
		pass "$1 (no groff or mandoc: rendering not checked)"
		return
		;;
	esac
	if [ "$rc" -eq 0 ] && [ ! -s lint.out ]; then
		pass "$1 (checked with $checker)"
	else
		fail "$1" "$checker: exit $rc: $(head -c 300 lint.out)"
	fi
}

# options PAGE: the long options of PAGE's OPTIONS lists (every '.Sh OPTIONS...' section), one
# line each: the option, 1 if its entry has a description (text before the next entry), and
# 1 if that text points to qusgm-solver(7).  Options on one .It line share its text.
options() {
	awk '
	function flush(   m, a, i) {
		if (names != "") { m = split(names, a, " "); for (i = 1; i <= m; i++) print a[i], body, ref }
		names = ""
	}
	/^\.Sh/ { flush(); ins = ($0 ~ /^\.Sh OPTIONS/); depth = 0; next }
	!ins { next }
	/^\.Bl/ { depth++; if (depth > 1 && names != "") body = 1; next }
	/^\.El/ { if (depth == 1) flush(); depth--; next }
	depth == 1 && /^\.It/ {
		flush(); body = 0; ref = 0
		n = split($0, w, " ")
		for (i = 1; i < n; i++)
			if (w[i] == "Fl" && w[i + 1] ~ /^-[a-zA-Z0-9]/) { t = w[i + 1]; sub(/[,;.]$/, "", t); names = names " -" t }
		next
	}
	names != "" { body = 1; if ($0 ~ /qusgm-solver 7/) ref = 1 }
	END { flush() }' "$1"
}
solver="$TOP/share/man/man7/qusgm-solver.7"
options "$solver" >solver.opts

ntools=0
for t in "$BIN"/*; do
	[ -f "$t" ] && [ -x "$t" ] || continue
	tool=$(basename "$t")
	ntools=$((ntools + 1))
	page="$TOP/share/man/man1/$tool.1"
	expect_ok "$tool-help-exits-0" "$t" --help
	help_joined "$t" >help.txt 2>/dev/null
	# --help fits a terminal of 80 columns
	wide=$("$t" --help 2>/dev/null | awk 'length($0) > 80 { n++ } END { print n + 0 }')
	expect_num "$tool --help: no line over 80 columns" "$wide" == 0
	expect_ok "$tool-version-exits-0" "$t" --version
	if "$t" --version 2>/dev/null | grep -q "^$tool "; then
		pass "$tool-version-names-tool"
	else
		fail "$tool-version-names-tool" "'$("$t" --version 2>&1 | head -c 100)'"
	fi
	if [ ! -f "$page" ]; then
		fail "$tool-man-page" "no $page"
		continue
	fi
	pass "$tool-man-page"
	render "$page" >page.txt
	missing=""
	for opt in $(grep -oE -- '--[a-zA-Z0-9][a-zA-Z0-9-]*' help.txt | sort -u); do
		grep -qF -- "$opt" page.txt || missing="$missing $opt"
	done
	if [ -z "$missing" ]; then
		pass "$tool-man-page-has-every-long-option"
	else
		fail "$tool-man-page-has-every-long-option" "not in $tool.1:$missing"
	fi
	# described: an entry of its own with text, or one that points to qusgm-solver(7), where
	# the option has an entry with text; and no entry for an option --help does not print
	options "$page" >page.opts
	undescribed="" unknown=""
	for opt in $(grep -oE -- '^ +(-[a-zA-Z], )?--[a-zA-Z0-9][a-zA-Z0-9-]*' help.txt | grep -oE -- '--[a-zA-Z0-9-]+' | sort -u); do
		if grep -q -- "^$opt 1 0$" page.opts; then
			:
		elif grep -q -- "^$opt 1 1$" page.opts && grep -q -- "^$opt 1 " solver.opts; then
			:
		else
			undescribed="$undescribed $opt"
		fi
	done
	for opt in $(cut -d' ' -f1 page.opts | sort -u); do
		grep -qE -- "^ +(-[a-zA-Z], )?$opt( |$)" help.txt || unknown="$unknown $opt"
	done
	if [ -z "$undescribed" ]; then
		pass "$tool-man-page-describes-every-option-of-help"
	else
		fail "$tool-man-page-describes-every-option-of-help" "no description in $tool.1's OPTIONS (or qusgm-solver.7):$undescribed"
	fi
	if [ -z "$unknown" ]; then
		pass "$tool-man-page-lists-no-option-help-lacks"
	else
		fail "$tool-man-page-lists-no-option-help-lacks" "in $tool.1's OPTIONS, not in --help:$unknown"
	fi
	# a tool without a minimiser promises no solver detail
	if ! grep -q -- '--method' help.txt && grep -qiE 'solver|minimis' help.txt; then
		fail "$tool --help: no solver words without a solver" "$(grep -iE 'solver|minimis' help.txt | head -n 1)"
	else
		pass "$tool --help: no solver words without a solver"
	fi
	# '-o ... instead of stdout' only where stdout is what -o would replace
	if grep -q -- '-o, --output.*instead of stdout' help.txt && grep -q '^Usage:.*\(loadtest\|shear\)' help.txt; then
		fail "$tool --help: -o says what it writes" "$(grep -- '-o, --output' help.txt)"
	else
		pass "$tool --help: -o says what it writes"
	fi
	# one statement of each default
	if grep -E '\(default[^)]*\).*\[default: ' help.txt >dd.txt; then
		fail "$tool --help: each default said once" "$(head -n 1 dd.txt)"
	else
		pass "$tool --help: each default said once"
	fi
	if grep -q '^\.Sh EXIT STATUS' "$page" || grep -q '^\.SH "\{0,1\}EXIT STATUS' "$page"; then
		pass "$tool-man-page-exit-status"
	else
		fail "$tool-man-page-exit-status" "no EXIT STATUS section"
	fi
	lint "$tool-man-page-renders-cleanly" "$page"
done
if [ "$ntools" -gt 0 ]; then pass "tools-found ($ntools)"; else fail tools-found "no tools in $BIN"; fi

for page in man5/qusgm-pack.5 man5/qusgm-tables.5 man7/qusgm.7 man7/qusgm-solver.7; do
	name=$(basename "$page")
	if [ -f "$TOP/share/man/$page" ]; then
		pass "$name-exists"
		lint "$name-renders-cleanly" "$TOP/share/man/$page"
	else
		fail "$name-exists" "no share/man/$page"
	fi
done
# every option of qusgm-solver(7) is described and is an option of some tool's --help
for t in densify frictionalize loadtest dissociate; do "$t" --help; done >solverhelp.txt 2>/dev/null
bad=""
while read -r opt body ref; do
	[ "$body" = 1 ] && grep -qE -- "^ +$opt( |$)" solverhelp.txt || bad="$bad $opt"
done <solver.opts
if [ -s solver.opts ] && [ -z "$bad" ]; then
	pass "qusgm-solver.7 describes options the tools have ($(wc -l <solver.opts))"
else
	fail "qusgm-solver.7 describes options the tools have" "none read, or undescribed or unknown:$bad"
fi
# qusgm-tables(5) is share/doc/tables.md converted (make man-tables), so the two never disagree
version=$(sed -n 's/^VERSION *= *//p' "$TOP/Makefile")
if perl "$TOP/share/man/md2man.pl" "$version" <"$TOP/share/doc/tables.md" >tables.5 2>md2man.err &&
	cmp -s tables.5 "$TOP/share/man/man5/qusgm-tables.5"; then
	pass "qusgm-tables.5 is share/doc/tables.md converted"
else
	fail "qusgm-tables.5 is share/doc/tables.md converted" "run make man-tables $(head -c 200 md2man.err)"
fi
# every .Xr of every page to a page of qusgm (a tool's, or qusgm-*) names a page of the tree
bad=""
for page in "$TOP"/share/man/man*/*.[0-9]; do
	for ref in $(sed -n 's/^\.Xr \([a-z][a-z0-9-]*\) \([0-9]\).*/\1.\2/p' "$page" | sort -u); do
		case ${ref%.*} in qusgm*) ;; *) [ -x "$BIN/${ref%.*}" ] || continue ;; esac
		[ -f "$TOP/share/man/man${ref##*.}/$ref" ] || bad="$bad $(basename "$page"):$ref"
	done
done
if [ -z "$bad" ]; then pass "every .Xr names a page of the tree"; else fail "every .Xr names a page of the tree" "$bad"; fi
# --help never shows 'nan' as a default (an option not given): it says what the default means
# (issue 19)
for t in densify dissociate frictionalize loadtest moduli packexport packgen packimport packinfo; do
	if "$t" --help 2>&1 | grep -q 'default: nan'; then fail "$t --help: no [default: nan]" "$("$t" --help | grep 'default: nan' | head -n 1)"; else pass "$t --help: no [default: nan]"; fi
done
if loadtest --help | grep -q -- '--to-stress PA .*\[default: none\]$'; then pass "loadtest --help: --to-stress [default: none]"; else fail "loadtest --help: --to-stress [default: none]" "$(loadtest --help | grep -- --to-stress)"; fi
# make install PREFIX=...: the tools, their pages and the docs land under PREFIX (it stopped
# at a share/presets that does not exist; issue 19).  Against the tools under test: B is
# their build directory, which is up to date, so nothing is rebuilt.  The optimised build's
# only, as in install.sh: make install installs the shared library too, which make check
# builds there alone, so in the sanitizer build it compiled the whole library a second time
# (-fPIC), half a minute of CPU, to test a copy that does not depend on the build.
if [ "${BIN#*build-san}" != "$BIN" ]; then
	echo "SKIP make install PREFIX=... (left to the optimised build)"
elif make -s -C "$TOP" install B="$(dirname "$BIN")" PREFIX="$PWD/inst" >inst.log 2>&1 &&
	[ -x inst/bin/packgen ] && [ -f inst/share/man/man1/packinfo.1 ] && [ -f inst/share/qusgm/doc/pack-format.md ] &&
	[ -f inst/share/man/man5/qusgm-tables.5 ] && [ -f inst/share/man/man7/qusgm.7 ] && [ -f inst/share/man/man7/qusgm-solver.7 ] &&
	[ -f inst/share/qusgm/doc/physics.md ]; then
	pass "make install PREFIX=..."
else
	fail "make install PREFIX=..." "$(tail -n 1 inst.log)"
fi
