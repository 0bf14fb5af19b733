#!/bin/sh
# Runs every test against each build directory given (build, build-san) and prints one
# closing line "N passed, N failed".  Unit tests (B/tests/*) and tool tests (tests/tools/*.sh)
# print one PASS/FAIL line per check; a test program that exits nonzero without printing a
# FAIL line (a crash, a sanitizer report) counts as one failure.
#
# The build directories run at the same time, one process each (the machines this runs on
# have two cores and the tests are sequential within a build); each build's lines are shown
# when it is done, in the order given.  TEST_SERIAL=1 runs them one after the other instead.
set -u
top=$(cd "$(dirname "$0")/.." && pwd)
out="$top/tests/out"
rm -rf "$out"
mkdir -p "$out"
passed=0
failed=0

run_one() {	# name, log, command...
	name=$1 log=$2
	shift 2
	"$@" >"$log" 2>"$log.err"
	rc=$?
	p=$(grep -c '^PASS ' "$log")
	f=$(grep -c '^FAIL ' "$log")
	if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
		f=1
		echo "FAIL $name: exited with status $rc and no FAIL line; stderr:" 
		tail -n 15 "$log.err" | sed 's/^/    /'
	fi
	grep '^FAIL ' "$log" | sed "s|^FAIL |FAIL $name: |"
	if [ "$f" -gt 0 ] && [ -s "$log.err" ]; then
		tail -n 5 "$log.err" | sed 's/^/    stderr: /'
	fi
	printf '%-40s %4d passed %4d failed\n' "$name" "$p" "$f"
	passed=$((passed + p))
	failed=$((failed + f))
}

run_build() {	# build directory name: its lines on stdout, "passed failed" last
	b=$1
	bdir="$top/$b"
	[ -d "$bdir" ] || { echo "FAIL tests/run.sh: no build directory $b"; echo "0 1"; return; }
	for t in "$bdir"/tests/*; do
		[ -x "$t" ] || continue
		n=$(basename "$t")
		mkdir -p "$out/$b/unit/$n.d"
		cd "$out/$b/unit/$n.d" || exit 1
		run_one "$b/unit/$n" "$out/$b/unit/$n.log" "$t"
		cd "$top" || exit 1
	done
	for t in "$top"/tests/tools/*.sh; do
		[ -f "$t" ] || continue
		n=$(basename "$t" .sh)
		[ "$n" = lib ] && continue	# the helpers, not a test
		w="$out/$b/tools/$n.d"
		mkdir -p "$w"
		cd "$w" || exit 1
		run_one "$b/tools/$n" "$out/$b/tools/$n.log" env BIN="$bdir/bin" TOP="$top" sh "$t"
		cd "$top" || exit 1
	done
	echo "$passed $failed"
}

for b in "$@"; do
	if [ "${TEST_SERIAL:-0}" = 1 ]; then
		run_build "$b" >"$out/$b.lines"
		sed '$d' "$out/$b.lines"
	else
		run_build "$b" >"$out/$b.lines" &
	fi
done
wait
passed=0
failed=0
for b in "$@"; do
	[ "${TEST_SERIAL:-0}" = 1 ] || sed '$d' "$out/$b.lines"
	read -r p f <<EOF
$(tail -n 1 "$out/$b.lines")
EOF
	passed=$((passed + p))
	failed=$((failed + f))
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
