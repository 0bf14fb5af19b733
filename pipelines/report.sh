#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# report.sh STUDY OUT "N_G2740 N_G5036 N_Q2654": the markdown report of one study, from the
# tables the study made (pipelines/Makefile calls it; OUT/STUDY/commands.txt holds the exact
# commands).  Every number below is computed here from those tables; the paper's numbers are
# quoted from its text.
set -e
study=$1 out=$2
set -- $3
n2740=$1 n5036=$2 n2654=$3
here=$(cd "$(dirname "$0")" && pwd)
cols="sh $here/cols.sh"
R=$out/runs
P=$out/packs
bin=${BIN:-../build/bin}

mpa() { awk '{ printf "%.2f", $1 / 1e6 }'; }
gpa() { awk '{ printf "%.3f", $1 / 1e9 }'; }
# first / last value of column C of table T
first() { $cols "$1" "$2" | head -n 1; }
last() { $cols "$1" "$2" | tail -n 1; }
# column C of a moduli table T at its first fitted window, and at its last full fitted one:
# a window with K or G nan (moduli rejects the fit: a rearrangement of a frictionless pack
# inside it) or the short window at the end of the curve is no measurement of the trend
mfirst() { $cols "$1" K G "$2" | awk '$1 !~ /nan/ && $2 !~ /nan/ { print $3; exit }'; }
mlast() { $cols "$1" n K G "$2" | awk '$1 > nmax { nmax = $1 } $1 == nmax && $2 !~ /nan/ && $3 !~ /nan/ { v = $4 } END { print v }'; }
# interp T C S: column C of moduli table T at sigma_c = S (linear between windows), or "-"
interp() {
	$cols "$1" sigma_c "$2" | awk -v s="$3" '
		NR > 1 && (ps - s) * ($1 - s) <= 0 && ps != $1 { printf "%.6g", pv + ($2 - pv) * (s - ps) / ($1 - ps); found = 1; exit }
		{ ps = $1; pv = $2 }
		END { if (!found) printf "-" }'
}
# growth exponent of column C against sigma_c over a moduli table: slope of log C on log
# sigma_c over its full fitted windows (as mlast)
expo() {
	$cols "$1" n sigma_c "$2" | awk '{ w[NR] = $1; s[NR] = $2; v[NR] = $3; if ($1 > nmax) nmax = $1 }
		END { for (i = 1; i <= NR; i++) if (w[i] == nmax && v[i] !~ /nan/ && v[i] > 0) {
			x = log(s[i]); y = log(v[i]); k++; sx += x; sy += y; sxx += x * x; sxy += x * y }
		      if (k > 2) printf "%.2f", (k * sxy - sx * sy) / (k * sxx - sx * sx); else printf "-" }'
}
# common stress of several moduli tables: the middle of the overlap of their sigma_c ranges
common() {
	for t in "$@"; do $cols "$t" sigma_c | awk 'NR == 1 { lo = hi = $1 } { if ($1 < lo) lo = $1; if ($1 > hi) hi = $1 } END { print lo, hi }'; done |
	    awk 'NR == 1 { lo = $1; hi = $2 } { if ($1 > lo) lo = $1; if ($2 < hi) hi = $2 } END { if (lo < hi) printf "%.6g", (lo + hi) / 2; else printf "-" }'
}
info() { "$bin/packinfo" "$1" | awk -v k="$2" '$1 == k { print $2 }'; }
# the volume-averaged confining stress tr(sig_lw) / 3 of each row of table T
lw_mean() { $cols "$1" sig_lw_xx sig_lw_yy sig_lw_zz | awk '{ printf "%.17g\n", ($1 + $2 + $3) / 3 }'; }
fric_summary() {	# run: phase (b) in one line
	f=$R/$1/fric.tsv
	ninc=$(($($cols "$f" inc | wc -l) - 1))
	printf '| %s | %s | %s -> %s | %s -> %s | %s | %s | %s -> %s (max %s) |\n' "$1" "$ninc" \
	    "$(first "$f" sigma_c | mpa)" "$(last "$f" sigma_c | mpa)" \
	    "$(lw_mean "$f" | head -n 1 | mpa)" "$(lw_mean "$f" | tail -n 1 | mpa)" \
	    "$($cols "$f" sliding_ratio | tail -n 10 | awk '{ s += $1 } END { printf "%.3f", s / NR }')" \
	    "$($cols "$f" trial_slip_ratio | tail -n 10 | awk '{ s += $1 } END { printf "%.3f", s / NR }')" \
	    "$($cols "$f" G | sed -n 2p | gpa)" "$(last "$f" G | gpa)" \
	    "$($cols "$f" G | awk '$1 !~ /nan/ && $1 > m { m = $1 } END { print m }' | gpa)"
}
fric_header() {
	echo '| run | phase (b) increments | sigma_c at the walls (MPa) | volume-averaged sigma_c (MPa) | sliding ratio (mean of last 10) | trial slip ratio (mean of last 10) | G (GPa) first -> last |'
	echo '| --- | --- | --- | --- | --- | --- | --- |'
}
test_summary() {	# run: the uniaxial test's moduli in one line
	m=$R/$1/moduli.tsv
	printf '| %s | %s -> %s | %s -> %s | %s -> %s | %s | %s |\n' "$1" \
	    "$(mfirst "$m" sigma_c | mpa)" "$(mlast "$m" sigma_c | mpa)" \
	    "$(mfirst "$m" K | gpa)" "$(mlast "$m" K | gpa)" "$(mfirst "$m" G | gpa)" "$(mlast "$m" G | gpa)" \
	    "$(expo "$m" K)" "$(expo "$m" G)"
}
test_header() {
	echo '| run | sigma_c (MPa) | K (GPa) | G (GPa) | exponent of K | exponent of G |'
	echo '| --- | --- | --- | --- | --- | --- |'
}
at_common() {	# runs...: K and G of each at the common stress
	tabs=""
	for r in "$@"; do tabs="$tabs $R/$r/moduli.tsv"; done
	s=$(common $tabs)
	if [ "$s" = - ]; then
		echo "The runs' stress ranges do not overlap: no common stress to compare at."
		return
	fi
	echo "At the common confining stress sigma_c = $(echo "$s" | mpa) MPa (middle of the overlap of the tests' ranges, linear interpolation between windows):"
	echo
	echo '| run | K (GPa) | G (GPa) |'
	echo '| --- | --- | --- |'
	for r in "$@"; do
		printf '| %s | %s | %s |\n' "$r" "$(interp "$R/$r/moduli.tsv" K "$s" | gpa)" "$(interp "$R/$r/moduli.tsv" G "$s" | gpa)"
	done
}

