#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# make validate: the frictionless compaction of the paper's G5036 glass pack (physics.md §10;
# Holtzman et al. 2009): a pack of 5036 grains densified to 1 MPa, then compacted
# frictionlessly to 2, 5, 10, 20 and 35 MPa, each stage by running densify again on the
# previous stage's pack with a higher --stress (on a dense pack densify only compacts).
# Porosity and mean coordination at each stress are set beside the paper's
# (37.4 -> 35.1 %, 6.24 -> 7.15 over 1 -> 35 MPa).  Results: validate/results.md.
#
# SMALL=1 runs a 1000-grain pack instead (a few minutes); SEED overrides the seed;
# N=GRAINS sets the size outright; RESULTS=FILE writes the report elsewhere.
# The run fails (exit 1) when a check fails; the report is written either way.
set -u
bin=${1:-build/bin}
case $bin in /*) ;; *) bin=$(pwd)/$bin ;; esac
top=$(cd "$(dirname "$0")/.." && pwd)
out="$top/validate"
work="$out/work"
res=${RESULTS:-$out/results.md}
case $res in /*) ;; *) res=$(pwd)/$res ;; esac
export LC_ALL=C
if [ "${SMALL:-0}" = 1 ]; then n=1000; else n=5036; fi
n=${N:-$n}
seed=${SEED:-5036}
stresses="1e6 2e6 5e6 1e7 2e7 3.5e7"
mkdir -p "$work"
rm -f "$work"/*
cd "$work" || exit 1

fails=0
checks=""
nin=0
check() {	# DESCRIPTION CONDITION(awk expression on a, b) A B
	if awk -v a="$3" -v b="$4" "BEGIN { exit !($2) }"; then
		checks="$checks
- PASS: $1"
	else
		checks="$checks
- FAIL: $1"
		fails=$((fails + 1))
	fi
}

# coord PACK: from the contact lines, the mean number of grain-grain contacts per grain and
# the mean coordination (wall contacts counted once) of the grains that touch no wall.
coord() {
	awk '$1 == "grains" && !on { ng = $2 }
	     /^end$/ { on = 1; next }
	     !on { next }
	     NF == 8 { id[++g] = $1; next }
	     NF == 7 {
		if ($2 ~ /^[xyz](lo|hi)$/) { wall[$1] = 1; cnt[$1]++ }
		else { cnt[$1]++; cnt[$2]++; gg++ }
	     }
	     END {
		for (k = 1; k <= g; k++) if (!(id[k] in wall)) { ni++; si += cnt[id[k]] }
		printf "%.4f %.4f %d\n", 2 * gg / ng, ni ? si / ni : 0, ni
	     }' "$1"
}

t0=$(date +%s)
/usr/bin/time -f '%e' -o gen.time "$bin/packgen" -n "$n" --seed "$seed" -o loose.pack 2>gen.err || {
	echo "validate: packgen failed: $(tail -n 1 gen.err)" >&2
	exit 1
}
"$bin/packinfo" loose.pack >loose.info
rows=""
prev=loose.pack
k=0
only_compacts=yes
for s in $stresses; do
	k=$((k + 1))
	pk=s$k.pack
	# --allow-limit: a minimisation that stops at --max-iter is reported as a failed check,
	# and the stages go on so that the report still has numbers
	if ! /usr/bin/time -f '%e %M' -o s$k.time "$bin/densify" --allow-limit --stress "$s" --log s$k.tsv -o "$pk" "$prev" 2>s$k.err; then
		echo "validate: densify --stress $s failed: $(tail -n 1 s$k.err)" >&2
		rows="$rows
| $s | failed: $(tail -n 1 s$k.err | sed 's/|/\\|/g') | | | | | | | | | | | | |"
		fails=$((fails + 1))
		break
	fi
	"$bin/packinfo" "$pk" >s$k.info
	read -r secs kib <s$k.time
	check "$s Pa: no minimisation stopped at --max-iter$(grep -q 'iteration limit' s$k.err && echo ": $(tail -n 1 s$k.err)")" \
	    'a == 0' "$(grep -c 'iteration limit' s$k.err)" 0
	grow=$(grep -c '^grow' s$k.tsv)
	comp=$(grep -c '^compact' s$k.tsv)
	iters=$(awk -F '\t' '!/^#/ { s += $8 } END { print s }' s$k.tsv)
	dres=$(tail -n 1 s$k.tsv | cut -f 9)
	set -- $(coord "$pk")
	zgg=$1 zin=$2 nin=$3
	v() { awk -v k="$1" '$1 == k { print $2 }' s$k.info; }
	por=$(v porosity) z=$(v coordination) sc=$(v sigma_c) resid=$(v residual) u4=$(v under4) rat=$(v rattlers)
	bpor=$(v bulk_porosity) bz=$(v bulk_coordination)
	paper_p="" paper_z=""
	[ "$s" = 1e6 ] && paper_p=37.4 paper_z=6.24
	[ "$s" = 3.5e7 ] && paper_p=35.1 paper_z=7.15
	rows="$rows
$(awk -v s="$s" -v sc="$sc" -v p="$por" -v pp="$paper_p" -v z="$z" -v pz="$paper_z" -v zg="$zgg" -v zi="$zin" -v bp="$bpor" -v bz="$bz" \
	    -v u="$u4" -v r="$rat" -v res="$resid" -v dres="$dres" -v it="$iters" -v g="$grow" -v c="$comp" -v t="$secs" \
	    'BEGIN { printf "| %g | %.4g | %.2f | %.2f | %s | %.3f | %.3f | %s | %.3f | %.3f | %d / %d | %.1e | %.1e | %d (%d grow, %d compact) | %.1f |",
	        s / 1e6, sc / 1e6, 100 * p, 100 * bp, pp == "" ? "" : pp, z, bz, pz == "" ? "" : pz, zg, zi, u, r, res, dres, it, g, c, t }')"
	check "$s Pa: sigma_c within 1 % of the target" 'a / b - 1 <= 0.01 && b / a - 1 <= 0.01' "$sc" "$s"
	check "$s Pa: packinfo residual <= 1e-4" 'a <= 1e-4' "$resid" 0
	check "$s Pa: no grain under 4 contacts, no rattlers" 'a == 0 && b == 0' "$u4" "$rat"
	check "$s Pa: coordination away from the walls >= 6 (isostatic)" 'a >= 6' "$zin" 0
	if [ "$k" -gt 1 ]; then
		[ "$grow" -eq 0 ] || only_compacts="no: $grow growth rounds at $s Pa"
		check "$s Pa: porosity below the previous stage's" 'a < b' "$por" "$ppor"
		check "$s Pa: coordination above the previous stage's" 'a > b' "$z" "$pz_prev"
		check "$s Pa: the reference box is kept" 'a == b' "$(grep -cxF "$(grep '^refbox' "$prev")" "$pk")" 1
	fi
	ppor=$por pz_prev=$z
	[ "$s" = 1e6 ] && por1=$por z1=$z
	prev=$pk
done
check "densify on an already dense pack only compacts ($only_compacts)" 'a == 1' "$([ "$only_compacts" = yes ] && echo 1 || echo 0)" 0
t1=$(date +%s)

{
	echo "# qusgm validation: frictionless compaction of a glass pack ($n grains)"
	echo
	echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
	echo "- commit: $(cd "$top" && git rev-parse --short HEAD 2>/dev/null || echo unknown)"
	echo "- machine: $(nproc) cores, $(awk -F: '/model name/ {print $2; exit}' /proc/cpuinfo | sed 's/^ *//')"
	echo "- pack: \`packgen -n $n --seed $seed\` (glass, radii 0.07-0.13 mm), $(awk '$1 == "grains" { print $2 }' loose.info) grains," \
	    "loose porosity $(awk '$1 == "porosity" { printf "%.2f %%", 100 * $2 }' loose.info)," \
	    "coordination $(awk '$1 == "coordination" { printf "%.3f", $2 }' loose.info); packgen took $(cat gen.time) s"
	echo "- stages: \`densify --stress 1e6\` on the loose pack, then \`densify --stress S\` on the previous stage's pack"
	echo "  (default options: lbfgs, --tol 1e-4, --stress-tol 0.01); total $((t1 - t0)) s"
	echo "- paper: G5036, Holtzman, Silin & Patzek (2009), frictionless: porosity 37.4 -> 35.1 %,"
	echo "  coordination 6.24 -> 7.15 over sigma_c 1 -> 35 MPa (physics.md §10)"
	echo
	echo "| target (MPa) | sigma_c (MPa) | porosity (%) | bulk porosity (%) | paper | coordination | bulk coordination | paper | grain-grain contacts per grain | coordination off the walls | under4 / rattlers | residual (packinfo) | residual (densify) | iterations (stages) | time (s) |"
	echo "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
	echo "$rows" | sed '/^$/d'
	echo
	if [ -n "${por1:-}" ] && [ "$k" -eq 6 ] && [ -n "${ppor:-}" ]; then
		awk -v p1="$por1" -v p2="$ppor" -v z1="$z1" -v z2="$pz_prev" 'BEGIN {
		    printf "From 1 to 35 MPa porosity falls by %.2f points (paper 2.3) and coordination rises by %.3f (paper 0.91).\n\n",
		        100 * (p1 - p2), z2 - z1 }'
	fi
	echo "Coordination is packinfo's: grain and wall contacts per grain, a wall contact counted once."
	echo "Grain-grain contacts per grain leaves the wall contacts out; coordination off the walls is"
	echo "the mean over the grains that touch no wall ($nin of $n at the last stage)."
	echo "The residual is the largest per-grain |F_i| / largest contact force on i: packinfo's from the"
	echo "pack as written, densify's (the log's last row) with that force floored at --tol-floor (1e-3)"
	echo "x the mean contact force, which the target 1e-4 applies to."
	echo "Porosity and coordination are of the whole box; the bulk ones (packinfo's bulk_porosity and"
	echo "bulk_coordination) of the inner box a mean grain diameter off each wall, without the"
	echo "looser wall layers: those are the ones to compare with the paper's bulk values."
	echo
	echo "## Checks"
	echo "$checks" | sed '/^$/d'
	echo
	echo "$fails failed"
	echo
	echo "## densify logs"
	echo
	echo "One row per stage (densify(1), LOG): the equilibria each run went through."
	for f in s*.tsv; do
		[ -f "$f" ] || continue
		echo
		echo "### $(grep '^history densify' "${f%.tsv}.pack" 2>/dev/null | tail -n 1 | sed 's/^history densify [^:]*: //; s/ ;.*//')"
		echo
		echo '```'
		cat "$f"
		echo '```'
	done
} >"$res"
cat "$res"
cd "$top" && rm -rf "$work"
[ "$fails" -eq 0 ]
