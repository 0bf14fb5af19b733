# SPDX-License-Identifier: GPL-3.0-or-later
# install: make install into a staged DESTDIR installs the library (static and shared, with its
# soname links), its public headers under include/qusgm (the umbrella qusgm.h and what it
# includes, no other), qusgm.pc and the Python package where the python3 of PREFIX finds it;
# the libraries export the API of lib/qusgm.api alone, each name prefixed qusgm_, and the list
# is what the public headers declare; every installed header compiles alone as C and as C++;
# a user's program (tests/install/example.c), which defines functions named as qusgm's
# internal ones, compiles against the staged install through `pkg-config --cflags --libs
# qusgm` as C (linked shared and static) and as C++, and reads a pack and evaluates the
# functional as packinfo measures it; make uninstall leaves no file behind (issues 18, 46).
. "$TOP/tests/tools/lib.sh"

# the install is the optimised build's: make check builds the shared library there only (its
# second, -fPIC, compile of the library would double the sanitizer build's time)
if [ "${BIN#*build-san}" != "$BIN" ]; then
	echo "SKIP install (left to the optimised build)"
	exit 0
fi
B=$(dirname "$BIN")	# the build under test, up to date: nothing is rebuilt
ver=$(awk '$1 == "VERSION" && $2 == "=" { print $3; exit }' "$TOP/Makefile")	# the release
stage=$PWD/stage
lib=$stage/usr/local/lib
inc=$stage/usr/local/include/qusgm
if make -s -C "$TOP" install B="$B" DESTDIR="$stage" PREFIX=/usr/local >inst.log 2>&1; then
	pass "make install DESTDIR=... PREFIX=/usr/local"
else
	fail "make install DESTDIR=... PREFIX=/usr/local" "$(tail -n 3 inst.log)"
fi
for f in libqusgm.a libqusgm.so.$ver pkgconfig/qusgm.pc; do
	if [ -f "$lib/$f" ]; then pass "installed lib/$f"; else fail "installed lib/$f" "missing"; fi
done
if [ "$(readlink "$lib/libqusgm.so.0")" = libqusgm.so.$ver ] && [ "$(readlink "$lib/libqusgm.so")" = libqusgm.so.0 ]; then
	pass "libqusgm.so -> libqusgm.so.0 -> libqusgm.so.$ver"
else
	fail "libqusgm.so -> libqusgm.so.0 -> libqusgm.so.$ver" "$(ls -l "$lib" | tr '\n' ' ')"
fi
if ! command -v readelf >/dev/null 2>&1; then
	echo "SKIP soname (no readelf)"
elif readelf -d "$lib/libqusgm.so.$ver" | grep -q 'SONAME.*\[libqusgm\.so\.0\]'; then
	pass "soname libqusgm.so.0"
else
	fail "soname libqusgm.so.0" "$(readelf -d "$lib/libqusgm.so.$ver" | grep SONAME)"
fi
# the headers installed are the umbrella lib/qusgm.h and those it includes, in their layers'
# folders, and no other (table.h, fileio.h, loadpath.h... are internal)
want=$(cd "$TOP/lib" && ${CC:-cc} -MM -I. $(pkg-config --cflags gsl 2>/dev/null) qusgm.h | tr ' \\' '\n\n' | grep '\.h$' | sort -u)
have=$(cd "$inc" 2>/dev/null && find . -name '*.h' | sed 's|^\./||' | sort)
if [ -n "$want" ] && [ "$want" = "$have" ]; then
	pass "headers: qusgm.h and what it includes, no other ($(echo "$have" | wc -l))"
else
	fail "headers: qusgm.h and what it includes, no other" "missing: $(echo "$want" | grep -vxF "$have" | tr '\n' ' ') extra: $(echo "$have" | grep -vxF "$want" | tr '\n' ' ')"
fi
for h in base/table.h base/fileio.h qs/loadpath.h base/lanes.h; do
	if [ -e "$inc/$h" ]; then fail "internal $h not installed" "$inc/$h"; else pass "internal $h not installed"; fi