# the seconds of the tool runs this study needs: their names from commands.txt (make -n of
# the study's data), their times from OUT/times.tsv (timed.sh), the last time of each
study_time() {
	awk 'FNR == NR { t[$1] = $2; next }
	     { for (i = 1; i < NF; i++) if ($i ~ /timed\.sh$/) { n++; s += t[$(i + 2)]; if (!($(i + 2) in t)) miss++ } }
	     END { printf "%d tool runs, %.0f s on one core", n, s; if (miss) printf " (%d not timed)", miss }' \
	    "$out/times.tsv" "$out/$study/commands.txt" 2>/dev/null || echo "not timed"
}

echo "# $study"
echo
if [ "$study" = s-fig5 ]; then
	echo "Pack: ${N_HYD:-?} grains, quartz with hydrate (seed ${SEED:-1})."
elif [ "$study" = platy ]; then
	echo "Packs: ${N_PLATY:-?} spheroplates per platyness (seed ${SEED:-1}), sheared at I = ${PLATY_I:-?} to gamma ${PLATY_STRAIN:-?}, steady state from gamma ${PLATY_FROM:-?}."
else
	echo "Pack sizes: G2740-style $n2740 grains, G5036-style $n5036, Q2654-style $n2654 (seed ${SEED:-1})."
