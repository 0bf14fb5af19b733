# SPDX-License-Identifier: GPL-3.0-or-later
# version: one version everywhere, and the exact source in every tool's --version and in the
# history lines they write.  The Makefile's VERSION is the release; cli.h, the Python reader,
# the man pages, CITATION.cff and NEWS name the same one.  Built from a git checkout, the
# tools name VERSION+DESCRIBE, DESCRIBE being `git describe --always --dirty` of the tree
# they were built from (the Makefile's QUSGM_SOURCE_VERSION, kept in BUILD/source-version);
# outside git the Makefile and cli.c fall back to VERSION alone.  A few seconds.
. "$TOP/tests/tools/lib.sh"

ver=$(awk '$1 == "VERSION" && $2 == "=" { print $3; exit }' "$TOP/Makefile")
if printf '%s\n' "$ver" | grep -Eq '^[0-9]+\.[0-9]+\.[0-9]+$'; then pass "the Makefile's VERSION ($ver)"; else fail "the Makefile's VERSION" "'$ver'"; fi

# --- one release number everywhere ------------------------------------------------------------
same_version() {	# NAME FOUND
	if [ "$2" = "$ver" ]; then pass "$1 says $ver"; else fail "$1 says $ver" "'$2'"; fi
}
same_version "lib/base/cli.h QUSGM_VERSION" "$(sed -n 's/^#define QUSGM_VERSION "\(.*\)"$/\1/p' "$TOP/lib/base/cli.h")"
same_version "share/python/qusgm __version__" "$(sed -n 's/^__version__ = "\(.*\)"$/\1/p' "$TOP/share/python/qusgm/__init__.py")"
same_version "CITATION.cff version" "$(sed -n 's/^version: *//p' "$TOP/CITATION.cff")"
same_version "NEWS's newest version" "$(grep -E '^[0-9]+\.[0-9]+\.[0-9]+' "$TOP/NEWS" | head -n 1)"
bad=
for m in "$TOP"/share/man/man*/*.[0-9]; do
	# mdoc pages (.Os), or a man(7) page made from markdown (.TH's fourth field)
	grep -qx "\.Os qusgm $ver" "$m" || grep -q "^\.TH [^ ]* [0-9] \"[^\"]*\" \"qusgm $ver\"" "$m" ||
		bad="$bad ${m#"$TOP"/}"
done
if [ -z "$bad" ]; then pass "every man page names qusgm $ver (.Os or .TH)"; else fail "every man page names qusgm $ver (.Os or .TH)" "not:$bad"; fi

# --- the source version the tools were built with ----------------------------------------------
build=$(dirname "$BIN")
ingit=
if [ -e "$TOP/.git" ] && command -v git >/dev/null 2>&1 && git -C "$TOP" rev-parse HEAD >/dev/null 2>&1; then ingit=yes; fi
if [ -f "$build/source-version" ]; then
	src=$(cat "$build/source-version")
	pass "the build recorded its source version ($src)"
else
	src=$(packgen --version | sed 's/^packgen (qusgm) //')
	echo "SKIP $build/source-version (tools not built by the Makefile): checking packgen's '$src'"
fi
if [ -n "$ingit" ]; then
	# VERSION+DESCRIBE: DESCRIBE as git describe --always --dirty prints it, naming a commit of
	# this repository (an abbreviated hash, or TAG-N-gHASH once tags exist)
	desc=${src#"$ver"+}
	hash=$(printf '%s\n' "$desc" | sed -E 's/-dirty$//; s/^.*-g([0-9a-f]+)$/\1/')
	if [ "$desc" != "$src" ] && printf '%s\n' "$hash" | grep -Eq '^[0-9a-f]{7,40}$' &&
	    git -C "$TOP" cat-file -e "$hash^{commit}" 2>/dev/null; then
		pass "in a git checkout the source version is $ver+DESCRIBE, DESCRIBE naming a commit here ($desc)"
	else
		fail "in a git checkout the source version is $ver+DESCRIBE, DESCRIBE naming a commit here" "'$src'"
	fi
	# what the Makefile computes now is git describe --always --dirty of the tree now (another
	# commit or edit since the build may differ from $src: that is what the rebuild picks up)
	now=$(env -u QUSGM_SOURCE_VERSION make -s -C "$TOP" version 2>make.err)
	want="$ver+$(git -C "$TOP" describe --always --dirty 2>/dev/null)"
	if [ "$now" = "$want" ]; then pass "make version is VERSION+git describe --always --dirty ($now)"; else fail "make version is VERSION+git describe --always --dirty" "'$now', git: '$want'"; fi
else
	same_version "outside git the source version" "$src"
fi

# --- every tool's --version names it ----------------------------------------------------------
bad=
n=0
for c in "$TOP"/tools/*.c; do
	t=$(basename "$c" .c)
	n=$((n + 1))
	out=$("$t" --version 2>&1)
	[ "$out" = "$t (qusgm) $src" ] || bad="$bad [$t: '$out']"
done
if [ -z "$bad" ]; then pass "--version of all $n tools: 'TOOL (qusgm) $src'"; else fail "--version of every tool names the source" "$bad"; fi

# --- and every history line written ------------------------------------------------------------
hist_check() {	# TOOL PACK: PACK's last history line is TOOL's, naming the source version
	last=$(grep '^history ' "$2" | tail -n 1)
	case "$last" in
	"history $1 $src: $1 "*) pass "$1's history line names $src" ;;
	*) fail "$1's history line names $src" "'$(printf '%s' "$last" | head -c 200)'" ;;
	esac
}
expect_ok "packgen writes a pack" packgen -n 30 --seed 2 -o loose.pack
hist_check packgen loose.pack
expect_ok "densify writes a pack" densify --stress 1e6 -o dense.pack loose.pack
hist_check densify dense.pack
if [ "$(grep -c '^history ' dense.pack)" = 2 ] && grep -q "^history packgen $src: " dense.pack; then
	pass "densify keeps packgen's line before its own"
else
	fail "densify keeps packgen's line before its own" "$(grep '^history ' dense.pack | cut -c1-80 | tr '\n' '|')"
fi
packexport --xyzr dense.pack >d.xyzr 2>/dev/null
expect_ok "packimport writes a pack" packimport -o imp.pack d.xyzr
hist_check packimport imp.pack

# --- outside git: VERSION alone -----------------------------------------------------------------
# The Makefile in a tree without .git (as a tarball unpacks) names VERSION alone ...
mkdir -p tarball
cp "$TOP/Makefile" tarball/
got=$(cd tarball && env -u QUSGM_SOURCE_VERSION make -s version 2>make.err)
same_version "make version outside git" "$got"
# ... and cli.c compiled without the Makefile's define falls back to QUSGM_VERSION
if cc -std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -I"$TOP/lib" -c -o cli.o "$TOP/lib/base/cli.c" 2>cc.err; then
	if strings -a cli.o | grep -qx "$ver"; then
		if strings -a cli.o | grep -q "^$ver+"; then
			fail "cli.c without the define names $ver alone" "a '$ver+' string in cli.o"
		else
			pass "cli.c without the define names $ver alone"
		fi
	else
		fail "cli.c without the define names $ver alone" "no string '$ver' in cli.o"
	fi
else
	fail "cli.c compiles without the Makefile's define" "$(head -c 300 cc.err)"
fi
