# manpages: every tool has a man page that documents every long option its --help prints,
# --help and --version succeed, and the pages render without warnings.
. "$TOP/tests/tools/lib.sh"

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

ntools=0
for t in "$BIN"/*; do
	[ -f "$t" ] && [ -x "$t" ] || continue
	tool=$(basename "$t")
	ntools=$((ntools + 1))
	page="$TOP/share/man/man1/$tool.1"
	expect_ok "$tool-help-exits-0" "$t" --help
	"$t" --help >help.txt 2>/dev/null
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
	if grep -q '^\.Sh EXIT STATUS' "$page" || grep -q '^\.SH "\{0,1\}EXIT STATUS' "$page"; then
		pass "$tool-man-page-exit-status"
	else
		fail "$tool-man-page-exit-status" "no EXIT STATUS section"
	fi
	lint "$tool-man-page-renders-cleanly" "$page"
done
if [ "$ntools" -gt 0 ]; then pass "tools-found ($ntools)"; else fail tools-found "no tools in $BIN"; fi

page5="$TOP/share/man/man5/qusgm-pack.5"
if [ -f "$page5" ]; then
	pass qusgm-pack.5-exists
	lint qusgm-pack.5-renders-cleanly "$page5"
else
	fail qusgm-pack.5-exists "no $page5"
fi
# --help never shows 'nan' as a default (an option not given): it says what the default means
# (issue 19)
for t in densify dissociate frictionalize loadtest moduli packexport packgen packimport packinfo; do
	if "$t" --help 2>&1 | grep -q 'default: nan'; then fail "$t --help: no [default: nan]" "$("$t" --help | grep 'default: nan' | head -n 1)"; else pass "$t --help: no [default: nan]"; fi
done
if loadtest --help | grep -q -- '--to-stress PA .*\[default: none\]$'; then pass "loadtest --help: --to-stress [default: none]"; else fail "loadtest --help: --to-stress [default: none]" "$(loadtest --help | grep -- --to-stress)"; fi
# make install PREFIX=...: the tools, their pages and the docs land under PREFIX (it stopped
# at a share/presets that does not exist; issue 19).  Against the tools under test: B is
# their build directory, which is up to date, so nothing is rebuilt.
if make -s -C "$TOP" install B="$(dirname "$BIN")" PREFIX="$PWD/inst" >inst.log 2>&1 &&
	[ -x inst/bin/packgen ] && [ -f inst/share/man/man1/packinfo.1 ] && [ -f inst/share/qusgm/doc/pack-format.md ]; then
	pass "make install PREFIX=..."
else
	fail "make install PREFIX=..." "$(tail -n 1 inst.log)"
fi