fi
echo "Figure: \`$study.png\`; exact commands: \`commands.txt\`; remake: \`make -C pipelines $study$( [ "$out" = out-small ] && echo ' SMALL=1')\`."
echo "Cost: $(study_time) (the sum of its stages; run alone with -j1 it takes about that long)."
if [ -n "${PIC:-}" ]; then
	echo
	if [ "$study" = platy ]; then
	echo "The pack \`${PIC#$out/}\` after its shear: the plates centred within half a plate width of the middle plane z = z_c, seen along z (x the shear direction, y the gradient, up), each the trace of its mid-plane, coloured by |n_y| (1: face normal along the gradient; share/plot/packpic.sh):"
	else
	echo "The pack \`${PIC#$out/}\`: a slab one mean radius thick through its middle, seen along y (z up); discs coloured by $( [ "$study" = s-fig5 ] && echo "phase (1: hydrate)" || echo "each grain's number of contacts"), lines from centre to centre with a width that follows the normal force (share/plot/packpic.sh):"
	fi
	echo
	echo "![pack](pack.png)"
fi
echo
case $study in
fig4)
	cat <<'EOF'
**Paper** (frictional, Fig. 4, G2740, mu = 0.3): during phase (b) the sliding ratio rises fast and
saturates at about 0.09-0.11 while G, first high ("stiffer than typical experimental values"),
falls; once friction is developed (sigma_c from 4 to about 9 MPa) the moduli increase with sigma_c
in the uniaxial test.

**This run** (the sliding ratio comparable with the paper's counts the contacts committed at
their Coulomb limit mu P; the trial slip ratio, DEM codes' slip fraction, those whose trial force
reached it during the increment: share/doc/friction.md.  Moduli and G from the volume-averaged
stress; sigma_c of phase (b) at the walls, where frictionalize controls it, and volume-averaged)

EOF
	fric_header; fric_summary g2740-s4-mu0.3
	echo
	test_header; test_summary g2740-s4-mu0.3
	;;
fig5-6)
	cat <<'EOF'
**Paper** (frictional, Figs. 5-6): G2740 with sigma_c^(mu=0) = 4 and 10 MPa, mu = 0.3, phase (b)
to 9 and 19 MPa, then uniaxial tests; 10 MPa with mu = 0.5; G5036 frictionless.  The moduli grow
with sigma_c with an exponent falling from about 0.45 to 0.33; mu = 0.5 gives a larger G than
0.3; the frictionless pack a much smaller G; K agrees with glass-bead experiments, and the
effective-medium theory with no-slip contacts overestimates G.

**This run**

EOF
	fric_header
	for r in g2740-s4-mu0.3 g2740-s10-mu0.3 g2740-s10-mu0.5; do fric_summary $r; done
	echo
	test_header
	for r in g2740-s4-mu0.3 g2740-s10-mu0.3 g2740-s10-mu0.5 g5036-s4-mu0; do test_summary $r; done
	echo
	echo '| run | last full window: K / K_emt | G / G_emt_rough | G / G_emt_smooth |'
	echo '| --- | --- | --- | --- |'
	for r in g2740-s4-mu0.3 g2740-s10-mu0.3 g2740-s10-mu0.5 g5036-s4-mu0; do
		m=$R/$r/moduli.tsv
		echo "$(mlast $m K) $(mlast $m G) $(mlast $m K_emt) $(mlast $m G_emt_rough) $(mlast $m G_emt_smooth)" |
		    awk -v r=$r '{ printf "| %s | %.2f | %.2f | %.2f |\n", r, $1 / $3, $2 / $4, $2 / $5 }'
	done
	echo
	at_common g2740-s10-mu0.3 g2740-s10-mu0.5
	;;
fig7)
	cat <<'EOF'
**Paper** (frictional, Fig. 7): six packs with sigma_c^(mu=0) = 4, 10, 20, 41, 54 and 74 MPa,
mu = 0.3.  At a given sigma_c, K is lower for packs densified to a higher stress (about 1 %
between 4 and 10 MPa, about 10 % with 41 MPa); G is less sensitive.

**This run** (tests to 150 MPa; the 74 MPa pack, whose phase (b) ends above that, 60 increments)

