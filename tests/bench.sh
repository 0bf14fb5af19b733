#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# make bench: at 2740, 1e4 and 1e5 grains,
#  - packgen: wall time and peak memory of making the loose pack (seed 1, glass);
#  - densify to 4 MPa: wall time, peak memory, iterations (the log's sum), per minimiser;
#  - one isotropic strain increment of 1e-4 from the dense pack, per minimiser
#    (build/bench/increment): iterations, evaluations, time per evaluation per contact;
#  - frictionalize, and uniaxial increments with and without friction (build/bench/fincrement);
#  - the frictional functional's cost per contact per evaluation, term by term, at the state of
#    a uniaxial increment from the frictionalized pack (build/bench/frevaluate);
#  - the rest of the chain from the frictionalized pack: a 1 % uniaxial loadtest, and moduli;
#  - the cost of one evaluation of the functional on the first size's dense pack tiled up to
#    BENCH_TILES (default "1 2 3 4": 2740 to 175360 grains; build/bench/evalscale);
#  - the spheroplate element contacts against libccd's penetration queries on random
#    near-contact pairs at platyness 0.14, 0.5, 0.8 (build/bench/platecontact, ~10 s).
# Results go to bench/results.md (readable tables) with the machine and the commit.
#
# Knobs: BENCH_SIZES (e.g. "2740 10000" for a quicker run; " " only gathers the rows of earlier runs into results.md); BENCH_METHODS (densify's
# minimisers, default "cg fire lbfgs"); BENCH_FRIC_MAX (largest size that is frictionalized,
# default 10000: about an hour at 1e5 grains); BENCH_REGEN=1 remakes the loose packs.  The
# packs are kept in bench/ (loose-N.pack.gz, dense-N-METHOD.pack.gz, the densify logs) so
# that a later run reuses the loose ones: packgen takes about an hour at 1e5 grains.
# Each size's rows are kept too (bench/rows-N.*, with the date and commit of the run that
# made them), and results.md gathers every size measured so far, so that sizes can be run
# separately (BENCH_SIZES=100000 BENCH_METHODS=lbfgs on one core while the others run).
# BENCH_FINC_METHODS (default "all": fincrement's four minimisers; "lbfgs" at 1e5, where cg
# and fire take minutes per increment).
# BENCH_REUSE_DENSE=1 reuses the dense packs and rows of an earlier run (densify skipped).
# BENCH_NOTE: a remark kept with the size's date and commit (what else ran on the machine).
# BENCH_THREADS (default 1): the OpenMP threads of every program, so that the tables stay
# one core's figures unless asked otherwise.
set -u
export OMP_NUM_THREADS="${BENCH_THREADS:-1}"
bin=${1:-build/bin}
case $bin in /*) ;; *) bin=$(pwd)/$bin ;; esac
incr="$bin/../bench/increment"
fincr="$bin/../bench/fincrement"
escale="$bin/../bench/evalscale"
frev="$bin/../bench/frevaluate"
platec="$bin/../bench/platecontact"
top=$(cd "$(dirname "$0")/.." && pwd)
out="$top/bench"
mkdir -p "$out"
res="$out/results.md"
tmp="$out/run.tmp.$$"	# per run: sizes can run side by side
sizes=${BENCH_SIZES:-"2740 10000 100000"}
methods=${BENCH_METHODS:-"cg fire lbfgs"}
export LC_ALL=C

# info FILE KEY [FORMAT]
info() { awk -v k="$2" -v f="${3:-%s}" '$1 == k { printf f, $2 }' "$1"; }

# save N: the rows of size N, for this and later runs' results.md
save() {
	for t in gen dens inc fric finc kern chain; do
		eval "printf '%s\n' \"\$${t}_rows\"" | sed '/^$/d' >"$out/rows-$1.$t"
	done
	echo "$(date -u '+%Y-%m-%d %H:%M UTC'), commit $(cd "$top" && git rev-parse --short HEAD 2>/dev/null || echo unknown)${BENCH_NOTE:+ ($BENCH_NOTE)}" >"$out/rows-$1.stamp"
}

for n in $sizes; do
	gen_rows="" dens_rows="" inc_rows="" fric_rows="" finc_rows="" kern_rows="" chain_rows=""
	loose="$out/loose-$n.pack.gz"
	# packgen: make the loose pack, or reuse the one an earlier run made
	if [ "${BENCH_REGEN:-0}" = 1 ] || [ ! -s "$loose" ] || [ ! -s "$out/loose-$n.time" ]; then
		if ! /usr/bin/time -f '%e %M' -o "$tmp.time" "$bin/packgen" -n "$n" --seed 1 -o "$loose" 2>"$tmp.err"; then
			gen_rows="$gen_rows
| $n | failed: $(tail -n 1 "$tmp.err") | | | | | | |"
			save "$n"
			continue
		fi
		mv "$tmp.time" "$out/loose-$n.time"
		made=now
	else
		made="earlier run"
	fi
	read -r secs kib <"$out/loose-$n.time"
	"$bin/packinfo" "$loose" >"$tmp.info"
	gen_rows="$gen_rows
$(awk -v n="$n" -v s="$secs" -v k="$kib" -v p="$(info "$tmp.info" porosity %.4f)" -v c="$(info "$tmp.info" coordination %.3f)" \
	    -v o="$(info "$tmp.info" overlap_max %.2e)" -v m="$made" \
	    'BEGIN { printf "| %d | %.1f | %.1f | %.2f | %s | %s | %s | %s |", n, s, k / 1024, k / n, p, c, o, m }')"

	for m in $methods; do
		dense="$out/dense-$n-$m.pack.gz"
		log="$out/dense-$n-$m.tsv"
		# BENCH_REUSE_DENSE=1: keep an earlier run's dense pack and its row (densify takes
		# over an hour at 1e5 grains), so that the later stages can be measured alone
		if [ "${BENCH_REUSE_DENSE:-0}" = 1 ] && [ -s "$dense" ] && [ -s "$out/rows-$n.dens" ] &&
		    grep -q "^| $n | $m |" "$out/rows-$n.dens"; then
			dens_rows="$dens_rows
$(grep "^| $n | $m |" "$out/rows-$n.dens")"
			continue
		fi
		if ! /usr/bin/time -f '%e %M' -o "$tmp.time" "$bin/densify" --stress 4e6 --method "$m" --log "$log" \
		    -o "$dense" "$loose" 2>"$tmp.err"; then
			dens_rows="$dens_rows
| $n | $m | failed: $(tail -n 1 "$tmp.err") | | | | | | | | | |"
			continue
		fi
		read -r secs kib <"$tmp.time"
		"$bin/packinfo" "$dense" >"$tmp.info"
		# iterations: the sum over the log's stages; per iteration per contact uses the
		# final contact count (grain-grain plus grain-wall)
		set -- $(awk -F '\t' '!/^#/ { it += $8; st[$1]++ } END { print it + 0, st["grow"] + 0, st["compact"] + 0 }' "$log")
		iters=$1 grow=$2 comp=$3
		nc=$(($(info "$tmp.info" contacts_gg) + $(info "$tmp.info" contacts_gw)))
		dens_rows="$dens_rows
$(awk -v n="$n" -v m="$m" -v s="$secs" -v k="$kib" -v it="$iters" -v g="$grow" -v c="$comp" -v nc="$nc" \
		    -v sc="$(info "$tmp.info" sigma_c)" -v p="$(info "$tmp.info" porosity)" -v z="$(info "$tmp.info" coordination)" \
		    -v r="$(info "$tmp.info" residual)" \
		    'BEGIN { printf "| %d | %s | %.1f | %.1f | %d | %d / %d | %d | %.0f | %.3f | %.4f | %.3f | %.1e |",
		        n, m, s, k / 1024, it, g, c, nc, it ? 1e9 * s / it / nc : 0, sc / 1e6, p, z, r }')"
	done

	# one strain increment from the dense pack of the default minimiser (lbfgs), or of the
	# first method run
	m=$(echo $methods | cut -d ' ' -f 1)
	case " $methods " in *" lbfgs "*) m=lbfgs ;; esac
	dense="$out/dense-$n-$m.pack.gz"
	if [ ! -x "$incr" ]; then
		inc_rows="$inc_rows
| $n | (no $incr: run make bench) | | | | | | | |"
	elif [ -s "$dense" ] && "$incr" "$dense" >"$tmp.inc" 2>"$tmp.err"; then
		inc_rows="$inc_rows
$(awk -F '\t' '!/^#/ { printf "| %d | %s | %d | %d | %d | %.4f | %.1f | %.1f | %s |\n", $2, $1, $3, $4, $5, $6, $4 && $3 ? 1e9 * $6 / $4 / $3 : 0, $7, $8 }' "$tmp.inc")"
	else
		inc_rows="$inc_rows
| $n | failed: $(tail -n 1 "$tmp.err" 2>/dev/null) | | | | | | | |"
	fi

	# frictionalize (mu 0.3) the same dense pack, then uniaxial increments with and without
	# friction from its output
	fric="$out/fric-$n.pack.gz"
	if [ "$n" -gt "${BENCH_FRIC_MAX:-10000}" ]; then
		fric_rows="| $n | skipped (BENCH_FRIC_MAX ${BENCH_FRIC_MAX:-10000}) | | | | | | |"
		finc_rows="| $n | skipped | | | | | | | | |"
		chain_rows="| $n | skipped | | | | | | | | | |"
	elif [ -s "$dense" ] && /usr/bin/time -f '%e %M' -o "$tmp.time" "$bin/frictionalize" --mu 0.3 \
	    --log "$out/fric-$n.tsv" -o "$fric" "$dense" 2>"$tmp.err"; then
		read -r secs kib <"$tmp.time"
		fric_rows="$fric_rows
$(awk -F '\t' -v n="$n" -v s="$secs" -v k="$kib" '!/^#/ && $1 > 0 { it += $18; inc = $1; sr = $16; sc = $12 }
		    END { printf "| %d | %.1f | %.1f | %d | %.1f | %.1f | %.4f | %.3f |", n, s, k / 1024, inc, it / inc, s / inc, sr, sc / 1e6 }' "$out/fric-$n.tsv")"
		for fm in ${BENCH_FINC_METHODS:-all}; do
			[ "$fm" = all ] && fm=""
			if [ -x "$fincr" ] && "$fincr" "$fric" 5 1e-4 $fm >"$tmp.finc" 2>"$tmp.err"; then
				finc_rows="$finc_rows
$(awk -F '\t' '!/^#/ { printf "| %d | %s | %s | %d | %.1f | %.1f | %.4f | %.1f | %.1e | %.4f |\n", $3, $1 == "mu" ? "mu 0.3" : "none", $2, $4, $6, $7, $8, $9, $10, $11 }' "$tmp.finc")"
			else
				finc_rows="$finc_rows
| $n | failed: $(tail -n 1 "$tmp.err" 2>/dev/null) | | | | | | | | |"
			fi
		done
		# the frictional functional's cost per contact per evaluation, term by term
		if [ -x "$frev" ] && "$frev" "$fric" 2 >"$tmp.kern" 2>"$tmp.err"; then
			kern_rows="$kern_rows
$(awk -F '\t' '!/^#/ { printf "| %d | %s | %d | %d | %.0f | %.1f |\n", $2, $1, $3, $4, $5 / 1e3, $6 }' "$tmp.kern")"
		else
			kern_rows="$kern_rows
| $n | failed: $(tail -n 1 "$tmp.err" 2>/dev/null) | | | | |"
		fi
		# the rest of the chain: a 1 % uniaxial test (100 increments of 1e-4, loadtest's
		# defaults) from the frictionalized pack, and moduli's fit of its curve
		curve="$out/chain-$n.tsv"
		if /usr/bin/time -f '%e %M' -o "$tmp.time" "$bin/loadtest" -p uniaxial -n 100 \
		    -o "$out/chain-$n.pack.gz" "$fric" >"$curve" 2>"$tmp.err" &&
		    read -r lsecs lkib <"$tmp.time" &&
		    /usr/bin/time -f '%e %M' -o "$tmp.time" "$bin/moduli" "$curve" >"$tmp.mod" 2>"$tmp.err"; then
			read -r msecs mkib <"$tmp.time"
			chain_rows="$chain_rows
$(awk -F '\t' -v n="$n" -v s="$lsecs" -v k="$lkib" -v ms="$msecs" -v mk="$mkib" -v mod="$tmp.mod" '
			    # columns by name from the # header (units in brackets dropped)
			    function cols(line, a,   f, i, nf) { sub(/^# /, "", line); nf = split(line, f, "\t")
				for (i = 1; i <= nf; i++) { sub(/\[.*/, "", f[i]); a[f[i]] = i } }
			    /^# / && /iterations/ { cols($0, c); next }
			    /^#/ { next }
			    { rows++; if (rows > 1) { it += $c["iterations"]; inc++ }; sc = $c["sigma_c"] }
			    END {
				while ((getline l < mod) > 0) {
					if (l ~ /^# / && l ~ /inc_from/) { cols(l, m); continue }
					if (l ~ /^#/) continue
					split(l, f, "\t"); K = f[m["K"]]; G = f[m["G"]]
				}
				printf "| %d | %.1f | %.1f | %d | %.1f | %.2f | %.3f | %.1f | %.1f | %.2f | %.2f |",
				    n, s, k / 1024, inc, inc ? it / inc : 0, inc ? s / inc : 0, sc / 1e6, ms, mk / 1024, K / 1e9, G / 1e9 }' "$curve")"
		else
			chain_rows="$chain_rows
| $n | failed: $(tail -n 1 "$tmp.err" 2>/dev/null) | | | | | | | | | |"
		fi
	else
		fric_rows="$fric_rows
| $n | failed: $(tail -n 1 "$tmp.err" 2>/dev/null) | | | | | | |"
	fi
	save "$n"
done

# the functional's cost per evaluation against N, on the first size's dense pack tiled (only
# from a first size up to 1e4 grains: 4^3 tiles of 1e5 would be 6.4 million; otherwise the
# rows of an earlier run are kept)
first=$(echo $sizes | cut -d ' ' -f 1)
firstm=$(echo $methods | cut -d ' ' -f 1)
case " $methods " in *" lbfgs "*) firstm=lbfgs ;; esac
if [ -n "$first" ] && [ "$first" -le 10000 ]; then
	if [ -x "$escale" ] && [ -s "$out/dense-$first-$firstm.pack.gz" ] &&
	    "$escale" "$out/dense-$first-$firstm.pack.gz" ${BENCH_TILES:-1 2 3 4} >"$tmp.scale" 2>"$tmp.err"; then
		awk -F '\t' '!/^#/ { printf "| %d | %d | %d | %.4f | %.5f | %.1f |\n", $1, $2, $3, $4, $5, $6 }' "$tmp.scale" >"$out/rows-scale"
	else
		echo "| failed: $(tail -n 1 "$tmp.err" 2>/dev/null) | | | | | |" >"$out/rows-scale"
	fi
	echo "$first" >"$out/rows-scale.size"
fi
first=$(cat "$out/rows-scale.size" 2>/dev/null || echo "$first")

# the spheroplate contacts: independent of the sizes, so run every time
if [ -x "$platec" ] && "$platec" >"$tmp.plate" 2>"$tmp.err"; then
	awk -F '\t' '!/^#/ { printf "| %s | %.2f | %d | %.3f | %s | %s |\n", $1, $2, $3, $4, $5, $6 }' "$tmp.plate" >"$out/rows-plate"
else
	echo "| failed: $(tail -n 1 "$tmp.err" 2>/dev/null) | | | | | |" >"$out/rows-plate"
fi

# every size measured so far, this run's and earlier runs', in order of size
all=$(for f in "$out"/rows-*.stamp; do [ -f "$f" ] && basename "$f" .stamp | sed 's/^rows-//'; done | sort -n)
rows() { for k in $all; do cat "$out/rows-$k.$1" 2>/dev/null; done; }

{
	echo "# qusgm benchmarks"
	echo
	echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
	echo "- commit: $(cd "$top" && git rev-parse --short HEAD 2>/dev/null || echo unknown)"
	echo "- machine: $(getconf _NPROCESSORS_ONLN) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo), $(awk -F: '/model name/ {print $2; exit}' /proc/cpuinfo | sed 's/^ *//')"
	echo "- every program runs on $OMP_NUM_THREADS thread(s) (BENCH_THREADS; OMP_NUM_THREADS)"
	echo "- sizes measured (date and commit of the run that made the rows):"
	for k in $all; do echo "  - $k grains: $(cat "$out/rows-$k.stamp")"; done
	echo
	echo "## packgen (DEM compaction to a loose pack, seed 1, glass)"
	echo
	echo "| grains | wall time (s) | peak memory (MiB) | memory per grain (KiB) | porosity | coordination | largest overlap/R | pack made |"
	echo "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | :--- |"
	rows gen
	echo
	echo "## densify to 4 MPa (from the packgen pack; --tol 1e-4; the default --onset, 1e5 Pa)"
	echo
	echo "Iterations are the sum over the log's stages (growth rounds and compaction steps);"
	echo "time per iteration per contact divides the wall time by them and by the final contacts."
	echo "At 1e6 grains densify takes hours: \`make bench-1e6\` runs it in calls that go on from its"
	echo "checkpoint, and bench/densify-1e6.md says how far it got."
	echo
	echo "| grains | method | wall time (s) | peak memory (MiB) | iterations | stages grow / compact | contacts | ns per iteration per contact | sigma_c (MPa) | porosity | coordination | residual |"
	echo "| ---: | :--- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
	rows dens
	echo
	echo "## one isotropic strain increment of 1e-4 from the dense pack (build/bench/increment)"
	echo
	echo "From densify's lbfgs pack at 4 MPa (the default minimiser's); one sub-increment with the affine guess, minimised to the"
	echo "residual 1e-4 (largest per-grain |F_i| / largest contact force on i); wall time includes"
	echo "the neighbour lists.  An evaluation is one pass of energy and gradient."
	echo
	echo "| grains | method | contacts | iterations | evaluations | wall time (s) | ns per iteration per contact | ns per evaluation per contact | residual |"
	echo "| ---: | :--- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
	rows inc
	echo
	echo "## frictionalize (mu 0.3, uniaxial increments of 1e-4 until the sliding ratio saturates)"
	echo
	echo "| grains | wall time (s) | peak memory (MiB) | increments | iterations per increment | s per increment | sliding ratio | sigma_c at the end (MPa) |"
	echo "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
	rows fric
	echo
	echo "## uniaxial increments of 1e-4 from the frictionalized pack (build/bench/fincrement)"
	echo
	echo "Five increments along z through loadtest's loader, per minimiser, with friction (6N unknowns,"
	echo "the pack's history) and without (3N, mu 0, from the same positions); means per increment,"
	echo "commit of the history and the row's measures included."
	echo
	echo "| grains | friction | method | contacts | iterations | evaluations | s per increment | ns per evaluation per contact | largest residual | sliding ratio |"
	echo "| ---: | :--- | :--- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
	rows finc
	echo
	echo "## one evaluation of the frictional functional, term by term (build/bench/frevaluate)"
	echo
	echo "At the state of one uniaxial 1e-4 increment from the frictionalized pack minimised to the"
	echo "residual 1e-3 (tangential displacements developed, some contacts sliding): the whole"
	echo "functional (Hertz and friction, 6N unknowns) and each term alone, timed for 2 s each on"
	echo "one thread; contacts are the friction term's reference contacts, Hertz's touching ones."
	echo
	echo "| grains | term | contacts | evaluations timed | us per evaluation | ns per evaluation per contact |"
	echo "| ---: | :--- | ---: | ---: | ---: | ---: |"
	rows kern
	echo
	echo "## the rest of the chain: a 1 % uniaxial test and its moduli"
	echo
	echo "loadtest -p uniaxial -n 100 (increments of 1e-4, its defaults) from the frictionalized pack,"
	echo "then moduli on its curve; K and G are the last interval's (1 increment, the lw stress)."
	echo
	echo "| grains | loadtest wall time (s) | peak memory (MiB) | increments | iterations per increment | s per increment | sigma_c at the end (MPa) | moduli wall time (s) | moduli peak memory (MiB) | K (GPa) | G (GPa) |"
	echo "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
	rows chain
	echo
	echo "## one evaluation of the functional against N (build/bench/evalscale)"
	echo
	echo "The dense $first-grain pack tiled M x M x M times in one box; the first evaluation builds"
	echo "the neighbour list, the next ones reuse it (energy, gradient, per-grain largest force)."
	echo "Constant ns per evaluation per contact means a cost linear in N."
	echo
	echo "| copies | grains | contacts | first evaluation (s) | evaluation (s) | ns per evaluation per contact |"
	echo "| ---: | ---: | ---: | ---: | ---: | ---: |"
	cat "$out/rows-scale" 2>/dev/null
	echo
	echo "## spheroplate element contacts against libccd (build/bench/platecontact)"
	echo
	echo "Random pairs of outer radius 1 (SHAPE_R_EDGE) and random orientations whose cores are"
	echo "r_i + r_j - delta apart, delta uniform in [0, 0.02); each method sweeps them for 0.4 s."
	echo "libccd with its default tolerances (1e-4) and with 1e-8; 'depth off' is the fraction of"
	echo "pairs whose depth differs from r_i + r_j - d by more than 10 %."
	echo
	echo "| method | platyness | pairs | us per call | element contacts per interaction | depth off by > 10 % |"
	echo "| :--- | ---: | ---: | ---: | ---: | ---: |"
	cat "$out/rows-plate" 2>/dev/null
} >"$res"
rm -f "$tmp".*
cat "$res"
