#!/bin/sh
# make bench-plates (and make bench): the spheroplate DEM's costs (issue 13).
#  - packgen --shape spheroplate: wall time and steps to static equilibrium, per platyness
#    and size (the packs are kept in bench/plates-N-ETA.pack.gz and reused; BENCH_REGEN=1
#    remakes them);
#  - one DEM step of each pack (build/bench/platestep, 200 steps): time per step per plate
#    and element contacts per second.
# Knobs: BENCH_PLATE_SIZES (default "1000 8000"), BENCH_PLATE_ETAS (default "0 0.5 0.8").
# Results: bench/plates.md, with the machine and the commit.
set -u
export OMP_NUM_THREADS="${BENCH_THREADS:-1}"	# one core's figures unless asked
bin=${1:-build/bin}
case $bin in /*) ;; *) bin=$(pwd)/$bin ;; esac
step="$bin/../bench/platestep"
top=$(cd "$(dirname "$0")/.." && pwd)
out="$top/bench"
mkdir -p "$out"
export LC_ALL=C
sizes=${BENCH_PLATE_SIZES:-"1000 8000"}
etas=${BENCH_PLATE_ETAS:-"0 0.5 0.8"}
for n in $sizes; do
	for eta in $etas; do
		pk="$out/plates-$n-$eta.pack.gz"
		if [ "${BENCH_REGEN:-0}" = 1 ] || [ ! -s "$pk" ] || [ ! -s "$out/plates-$n-$eta.gen" ]; then
			if ! /usr/bin/time -f '%e %M' -o "$out/plates-$n-$eta.time" "$bin/packgen" --shape spheroplate \
			    --platyness "$eta" -n "$n" --seed 1 -v -o "$pk" 2>"$out/plates-$n-$eta.log"; then
				echo "| $n | $eta | failed: $(tail -n 1 "$out/plates-$n-$eta.log") | | | | | | | |" >"$out/plates-$n-$eta.gen"
				continue
			fi
			steps=$(awk '/at rest after/ { for (i = 1; i <= NF; i++) if ($i == "after") print $(i + 1) }' "$out/plates-$n-$eta.log")
			read -r secs kib <"$out/plates-$n-$eta.time"
			# packing_fraction for plates and the plate engine's spheres (porosity for any other pack)
			phi=$("$bin/packinfo" "$pk" | awk '$1 == "packing_fraction" { f = $2 } $1 == "porosity" { p = $2 }
			    END { printf "%.4f", f != "" ? f : 1 - p }')
			echo "$secs $kib $steps $phi $(date -u '+%Y-%m-%d') $(cd "$top" && git rev-parse --short HEAD 2>/dev/null)" >"$out/plates-$n-$eta.gen"
		fi
		"$step" "$pk" 200 >"$out/plates-$n-$eta.step" 2>&1 || echo "failed" >"$out/plates-$n-$eta.step"
	done
done
{
	echo "# qusgm benchmarks: spheroplate DEM"
	echo
	echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
	echo "- commit: $(cd "$top" && git rev-parse --short HEAD 2>/dev/null || echo unknown)"
	echo "- machine: $(getconf _NPROCESSORS_ONLN) cores, $(awk -F: '/model name/ {print $2; exit}' /proc/cpuinfo | sed 's/^ *//'); every program on $OMP_NUM_THREADS thread(s) (BENCH_THREADS)"
	echo
	echo "packgen --shape spheroplate --seed 1 (P's law and defaults: friction 0.58 between grains during compaction, frictionless walls, kappa 1e4,"
	echo "rest at unbalanced force 1e-3); then 200 DEM steps of the static pack without local damping."
	echo
	echo "| plates | eta | packgen wall time (s) | peak memory (MiB) | steps to rest | packing fraction | interactions | element contacts | us per step per plate | element contacts per s |"
	echo "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
	# every pack measured so far, this run's and earlier runs'
	for n in $(ls "$out" | sed -n 's/^plates-\([0-9]*\)-.*\.gen$/\1/p' | sort -nu); do
		for eta in $(ls "$out" | sed -n "s/^plates-$n-\(.*\)\.gen\$/\1/p" | sort -n); do
			g="$out/plates-$n-$eta.gen" s="$out/plates-$n-$eta.step"
			[ -s "$g" ] || continue
			if grep -q '^|' "$g"; then cat "$g"; continue; fi
			read -r secs kib steps phi _ _ <"$g"
			awk -F '\t' -v n="$n" -v e="$eta" -v s="$secs" -v k="$kib" -v st="$steps" -v p="$phi" \
			    '!/^#/ && NF >= 7 { printf "| %d | %s | %.1f | %.1f | %s | %s | %d | %d | %.3f | %.3g |\n", n, e, s, k / 1024, st, p, $3, $4, $6, $7 }' "$s"
		done
	done
} >"$out/plates.md.tmp" && mv "$out/plates.md.tmp" "$out/plates.md" && cat "$out/plates.md"
