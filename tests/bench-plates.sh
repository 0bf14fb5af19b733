#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# make bench-plates (and make bench): the spheroplate DEM's costs.
#  - packgen --shape spheroplate: wall time, steps to static equilibrium and packing fraction per
#    platyness and size (the packs are kept in bench/plates-N-ETA.pack.gz and reused;
#    BENCH_REGEN=1 remakes them);
#  - the shear the platy paper runs (shear, I = 1e-3, kappa 1e4): the pack is first sheared to
#    gamma BENCH_PRESHEAR (default 0.1, past the start-up; kept as bench/plates-N-ETA-sheared.pack.gz),
#    then sheared on for about BENCH_SHEAR_STEPS steps (default 1000) on 1 and on 2 threads,
#    three rounds alternating: CPU seconds per step per plate on one thread (user + sys, the
#    least of the three; the setup, read from runs of a few steps, taken off), the wall-time
#    speed-up of two threads (least wall times), and whether the tables are the same bytes;
#  - 200 DEM steps of the static pack (build/bench/platestep): CPU per step per plate.
# Knobs: BENCH_PLATE_SIZES (default "8000"), BENCH_PLATE_ETAS (default "0 0.14 0.5 0.8").
# Each run's rows replace that size's and platyness's row in bench/plates.md's table (the other rows stay,
# with their own machine and source); the sections from the first '## ' heading on are kept.
set -u
bin=${1:-build/bin}
case $bin in /*) ;; *) bin=$(pwd)/$bin ;; esac
step="$bin/../bench/platestep"
top=$(cd "$(dirname "$0")/.." && pwd)
out="$top/bench"
mkdir -p "$out"
export LC_ALL=C
sizes=${BENCH_PLATE_SIZES:-"8000"}
etas=${BENCH_PLATE_ETAS:-"0 0.14 0.5 0.8"}
pre=${BENCH_PRESHEAR:-0.1}
nsteps=${BENCH_SHEAR_STEPS:-1000}
src=$("$bin/shear" --version | awk '{print $NF}' | sed 's/+.*//')	# the version, without a commit
machine="$(getconf _NPROCESSORS_ONLN) cores, $(awk -F: '/model name/ {print $2; exit}' /proc/cpuinfo | sed 's/^ *//')"

# the shear's steps per unit strain at I = 1e-3, kappa 1e4 (measured), to pick a strain of
# about nsteps steps
rate() {
	case $1 in 0) echo 4.25e5 ;; 0.14) echo 3.6e5 ;; 0.33) echo 2.6e5 ;; 0.5) echo 1.9e5 ;; *) echo 6.9e4 ;; esac
}

# cpu SECONDS and wall SECONDS of a command (its stdout into $1), from /usr/bin/time
timed() {
	o=$1 t=$2
	shift 2
	/usr/bin/time -f '%U %S %e' -o "$t" "$@" >"$o"
}

