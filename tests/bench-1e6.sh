#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# tests/bench-1e6.sh BIN BENCHBIN: make bench-1e6.  The chain's first stages at a million grains
# (issue 17): packgen, densify to 4 MPa, one frictional uniaxial 1e-4 increment, each timed
# with its peak memory, in BENCH_1E6_DIR (default bench/1e6; at 1e6 about 250 MB: the loose
# and dense packs, densify's checkpoint while it runs).
#
# Hours of work (packgen about 2 h and densify many on two threads), so it goes on where it
# stopped: a stage whose output exists is not run again, and densify runs with --checkpoint,
# so each call of this script continues it from its last stage (--time-limit
# BENCH_1E6_LIMIT seconds, 0 for none: the call then stops with exit status 75, which make
# reports as "Error 75", and the next call goes on; the pack is the uninterrupted run's to
# the byte).  Do not change densify's code between the calls of one run: a checkpoint
# records the options and the input, not the build.  Every densify call is a
# line of runs.txt and a file runK.time ("WALL s PEAK KiB"); the summary adds them up.
#
# Knobs: BENCH_1E6_N (1000000), BENCH_1E6_THREADS (2), BENCH_1E6_LIMIT (0).
set -u
BIN=${1:-build/bin}
BBIN=${2:-build/bench}
case $BIN in /*) ;; *) BIN=$(pwd)/$BIN ;; esac
case $BBIN in /*) ;; *) BBIN=$(pwd)/$BBIN ;; esac
D=${BENCH_1E6_DIR:-bench/1e6}
N=${BENCH_1E6_N:-1000000}
T=${BENCH_1E6_THREADS:-2}
LIMIT=${BENCH_1E6_LIMIT:-0}
mkdir -p "$D" && cd "$D" || exit 1
now() { date -u +%FT%TZ; }
say() { echo "bench-1e6: $*"; }

if [ ! -s loose.pack.gz ]; then
	say "packgen -n $N on $T threads (about 2 h at 1e6)"
	/usr/bin/time -f "%e s %M KiB" -o pg.time "$BIN/packgen" -v --threads "$T" -n "$N" --seed 1 \
	    -o loose.pack.gz 2>pg.err || { say "packgen failed: $(tail -n 1 pg.err)"; exit 1; }
fi
[ -s loose.info ] || "$BIN/packinfo" loose.pack.gz >loose.info || exit 1

if [ ! -s dense.pack.gz ]; then
	k=$(($(ls run*.time 2>/dev/null | wc -l) + 1))
	say "densify, call $k, on $T threads (--time-limit $LIMIT)"
	echo "run $k start $(now) limit $LIMIT threads $T" >>runs.txt
	/usr/bin/time -f "%e s %M KiB" -o "run$k.time" "$BIN/densify" -v --threads "$T" --stress 4e6 \
	    --checkpoint dense.ck.pack.gz --time-limit "$LIMIT" --log dense.tsv -o dense.pack.gz loose.pack.gz 2>>ds.err
	rc=$?
	echo "run $k end $(now) rc $rc" >>runs.txt
	if [ "$rc" -eq 75 ]; then
		say "densify stopped at the time limit after $(tail -n 2 ds.err | grep -o '[a-z]* [0-9]*  sigma_c' | tail -n 1 | cut -d' ' -f1-2); run again to go on"
		exit 75
	fi
	[ "$rc" -eq 0 ] || { say "densify failed: $(tail -n 1 ds.err)"; exit 1; }
	"$BIN/packinfo" dense.pack.gz >dense.info || exit 1
fi

if [ ! -s increment.out ]; then
	say "one frictional uniaxial 1e-4 increment from the dense pack"
	OMP_NUM_THREADS=$T FINCREMENT_CASE=mu /usr/bin/time -f "%e s %M KiB" -o increment.time \
	    "$BBIN/fincrement" dense.pack.gz 1 1e-4 lbfgs >increment.tmp 2>increment.err &&
	    mv increment.tmp increment.out || { say "the increment failed: $(tail -n 1 increment.err)"; exit 1; }
fi

# The summary: every stage's time and memory, densify's iterations per phase from its log.
{
	echo "# bench-1e6 summary ($N grains, $T threads)"
	echo "packgen	$(cat pg.time 2>/dev/null)	$(tail -n 1 pg.err 2>/dev/null)"
	awk '$1 == "porosity" || $1 == "coordination" || $1 == "under4" || $1 == "overlap_max" { printf "loose %s %s\n", $1, $2 }' loose.info
	# (time adds a line "Command exited with non-zero status 75" for a stopped call)
	cat run*.time | awk '/ KiB$/ { s += $1; if ($3 > m) m = $3; k++ } END { printf "densify\t%.1f s in %d calls, peak %d KiB\n", s, k, m }'
	awk -F '\t' 'NR > 1 { it[$1] += $8; n[$1]++; t += $8 }
	    END { for (s in it) printf "densify %s: %d stages, %d iterations\n", s, n[s], it[s]; printf "densify iterations %d\n", t }' dense.tsv
	[ -s dense.info ] && awk '$1 == "porosity" || $1 == "coordination" || $1 == "sigma_c" || $1 == "residual" || $1 == "under4" { printf "dense %s %s\n", $1, $2 }' dense.info
	[ -s increment.out ] && echo "increment	$(cat increment.time)" && cat increment.out
} >summary.txt
cat summary.txt