EOF
	fric_header
	for s in 4 10 20 41 54 74; do fric_summary g2740-s$s-mu0.3-f7; done
	echo
	test_header
	for s in 4 10 20 41 54 74; do test_summary g2740-s$s-mu0.3-f7; done
	echo
	at_common g2740-s4-mu0.3-f7 g2740-s10-mu0.3-f7 g2740-s20-mu0.3-f7 g2740-s41-mu0.3-f7 g2740-s54-mu0.3-f7
	;;
fig8)
	cat <<'EOF'
**Paper** (frictional, Fig. 8): strain steps of 5e-5, 5e-4, and 5e-4 in phase (b) followed by
5e-5 in the test give nearly the same moduli: the results are robust to the increment.

**This run** (moduli windows of 1e-3 strain: 20, 2 and 20 increments)

EOF
	fric_header
	for r in g2740-s4-mu0.3-d5e-5 g2740-s4-mu0.3-d5e-4 g2740-s4-mu0.3-d5e-4-5e-5; do fric_summary $r; done
	echo
	test_header
	for r in g2740-s4-mu0.3-d5e-5 g2740-s4-mu0.3-d5e-4 g2740-s4-mu0.3-d5e-4-5e-5; do test_summary $r; done
	echo
	at_common g2740-s4-mu0.3-d5e-5 g2740-s4-mu0.3-d5e-4 g2740-s4-mu0.3-d5e-4-5e-5
	;;
fig9)
	cat <<'EOF'
**Paper** (frictional, Fig. 9): mu = 0.5 gives larger moduli than mu = 0.3, G much more than K.

**This run** (sigma_c^(mu=0) = 10 MPa)

EOF
	fric_header
	for r in g2740-s10-mu0.3 g2740-s10-mu0.5; do fric_summary $r; done
	echo
	test_header
	for r in g2740-s10-mu0.3 g2740-s10-mu0.5; do test_summary $r; done
	echo
	at_common g2740-s10-mu0.3 g2740-s10-mu0.5
	;;
s-fig3)
	c=$R/q2654-s60-poly/curve.tsv
	cat <<'EOF'
**Paper** (frictionless, Fig. 3, Q2654 quartz): a polyaxial loading-unloading cycle between
about 60 and 300 MPa; porosity 35.8 -> 30.5 %, coordination 7.23 -> 8.26; loading and unloading
curves differ (hysteresis) through irreversible rearrangements of the contact network.

**This run** (frictionless, strain increments in the ratio 1 : 1.5 : 2 along x : y : z, 2e-4
along z per increment, to sigma_c = 300 MPa and back to 60 MPa)

EOF
	$cols "$c" seg sigma_c porosity coordination eps_zz sig_zz | awk -F'\t' '
		NR == 1 { s0 = $2; p0 = $3; c0 = $4; e0 = $5; z0 = $6 }
		$1 == 1 { pk = $2; pp = $3; pc = $4; pe = $5; nl++ }
		$1 == 2 { nu++ }
		{ s1 = $2; p1 = $3; c1 = $4; e1 = $5; z1 = $6 }
		END {
			printf "| | start | peak of loading | end of unloading |\n| --- | --- | --- | --- |\n"
			printf "| sigma_c (MPa) | %.1f | %.1f | %.1f |\n", s0 / 1e6, pk / 1e6, s1 / 1e6
			printf "| porosity (%%) | %.2f | %.2f | %.2f |\n", 100 * p0, 100 * pp, 100 * p1
			printf "| coordination | %.2f | %.2f | %.2f |\n", c0, pc, c1
			printf "| eps_zz | %.5f | %.5f | %.5f |\n", e0, pe, e1
			printf "\n%d loading and %d unloading increments.\n", nl, nu
		}'
	echo
	# hysteresis: sig_zz of loading and unloading at the same eps_zz, over the common range
	$cols "$c" seg eps_zz sig_zz | awk -F'\t' '
		$1 == 1 { le[++nl] = $2; ls[nl] = $3 }
		$1 == 2 { ue[++nu] = $2; us[nu] = $3 }
		END {
			for (k = 1; k <= nu; k++)
				for (j = 2; j <= nl; j++)
					if ((le[j - 1] - ue[k]) * (le[j] - ue[k]) <= 0 && le[j] != le[j - 1]) {
						s = ls[j - 1] + (ls[j] - ls[j - 1]) * (ue[k] - le[j - 1]) / (le[j] - le[j - 1])
						d = s - us[k]; if (d < 0) d = -d
						if (d > dm) { dm = d; em = ue[k]; sl = s; su = us[k] }
						break
					}
			printf "Largest gap between the loading and unloading sig_zz at the same eps_zz: %.2f MPa (at eps_zz = %.5f: %.2f loading, %.2f unloading).\n", dm / 1e6, em, sl / 1e6, su / 1e6
		}'
	;;
