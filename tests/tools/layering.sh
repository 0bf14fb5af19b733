# SPDX-License-Identifier: GPL-3.0-or-later
# layering: lib/'s include graph keeps its layers (tests/layers.sh, share/doc/library.md).
# The checker runs on the tree, then on copies with one fault added on purpose (a forbidden
# include, a circle, an include without its layer), each of which it must reject.
. "$TOP/tests/tools/lib.sh"

if sh "$TOP/tests/layers.sh" "$TOP" >layers.out 2>&1; then
	pass "the include graph of lib/ and tools/ keeps the layers"
else
	fail "the include graph of lib/ and tools/ keeps the layers" "$(head -c 600 layers.out)"
fi

# rejected NAME REGEX FILE LINE [FILE LINE]: a fresh copy of lib/ and tools/ with each LINE
# appended to its FILE must fail the checker with a report matching REGEX.
rejected() {
	n=$1 re=$2
	shift 2
	rm -rf copy && mkdir -p copy && cp -R "$TOP/lib" "$TOP/tools" copy/
	while [ $# -ge 2 ]; do
		printf '%s\n' "$2" >>"copy/$1"
		shift 2
	done
	if sh "$TOP/tests/layers.sh" copy >bad.out 2>&1; then
		fail "$n" "the checker accepted it"
	elif grep -Eq -- "$re" bad.out; then
		pass "$n"
	else
		fail "$n" "$(head -c 300 bad.out)"
	fi
	rm -rf copy
}

rejected "a contact file including qs/functional.h is rejected" \
	'lib/contact/cell.c: layer contact must not include qs/functional.h' \
	lib/contact/cell.c '#include "qs/functional.h"'
rejected "qs including dem is rejected" 'layer qs must not include dem/dem.h' \
	lib/qs/densify.c '#include "dem/dem.h"'
rejected "an include circle inside a layer is rejected" 'include circle' \
	lib/base/msg.c '#include "base/numfmt.h"' lib/base/numfmt.c '#include "base/msg.h"'
rejected "an include without its layer is rejected" 'is not a lib header named by its layer' \
	tools/moduli.c '#include "msg.h"'
