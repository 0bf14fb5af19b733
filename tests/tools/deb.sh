# SPDX-License-Identifier: GPL-3.0-or-later
# deb: the Debian packaging (debian/) against what make install installs, cheaply (make deb
# builds the packages themselves, minutes, and runs lintian and the packaged tools): the
# changelog's version is the Makefile's, make install with debian/rules' own INSTALL_VARS
# puts every file where exactly one package's debian/*.install takes it and every line of
# those files takes something (dh_install and dh_missing's checks), without calling apt-get;
# the installed studies find the installed tools and plot scripts, and the Python module
# imports from where python3-qusgm puts it.
. "$TOP/tests/tools/lib.sh"

# the install is the optimised build's (as in install.sh: the sanitizer build has no shared library)
if [ "${BIN#*build-san}" != "$BIN" ]; then
	echo "SKIP deb (left to the optimised build)"
	exit 0
fi
B=$(dirname "$BIN")
deb=$TOP/debian
ver=$(awk '$1 == "VERSION" && $2 == "=" { print $3; exit }' "$TOP/Makefile")
cver=$(sed -n '1s/^qusgm (\([^)]*\)).*/\1/p' "$deb/changelog")
if [ "$cver" = "$ver" ]; then pass "debian/changelog version $cver = the Makefile's"; else fail "debian/changelog version = the Makefile's" "'$cver' and '$ver'"; fi
if [ "$(cat "$deb/compat" 2>/dev/null)" = "" ] && grep -q 'debhelper-compat (= 13)' "$deb/control"; then pass "debhelper compat 13"; else fail "debhelper compat 13" "$(grep debhelper "$deb/control")"; fi
if head -n 1 "$deb/copyright" | grep -q '^Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/$' &&
	grep -q '^License: GPL-3+$' "$deb/copyright"; then pass "debian/copyright: DEP-5, GPL-3+"; else fail "debian/copyright: DEP-5, GPL-3+" "$(head -n 3 "$deb/copyright")"; fi

# make install as debian/rules runs it; no apt-get on the way (a stub first on PATH records a call)
triplet=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || echo multiarch-triplet)
vars=$(sed -n 's/^INSTALL_VARS = //p' "$deb/rules" | sed "s/\$(DEB_HOST_MULTIARCH)/$triplet/g")
stage=$PWD/stage
mkdir -p stub
printf '#!/bin/sh\necho "$0 $*" >>%s/apt.calls\nexit 1\n' "$PWD" >stub/apt-get
chmod +x stub/apt-get
# shellcheck disable=SC2086
if [ -n "$vars" ] && PATH=$PWD/stub:$PATH make -s -C "$TOP" install B="$B" DESTDIR="$stage" $vars >inst.log 2>&1; then
	pass "make install DESTDIR=... $vars"
else
	fail "make install DESTDIR=... with debian/rules' INSTALL_VARS" "'$vars': $(tail -n 3 inst.log)"
fi
if [ -e apt.calls ]; then fail "make install calls no apt-get" "$(cat apt.calls)"; else pass "make install calls no apt-get"; fi