s-fig4)
	cat <<'EOF'
**Paper** (frictionless, Fig. 4, G5036 glass): isotropic compression from about 1 to 35 MPa with
uniaxial probes; porosity 37.4 -> 35.1 %, coordination 6.24 -> 7.15; K agrees with acoustic
experiments on glass beads with no adjustment of parameters, G is underestimated (no friction).

**This run** (each stress: densify of the 1 MPa pack, then a probe of 3 uniaxial increments of
1e-4 along each of x, y and z, fitted together: G is the mean of the three axes', since one
axis's G of a frictionless pack varies by 40-60 %; volume-averaged stress; porosity and
coordination of the whole box, a wall contact counted once)

EOF
	echo '| sigma_c^(mu=0) (MPa) | porosity (%) | coordination | sigma_c of the probe (MPa) | K (GPa) | G (GPa) | K_emt (GPa) | G_emt rough / smooth (GPa) |'
	echo '| --- | --- | --- | --- | --- | --- | --- | --- |'
	for s in 1 2 5 10 20 35; do
		pk=$P/g5036.s$s.pack.gz
		m=$R/g5036-s$s-probe/moduli.tsv
		printf '| %s | %.2f | %.2f | %s | %s | %s | %s | %s / %s |\n' "$s" \
		    "$(info "$pk" porosity | awk '{ print 100 * $1 }')" "$(info "$pk" coordination)" \
		    "$(first "$m" sigma_c | mpa)" "$(first "$m" K | gpa)" "$(first "$m" G | gpa)" \
		    "$(first "$m" K_emt | gpa)" "$(first "$m" G_emt_rough | gpa)" "$(first "$m" G_emt_smooth | gpa)"
	done
	;;
platy)
	sm=$out/platy/summary.tsv
	cat <<'EOF'
**Paper** (platy-particle, Boton et al. 2013, 8000 plates, I about 1e-3, kappa >= 1e3, averages over
gamma 1.5-2.5; its text gives the trends from eta = 0 to 0.8, which the second table quotes):
q/p rises from about 0.3 to 0.7 (Fig. 7), the packing fraction peaks near eta 0.3 (Fig. 8), a_m
rises from 0 to 0.6 (Fig. 11), Z from 3.6 to 4.3 while chi falls from 0.20 to 0.05 (Fig. 12),
a_n from 0.3 to 1.2 (Fig. 14), a_ln falls from 0 to -0.2 and a_lt from 0 to -0.4 (Fig. 17), a_fn
rises only from 0.2 to 0.3 while a_ft rises from 0 to 0.7 (Fig. 20), K_s from 0.1 to 0.4 (Fig.
21), and eq. 28 approximates q/p well below eta 0.3 and overestimates it above (Fig. 22).

