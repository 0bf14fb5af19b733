#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# make killtest: every tool that writes files is killed with TERM, INT, HUP and KILL at
# moments drawn from a seeded sequence (reproducible: KILLTEST_SEED, KILLTEST_REPS), including
# during the .gz compression of its output (big inputs for packimport and packexport), and
# after each kill:
#   - each target is absent or complete: packinfo reads a pack, a table ends with a complete
#     row, and the bytes are those of an undisturbed run (every tool here is deterministic);
#     a log (densify's, frictionalize's --log) is kept with the rows written so far: the
#     first rows of an undisturbed run's, the elapsed seconds aside;
#   - no temporary file is left (TERM, INT, HUP); for KILL, only the documented
#     .NAME.XXXXXX and .NAME.XXXXXX.z may be left (share/man/man1, CAVEATS), listed as KILL-LEFT.
# Prints PASS/FAIL lines and "N passed, N failed"; exits nonzero on failure.
# Not part of make check: it takes a minute or more and depends on timing.
# usage: sh tests/killtest.sh [BINDIR]   (default build/bin)
set -u
top=$(cd "$(dirname "$0")/.." && pwd)
BIN=$(cd "${1:-$top/build/bin}" && pwd) || exit 2
PATH="$BIN:$PATH"
export LC_ALL=C
seed=${KILLTEST_SEED:-19}
reps=${KILLTEST_REPS:-3}
w="$top/tests/out/killtest"
rm -rf "$w"
mkdir -p "$w/in" "$w/ref"
: >"$w/tally"

# The inputs: a small chain, and a 125000-grain pack (12 MB) whose compression takes time.
cd "$w/in" || exit 2
packgen -q -n 300 --seed 3 -o loose.pack &&
densify -q --stress 4e6 -o dense.pack loose.pack &&
frictionalize -q --max-inc 6 --window 3 --window-overlap 0 --allow-limit -o fr.pack dense.pack &&
loadtest -q --path uniaxial --steps 5 fr.pack >lt.tsv &&
awk 'BEGIN { n = 50; for (i = 0; i < n; i++) for (j = 0; j < n; j++) for (k = 0; k < n; k++)
	printf "%.6e %.6e %.6e 1e-4\n", (i + 0.5) * 2.1e-4, (j + 0.5) * 2.1e-4, (k + 0.5) * 2.1e-4 }' >big.xyzr &&
packimport -q -o big.pack big.xyzr || { echo "FAIL killtest: cannot make the inputs"; echo "0 passed, 1 failed"; exit 1; }
I="$w/in"

# The cases: name | targets (space-separated) | command (run with sh -c in the case directory)
cases="packgen|p.pack.gz|packgen -q -n 300 --seed 3 -o p.pack.gz
densify|d.pack.gz d.tsv|densify -q --stress 4e6 --log d.tsv -o d.pack.gz $I/loose.pack
frictionalize|f.pack.gz f.tsv|frictionalize -q --max-inc 6 --window 3 --window-overlap 0 --allow-limit --log f.tsv -o f.pack.gz $I/dense.pack
loadtest|l.pack.gz|loadtest -q --path uniaxial --steps 5 -o l.pack.gz $I/fr.pack >/dev/null
dissociate|s.pack.gz|dissociate -q --pex 2e5 -o s.pack.gz $I/dense.pack
moduli|m.tsv.gz|moduli -q -o m.tsv.gz $I/lt.tsv
packexport|x.xyzr.gz|packexport -q --xyzr -o x.xyzr.gz $I/big.pack
packimport|i.pack.gz|packimport -q -o i.pack.gz $I/big.xyzr"

