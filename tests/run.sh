#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Runs every test against each build directory given (build, build-san) and prints one
# closing line "N passed, N failed".  Unit tests (B/tests/*) and tool tests (tests/tools/*.sh)
# print one PASS/FAIL line per check; a test program that exits nonzero without printing a
# FAIL line (a crash, a sanitizer report) counts as one failure.
#
# The tests of all builds form one queue that TEST_JOBS workers take from (default: the
# cores online; TEST_SERIAL=1 means one).  Each test runs in its own directory under
# tests/out, so they do not see each other.  The queue starts with the tests that took
# longest last time (build/.test-times, written at the end of each run; on a fresh clone the
# tool tests of the last build come first, the sanitizer build's being the slowest), so that
# a long test does not start last and leave one core idle: with the old one-process-per-build
# split the sanitizer build alone took 8 of make check's 9 minutes.  Every test's lines are
# printed afterwards in a fixed order (build, then unit before tool tests), whatever the
# order they ran in, with the wall seconds each took and its CPU seconds (user + system,
# itself and what it ran), and at the end the sum of the CPU seconds.
set -u
top=$(cd "$(dirname "$0")/.." && pwd)
out="$top/tests/out"

# One test: "run.sh --one BUILD unit|tools NAME".  Writes OUT/BUILD/KIND/NAME.{log,err,lines,res}.
if [ "${1:-}" = --one ]; then
	b=$2 kind=$3 n=$4
	bdir="$top/$b"
	w="$out/$b/$kind/$n.d"
	log="$out/$b/$kind/$n.log"
	rm -rf "$w"	# a test starts in an empty directory, on a rerun too
	mkdir -p "$w"
	cd "$w" || exit 1
	t0=$(cut -d' ' -f1 /proc/uptime 2>/dev/null || echo 0)
	if [ "$kind" = unit ]; then
		"$bdir/tests/$n" >"$log" 2>"$log.err"
	else
		env BIN="$bdir/bin" TOP="$top" sh "$top/tests/tools/$n.sh" >"$log" 2>"$log.err"
	fi
	rc=$?
	t1=$(cut -d' ' -f1 /proc/uptime 2>/dev/null || echo 0)
	# the CPU seconds (user + system) of the test and everything it ran: this shell ran
	# nothing else, and its children are waited for.  On a loaded machine the wall seconds
	# grow, the CPU seconds do not: they show where make check's time really goes.
	times >"$log.times"
	cpu=$(awk 'NR == 2 { for (i = 1; i <= 2; i++) { split($i, a, "m"); s += a[1] * 60 + a[2] } print s }' "$log.times")
	name="$b/$kind/$n"
	p=$(grep -c '^PASS ' "$log")
	f=$(grep -c '^FAIL ' "$log")
	{
		if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
			f=1
			echo "FAIL $name: exited with status $rc and no FAIL line; stderr:"
			tail -n 15 "$log.err" | sed 's/^/    /'
		fi
		grep '^FAIL ' "$log" | sed "s|^FAIL |FAIL $name: |"
		if [ "$f" -gt 0 ] && [ -s "$log.err" ]; then
			tail -n 5 "$log.err" | sed 's/^/    stderr: /'
		fi
		# wall seconds per test, so that a slow one shows (make check has a 10-minute budget)
		printf '%-40s %4d passed %4d failed %6.1f s %6.1f s CPU\n' "$name" "$p" "$f" \
			"$(echo "$t0 $t1" | awk '{print $2 - $1}')" "$cpu"
	} >"$out/$b/$kind/$n.lines"
	echo "$p $f $(echo "$t0 $t1" | awk '{print $2 - $1}') $cpu $name" >"$out/$b/$kind/$n.res"
	exit 0
fi

rm -rf "$out"
mkdir -p "$out"
# one OpenMP thread per tool: the queue already keeps every core busy, and two tools of two
# spinning threads each on two cores ran make check a third slower (tests/tools/threads.sh
# asks for its threads with --threads)
OMP_NUM_THREADS=${TEST_OMP_THREADS:-1}
# and the threads of the runs that ask for two (--threads 2, the unit tests' two-thread
# cases) sleep at a barrier instead of spinning: a spinning thread takes the core from the
# other job (the bytes do not depend on it).  The sanitizer build's test_dem took 20-30 s of
# CPU with spinning threads, 5 s with sleeping ones.
OMP_WAIT_POLICY=passive
export OMP_NUM_THREADS OMP_WAIT_POLICY

# The jobs in the fixed order their lines are printed in: "BUILD KIND NAME".
for b in "$@"; do
	bdir="$top/$b"
	if [ ! -d "$bdir" ]; then
		echo "$b missing -"
		continue
	fi
	for t in "$bdir"/tests/*; do
		[ -f "$t" ] && [ -x "$t" ] && echo "$b unit $(basename "$t")"
	done
	for t in "$top"/tests/tools/*.sh; do
		[ -f "$t" ] || continue
		n=$(basename "$t" .sh)
		[ "$n" = lib ] && continue	# the helpers, not a test
		echo "$b tools $n"
	done
done >"$out/jobs"

# getconf, not nproc: GNU nproc answers OMP_NUM_THREADS, which is 1 here (above)
jobs=${TEST_JOBS:-$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)}
[ "${TEST_SERIAL:-0}" = 1 ] && jobs=1
times="$top/build/.test-times"

# The order they run in: longest first by the last run's times; without them, tool tests
# before unit tests and the last build given first.
awk -v times="$times" '
	BEGIN { while ((getline l < times) > 0) { split(l, a, " "); t[a[2]] = a[1] } }
	$2 == "missing" { next }
	$1 != last { last = $1; nb++ }
	{
		name = $1 "/" $2 "/" $3
		w = (name in t) ? t[name] : ($2 == "tools" ? 2000 : 1000) + nb * 100
		printf "%012.3f %s %s %s\n", w, $1, $2, $3
	}' "$out/jobs" | sort -r | cut -d' ' -f2- >"$out/queue"
q0=$(cut -d' ' -f1 /proc/uptime 2>/dev/null || echo 0)
xargs -P "$jobs" -L 1 sh "$top/tests/run.sh" --one <"$out/queue"

passed=0
failed=0
while read -r b kind n; do
	if [ "$kind" = missing ]; then
		echo "FAIL tests/run.sh: no build directory $b"
		failed=$((failed + 1))
		continue
	fi
	if [ ! -f "$out/$b/$kind/$n.res" ]; then
		echo "FAIL $b/$kind/$n: the test did not run to its end"
		failed=$((failed + 1))
		continue
	fi
	cat "$out/$b/$kind/$n.lines"
	read -r p f s c name <"$out/$b/$kind/$n.res"
	passed=$((passed + p))
	failed=$((failed + f))
	echo "$s $name" >>"$out/times"
	echo "$c $name" >>"$out/cpu"
done <"$out/jobs"
# keep the times of builds not run this time (make check-fast runs only build/)
if [ -d "$top/build" ] && [ -f "$out/times" ]; then
	{ [ -f "$times" ] && awk 'NR == FNR { seen[$2] = 1; next } !($2 in seen)' "$out/times" "$times"
	  cat "$out/times"; } >"$times.new" && mv "$times.new" "$times"
fi
# the sums: the CPU seconds of all tests (the measure of their cost, whatever the load) and
# the wall seconds of the queue
[ -f "$out/cpu" ] && awk -v wall="$(awk -v t0="$q0" '{ print $1 - t0 }' /proc/uptime 2>/dev/null)" \
	'{ s += $1 } END { printf "tests: %.0f s CPU in all, %.0f s wall\n", s, wall }' "$out/cpu"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