# each file (or link) installed, and the packages whose .install lines take it
(cd "$stage" && find . ! -type d | sed 's|^\./||' | sort) >files
: >owners
for f in "$deb"/*.install; do
	p=$(basename "$f" .install)
	while read -r pat; do
		[ -n "$pat" ] || continue
		pat=$(printf '%s\n' "$pat" | sed "s/\${DEB_HOST_MULTIARCH}/$triplet/g")
		n=0
		for m in "$stage"/$pat; do
			[ -e "$m" ] || [ -L "$m" ] || continue
			n=$((n + 1))
			(cd "$stage" && find "${m#"$stage"/}" ! -type d) | sed "s|\$|	$p|" >>owners
		done
		if [ "$n" -gt 0 ]; then pass "$p.install: $pat"; else fail "$p.install: $pat" "matches nothing make install installed"; fi
	done <"$f"
done
# every file in exactly one package
bad=$(awk -F '\t' 'NR == FNR { n[$1]++; who[$1] = who[$1] " " $2; next } n[$1] != 1 { print $1 " (" (n[$1] + 0) ":" who[$1] ")" }' owners files | head -n 5)
if [ -z "$bad" ]; then pass "every installed file in exactly one package ($(wc -l <files) files)"; else fail "every installed file in exactly one package" "$(echo "$bad" | tr '\n' ' ')"; fi
for want in "usr/bin/packgen	qusgm" "usr/lib/$triplet/libqusgm.so.0	libqusgm0" "usr/lib/$triplet/libqusgm.so.$ver	libqusgm0" \
	"usr/lib/$triplet/libqusgm.so	libqusgm-dev" "usr/lib/$triplet/libqusgm.a	libqusgm-dev" "usr/lib/$triplet/pkgconfig/qusgm.pc	libqusgm-dev" \
"usr/share/man/man1/densify.1	qusgm" "usr/share/qusgm/examples/triaxial.sh	qusgm" \
	"usr/share/qusgm/doc/NEWS	qusgm" "usr/share/qusgm/doc/README.md	qusgm" "usr/share/qusgm/doc/CITATION.cff	qusgm" \
	"usr/share/qusgm/pipelines/Makefile	qusgm" "usr/share/qusgm/plot/fig4.gp	qusgm"; do
	if grep -qxF "$want" owners; then pass "package of ${want%	*}: ${want#*	}"; else fail "package of ${want%	*}: ${want#*	}" "$(grep -F "${want%	*}" owners | head -n 2 | tr '\n' ' ')"; fi
done
# the NEWS the changelog's entry points to is in the package qusgm
np=$(sed -n '3s|.*(NEWS, installed as /\(usr/[^)]*\)).*|\1|p' "$deb/changelog")
if [ -n "$np" ] && grep -qxF "$np	qusgm" owners; then pass "debian/changelog's NEWS ($np) in qusgm"; else fail "debian/changelog's NEWS in qusgm" "'$np': $(sed -n 3p "$deb/changelog")"; fi
hdr=$(grep '^usr/include/qusgm/.*\.h	libqusgm-dev$' owners | head -n 1)
if [ -n "$hdr" ]; then pass "libqusgm-dev: the headers (${hdr%	*} ...)"; else fail "libqusgm-dev: the headers in usr/include/qusgm" "$(grep include owners | head -n 3 | tr '\n' ' ')"; fi
py=$(grep '	python3-qusgm$' owners | grep '^usr/lib/python3/dist-packages/qusgm' | head -n 1)
if [ -n "$py" ]; then pass "python3-qusgm: ${py%	*}"; else fail "python3-qusgm: the module in usr/lib/python3/dist-packages" "$(grep python3-qusgm owners | head -n 3 | tr '\n' ' ')"; fi
# Debian's python3, the one python3-qusgm is for
py=$(command -v /usr/bin/python3 || command -v python3)
if ! $py -c 'import numpy' >/dev/null 2>&1; then
	echo "SKIP python3-qusgm import (no numpy for $py)"
elif PYTHONPATH=$stage/usr/lib/python3/dist-packages $py -c 'import qusgm; print(qusgm.__file__)' >py.out 2>py.err &&
	grep -q "^$stage/usr/lib/python3/dist-packages/qusgm" py.out; then
	pass "import qusgm from the staged dist-packages"
else
	fail "import qusgm from the staged dist-packages" "$(cat py.out py.err | head -c 300)"
fi

# the installed studies run the installed tools and find the installed plot scripts (make -n:
# a missing plot script is a missing prerequisite; BIN, which the tests export, unset)
PATH=$stage/usr/bin:$PATH env -u BIN make -n -C "$stage/usr/share/qusgm/pipelines" OUT="$PWD/studies" SMALL=1 fig4 >studies.n 2>studies.err
rc=$?
if [ "$rc" -eq 0 ] && grep -q "^.*$stage/usr/bin/packgen -n 300 " studies.n && grep -q 'gnuplot.*\.\./plot/fig4\.gp' studies.n; then
	pass "installed pipelines: make -n fig4 runs $stage/usr/bin/packgen and plot/fig4.gp"
else
	fail "installed pipelines: make -n fig4" "exit $rc: $(cat studies.err | head -c 300)"
fi