**This run** (mean +- standard deviation over the steady-state window: the shear's rows for
tau/sigma, q/p, phi and Z; the snapshots' descriptors, over the free grains, for the rest;
angles in degrees; "direct": the tangential tensors' own anisotropies and eq. 28 with them)

EOF
	echo '| eta | tau_w/sigma_w | q/p | eq. 28 | phi | Z | chi | a_m | theta_m | a_n | theta_n | a_ln | a_lt | a_fn | a_ft | K_s | eq. 28 direct | a_ft direct | theta_ft direct | M1 - M3 | S |'
	echo '| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |'
	$cols "$sm" eta tau_sigma tau_sigma_sd qp qp_sd qp_harmonic qp_harmonic_sd phi phi_sd Z Z_sd floating_fraction_free \
	    floating_fraction_free_sd a_m a_m_sd theta_m a_n a_n_sd theta_n a_ln a_lt a_fn a_ft K_s K_s_sd \
	    qp_harmonic_direct a_ft_direct theta_ft_direct M1_M3 nematic_S |
	    awk -F '\t' '{ printf "| %s | %.3f +- %.3f | %.3f +- %.3f | %.3f +- %.3f | %.3f +- %.3f | %.2f +- %.2f | %.3f +- %.3f | %.2f +- %.2f | %.0f | %.2f +- %.2f | %.0f | %.3f | %.3f | %.3f | %.3f | %.3f +- %.3f | %.3f | %.3f | %.0f | %.2f | %.2f |\n",
	      $1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14, $15, $16, $17, $18, $19, $20, $21, $22, $23, $24, $25,
	      $26, $27, $28, $29, $30 }'
	echo
	echo "The trends, first platyness against the last, beside the paper's (eta 0 -> 0.8):"
	echo
	echo '| quantity | paper | this run | same direction |'
	echo '| --- | --- | --- | --- |'
	for q in "qp 0.3 0.7" "Z 3.6 4.3" "floating_fraction_free 0.20 0.05" "a_m 0 0.6" "a_n 0.3 1.2" "a_ln 0 -0.2" "a_lt 0 -0.4" \
	    "a_fn 0.2 0.3" "a_ft 0 0.7" "K_s 0.1 0.4"; do
		set -- $q
		a=$($cols "$sm" "$1" | head -n 1)
		b=$($cols "$sm" "$1" | tail -n 1)
		# a_m of spheres does not exist (nan): no direction to compare
		awk -v n="$1" -v p="$2" -v q="$3" -v a="$a" -v b="$b" 'BEGIN {
			if (a == "nan" || b == "nan") { printf "| %s | %s -> %s | %s -> %s | - |\n", n, p, q, a, b; exit }
			printf "| %s | %s -> %s | %.3f -> %.3f | %s |\n", n, p, q, a, b, ((q - p) * (b - a) > 0) ? "yes" : "no" }'
	done
	;;
s-fig5)
	sm=$out/s-fig5/summary.tsv
	pk=$P/hyd.s21.pack.gz
	cat <<'EOF'
**Paper** (frictionless, section 4 and Fig. 5): a 2740-grain hydrate-bearing sediment, the
smallest grains hydrate and the rest quartz, porosity about 45 % with the hydrate counted as
pore space, hydrate saturation S = 0.215, effective stress about 21 MPa, Biot-Willis
coefficient 0.8.  Dissociation shrinks the hydrate grains (dS < 0) and raises the pore pressure
(p_ex), which shrinks every grain and expands the pack; both moduli fall (Fig. 5: against p_ex
at dS = -0.01 and against dS at p_ex = 1 MPa).  The paper gives no values.