done

# the exported symbols: the API of lib/qusgm.api, prefixed qusgm_, and no other
api=$(sed -e 's/#.*//' -e '/^[[:space:]]*$/d' "$TOP/lib/qusgm.api" | sort)
if command -v nm >/dev/null 2>&1; then
	want=$(echo "$api" | sed 's/^/qusgm_/' | sort)
	dyn=$(nm -D --defined-only "$lib/libqusgm.so.$ver" 2>/dev/null | awk 'NF == 3 && $2 ~ /[A-Z]/ { print $3 }' | sort)
	sta=$(nm -g --defined-only "$lib/libqusgm.a" 2>/dev/null | awk 'NF == 3 { print $3 }' | sort)
	if [ "$dyn" = "$want" ]; then
		pass "libqusgm.so exports the API alone, qusgm_ names ($(echo "$dyn" | wc -l))"
	else
		fail "libqusgm.so exports the API alone, qusgm_ names" "extra: $(echo "$dyn" | grep -vxF "$want" | head -n 5 | tr '\n' ' ') missing: $(echo "$want" | grep -vxF "$dyn" | head -n 5 | tr '\n' ' ')"
	fi
	if [ "$sta" = "$want" ]; then
		pass "libqusgm.a defines the API alone as globals, qusgm_ names"
	else
		fail "libqusgm.a defines the API alone as globals, qusgm_ names" "extra: $(echo "$sta" | grep -vxF "$want" | head -n 5 | tr '\n' ' ') missing: $(echo "$want" | grep -vxF "$sta" | head -n 5 | tr '\n' ' ')"
	fi
	# the list is what the public headers (those qusgm.h includes by name) declare, of the
	# library's own symbols: a function added to a public header joins the API
	own=$(nm -g --defined-only "$B/libqusgm.a" | awk 'NF == 3 { print $3 }' | sort -u)
	decl=$(for h in $(sed -n 's/^#include "\(.*\)"$/\1/p' "$TOP/lib/qusgm.h"); do
		gcc -fpreprocessed -dD -E -P "$TOP/lib/$h" 2>/dev/null | grep -oE '[A-Za-z_][A-Za-z_0-9]*'
	done | sort -u | grep -xF "$own")
	if [ "$decl" = "$api" ]; then
		pass "lib/qusgm.api lists what the public headers declare ($(echo "$api" | wc -l) names)"
	else
		fail "lib/qusgm.api lists what the public headers declare" "not listed: $(echo "$decl" | grep -vxF "$api" | tr '\n' ' ') not declared: $(echo "$api" | grep -vxF "$decl" | tr '\n' ' ')"
	fi
else
	echo "SKIP exported symbols (no nm)"
fi

# the Python package, where the python3 of PREFIX finds it (the Makefile's PYTHON and PYTHONDIR)
py=$(command -v /usr/bin/python3 || command -v python3)
pydir=$("$py" "$TOP/share/python/pythondir.py" /usr/local)
if [ -f "$stage$pydir/qusgm/__init__.py" ] && [ -f "$stage$pydir/qusgm/py.typed" ]; then
	pass "installed the package qusgm in $pydir"
else
	fail "installed the package qusgm in $pydir" "$(find "$stage" -name '__init__.py' | head -n 3)"
fi
if "$py" -c 'import sys; sys.exit(sys.argv[1] not in sys.path)' "$pydir"; then
	pass "$pydir is on $py's sys.path"
else
	fail "$pydir is on $py's sys.path" "$("$py" -c 'import sys; print(sys.path)')"