# complete FILE REF: FILE is a complete, valid output (same bytes as REF, and readable); a log
# (its last column elapsed[s]: written as the run goes and kept when it is killed) holds the
# first rows of REF's, each complete, the elapsed seconds aside.
complete() {
	if head -n 1 "$1" | grep -q "$(printf '\telapsed\\[s\\]$')"; then
		[ -z "$(tail -c 1 "$1")" ] || { echo "log: last row has no newline"; return 1; }
		n=$(wc -l <"$1")
		awk -F '\t' -v OFS='\t' '{ NF--; print }' "$1" >plain.tmp
		head -n "$n" "$2" | awk -F '\t' -v OFS='\t' '{ NF--; print }' | cmp -s - plain.tmp ||
			{ echo "log: not the first $n lines of an undisturbed run's"; return 1; }
		rm -f plain.tmp
		return 0
	fi
	cmp -s "$1" "$2" || { echo "differs from an undisturbed run"; return 1; }
	case $1 in
	*.pack | *.pack.gz)
		packinfo "$1" >/dev/null 2>&1 || { echo "packinfo cannot read it"; return 1; } ;;
	*)
		if [ "${1%.gz}" != "$1" ]; then gzip -dc "$1"; else cat "$1"; fi >plain.tmp 2>/dev/null ||
			{ echo "does not decompress"; return 1; }
		[ -z "$(tail -c 1 plain.tmp)" ] || { echo "last row has no newline"; return 1; }
		awk '!/^#/ { if (nf && NF != nf) bad = 1; nf = NF } END { exit bad }' plain.tmp ||
			{ echo "rows of unequal length"; return 1; }
		rm -f plain.tmp ;;
	esac
	return 0
}

# References and durations (undisturbed runs).
echo "$cases" | while IFS='|' read -r name targets cmd; do
	mkdir -p "$w/ref/$name" && cd "$w/ref/$name" || exit 2
	t0=$(date +%s.%N)
	sh -c "$cmd" || { echo "FAIL $name: the undisturbed run failed"; echo F >>"$w/tally"; }
	t1=$(date +%s.%N)
	awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f\n", b - a }' >"$w/ref/$name.time"
done

n=0
for sig in TERM INT HUP KILL; do
	r=0
	while [ $r -lt "$reps" ]; do
		r=$((r + 1))
		echo "$cases" | {
		while IFS='|' read -r name targets cmd; do
			n=$((n + 1))
			d="$w/run/$name-$sig-$r"
			mkdir -p "$d" && cd "$d" || exit 2
			dur=$(cat "$w/ref/$name.time")
			# the seeded delay: uniform in [0, 1.1 x the undisturbed run time]
			delay=$(awk -v s="$seed" -v k="$name$sig$r" -v t="$dur" 'BEGIN { h = s; for (i = 1; i <= length(k); i++) h = (h * 31 + index("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789", substr(k, i, 1))) % 1000003; srand(h); printf "%.3f", rand() * 1.1 * t }')
			# a shell starts `cmd &` with INT ignored: env resets the four (GNU coreutils)
			env --default-signal=INT,TERM,HUP sh -c "exec $cmd" 2>err.txt &
			pid=$!
			sleep "$delay"
			kill -"$sig" $pid 2>/dev/null
			wait $pid 2>/dev/null
			rc=$?
			what="$name $sig at ${delay}s (of ${dur}s, exit $rc)"
			bad=""
			for t in $targets; do
				[ -e "$t" ] || continue
				why=$(complete "$t" "$w/ref/$name/$t") || bad="$bad $t: $why;"
			done
			case $rc in
			0 | 129 | 130 | 137 | 143) ;;
			*) bad="$bad exit status $rc ($(head -c 200 err.txt));" ;;
			esac
			left=$(ls -A | grep '^\.' | tr '\n' ' ')
			if [ "$sig" = KILL ] && [ -n "$left" ]; then
				for f in $left; do
					ok=0
					for t in $targets; do
						case $f in
						."$t".??????|."$t".??????.z) ok=1 ;;
						esac
					done
					[ $ok = 1 ] || bad="$bad undocumented leftover $f;"
				done
				echo "KILL-LEFT $name at ${delay}s: $left"
				echo "$left" >>"$w/killleft"
			elif [ -n "$left" ]; then
				bad="$bad temporary files left: $left;"
			fi
			if [ -n "$bad" ]; then
				echo "FAIL $what:$bad"
				echo F >>"$w/tally"
			else
				echo "PASS $what: $(for t in $targets; do [ -e "$t" ] && printf '%s complete ' "$t" || printf '%s absent ' "$t"; done)"
				echo P >>"$w/tally"
			fi
		done
		}
	done
done
if [ -f "$w/killleft" ]; then
	echo "KILL left temporaries (documented) in $(wc -l <"$w/killleft") runs: $(wc -w <"$w/killleft") files, $(tr ' ' '\n' <"$w/killleft" | grep -c '\.z$') of them the compressed .z"
else
	echo "KILL left no temporary"
fi
passed=$(grep -c P "$w/tally")
failed=$(grep -c F "$w/tally")
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
