#!/bin/sh
# make bench: packgen wall time and peak memory at 2740, 1e4 and 1e5 grains.
# Results go to bench/results.md (a readable table) with the machine and the commit.
# BENCH_SIZES overrides the sizes (e.g. BENCH_SIZES="2740 10000" for a quicker run).
set -u
bin=${1:-build/bin}
top=$(cd "$(dirname "$0")/.." && pwd)
out="$top/bench"
mkdir -p "$out"
res="$out/results.md"
tmp="$out/run.tmp"
sizes=${BENCH_SIZES:-"2740 10000 100000"}
{
	echo "# qusgm benchmarks"
	echo
	echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
	echo "- commit: $(cd "$top" && git rev-parse --short HEAD 2>/dev/null || echo unknown)"
	echo "- machine: $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo), $(awk -F: '/model name/ {print $2; exit}' /proc/cpuinfo | sed 's/^ *//')"
	echo
	echo "## packgen (DEM compaction to a loose pack, seed 1, glass)"
	echo
	echo "| grains | wall time (s) | peak memory (MiB) | memory per grain (KiB) | porosity | coordination | largest overlap/R |"
	echo "| ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
} >"$res"
for n in $sizes; do
	/usr/bin/time -f '%e %M' -o "$tmp.time" "$bin/packgen" -n "$n" --seed 1 -o "$tmp.pack" 2>"$tmp.err" || {
		echo "| $n | failed: $(tail -n 1 "$tmp.err") | | | | | |" >>"$res"
		continue
	}
	read -r secs kib <"$tmp.time"
	"$bin/packinfo" "$tmp.pack" >"$tmp.info"
	por=$(awk '$1 == "porosity" { printf "%.4f", $2 }' "$tmp.info")
	coo=$(awk '$1 == "coordination" { printf "%.3f", $2 }' "$tmp.info")
	ovl=$(awk '$1 == "overlap_max" { printf "%.2e", $2 }' "$tmp.info")
	awk -v n="$n" -v s="$secs" -v k="$kib" -v p="$por" -v c="$coo" -v o="$ovl" \
	    'BEGIN { printf "| %d | %.1f | %.1f | %.2f | %s | %s | %s |\n", n, s, k / 1024, k / n, p, c, o }' >>"$res"
done
rm -f "$tmp".*
cat "$res"