fi
if grep -q PYTHONPATH inst.log; then fail "PREFIX=/usr/local: no word of PYTHONPATH" "$(grep PYTHONPATH inst.log)"; else pass "PREFIX=/usr/local: no word of PYTHONPATH"; fi
# a PREFIX whose folder that python3 does not search: make install says the PYTHONPATH to set,
# and with it the package imports (it said nothing, issue 59)
opt=/opt/qusgm-test-$$
optpy=$("$py" "$TOP/share/python/pythondir.py" "$opt")
make -s -C "$TOP" install B="$B" DESTDIR="$PWD/stage2" PREFIX="$opt" >inst2.log 2>&1
if "$py" -c 'import sys; sys.exit(sys.argv[1] in sys.path)' "$optpy" && grep -qxF "qusgm: the Python package is in $optpy, where $py does not look: set PYTHONPATH=$optpy (share/doc/library.md)" inst2.log; then
	pass "PREFIX=$opt: make install says to set PYTHONPATH=$optpy"
else
	fail "PREFIX=$opt: make install says to set PYTHONPATH=$optpy" "$(tail -n 2 inst2.log)"
fi
pp=$PWD/stage2$optpy
if [ "$(cd / && PYTHONPATH=$pp "$py" -c 'import qusgm; print(qusgm.__file__)' 2>&1)" = "$pp/qusgm/__init__.py" ]; then
	pass "PREFIX=$opt: with that PYTHONPATH, import qusgm finds the installed package"
else
	fail "PREFIX=$opt: with that PYTHONPATH, import qusgm finds the installed package" "$(cd / && PYTHONPATH=$pp "$py" -c 'import qusgm' 2>&1 | tail -n 1)"
fi
rm -rf stage2

# pkg-config, pointed at the stage: the staged qusgm.pc names /usr/local, so a copy with its
# prefix line moved into the stage (libdir and includedir follow ${prefix}); a
# --define-variable=prefix or PKG_CONFIG_SYSROOT_DIR would move gsl's and ccd's paths too
if command -v pkg-config >/dev/null 2>&1 && [ -f "$lib/pkgconfig/qusgm.pc" ]; then
	mkdir -p pc
	sed "s|^prefix=.*|prefix=$stage/usr/local|" "$lib/pkgconfig/qusgm.pc" >pc/qusgm.pc
	pc() { PKG_CONFIG_PATH=$PWD/pc pkg-config "$@"; }
	if [ "$(pc --modversion qusgm)" = "$ver" ]; then pass "pkg-config --modversion qusgm"; else fail "pkg-config --modversion qusgm" "$(pc --modversion qusgm 2>&1)"; fi
	cflags=$(pc --cflags qusgm) libs=$(pc --libs qusgm)
	case " $cflags $libs " in
	*" -I$inc "*" -L$lib -lqusgm "*) pass "pkg-config --cflags --libs qusgm ($cflags $libs)" ;;
	*) fail "pkg-config --cflags --libs qusgm" "'$cflags $libs'" ;;
	esac
	# the static link: the archive by name (-l:), the private dependencies from --static
	slibs=$(pc --static --libs qusgm | sed 's/-lqusgm\( \|$\)/-l:libqusgm.a /')
else
	echo "SKIP pkg-config checks (no pkg-config)"
	cflags="-I$inc" libs="-L$lib -lqusgm" slibs="-L$lib -l:libqusgm.a -lgsl -lgslcblas -lccd -lz -lm"
fi