for n in $sizes; do
	for eta in $etas; do
		base="$out/plates-$n-$eta"
		pk="$base.pack.gz"
		if [ "${BENCH_REGEN:-0}" = 1 ] || [ ! -s "$pk" ] || [ ! -s "$base.gen" ]; then
			if ! OMP_NUM_THREADS=1 /usr/bin/time -f '%e %M' -o "$base.time" "$bin/packgen" --shape spheroplate \
			    --platyness "$eta" -n "$n" --seed 1 -v -o "$pk" 2>"$base.log"; then
				echo "packgen failed: $(tail -n 1 "$base.log")" >"$base.gen"
				continue
			fi
			steps=$(awk '/at rest after/ { for (i = 1; i <= NF; i++) if ($i == "after") print $(i + 1) }' "$base.log")
			read -r secs kib <"$base.time"
			phi=$("$bin/packinfo" "$pk" | awk '$1 == "packing_fraction" { f = $2 } $1 == "porosity" { p = $2 }
			    END { printf "%.4f", f != "" ? f : 1 - p }')
			echo "$secs $kib $steps $phi $src" >"$base.gen"
			rm -f "$base-sheared.pack.gz"
		fi
		grep -q ' ' "$base.gen" && ! grep -q failed "$base.gen" || continue
		# past the start-up
		if [ ! -s "$base-sheared.pack.gz" ]; then
			OMP_NUM_THREADS=1 "$bin/shear" --threads 1 -g "$pre" --every "$pre" -o "$base-sheared.pack.gz" "$pk" \
			    >"$base-preshear.tsv" 2>"$base-preshear.log" || { echo "preshear failed" >"$base.shear"; continue; }
			echo "$pre" >"$base-sheared.gamma"
		fi
		g=$(awk -v r="$(rate "$eta")" -v s="$nsteps" 'BEGIN { printf "%.6f", s / r }')
		g0=$(awk -v r="$(rate "$eta")" 'BEGIN { printf "%.8f", 20 / r }')
		run() {	# THREADS STRAIN NAME (the sheared pack is past the start: no relaxation, which would
			# be most of the setup taken off)
			OMP_NUM_THREADS=$1 timed "$base-$3.tsv" "$base-$3.t" "$bin/shear" --threads "$1" --relax-tol 0 -g "$2" \
			    --every "$2" -o /dev/null "$base-sheared.pack.gz"
		}
		# the machine's own ceiling for two threads: two independent one-thread runs at once
		# (on a shared or virtual machine the second core is rarely a whole one)
		pair() {
			run 1 "$g" pairA-$1 & pa=$!
			run 1 "$g" pairB-$1 || { wait $pa; return 1; }
			wait $pa
		}
		# three rounds, one and two threads alternating; the least time of each (a shared
		# machine only ever adds)
		ok=1
		for rep in 1 2 3; do
			run 1 "$g0" setup1-$rep && run 1 "$g" one-$rep && run 2 "$g0" setup2-$rep && run 2 "$g" two-$rep &&
			    pair $rep || ok=0
		done
		[ $ok = 1 ] || {
			echo "shear failed" >"$base.shear"
			continue
		}
		same=no
		cmp -s "$base-one-1.tsv" "$base-two-1.tsv" && cmp -s "$base-one-1.tsv" "$base-one-3.tsv" && same=yes
		awk -v n="$n" -v same="$same" -v base="$base" '
		    function last(f,   l, s) { while ((getline l < f) > 0) if (l !~ /^#/) { split(l, s, "\t"); st = s[1] } close(f); return st }
		    function tm(f, k,   a) { getline a < f; close(f); split(a, v, " "); return k == "cpu" ? v[1] + v[2] : v[3] }
		    function least(name, k,   r, m, t) { m = -1; for (r = 1; r <= 3; r++) { t = tm(base "-" name "-" r ".t", k); if (m < 0 || t < m) m = t } return m }
		    function pairwall(   r, m, t, u) { m = -1; for (r = 1; r <= 3; r++) { t = tm(base "-pairA-" r ".t", "wall"); u = tm(base "-pairB-" r ".t", "wall"); if (u > t) t = u; if (m < 0 || t < m) m = t } return m }
		    BEGIN {
			ds = last(base "-one-1.tsv") - last(base "-setup1-1.tsv")
			cpu = (least("one", "cpu") - least("setup1", "cpu")) / ds / n * 1e6
			w1 = least("one", "wall") - least("setup1", "wall"); w2 = least("two", "wall") - least("setup2", "wall")
			wp = pairwall() - least("setup1", "wall")	# the work of two runs in this wall time
			printf "%d %.3f %.2f %s %.2f\n", ds, cpu, w1 / w2, same, 2 * w1 / wp
		    }' >"$base.shear"
		OMP_NUM_THREADS=1 "$step" "$pk" 200 >"$base.step" 2>&1 || echo "failed" >"$base.step"
		# the shear's steady state at the snapshot (packing fraction, Z, elements per interaction)
		awk -F '\t' -v pre="$(cat "$base-sheared.gamma" 2>/dev/null || echo "$pre")" '!/^#/ && NF > 16 { phi = $15; z = $16; el = $17 } END { printf "%s %.4f %.2f %.3f\n", pre, phi, z, el }' \
		    "$base-preshear.tsv" >"$base.state"
		{
			read -r secs kib steps phi _ <"$base.gen"
			read -r ds cpu speed same ceiling <"$base.shear"
			read -r spre sphi sz sel <"$base.state"
			st=$(awk -F '\t' '!/^#/ && NF >= 7 { printf "%.3f", $6 }' "$base.step")
			printf '| %d | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n' "$n" "$eta" "$secs" "$steps" \
			    "$phi" "$spre" "$sphi" "$sz" "$sel" "$ds" "$cpu" "$speed" "$ceiling" "$same" "$st" "$src, $machine"
		} >"$base.row"
	done
done
{
	echo "# qusgm benchmarks: spheroplate DEM"
	echo
	echo "packgen --shape spheroplate --seed 1 (P's law and defaults: friction 0.58 between grains during compaction, kappa 1e4, rest at"
	echo "unbalanced force 1e-3), one thread; then shear at I = 1e-3 (sigma_w from the pack, kappa 1e4) past the start-up (to the row's"
	echo "pre-shear gamma, BENCH_PRESHEAR, one thread), then on for about $nsteps steps on one and on two threads (without the start's relaxation, \`--relax-tol 0\`), three rounds alternating, the least times kept.  CPU is user + sys per step per plate on one thread, the setup"
	echo "(reading, gluing, the first list) taken off; the speed-up is the wall time of one thread over two; the machine's ceiling is"
	echo "what two independent one-thread runs at once achieve (twice the one-thread wall time over the pair's; a shared or virtual"
	echo "machine's second core is rarely a whole one); 'same' says whether the two tables are the same bytes.  The static step is 200 undamped steps of packgen's pack (build/bench/platestep)."
	echo "phi, Z and elements per interaction are the shear's at the pre-shear gamma (P's Z: interactions per free grain)."
	echo
	echo "| plates | eta | packgen (s) | steps to rest | packing fraction | pre-shear gamma | shear phi | shear Z | elements per interaction | shear steps | us per step per plate, 1 thread | speed-up, 2 threads | the machine's ceiling | same bytes | static step (us per plate) | source, machine |"
	echo "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | :-: | ---: | --- |"
	for r in $(ls "$out" | sed -n 's/^plates-\([0-9]*\)-\([0-9.]*\)\.row$/\1-\2/p' | sort -t- -k1,1n -k2,2n); do
		cat "$out/plates-$r.row"
	done
} >"$out/plates.md.tmp" && mv "$out/plates.md.tmp" "$out/plates.md.new"
# keep the sections below the current table (the comparisons, the history)
if [ -f "$out/plates.md" ] && grep -q '^## ' "$out/plates.md"; then
	echo >>"$out/plates.md.new"
	sed -n '/^## /,$p' "$out/plates.md" >>"$out/plates.md.new"
fi
mv "$out/plates.md.new" "$out/plates.md" && cat "$out/plates.md"
