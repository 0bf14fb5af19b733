# SPDX-License-Identifier: GPL-3.0-or-later
# manexamples: the EXAMPLES section of every man page runs as typed.  The commands of a page
# are its literal displays (.Bd -literal ... .Ed) and its one-line literal displays (.Dl) in
# that section, the roff escapes they use decoded (\e, \\, \-, \&, \(dq; any other escape
# fails the page, so that a new one is decoded here rather than typed wrong).  Each page's
# commands run in order as one script in a fresh empty directory, with the tools under test
# first on PATH, under bash with -e and pipefail (a failing tool in the middle of a pipe
# fails the page): one PASS or FAIL line per page.  A page whose displays are packs rather
# than commands (qusgm-pack(5): a block that starts "qusgm-pack ") has each pack read by
# packinfo instead.  Issue 59: 13 of the 62 commands of the pages failed as typed, on inputs
# no example made, and two printed the wrong column without a word.
#
# The examples are small on purpose (200 grains, 100 plates, short tests): the whole test takes
# 37-43 s of CPU in the optimised build (loadtest(1)'s page 8 s, packgen's and shear's 5 s,
# packview's 4 s with Chromium).  It runs in the build named build only: under the sanitizers
# the same commands took 200 s of CPU, a third of make check's budget, to run invocations
# that each tool's own test already runs under them; what this test checks is the pages.
# packview(1)'s screenshot needs Chromium: make check installs it as root (browserdeps);
# without it that page fails and says what to install, as tests/tools/packview.sh does.
. "$TOP/tests/tools/lib.sh"

if [ "$(basename "$(dirname "$BIN")")" != build ]; then
	echo "SKIP manexamples (the build named build runs it: the pages, not the tools, are under test)"
	exit 0
fi

if ! command -v bash >/dev/null 2>&1; then
	fail "bash" "bash not installed: the examples run under bash -e -o pipefail"
	exit 0
fi
here=$(pwd)

# examples PAGE: the commands of PAGE's EXAMPLES section, decoded; exit 3 on an unknown
# escape (its line on stderr)
examples() {
	awk '
	function decode(s,   out, c, i, n) {
		out = ""
		n = length(s)
		for (i = 1; i <= n; i++) {
			c = substr(s, i, 1)
			if (c != "\\") { out = out c; continue }
			if (substr(s, i + 1, 1) == "e" || substr(s, i + 1, 1) == "\\") { out = out "\\"; i++ }
			else if (substr(s, i + 1, 1) == "-") { out = out "-"; i++ }
			else if (substr(s, i + 1, 1) == "&") { i++ }
			else if (substr(s, i + 1, 3) == "(dq") { out = out "\""; i += 3 }
			else { print FILENAME ": unknown escape in an example: " s > "/dev/stderr"; bad = 1; i++ }
		}
		return out
	}
	/^\.Sh / { ex = ($0 == ".Sh EXAMPLES"); lit = 0; next }
	!ex { next }
	/^\.Bd -literal/ { lit = 1; next }
	/^\.Ed/ { if (lit) print "#--"; lit = 0; next }
	lit { print decode($0); next }
	/^\.Dl / { print decode(substr($0, 5)); print "#--"; next }
	END { exit bad ? 3 : 0 }' "$1"
}

# a .Dl line is filled like text: one wider than the 80 columns of a terminal (69 characters
# after its indent of 11) is broken in two where it is shown, and no longer runs as typed
for page in "$TOP"/share/man/man[157]/*.[157]; do
	awk -v p="$(basename "$page")" '/^\.Dl / {
		t = substr($0, 5); gsub(/\\&/, "", t); gsub(/\\\(dq/, "x", t); gsub(/\\[-e\\]/, "x", t)
		if (length(t) > 69) print p ": " substr($0, 5) }' "$page"
done >wide.txt
if [ -s wide.txt ]; then
	fail "no .Dl example wider than 80 columns" "$(head -n 3 wide.txt)"
else
	pass "no .Dl example wider than 80 columns"
fi

npages=0
for page in "$TOP"/share/man/man[157]/*.[157]; do
	name=$(basename "$page")
	examples "$page" >"$name.sh" 2>"$name.err" || { fail "$name: examples read" "$(cat "$name.err")"; continue; }
	[ -s "$name.sh" ] || continue
	npages=$((npages + 1))
	d="$here/$name.d"
	rm -rf "$d"
	mkdir -p "$d"
	if head -n 1 "$name.sh" | grep -q '^qusgm-pack '; then
		# packs: each block (up to its "#--" line) read by packinfo
		awk -v d="$d" '/^#--$/ { close(f); k++; next } { f = d "/block" k ".pack"; print > f }' "$name.sh"
		bad= nb=0
		for b in "$d"/block*.pack; do
			nb=$((nb + 1))
			packinfo "$b" >"$b.info" 2>"$b.err" || bad="$bad $(basename "$b"): $(head -c 200 "$b.err")"
		done
		if [ -z "$bad" ]; then pass "$name: its $nb example packs read"; else fail "$name: its $nb example packs read" "$bad"; fi
		continue
	fi
	sed '/^#--$/d' "$name.sh" >"$d.script"
	nc=$(grep -c '' "$d.script")
	if grep -q '^chromium ' "$d.script" && ! command -v chromium >/dev/null 2>&1; then
		fail "$name: its examples run as typed" "chromium not installed (make check installs it as root: apt-get install chromium)"
		continue
	fi
	# no D-Bus for Chromium to wait for (tests/tools/packview.sh); HOME the page's directory,
	# so that Chromium's profile is its own, not one another test's Chromium holds; a bound
	# on a hung example
	if (cd "$d" && HOME=$d DBUS_SESSION_BUS_ADDRESS=disabled: timeout 300 bash -e -o pipefail "$d.script" >"$d.out" 2>"$d.err"); then
		pass "$name: its examples run as typed ($nc lines)"
	else
		rc=$?
		fail "$name: its examples run as typed" "exit $rc: $(grep -v '^$' "$d.err" | tail -n 3 | head -c 400)"
	fi
done
expect_num "pages with examples" "$npages" '>=' 12
