#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# make bench-peers: qusgm against LIGGGHTS (Hertz-Mindlin DEM) on the same oedometric
# increments of 1e-4 from the same frictional G2740-like pack; results in bench/peers.md.
#
#  - the pack: packgen -n 2740 --seed 1 | densify --stress 4e6 | frictionalize --mu 0.3, as
#    make bench makes it, but of one glass (E 70 GPa, nu 0.2, rho 2420 for every grain:
#    LIGGGHTS gives moduli per atom type, and binned moduli would leave a force error of
#    their spread in every contact); kept in bench/peers-work/ and reused;
#  - qusgm: loadtest -p uniaxial -d 1e-4 -n 1, PEERS_INCREMENTS times, each from the pack the
#    last one wrote (a test split into runs repeats one run's rows), one thread;
#  - LIGGGHTS (serial): packexport --lammps-data, six mesh walls at the pack's walls (E 7 TPa,
#    nu 0.495, mu 0.3), pair gran hertz tangential history, mu 0.3; a settle at the start,
#    then per increment the top wall moved by 1e-4 of the height and a settle until the mean
#    unbalanced force over the mean contact force is below a tolerance, once per tolerance of
#    PEERS_LIGGGHTS_TOLS (default "1e-4 1e-6": DEM practice, and 100 times tighter);
#  - after each LIGGGHTS increment its positions and contact forces go back into a copy of the
#    qusgm pack (tests/peers-readback.awk) and packinfo reports the residual in qusgm's
#    definition, with LIGGGHTS's tangential forces as the contacts' Q0;
#  - qusgm again, from LIGGGHTS's settled start (the last tolerance's), so that both load the
#    same state.
#
# Knobs: PEERS_INCREMENTS (default 10), PEERS_LIGGGHTS_TOLS ("1e-4 1e-6"), PEERS_DT_FRACTION
# (time step over the Rayleigh time, 0.1: at 0.2 the pack kept vibrating, the mean
# unbalanced force stuck near 1e-2), PEERS_DAMP_TIME (the viscous damping's m/gamma in Rayleigh
# times, 40), PEERS_MAX_STEPS (settle limit per increment, 400000), PEERS_REGEN=1 remakes the
# pack, LIGGGHTS (the binary, default liggghts).
set -u
export OMP_NUM_THREADS=1 LC_ALL=C
bin=${1:-build/bin}
case $bin in /*) ;; *) bin=$(pwd)/$bin ;; esac
top=$(cd "$(dirname "$0")/.." && pwd)
work="$top/bench/peers-work"
res="$top/bench/peers.md"
K=${PEERS_INCREMENTS:-10}
tols=${PEERS_LIGGGHTS_TOLS:-1e-4 1e-6}
dtf=${PEERS_DT_FRACTION:-0.1}
dampt=${PEERS_DAMP_TIME:-40}
maxst=${PEERS_MAX_STEPS:-400000}
lig=${LIGGGHTS:-liggghts}
mkdir -p "$work"
cd "$work" || exit 1

die() { echo "bench-peers: $*" >&2; exit 1; }
command -v "$lig" >/dev/null 2>&1 || die "no $lig (apt-get install liggghts)"

# --- the pack -----------------------------------------------------------------------------
if [ "${PEERS_REGEN:-0}" = 1 ] || [ ! -s fric.pack ]; then
	printf 'E 70e9\nnu 0.2\nrho 2420\nspread 0\n' >glass-uniform.mat
	"$bin/packgen" -n 2740 --seed 1 --material ./glass-uniform.mat -o loose.pack.gz &&
	    "$bin/densify" --stress 4e6 -o dense.pack.gz loose.pack.gz &&
	    "$bin/frictionalize" --mu 0.3 --log fric.tsv -o fric.pack dense.pack.gz ||
	    die "making the pack failed"
fi
info() { "$bin/packinfo" "$1" | awk -v k="$2" '$1 == k { print $2 }'; }

# --- qusgm: K increments, one run each ----------------------------------------------------
# state PACK: sig_zz, lz, residual and residual_median as packinfo reports them
state() { "$bin/packinfo" "$1" | awk '$1 == "sig_zz" { s = $2 } $1 == "lz" { l = $2 } $1 == "residual" { r = $2 }
	$1 == "residual_median" { m = $2 } END { printf "%s\t%s\t%s\t%s\n", s, l, r, m }'; }
# qchain P START: K increments from START, packs P0.pack .. PK.pack, rows (increment, CPU s,
# iterations, then the state) in P.rows
qchain() {
	cp "$2" "${1}0.pack"
	printf '0\t0\t0\t%s\n' "$(state "${1}0.pack")" >"$1.rows"
	k=1
	while [ "$k" -le "$K" ]; do
		/usr/bin/time -f '%U %S' -o q.time "$bin/loadtest" -p uniaxial -d 1e-4 -n 1 -o "$1$k.pack" \
		    "$1$((k - 1)).pack" >"$1$k.tsv" 2>q.err || die "loadtest: $(tail -n 1 q.err)"
		printf '%d\t%s\t%s\t%s\n' "$k" "$(awk '{ print $1 + $2 }' q.time)" \
		    "$(awk -F '\t' '!/^#/ && $2 != 0 { print $18 }' "$1$k.tsv")" "$(state "$1$k.pack")" >>"$1.rows"
		k=$((k + 1))
	done
}
qchain q fric.pack

# --- LIGGGHTS: the same pack, walls and increments -----------------------------------------
# From the pack: the box, the walls' and the grains' moduli (one E and nu for all, checked),
# the time step (PEERS_DT_FRACTION of the Rayleigh time of the smallest grain, pi r sqrt(rho/G) / (0.1631 nu
# + 0.8766)), the top wall's move per increment (1e-4 of the height) and the viscous damping
# gamma = (mean grain mass) / (PEERS_DAMP_TIME Rayleigh times).
awk '$1 == "box" { print "box", $2, $3, $4, $5, $6, $7 }
     $1 == "walls" { print "walls", $2, $3, $4 }
     $1 == "friction" { print "mu", $2 }
     $1 == "end" { g = 1; next }
     g && n < G { n++; if (n == 1 || $5 < rmin) rmin = $5; E[$6]; nu[$7]; rho = $8; m += 4.18879020478639 * $8 * $5 ^ 3 }
     $1 == "grains" { G = $2 }
     END { ne = nn = 0; for (e in E) { ne++; e0 = e }; for (v in nu) { nn++; v0 = v }
           print "grain", e0, v0, rho, rmin, m / G, ne, nn }' fric.pack >lig.par
set -- $(awk '$1 == "box"' lig.par)
xlo=$2 ylo=$3 zlo=$4 xhi=$5 yhi=$6 zhi=$7
set -- $(awk '$1 == "walls"' lig.par)
Ew=$2 nuw=$3 muw=$4
mu=$(awk '$1 == "mu" { print $2 }' lig.par)
set -- $(awk '$1 == "grain"' lig.par)
E=$2 nu=$3 rho=$4 rmin=$5 mmean=$6
[ "$7" = 1 ] && [ "$8" = 1 ] || die "the pack's grains have $7 moduli and $8 Poisson ratios; LIGGGHTS here takes one of each"
# the LIGGGHTS side's constants, printed for the report
eval "$(awk -v E="$E" -v nu="$nu" -v rho="$rho" -v r="$rmin" -v f="$dtf" -v zlo="$zlo" -v zhi="$zhi" -v m="$mmean" -v dt="$dampt" 'BEGIN {
	G = E / (2 * (1 + nu)); tr = 3.141592653589793 * r * sqrt(rho / G) / (0.1631 * nu + 0.8766)
	printf "trayl=%.6g dt=%.6g dz=%.6g gamma=%.6g\n", tr, f * tr, 1e-4 * (zhi - zlo), m / (dt * tr) }')"

# the data file: two atom types (1 the grains, 2 the walls' material), the domain from a tenth
# of the box below it to one and a half boxes above it, so that the walls lie inside it
"$bin/packexport" --lammps-data fric.pack | awk '
	/ atom types$/ { print "2 atom types"; next }
	/ xlo xhi$| ylo yhi$| zlo zhi$/ { d = $2 - $1; printf "%.17g %.17g %s %s\n", $1 - d / 10, $2 + 1.5 * d, $3, $4; next }
	{ print }' >lig.data
# six walls, each one triangle whose legs are 2.42 box lengths: it covers its face and a
# twentieth of the box around it with no edge near any grain (a plane of two triangles has
# a diagonal across the face, and the grains on it switched between the triangles, losing
# their tangential history, and kept the pack vibrating)
stl() {	# NAME AXIS POS: a plane normal to AXIS (0 x, 1 y, 2 z) at POS
	awk -v name="$1" -v ax="$2" -v pos="$3" -v lo="$xlo $ylo $zlo" -v hi="$xhi $yhi $zhi" 'BEGIN {
		split(lo, L, " "); split(hi, H, " ")
		u = (ax + 1) % 3 + 1; v = (ax + 2) % 3 + 1; w = ax + 1
		c0u = L[u] - (H[u] - L[u]) / 20; c0v = L[v] - (H[v] - L[v]) / 20
		lu = 2.42 * (H[u] - L[u]); lv = 2.42 * (H[v] - L[v])
		cu[1] = c0u; cv[1] = c0v; cu[2] = c0u + lu; cv[2] = c0v; cu[3] = c0u; cv[3] = c0v + lv
		nrm[u] = nrm[v] = 0; nrm[w] = 1
		printf "solid %s\nfacet normal %g %g %g\nouter loop\n", name, nrm[1], nrm[2], nrm[3]
		for (k = 1; k <= 3; k++) {
			p[u] = cu[k]; p[v] = cv[k]; p[w] = pos
			printf "vertex %.17g %.17g %.17g\n", p[1], p[2], p[3]
		}
		printf "endloop\nendfacet\nendsolid %s\n", name }' >"$1.stl"
}
stl xlo 0 "$xlo"; stl xhi 0 "$xhi"; stl ylo 1 "$ylo"; stl yhi 1 "$yhi"; stl zlo 2 "$zlo"; stl zhi 2 "$zhi"

# the input: the settle loop stops on the mean unbalanced force ratio, the mean over the
# grains of |F_i| (the contact forces: the viscous drag -gamma v taken back out of f) over the
# start pack's mean normal contact force (packinfo force_mean: LIGGGHTS 3.8's compute reduce
# has no norm or sum of squares over the contacts), checked every 100 steps; each
# increment's state is dumped for the read-back
nmove=500
nchk=100
fmean=$(info fric.pack force_mean)
vz=$(awk -v dz="$dz" -v n="$nmove" -v dt="$dt" 'BEGIN { printf "%.10g", -dz / (n * dt) }')
lig_input() {	# TOL: the input script on stdout
cat <<EOT
# qusgm bench-peers: oedometric increments of the qusgm pack (tests/bench-peers.sh)
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
hard_particles yes
read_data lig.data
neighbor $(awk -v r="$rmin" 'BEGIN { printf "%.6g", 0.2 * r }') bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype $E $Ew
fix m2 all property/global poissonsRatio peratomtype $nu $nuw
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.1 0.1 0.1 0.1
fix m4 all property/global coefficientFriction peratomtypepair 2 $mu $muw $muw $muw
pair_style gran model hertz tangential history
pair_coeff * *
timestep $dt
fix xlo all mesh/surface file xlo.stl type 2
fix xhi all mesh/surface file xhi.stl type 2
fix ylo all mesh/surface file ylo.stl type 2
fix yhi all mesh/surface file yhi.stl type 2
fix zlo all mesh/surface/stress file zlo.stl type 2
fix zhi all mesh/surface/stress file zhi.stl type 2
fix walls all wall/gran model hertz tangential history mesh n_meshes 6 meshes xlo xhi ylo yhi zlo zhi
fix integr all nve/sphere
fix visc all viscous $gamma
compute pgl all pair/gran/local id force force_normal force_tangential
compute wgl all wall/gran/local id force_normal force_tangential
variable ux atom fx+$gamma*vx
variable uy atom fy+$gamma*vy
variable uz atom fz+$gamma*vz
variable u atom sqrt(v_ux*v_ux+v_uy*v_uy+v_uz*v_uz)
compute fu all reduce ave v_u
variable ufr equal c_fu/$fmean
variable szz equal f_zhi[3]/($(awk -v a="$xlo" -v b="$xhi" -v c="$ylo" -v d="$yhi" 'BEGIN { printf "%.17g", (b - a) * (d - c) }'))
thermo_style custom step cpu ke v_ufr v_szz
thermo $nchk
thermo_modify norm no lost error
variable st equal step
variable tl equal cpu

variable k loop 0 $K
label inc
variable s0 equal \${st}
if "\${k} == 0" then "jump SELF first"
fix mv all move/mesh mesh zhi linear 0 0 $vz
run $nmove
unfix mv
label first
run $nchk
label settle
variable ns equal \${st}-\${s0}
if "\${ufr} < $1" then "jump SELF settled"
if "\${ns} >= $maxst" then "print 'PEERS limit'" "jump SELF settled"
run $nchk pre no post no
jump SELF settle
label settled
print "PEERS inc \${k} steps \${ns} ufr \${ufr} szz \${szz}"
write_dump all custom atoms.\${k} id x y z modify format "%d %.17g %.17g %.17g"
dump dp all local 1 pairs.\${k} c_pgl[1] c_pgl[2] c_pgl[3] c_pgl[7] c_pgl[8] c_pgl[9] c_pgl[10] c_pgl[11] c_pgl[12]
dump dw all local 1 walls.\${k} c_wgl[1] c_wgl[2] c_wgl[3] c_wgl[4] c_wgl[5] c_wgl[6] c_wgl[7] c_wgl[8] c_wgl[9]
dump_modify dp format "%.0f %.0f %.0f %.17g %.17g %.17g %.17g %.17g %.17g"
dump_modify dw format "%.0f %.0f %.0f %.17g %.17g %.17g %.17g %.17g %.17g"
run 0
undump dp
undump dw
next k
jump SELF inc
EOT
}

# --- LIGGGHTS runs, one per tolerance, and the read-back of every state -------------------
ti=0
for tol in $tols; do
	ti=$((ti + 1))
	d="l$ti"
	rm -rf "$d"
	mkdir -p "$d"
	(cd "$d" && ln -s ../lig.data ../xlo.stl ../xhi.stl ../ylo.stl ../yhi.stl ../zlo.stl ../zhi.stl . &&
	    lig_input "$tol" >in.peers &&
	    /usr/bin/time -f '%U %S' -o lig.time "$lig" -in in.peers -log lig.log >lig.out 2>&1) ||
	    die "$lig failed (tolerance $tol): $(grep -m 1 ERROR "$d/lig.out")"
	# per increment: steps, the stop ratio, LIGGGHTS's own top-wall stress and the CPU
	# seconds: the run's CPU time shared out in proportion to the loop times between the
	# increments' ends (LIGGGHTS reports loop times as wall time)
	awk -v cpu="$(awk '{ print $1 + $2 }' "$d/lig.time")" '
		/^Loop time of/ { t += $4; T += $4 }
		/^PEERS limit/ { lim = 1 }
		/^PEERS inc/ { n++; k[n] = $3; st[n] = $5; u[n] = $7; s[n] = $9; lt[n] = t; l[n] = lim; t = 0; lim = 0 }
		END { for (i = 1; i <= n; i++) printf "%d\t%.4f\t%d\t%s\t%s\t%d\n", k[i], T ? cpu * lt[i] / T : 0, st[i], u[i], s[i], l[i] }' \
	    "$d/lig.out" >"$d/runs"
	: >"$d/rows"
	while read -r k secs steps ufr szz lim; do
		awk -v box="$xlo $ylo $zlo $xhi $yhi $(awk -v z="$zhi" -v k="$k" -v dz="$dz" 'BEGIN { printf "%.17g", z - k * dz }')" \
		    -v note="bench-peers: LIGGGHTS state after increment $k (tolerance $tol)" -f "$top/tests/peers-readback.awk" \
		    "$d/atoms.$k" "$d/pairs.$k" "$d/walls.$k" fric.pack >"$d/s$k.pack" || die "read-back of $d increment $k failed"
		# rows: increment, CPU s, steps, stop ratio, LIGGGHTS's top-wall stress, limit hit, then
		# the state
		printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$k" "$secs" "$steps" "$ufr" "$szz" "$lim" \
		    "$(state "$d/s$k.pack")" >>"$d/rows"
	done <"$d/runs"
done

# --- qusgm from LIGGGHTS's settled start (the last tolerance's), its tangential forces as the
# history: the same state for both
qchain p "l$ti/s0.pack"

# --- bench/peers.md ---------------------------------------------------------------------------
files="q.rows p.rows"
ti=0
for tol in $tols; do ti=$((ti + 1)); files="$files l$ti/rows"; done
ver=$(sed -n 's/^LIGGGHTS (Version \([^,]*\),.*/\1/p' l1/lig.out | head -n 1)
cpu=$(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -n 1)
commit=$(cd "$top" && git rev-parse --short HEAD 2>/dev/null || echo unknown)
{
	echo "# qusgm and LIGGGHTS on the same oedometric increments"
	echo
	echo "\`make bench-peers\` (tests/bench-peers.sh), $(date -u '+%Y-%m-%d %H:%M UTC'), commit $commit; $cpu, $(getconf _NPROCESSORS_ONLN) cores, each program on one (qusgm OMP_NUM_THREADS=1, $ver serial, no mpirun), load average $(cut -d ' ' -f 1 /proc/loadavg 2>/dev/null || echo unknown) at the start (on a shared machine CPU times move between runs by tens of per cent)."
	echo "From the same frictional pack, $K uniaxial-strain (oedometric) compressions of 1e-4 along z; CPU seconds are user + system."
	echo
	awk -v tols="$tols" -v K="$K" -F '\t' '
	FNR == 1 { f++ }
	{ k = $1; cpu[f, k] = $2; n[f, k] = $3
	  if (f <= 2) { sig[f, k] = $4; lz[f, k] = $5; res[f, k] = $6; med[f, k] = $7 }
	  else { sig[f, k] = $7; lz[f, k] = $8; res[f, k] = $9; med[f, k] = $10; ufr[f, k] = $4; lim[f, k] = $6 } }
	END {
		nt = split(tols, T, " ")
		# columns: qusgm, the LIGGGHTS runs, qusgm from the LIGGGHTS start (files 1, 3.., 2)
		nc = 0; col[++nc] = 1; for (t = 1; t <= nt; t++) col[++nc] = t + 2; col[++nc] = 2
		name[1] = "qusgm"; for (t = 1; t <= nt; t++) name[t + 2] = "LIGGGHTS, stop at " T[t]; name[2] = "qusgm from LIGGGHTS'"'"'s start"
		unit[1] = unit[2] = "iterations"; for (t = 1; t <= nt; t++) unit[t + 2] = "steps"
		printf "| per 1e-4 increment |"
		for (c = 1; c <= nc; c++) printf " %s (CPU s, %s) |", name[col[c]], unit[col[c]]
		printf "\n| ---: |"
		for (c = 1; c <= nc; c++) printf " ---: |"
		printf "\n"
		for (k = 1; k <= K; k++) {
			printf "| %d |", k
			for (c = 1; c <= nc; c++) { f = col[c]; printf " %.2f s, %d%s |", cpu[f, k], n[f, k], lim[f, k] ? " (limit)" : "" }
			printf "\n"
		}
		for (f = 1; f <= nt + 2; f++) { sc[f] = sn[f] = 0; for (k = 1; k <= K; k++) { sc[f] += cpu[f, k]; sn[f] += n[f, k] } }
		printf "| mean |"
		for (c = 1; c <= nc; c++) { f = col[c]; printf " **%.2f s**, %.0f |", sc[f] / K, sn[f] / K }
		printf "\n| start (not counted above) |"
		for (c = 1; c <= nc; c++) { f = col[c]; printf " %s |", f == 1 ? "frictionalize'"'"'s pack" : f == 2 ? "LIGGGHTS'"'"'s settled start, stop " T[nt] : sprintf("settle: %.2f s, %d", cpu[f, 0], n[f, 0]) }
		printf "\n\n"
		printf "The states, judged by packinfo in qusgm'"'"'s definitions (sig_zz: the Hertz normal forces on the two z walls from the overlaps, averaged, over the wall area; residual: per grain, |F_i| over its largest contact force, floored at 1e-3 of the mean normal force, with |M_i|/R_i; largest / median over the grains; eps_zz from the box height):\n\n"
		printf "| increment | eps_zz |"
		for (c = 1; c <= nc; c++) printf " %s: sig_zz [MPa] | residual, largest / median |", name[col[c]]
		printf "\n| ---: | ---: |"
		for (c = 1; c <= nc; c++) printf " ---: | ---: |"
		printf "\n"
		for (k = 0; k <= K; k++) {
			printf "| %d | %.1e |", k, 1 - lz[1, k] / lz[1, 0]
			for (c = 1; c <= nc; c++) { f = col[c]; printf " %.4f | %.1e / %.1e |", sig[f, k] / 1e6, res[f, k], med[f, k] }
			printf "\n"
		}
		# the constrained modulus: the least-squares slope of sig_zz against eps_zz over 0..K
		for (f = 1; f <= nt + 2; f++) {
			sx = sy = sxx = sxy = 0
			for (k = 0; k <= K; k++) { e = 1 - lz[f, k] / lz[f, 0]; sx += e; sy += sig[f, k]; sxx += e * e; sxy += e * sig[f, k] }
			m = K + 1; M[f] = (m * sxy - sx * sy) / (m * sxx - sx * sx)
			M1[f] = (sig[f, 1] - sig[f, 0]) / (1 - lz[f, 1] / lz[f, 0])
			Ml[f] = (sig[f, K] - sig[f, K - 1]) / ((lz[f, K - 1] - lz[f, K]) / lz[f, 0])
		}
		printf "| M = d sig_zz / d eps_zz [GPa]: fit over 0-%d (first increment, last) | |", K
		for (c = 1; c <= nc; c++) { f = col[c]; printf " **%.2f** (%.2f, %.2f) | |", M[f] / 1e9, M1[f] / 1e9, Ml[f] / 1e9 }
		printf "\n"
	}' $files
} >"$res.tmp" || die "writing the report failed"
set -- $(awk -F '\t' -v K="$K" '$1 == K { print $5, $7 }' l1/rows)
topK=$1 avgK=$2
set -- $(awk -F '\t' '$1 == 0 { print $7 }' l1/rows)
sig0=$1
q0sig=$(awk -F '\t' '$1 == 0 { print $4 }' q.rows)
lrm=$(info "l$ti/s$K.pack" residual_mean)
lrx=$(info "l$ti/s$K.pack" residual)
lrd=$(info "l$ti/s$K.pack" residual_median)
set -- $(awk -F '\t' '{ k = $1; s[FILENAME, k] = FILENAME == "p.rows" ? $4 : $7; l[FILENAME, k] = FILENAME == "p.rows" ? $5 : $8 }
    END { for (f = 1; f <= 2; f++) { F = f == 1 ? "p.rows" : LAST; x = y = xx = xy = 0
	for (k = 0; k <= K; k++) { e = 1 - l[F, k] / l[F, 0]; x += e; y += s[F, k]; xx += e * e; xy += e * s[F, k] }
	printf "%.3g ", ((K + 1) * xy - x * y) / ((K + 1) * xx - x * x) / 1e9 } }' K="$K" LAST="l$ti/rows" p.rows "l$ti/rows")
Mp=$1 Ml=$2
awk -v dt="$dt" -v tr="$trayl" -v dtf="$dtf" -v g="$gamma" -v dampt="$dampt" -v nm="$nmove" -v nc="$nchk" -v vz="$vz" \
    -v dz="$dz" -v E="$E" -v nu="$nu" -v Ew="$Ew" -v nuw="$nuw" -v mu="$mu" -v muw="$muw" -v K="$K" -v tols="$tols" \
    -v topK="$topK" -v avgK="$avgK" -v sig0="$sig0" -v q0="$q0sig" -v fm="$fmean" -v rmin="$rmin" -v rho="$rho" -v lrm="$lrm" -v lrx="$lrx" -v lrd="$lrd" -v tlast="$tol" -v Mp="$Mp" -v Ml="$Ml" 'BEGIN {
	H = dz / 1e-4; rate = 1e-4 / (nm * dt)
	printf "\n## How\n\n"
	printf "The pack: `packgen -n 2740 --seed 1 --material ./glass-uniform.mat | densify --stress 4e6 | frictionalize --mu 0.3` "
	printf "(bench/peers-work/, reused by later runs; PEERS_REGEN=1 remakes it), a glass of one E = %.3g GPa, nu = %g, rho = %g kg/m^3 for every grain ", E / 1e9, nu, rho
	printf "(make bench draws each grain'"'"'s E and nu with a 10 %% spread, but LIGGGHTS takes moduli per atom type, and binning them would put an error of the bin width into every contact force); "
	printf "walls E = %.3g TPa, nu = %g, grain and wall friction mu = %g, %g.\n\n", Ew / 1e12, nuw, mu, muw
	printf "qusgm: `loadtest -p uniaxial -d 1e-4 -n 1 -o q(k).pack q(k-1).pack`, %d times (a test split into runs repeats one run'"'"'s rows), ", K
	printf "so each increment'"'"'s CPU time includes reading and writing the pack; L-BFGS, --tol 1e-4 on the largest per-grain residual (the defaults).\n\n"
	printf "LIGGGHTS: `packexport --lammps-data` (atom_style granular), `liggghts -in in.peers` (bench/peers-work/l1/in.peers); "
	printf "`pair_style gran model hertz tangential history` and `fix wall/gran model hertz tangential history` on six mesh planes at the pack'"'"'s walls "
	printf "(one triangle each, reaching past the box, so that no triangle edge lies near a grain); "
	printf "`hard_particles yes` (LIGGGHTS refuses E above 1 GPa in SI units without it). "
	printf "Time step %.3g s = %g of the Rayleigh time %.3g s of the smallest grain (r = %.3g m): at 0.2 the pack never settled, its mean unbalanced force stayed near 1e-2 for 44000 steps with a few grains spinning at thousands of rad/s; at 0.1 and 0.05 it fell below 1e-7 within 1e4 steps (trial runs when this was written). ", dt, dtf, tr, rmin
	printf "Damping: coefficient of restitution 0.1 in the contacts and `fix viscous` gamma = %.3g kg/s, the mean grain mass over %g Rayleigh times. ", g, dampt
	printf "Each increment moves the top wall down by 1e-4 of the height (%.3g m) in %d steps (strain rate %.3g /s, inertial number about %.0e at the start stress), then runs in chunks of %d steps until the mean over the grains of the unbalanced contact force |F_i| (the viscous drag taken back out) ", dz, nm, rate, rate * 2e-4 * sqrt(rho / sig0), nc
	printf "over the start pack'"'"'s mean normal contact force (%.3g N) is below the tolerance (%s), as DEM users stop on an unbalanced-force ratio; its steps include the %d of the move. ", fm, tols, nm
	printf "CPU time per increment: the run'"'"'s user + system time shared out over the increments in proportion to LIGGGHTS'"'"'s loop times.\n\n"
	printf "The read-back: after each increment LIGGGHTS dumps the positions (`write_dump ... %%.17g`) and, from `compute pair/gran/local` and `wall/gran/local`, each contact'"'"'s normal and tangential force; tests/peers-readback.awk puts them into a copy of the qusgm pack "
	printf "(same radii and moduli, the box at that increment, LIGGGHTS'"'"'s tangential forces as the contacts'"'"' Q0, no torsion) and packinfo judges it. "
	printf "Its normal forces from the overlaps agree with LIGGGHTS'"'"'s to 1e-4 (largest relative difference over the contacts, checked when this was written). "
	printf "The forces balance in qusgm'"'"'s reading too: after increment %d of the run stopped at %s, packinfo'"'"'s residual_mean (mean |F_i| over the mean contact force, forces only) is %.1e, yet the per-grain residual (the larger of the force and moment ratios) has median %.1e and largest %.1e, so on most grains what LIGGGHTS leaves are the moments |M_i|/R_i: ", K, tlast, lrm, lrd, lrx
	printf "qusgm puts a contact'"'"'s tangential force on the plane of the contact circle (a wall'"'"'s plane for a wall), LIGGGHTS at r - delta/2 from each centre (`cri = radi - 0.5*deltan` in the LIGGGHTS-PUBLIC sources), and the two lever arms differ by half the overlap at a wall and by less between grains of unequal radii. "
	printf "Flipping the sign of the tangential forces gives a residual of 1.8, taking them out 0.9: the read-back'"'"'s convention is right.\n\n"
	printf "## What differs, and what was left out\n\n"
	printf "- The start: LIGGGHTS cannot be given the pack'"'"'s tangential history, so its contacts start with no tangential force; the settle at the start lets the pack relax from qusgm'"'"'s %.2f MPa to %.2f MPa, and its first increments load fresh, sticking contacts. The last columns start qusgm from LIGGGHTS'"'"'s settled state instead (its positions, and its tangential forces as the contacts'"'"' history), the same state for both. From it qusgm is the stiffer (M %s against %s GPa over the %d increments): the tangential laws differ (qusgm'"'"'s stick stiffness and sliding return map frozen over an increment, with torsion, share/doc/friction.md; LIGGGHTS'"'"'s incremental spring 8 G* a, without), not separated here.\n", q0 / 1e6, sig0 / 1e6, Mp, Ml, K
	printf "- sig_zz is the two z walls'"'"' average in both. The walls'"'"' friction makes the top wall carry more than the bottom: LIGGGHTS'"'"'s own top-wall reading (fix mesh/surface/stress) after increment %d is %.2f MPa against the average %.2f MPa.\n", K, topK / 1e6, avgK / 1e6
	printf "- qusgm has torsional couples at the contacts (M0); LIGGGHTS'"'"'s Hertz-Mindlin has none. Neither has rolling resistance.\n"
	printf "- Not run: YADE, several cores, larger packs, unloading, the per-grain scatter of the moduli.\n"
}' >>"$res.tmp"
mv "$res.tmp" "$res"
echo "wrote $res"