# each installed header compiles on its own with nothing but the installed -I, as C and as C++
CXX=${CXX:-c++}
command -v "$CXX" >/dev/null 2>&1 || CXX=
[ -n "$CXX" ] || echo "SKIP C++ (no c++ compiler; Debian: apt-get install g++)"
# and pedantic: C99 and C++17 with -pedantic -Werror (a user's program saw _Noreturn, C11's,
# and the compound literals of lanes.h's SIMD twins, issue 59)
bad= badxx= bad99= badxx17=
for h in "$inc"/qusgm.h "$inc"/*/*.h; do
	rel=${h#"$inc"/}
	printf '#include "%s"\n' "$rel" >hdr.c
	${CC:-cc} -std=c11 -Wall -Wextra -Werror $cflags $(pkg-config --cflags gsl 2>/dev/null) -fsyntax-only hdr.c 2>hdr.err || bad="$bad $rel"
	${CC:-cc} -std=c99 -pedantic -Wall -Wextra -Werror $cflags $(pkg-config --cflags gsl 2>/dev/null) -fsyntax-only hdr.c 2>hdr99.err || bad99="$bad99 $rel"
	[ -z "$CXX" ] || "$CXX" -x c++ -std=c++11 -Wall -Wextra -Werror $cflags $(pkg-config --cflags gsl 2>/dev/null) -fsyntax-only hdr.c 2>hdrxx.err || badxx="$badxx $rel"
	[ -z "$CXX" ] || "$CXX" -x c++ -std=c++17 -pedantic -Wall -Wextra -Werror $cflags $(pkg-config --cflags gsl 2>/dev/null) -fsyntax-only hdr.c 2>hdrxx17.err || badxx17="$badxx17 $rel"
done
if [ -z "$bad" ]; then pass "every installed header compiles alone"; else fail "every installed header compiles alone" "$bad: $(head -c 300 hdr.err)"; fi
if [ -z "$bad99" ]; then pass "every installed header compiles alone as -std=c99 -pedantic -Werror"; else fail "every installed header compiles alone as -std=c99 -pedantic -Werror" "$bad99: $(head -c 300 hdr99.err)"; fi
if [ -n "$CXX" ]; then
	if [ -z "$badxx" ]; then pass "every installed header compiles alone as C++"; else fail "every installed header compiles alone as C++" "$badxx: $(head -c 300 hdrxx.err)"; fi
	if [ -z "$badxx17" ]; then pass "every installed header compiles alone as -std=c++17 -pedantic -Werror"; else fail "every installed header compiles alone as -std=c++17 -pedantic -Werror" "$badxx17: $(head -c 300 hdrxx17.err)"; fi
fi

# A user's program, linked against the staged library.
cc_ex() { ${CC:-cc} -std=c11 -Wall -Wextra -Werror -o "$1" "$TOP/tests/install/example.c" $cflags $2 >"$1.err" 2>&1; }
if cc_ex ex_shared "$libs"; then pass "example.c: cc \$(pkg-config --cflags --libs qusgm)"; else fail "example.c: cc \$(pkg-config --cflags --libs qusgm)" "$(head -c 400 ex_shared.err)"; fi
if cc_ex ex_static "$slibs"; then pass "example.c linked with libqusgm.a ($slibs)"; else fail "example.c linked with libqusgm.a" "$(head -c 400 ex_static.err)"; fi
if [ -n "$CXX" ]; then
	if "$CXX" -x c++ -std=c++11 -Wall -Wextra -Werror -o ex_cxx "$TOP/tests/install/example.c" $cflags $libs >ex_cxx.err 2>&1; then
		pass "example.c as C++: c++ -x c++ \$(pkg-config --cflags --libs qusgm)"
	else
		fail "example.c as C++" "$(head -c 400 ex_cxx.err)"
	fi
fi
if command -v readelf >/dev/null 2>&1; then
	if readelf -d ex_shared | grep -q 'NEEDED.*libqusgm\.so\.0\]'; then pass "ex_shared needs libqusgm.so.0"; else fail "ex_shared needs libqusgm.so.0" "$(readelf -d ex_shared | grep NEEDED | tr '\n' ' ')"; fi
	if readelf -d ex_static | grep -q 'NEEDED.*libqusgm'; then fail "ex_static needs no libqusgm.so" "$(readelf -d ex_static | grep NEEDED | tr '\n' ' ')"; else pass "ex_static needs no libqusgm.so"; fi
fi

small_pack dense
packinfo dense.pack >info.txt 2>/dev/null
gzip -c dense.pack >dense.pack.gz
LD_LIBRARY_PATH=$lib ./ex_shared dense.pack >shared.txt 2>shared.err
rc_sh=$?
./ex_static dense.pack.gz >static.txt 2>static.err
rc_st=$?
if [ "$rc_sh" -eq 0 ] && [ "$rc_st" -eq 0 ]; then pass "example runs, shared and static (.gz), its own table_read path_parse file_is_gz called"; else fail "example runs, shared and static (.gz)" "exit $rc_sh $rc_st: $(cat shared.err static.err | head -c 300)"; fi
expect_same "shared and static print the same" shared.txt static.txt
if [ -n "$CXX" ]; then
	LD_LIBRARY_PATH=$lib ./ex_cxx dense.pack >cxx.txt 2>cxx.err
	if [ $? -eq 0 ]; then pass "the C++ example runs"; else fail "the C++ example runs" "$(head -c 300 cxx.err)"; fi
	expect_same "C++ and C print the same" cxx.txt shared.txt
fi
# the Python package of the stage, imported through PYTHONPATH, reads the pack as packinfo does
n=$(PYTHONPATH=$stage$pydir "$py" -c 'import sys, qusgm; p = qusgm.read_pack(sys.argv[1]); print(qusgm.__file__, len(p.grains))' dense.pack.gz 2>py.err)
if [ "$n" = "$stage$pydir/qusgm/__init__.py $(info_value info.txt grains)" ]; then
	pass "PYTHONPATH=\$DESTDIR$pydir: import qusgm, the installed one, reads the pack"
else
	fail "PYTHONPATH=\$DESTDIR$pydir: import qusgm" "'$n' $(tail -n 1 py.err)"
fi
# grains, porosity and sigma_c come from measure_pack, as packinfo's: the same numbers
for k in grains porosity sigma_c residual; do
	a=$(info_value shared.txt "$k") b=$(info_value info.txt "$k")
	if [ -n "$a" ] && [ "$a" = "$b" ]; then pass "example $k = packinfo's ($a)"; else fail "example $k = packinfo's" "'$a' and '$b'"; fi
done
# qs_residual is packinfo's residual by another sum (the functional's gradient, not the
# measures' contact forces, in another order): equal to rounding, 1e-9 relative
a=$(info_value shared.txt qs_residual) b=$(info_value info.txt residual)
if is_number "$a" && is_number "$b"; then
	expect_num "qs_residual = packinfo's residual to 1e-9" "$(rel "$a" "$b")" '<' 1e-9
else
	fail "qs_residual = packinfo's residual to 1e-9" "'$a' '$b'"
fi
expect_num "energy > 0" "$(info_value shared.txt energy)" '>' 0
# errors come through msg_geterr as file:line
printf 'qusgm-pack 9\n' >bad.pack
./ex_static bad.pack >bad.out 2>bad.err
if [ $? -eq 1 ] && grep -q 'bad.pack:1: pack format version 9 is newer' bad.err && [ ! -s bad.out ]; then
	pass "example: a reader error through qusgm_msg_geterr (file:line)"
else
	fail "example: a reader error through qusgm_msg_geterr (file:line)" "$(cat bad.err)"
fi

# the project's README, NEWS and CITATION.cff beside the other documents, the same bytes
# (issue 59: neither make install nor make deb installed them; the Debian changelog points to
# NEWS)
for f in README.md NEWS CITATION.cff; do
	if cmp -s "$TOP/$f" "$stage/usr/local/share/qusgm/doc/$f"; then
		pass "installed share/qusgm/doc/$f"
	else
		fail "installed share/qusgm/doc/$f" "missing or not $f of the tree"
	fi
done

# make uninstall with the same DESTDIR and PREFIX: no file left (the folders may stay)
if make -s -C "$TOP" uninstall B="$B" DESTDIR="$stage" PREFIX=/usr/local >uninst.log 2>&1; then
	pass "make uninstall"
else
	fail "make uninstall" "$(tail -n 3 uninst.log)"
fi
left=$(find "$stage" ! -type d | head -n 5)
if [ -z "$left" ]; then pass "make uninstall leaves no file"; else fail "make uninstall leaves no file" "$(echo "$left" | tr '\n' ' ')"; fi