EOF
	echo "**This run** (packgen --hydrate-volume ${HYD_F:-?}, densify to 21 MPa, frictionless; each point"
	echo "dissociate from that pack, then a probe of 3 uniaxial increments of 1e-5 along each of x, y"
	echo "and z fitted together; stresses volume-averaged, K and G at the probe's sigma_c).  densify"
	echo "grows the grains with fewer than 4 contacts, most of them small hydrate grains, so the dense"
	echo "pack's hydrate fraction is above packgen's:"
	echo
	echo "The dense pack: $(info "$pk" grains) grains, $(info "$pk" hydrate_grains) of them hydrate" \
	    "($(info "$pk" hydrate_volume_fraction | awk '{ printf "%.1f", 100 * $1 }') % of the grain volume);" \
	    "S = $(info "$pk" hydrate_saturation | awk '{ printf "%.3f", $1 }'), porosity" \
	    "$(info "$pk" porosity | awk '{ printf "%.1f", 100 * $1 }') % (hydrate as solid) and" \
	    "$(info "$pk" porosity_hydrate_as_pore | awk '{ printf "%.1f", 100 * $1 }') % (hydrate as pore space)."
	echo
	echo '| run | dS | p_ex (MPa) | S after | sigma_eff before -> after (MPa) | drop (MPa) | alpha_b p_ex (MPa) | total after (MPa) | K (GPa) | G (GPa) |'
	echo '| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |'
	# a probe whose isotropic fit leaves more than half of the stress change unexplained
	# (fit_rel > 0.5; the elastic probes here stay below 0.15) rearranged on the way: its K
	# and G are not moduli, and the slopes leave it out
	$cols "$sm" run dS pex S sigma_before sigma_after sigma_total K G fit_rel | awk -F '\t' '{
		re = $10 + 0 > 0.5
		printf "| %s | %s | %.1f | %.4f | %.2f -> %.2f | %.2f | %.2f | %.2f | %s | %s |\n", $1, $2, $3 / 1e6, $4, $5 / 1e6, $6 / 1e6,
		    ($5 - $6) / 1e6, 0.8 * $3 / 1e6, $7 / 1e6, ($8 ~ /nan/ ? "nan" : sprintf("%.3f", $8 / 1e9)) (re ? " (rearranged)" : ""),
		    ($9 ~ /nan/ ? "nan" : sprintf("%.3f", $9 / 1e9)) (re ? " (rearranged)" : "") }'
	rearr=$($cols "$sm" run fit_rel | awk '$2 + 0 > 0.5 { printf "%s%s", s, $1; s = ", " }')
	echo
	if [ -n "$rearr" ]; then
		echo "Rearranged during the probe (fit_rel above 0.5, left out of the slopes): $rearr."
		echo
	fi
	# least-squares slopes of K and G over each series (nan points and rearranged probes left out)
	slope() { awk -v xs="$1" '$3 !~ /nan/ && $4 + 0 <= 0.5 { x = $1 * xs; n++; sx += x; sy += $3; sxx += x * x; sxy += x * $3 }
		END { if (n > 1 && n * sxx != sx * sx) printf "%.1f", (n * sxy - sx * sy) / (n * sxx - sx * sx) / 1e6; else printf "-" }'; }
	sA() { $cols "$sm" pex dS "$1" fit_rel | awk '$2 + 0 == -0.01'; }
	sB() { $cols "$sm" dS pex "$1" fit_rel | awk '$2 + 0 == 1e6'; }
	echo "The falls, least-squares slopes over each series:"
	echo
	echo '| series | K (MPa per unit) | G (MPa per unit) |'
	echo '| --- | --- | --- |'
	echo "| p_ex at dS = -0.01, per MPa of p_ex | $(sA K | slope 1e-6) | $(sA G | slope 1e-6) |"
	echo "| dS at p_ex = 1 MPa, per 0.01 of -dS | $(sB K | slope -100) | $(sB G | slope -100) |"
	echo
	echo "Effective stress against the Biot prediction, p_ex alone (dS = 0): the drop over alpha_b p_ex is" \
	    "$($cols "$sm" dS pex sigma_before sigma_after | awk '$1 + 0 == 0 && $2 > 0 { printf "%.3f at p_ex = %.1f MPa", ($3 - $4) / (0.8 * $2), $2 / 1e6; f = 1 } END { if (!f) printf "-" }')" \
	    "(above 1 by the grains' own compression, about K / K_grain)."
	g0=$($cols "$sm" run G | awk '$1 == "hyd-d0-p0" { print $2 }')
	lost=$($cols "$sm" run G | awk -v g0="$g0" '$2 ~ /nan/ || $2 <= 0.01 * g0 { printf "%s%s", s, $1; s = ", " }')
	echo
	if [ -n "$lost" ]; then
		echo "Shear rigidity lost (G nan, or below 1 % of the pack's before dissociation) in: $lost."
	else
		echo "Shear rigidity kept at every point (G above 1 % of the pack's before dissociation)."
	fi
	;;
*)
	echo "report.sh: unknown study $study" >&2
	exit 2
	;;
esac
