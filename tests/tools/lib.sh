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
expect_num() {
	if awk -v a="$2" -v b="$4" "BEGIN { exit !(a $3 b) }"; then
		pass "$1 ($2 $3 $4)"
	else
		fail "$1" "$2 $3 $4 does not hold"
	fi
}

# info_value FILE KEY: the value of KEY in packinfo's key-value output.
info_value() { awk -v k="$2" '$1 == k { print $2 }' "$1"; }
