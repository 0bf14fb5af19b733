#!/bin/sh
# Runs every test against each build directory given (build, build-san) and prints one
# closing line "N passed, N failed".  Unit tests (B/tests/*) and tool tests (tests/tools/*.sh)
# print one PASS/FAIL line per check; a test program that exits nonzero without printing a
# FAIL line (a crash, a sanitizer report) counts as one failure.
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

for b in "$@"; do
	bdir="$top/$b"
	[ -d "$bdir" ] || { echo "FAIL tests/run.sh: no build directory $b"; failed=$((failed + 1)); continue; }
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
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
