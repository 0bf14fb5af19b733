# SPDX-License-Identifier: GPL-3.0-or-later
# Helpers for tool tests: source it, then call the checks.  Each check prints one
# "PASS name" or "FAIL name: why" line; tests/run.sh counts them.  $BIN is the directory of
# the tools under test, $TOP the source tree; the test runs in a fresh scratch directory.
: "${BIN:?BIN not set}" "${TOP:?TOP not set}"
PATH="$BIN:$PATH"
export LC_ALL=C

pass() { echo "PASS $1"; }
fail() { echo "FAIL $1: $2"; }

# expect_ok NAME CMD...: the command exits 0.
expect_ok() {
	n=$1
	shift
	if "$@" >ok.out 2>ok.err; then pass "$n"; else fail "$n" "exit $? ($(head -c 300 ok.err))"; fi
}

# expect_error NAME STATUS REGEX CMD...: exits with STATUS, prints nothing on stdout and
# exactly one line on stderr that matches the extended REGEX.
expect_error() {
	n=$1 want=$2 re=$3
	shift 3
	"$@" >err.out 2>err.err
	rc=$?
	lines=$(wc -l <err.err)
	if [ "$rc" -ne "$want" ]; then
		fail "$n" "exit $rc, wanted $want; stderr: $(head -c 300 err.err)"
	elif [ -s err.out ]; then
		fail "$n" "wrote to stdout on error"
	elif [ "$lines" -ne 1 ]; then
		fail "$n" "$lines lines on stderr, wanted 1: $(head -c 300 err.err)"
	elif ! grep -Eq -- "$re" err.err; then
		fail "$n" "stderr '$(cat err.err)' does not match /$re/"
	else
		pass "$n"
	fi
}

# expect_same NAME FILE1 FILE2: byte-identical.
expect_same() {
	if cmp -s "$2" "$3"; then pass "$1"; else fail "$1" "$2 and $3 differ"; fi
}

# expect_num NAME VALUE OP REF: numeric comparison with awk (OP: < <= > >= ==).
# Both sides must be numbers (awk compares an empty or non-numeric side as a string, and
# "" < 5 holds): a missing key fails rather than passes.
expect_num() {
	if ! is_number "$2" || ! is_number "$4"; then
		fail "$1" "not a number: '$2' $3 '$4'"
	elif awk -v a="$2" -v b="$4" "BEGIN { exit !(a $3 b) }"; then
		pass "$1 ($2 $3 $4)"
	else
		fail "$1" "$2 $3 $4 does not hold"
	fi
}

# is_number S: S is a decimal or exponent number (inf and nan are not)
is_number() { printf '%s\n' "$1" | grep -Eq '^[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?$'; }

# info_value FILE KEY: the value of KEY in packinfo's key-value output.
info_value() { awk -v k="$2" '$1 == k { print $2 }' "$1"; }

# rel A B: |A - B| / |B|
rel() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; if (d < 0) d = -d; if (b < 0) b = -b; print d / b }'; }

# rows FILE: the data rows of a table (no '#' lines: neither '##' lines nor the column header)
rows() { grep -v '^#' "$1"; }

# col FILE ROW COL: one value of a table (ROW counts data rows from 1)
col() { rows "$1" | awk -F '\t' -v r="$2" -v c="$3" 'NR == r { print $c }'; }

# small_pack dense|frictional [NAME]: the small pack of the loading tests, in the scratch
# directory: loose.pack (packgen, 200 grains, seed 5), dense.pack (densify --stress 4e6 of it)
# and, for frictional, fr.pack (frictionalize of dense.pack).  With NAME the last step is the
# check NAME (expect_ok); the other steps run with their stderr dropped.
small_pack() {
	sp_kind=$1 sp_name=${2-}
	packgen -n 200 --seed 5 -o loose.pack 2>/dev/null
	if [ "$sp_kind" = dense ]; then
		set -- densify --stress 4e6 -o dense.pack loose.pack
	else
		densify --stress 4e6 -o dense.pack loose.pack 2>/dev/null
		set -- frictionalize -o fr.pack dense.pack
	fi
	if [ -n "$sp_name" ]; then expect_ok "$sp_name" "$@"; else "$@" 2>/dev/null; fi
}

# expect_help_version TOOL OPTION...: the checks "--help" (TOOL --help exits 0, nothing on
# stderr, every OPTION named on stdout) and "--version" (TOOL --version exits 0, nothing on
# stderr, stdout starts with "TOOL ").
expect_help_version() {
	hv_tool=$1
	shift
	"$hv_tool" --help >help.out 2>help.err
	hv_rc=$?
	hv_ok=$([ "$hv_rc" -eq 0 ] && [ ! -s help.err ] && echo yes)
	for hv_opt in "$@"; do
		grep -q -- "$hv_opt" help.out || hv_ok=
	done
	if [ -n "$hv_ok" ]; then pass "--help"; else fail "--help" "exit $hv_rc"; fi
	"$hv_tool" --version >ver.out 2>ver.err
	hv_rc=$?
	if [ "$hv_rc" -eq 0 ] && grep -q "^$hv_tool " ver.out && [ ! -s ver.err ]; then pass "--version"; else fail "--version" "exit $hv_rc: $(cat ver.out)"; fi
}

# expect_refused CHECK OUTPUTS NAME STATUS REGEX CMD...: removes OUTPUTS (a list of files named
# nothing.*, those CMD is told to write), runs expect_error NAME STATUS REGEX CMD..., then the
# check "NAME: CHECK": none of OUTPUTS exists, nor a temporary file .nothing*.
expect_refused() {
	er_check=$1 er_outs=$2 n=$3 st=$4 re=$5
	shift 5
	rm -f $er_outs
	expect_error "$n" "$st" "$re" "$@"
	er_left=
	for er_f in $er_outs; do
		[ -e "$er_f" ] && er_left=yes
	done
	if [ -z "$er_left" ] && ! ls -a | grep -q '^\.nothing'; then pass "$n: $er_check"; else fail "$n: $er_check" "$(ls -a | tr '\n' ' ')"; fi
}

# help_joined CMD...: CMD --help with each option's entry on one line (--help wraps at 80
# columns, an entry's text going on at column 32), for the checks that read an entry.
help_joined() {
	"$@" --help | awk '/^                               [^ ]/ { sub(/^ +/, ""); line = line " " $0; next }
	    { if (NR > 1) print line; line = $0 } END { print line }'
}

# python_with_numpy: $py, Debian's python3 (or $PYTHON), with numpy, and the package of this
# tree on PYTHONPATH; else a FAIL line and status 1 (make check installs python3-numpy as root:
# without it a test fails, never skips)
python_with_numpy() {
	py=${PYTHON:-$(command -v /usr/bin/python3 || command -v python3)}
	if [ -z "$py" ] || ! "$py" -c 'import numpy' 2>/dev/null; then
		fail "a python3 with numpy" "'$py' (make check installs it as root: apt-get install python3-numpy)"
		return 1
	fi
	PYTHONPATH=$TOP/share/python
	export PYTHONPATH
}
