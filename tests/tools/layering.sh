# layering: lib/'s include graph keeps its layers (tests/layers.sh, share/doc/architecture.md).
# The checker runs on the tree, then on copies with one forbidden include and one include
# circle added on purpose, which it must reject.
. "$TOP/tests/tools/lib.sh"

if sh "$TOP/tests/layers.sh" "$TOP" >layers.out 2>&1; then
	pass "the include graph of lib/ and tools/ keeps the layers"
else
	fail "the include graph of lib/ and tools/ keeps the layers" "$(head -c 600 layers.out)"
fi

mkdir -p copy
cp -R "$TOP/lib" "$TOP/tools" copy/
# contact must not include qs
printf '#include "qs/functional.h"\n' >>copy/lib/contact/cell.c
if sh "$TOP/tests/layers.sh" copy >bad.out 2>&1; then
	fail "a contact file including qs/functional.h is rejected" "the checker accepted it"
elif grep -q 'lib/contact/cell.c: layer contact must not include qs/functional.h' bad.out; then
	pass "a contact file including qs/functional.h is rejected"
else
	fail "a contact file including qs/functional.h is rejected" "$(head -c 300 bad.out)"
fi
rm -rf copy && mkdir -p copy && cp -R "$TOP/lib" "$TOP/tools" copy/
# qs and dem are peers
printf '#include "dem/dem.h"\n' >>copy/lib/qs/densify.c
if sh "$TOP/tests/layers.sh" copy >bad.out 2>&1; then
	fail "qs including dem is rejected" "the checker accepted it"
else
	pass "qs including dem is rejected"
fi
rm -rf copy && mkdir -p copy && cp -R "$TOP/lib" "$TOP/tools" copy/
# a circle inside one layer: two base modules that include each other
printf '#include "base/numfmt.h"\n' >>copy/lib/base/msg.c
printf '#include "base/msg.h"\n' >>copy/lib/base/numfmt.c
if sh "$TOP/tests/layers.sh" copy >bad.out 2>&1; then
	fail "an include circle inside a layer is rejected" "the checker accepted it"
elif grep -q 'include circle' bad.out; then
	pass "an include circle inside a layer is rejected"
else
	fail "an include circle inside a layer is rejected" "$(head -c 300 bad.out)"
fi
rm -rf copy && mkdir -p copy && cp -R "$TOP/lib" "$TOP/tools" copy/
# an include that does not name its layer
printf '#include "msg.h"\n' >>copy/tools/moduli.c
if sh "$TOP/tests/layers.sh" copy >bad.out 2>&1; then
	fail "an include without its layer is rejected" "the checker accepted it"
else
	pass "an include without its layer is rejected"
fi
rm -rf copy
