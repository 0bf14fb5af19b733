# install: make install into a staged DESTDIR installs the library (static and shared, with its
# soname links), its headers under include/qusgm, qusgm.pc and the Python reader; a user's
# program (tests/install/example.c) compiles against the staged install through
# `pkg-config --cflags --libs qusgm`, linked shared and static, and reads a pack and evaluates
# the functional as packinfo measures it; make uninstall leaves no file behind (issue 18).
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
# every header of lib/ is installed, in its layer's folder
missing=
for h in "$TOP"/lib/*/*.h; do
	rel=${h#"$TOP"/lib/}
	[ -f "$inc/$rel" ] || missing="$missing $rel"
done
if [ -z "$missing" ]; then pass "headers in include/qusgm/LAYER/"; else fail "headers in include/qusgm/LAYER/" "missing:$missing"; fi
if [ -f "$stage/usr/local/share/qusgm/python/qusgm.py" ]; then pass "installed share/qusgm/python/qusgm.py"; else fail "installed share/qusgm/python/qusgm.py" missing; fi

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

# each installed header compiles on its own with nothing but the installed -I
bad=
for h in "$inc"/*/*.h; do
	rel=${h#"$inc"/}
	printf '#include "%s"\n' "$rel" >hdr.c
	${CC:-cc} -std=c11 -Wall -Wextra -Werror $cflags $(pkg-config --cflags gsl 2>/dev/null) -fsyntax-only hdr.c 2>hdr.err || bad="$bad $rel"
done
if [ -z "$bad" ]; then pass "every installed header compiles alone"; else fail "every installed header compiles alone" "$bad: $(head -c 300 hdr.err)"; fi

# A user's program, linked against the staged library.
cc_ex() { ${CC:-cc} -std=c11 -Wall -Wextra -Werror -o "$1" "$TOP/tests/install/example.c" $cflags $2 >"$1.err" 2>&1; }
if cc_ex ex_shared "$libs"; then pass "example.c: cc \$(pkg-config --cflags --libs qusgm)"; else fail "example.c: cc \$(pkg-config --cflags --libs qusgm)" "$(head -c 400 ex_shared.err)"; fi
if cc_ex ex_static "$slibs"; then pass "example.c linked with libqusgm.a ($slibs)"; else fail "example.c linked with libqusgm.a" "$(head -c 400 ex_static.err)"; fi
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
if [ "$rc_sh" -eq 0 ] && [ "$rc_st" -eq 0 ]; then pass "example runs, shared and static (.gz)"; else fail "example runs, shared and static (.gz)" "exit $rc_sh $rc_st: $(cat shared.err static.err | head -c 300)"; fi
expect_same "shared and static print the same" shared.txt static.txt
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
	pass "example: a reader error through msg_geterr (file:line)"
else
	fail "example: a reader error through msg_geterr (file:line)" "$(cat bad.err)"
fi

# make uninstall with the same DESTDIR and PREFIX: no file left (the folders may stay)
if make -s -C "$TOP" uninstall B="$B" DESTDIR="$stage" PREFIX=/usr/local >uninst.log 2>&1; then
	pass "make uninstall"
else
	fail "make uninstall" "$(tail -n 3 uninst.log)"
fi
left=$(find "$stage" ! -type d | head -n 5)
if [ -z "$left" ]; then pass "make uninstall leaves no file"; else fail "make uninstall leaves no file" "$(echo "$left" | tr '\n' ' ')"; fi
