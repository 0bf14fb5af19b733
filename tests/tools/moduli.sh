# SPDX-License-Identifier: GPL-3.0-or-later
# moduli as a user runs it: on loadtest curves of a small frictional pack (200 grains) and on
# tables written by hand from a known linear isotropic material, whose K and G it must give
# back; --window, segments, continued tests, isotropic paths (K only), --stress lw, --emt,
# the standard errors of K and G against least squares done here in awk, and the errors.  A
# few seconds in all.
. "$TOP/tests/tools/lib.sh"

# moduli columns: 1 seg, 2 inc_from, 3 inc_to, 4 n, 5 sigma_c, 6 sig_lat, 7 K, 8 G, 9 lambda,
# 10 E, 11 nu, 12 fit_rel, 13 K_se, 14 G_se (with --emt: 13 porosity, 14 coordination, 15 K_emt,
# 16 G_emt_rough, 17 G_emt_smooth, 18 K_se, 19 G_se: the standard errors come last)

small_pack frictional
expect_ok "loadtest makes the curve" loadtest --steps 6 fr.pack
mv ok.out curve.tsv

# --- a loadtest curve ------------------------------------------------------------------------
expect_ok "moduli reads a loadtest curve" moduli curve.tsv
mv ok.out m1.tsv
hdr=$(printf '# seg\tinc_from\tinc_to\tn\tsigma_c[Pa]\tsig_lat[Pa]\tK[Pa]\tG[Pa]\tlambda[Pa]\tE[Pa]\tnu\tfit_rel')
if [ "$(head -n 1 m1.tsv)" = "$hdr$(printf '\tK_se[Pa]\tG_se[Pa]')" ]; then pass "header"; else fail "header" "$(head -n 1 m1.tsv)"; fi
expect_num "one row per increment (6)" "$(rows m1.tsv | wc -l)" "==" 6
rows m1.tsv | awk -F '\t' '{ k = NR; if (NF != 14) bad = "row " NR ": " NF " columns"
	if (!($1 == 1 && $2 == k - 1 && $3 == k && $4 == 1)) bad = "row " NR ": seg " $1 " inc " $2 "-" $3 " n " $4
	if (!($7 > 1e8 && $7 < 1e11 && $8 > 1e7 && $8 < 1e11)) bad = "row " NR ": K " $7 " G " $8
	if (!($12 >= 0 && $12 < 0.05)) bad = "row " NR ": fit_rel " $12
	K = $7; G = $8
	e = $9 - (K - 2 * G / 3); if (e < 0) e = -e; if (e > 1e-9 * K) bad = "row " NR ": lambda " $9
	e = $10 - 9 * K * G / (3 * K + G); if (e < 0) e = -e; if (e > 1e-9 * $10) bad = "row " NR ": E " $10
	e = $11 - (3 * K - 2 * G) / (2 * (3 * K + G)); if (e < 0) e = -e; if (e > 1e-9) bad = "row " NR ": nu " $11 }
     END { if (bad) { print bad; exit 1 } }' >why &&
    pass "rows: seg 1, inc k-1..k, K G positive, lambda E nu from K and G" || fail "rows: seg 1, inc k-1..k, K G positive, lambda E nu from K and G" "$(cat why)"
# the default measure is the volume-averaged stress: an interval's sigma_c is the mean over its
# two end rows of tr(sig_lw) / 3, its sig_lat that of (sig_lw_xx + sig_lw_yy) / 2 (loading
# along z); with --stress wall both are the table's columns
expect_num "sigma_c of interval 2-3 is the mean of rows 2 and 3 of tr(sig_lw) / 3" \
    "$(rel "$(col m1.tsv 3 5)" "$(rows curve.tsv | awk -F '\t' 'NR == 3 || NR == 4 { s += ($9 + $10 + $11) / 6 } END { printf "%.17g", s }')")" "<" 1e-12
expect_num "sig_lat of interval 2-3 is the mean of rows 2 and 3 of (sig_lw_xx + sig_lw_yy) / 2" \
    "$(rel "$(col m1.tsv 3 6)" "$(rows curve.tsv | awk -F '\t' 'NR == 3 || NR == 4 { s += ($9 + $10) / 4 } END { printf "%.17g", s }')")" "<" 1e-12
moduli --stress wall curve.tsv >mw.tsv 2>/dev/null
expect_num "--stress wall: sigma_c of interval 2-3 is the mean of rows 2 and 3" \
    "$(rel "$(col mw.tsv 3 5)" "$(awk -v a="$(col curve.tsv 3 12)" -v b="$(col curve.tsv 4 12)" 'BEGIN { printf "%.17g", (a + b) / 2 }')")" "<" 1e-12
expect_num "--stress wall: sig_lat of interval 2-3 is the mean of rows 2 and 3" \
    "$(rel "$(col mw.tsv 3 6)" "$(awk -v a="$(col curve.tsv 3 13)" -v b="$(col curve.tsv 4 13)" 'BEGIN { printf "%.17g", (a + b) / 2 }')")" "<" 1e-12
cat curve.tsv | moduli >m1b.tsv 2>/dev/null
expect_same "stdin gives the same table" m1.tsv m1b.tsv
moduli -o m1c.tsv curve.tsv 2>/dev/null
expect_same "-o gives the same table" m1.tsv m1c.tsv

# --window: 6 increments in windows of 4 are one interval of 4 and one of 2
expect_ok "--window 4" moduli --window 4 curve.tsv
mv ok.out w4.tsv
if [ "$(rows w4.tsv | cut -f 1-4 | tr '\t\n' ', ')" = "1,0,4,4 1,4,6,2 " ]; then pass "--window 4: intervals 0-4 (n 4), 4-6 (n 2)"; else fail "--window 4: intervals 0-4 (n 4), 4-6 (n 2)" "$(rows w4.tsv | cut -f 1-4 | tr '\t\n' ', ')"; fi
expect_num "--window 6: one row" "$(moduli --window 6 curve.tsv 2>/dev/null | rows /dev/stdin | wc -l)" "==" 1
expect_error "--window 100: longer than the 6 increments, refused" 1 "^moduli: curve\.tsv: --window 100 is longer than the table's 6 increments \(7 rows\)$" moduli -k 100 curve.tsv
# segments: a window never spans two (loading 5, unloading 3, windows of 2)
loadtest --path 'uniaxial steps=5; uniaxial step=-1e-4 steps=3' fr.pack >cycle.tsv 2>/dev/null
expect_ok "--window 2 on a two-segment curve" moduli --window 2 cycle.tsv
if [ "$(rows ok.out | cut -f 1-4 | tr '\t\n' ', ')" = "1,0,2,2 1,2,4,2 1,4,5,1 2,5,7,2 2,7,8,1 " ]; then
	pass "--window 2: 3 intervals in segment 1, 2 in segment 2"
else
	fail "--window 2: 3 intervals in segment 1, 2 in segment 2" "$(rows ok.out | cut -f 1-4 | tr '\t\n' ', ')"
fi
expect_num "--window 1 on the two-segment curve: 8 rows" "$(moduli cycle.tsv 2>/dev/null | rows /dev/stdin | wc -l)" "==" 8

# a continued test (loadtest -o, then loadtest on that pack): the two tables concatenated give
# the moduli of one run (the second table's start row repeats a row and is skipped)
loadtest --steps 3 -o half.pack fr.pack >h1.tsv 2>/dev/null
loadtest --steps 3 half.pack >h2.tsv 2>/dev/null
cat h1.tsv h2.tsv >h12.tsv
expect_ok "moduli reads two concatenated tables of a continued test" moduli h12.tsv
mv ok.out m12.tsv
expect_same "continued test: the moduli of one run" m1.tsv m12.tsv

# an isotropic path determines K only: G, lambda, E and nu are nan (README, hooke.h)
loadtest --path isotropic --steps 3 fr.pack >iso.tsv 2>/dev/null
expect_ok "isotropic curve" moduli iso.tsv
rows ok.out | awk -F '\t' '!($7 > 1e8 && $7 < 1e11) { bad = "row " NR ": K " $7 }
     $8 != "nan" || $9 != "nan" || $10 != "nan" || $11 != "nan" { bad = "row " NR ": G " $8 " lambda " $9 " E " $10 " nu " $11 }
     END { if (NR != 3) bad = NR " rows"; if (bad) { print bad; exit 1 } }' >why &&
    pass "isotropic: K, and nan for G lambda E nu" || fail "isotropic: K, and nan for G lambda E nu" "$(cat why)"

# --stress lw: the volume-averaged columns, the default.  The same table with the sig_ and
# sig_lw_ names swapped, fitted on the wall columns, must give the same moduli (columns 7-12;
# sigma_c and sig_lat of --stress wall are the table's own columns).
expect_ok "--stress lw" moduli --stress lw curve.tsv
mv ok.out lw.tsv
expect_same "--stress lw is the default" lw.tsv m1.tsv
sed '/^# /{ s/\tsig_xx/\tTMPxx/; s/\tsig_yy/\tTMPyy/; s/\tsig_zz/\tTMPzz/
	s/\tsig_lw_xx/\tsig_xx/; s/\tsig_lw_yy/\tsig_yy/; s/\tsig_lw_zz/\tsig_zz/
	s/\tTMPxx/\tsig_lw_xx/; s/\tTMPyy/\tsig_lw_yy/; s/\tTMPzz/\tsig_lw_zz/ }' curve.tsv >swapped.tsv
moduli --stress wall swapped.tsv | cut -f 7-14 >sw.cols 2>/dev/null
cut -f 7-14 lw.tsv >lw.cols
expect_same "--stress lw fits the sig_lw_ columns" lw.cols sw.cols
if ! cmp -s lw.tsv mw.tsv; then pass "--stress lw differs from the wall stresses"; else fail "--stress lw differs from the wall stresses" "same table"; fi

# The walls' friction: an isotropic probe of the frictional pack (grain-wall mu 0.3) and of the
# same dense pack frictionalized with --wall-mu 0.  With frictionless walls the two measures
# must agree: each grain's forces balance to the residual 1e-4 of its largest contact force,
# which bounds the difference of the wall and volume-averaged stresses far below 1e-3 of K
# (measured 4e-7 on 1000 grains).  With frictional walls the wall normal forces miss the load
# the walls' friction carries and overstate K (1.30 against 0.82 GPa on 1000 grains): more
# than 5 % apart here.
frictionalize --wall-mu 0 -o fr0.pack dense.pack 2>/dev/null
loadtest --path isotropic --steps 3 fr.pack >iso_fr.tsv 2>/dev/null
loadtest --path isotropic --steps 3 fr0.pack >iso_fr0.tsv 2>/dev/null
k_wall=$(moduli --window 3 --stress wall iso_fr.tsv 2>/dev/null | col /dev/stdin 1 7)
k_lw=$(moduli --window 3 --stress lw iso_fr.tsv 2>/dev/null | col /dev/stdin 1 7)
k0_wall=$(moduli --window 3 --stress wall iso_fr0.tsv 2>/dev/null | col /dev/stdin 1 7)
k0_lw=$(moduli --window 3 --stress lw iso_fr0.tsv 2>/dev/null | col /dev/stdin 1 7)
expect_num "frictionless walls: isotropic K from the walls ($k0_wall) = volume-averaged ($k0_lw) within 1e-3" "$(rel "$k0_wall" "$k0_lw")" "<" 1e-3
expect_num "frictional walls: isotropic K from the walls ($k_wall) above the volume-averaged ($k_lw) by more than 5 %" \
    "$(awk -v a="$k_wall" -v b="$k_lw" 'BEGIN { printf "%.17g", a / b - 1 }')" ">" 0.05
expect_num "the grains' K does not depend on the walls' friction: volume-averaged K within 10 % ($k_lw, $k0_lw)" "$(rel "$k_lw" "$k0_lw")" "<" 0.1

# --emt glass: five more columns, the bulk state at each interval's end (the bulk_ columns,
# grains a diameter off the walls: the medium the theory models) and the effective-medium
# moduli of emt.h computed here from E 70 GPa, nu 0.2
expect_ok "--emt glass" moduli --emt glass curve.tsv
mv ok.out emt.tsv
hdr17=$(printf '%s\tporosity\tcoordination\tK_emt[Pa]\tG_emt_rough[Pa]\tG_emt_smooth[Pa]\tK_se[Pa]\tG_se[Pa]' "$hdr")
if [ "$(head -n 1 emt.tsv)" = "$hdr17" ]; then pass "--emt: header"; else fail "--emt: header" "$(head -n 1 emt.tsv)"; fi
rows emt.tsv | cut -f 1-12 >emt12.rows
rows m1.tsv | cut -f 1-12 >m1.rows
expect_same "--emt: the first 12 columns unchanged" m1.rows emt12.rows
rows emt.tsv | cut -f 18-19 >emtse.rows
rows m1.tsv | cut -f 13-14 >m1se.rows
expect_same "--emt: the standard errors last (18-19), the same as without it (13-14)" m1se.rows emtse.rows
rows curve.tsv >curve.rows
rows emt.tsv | awk -F '\t' 'NR == FNR { phi[$1] = $21; z[$1] = $22; next }
	{ k = FNR; if (NF != 19) bad = "row " k ": " NF " columns"
	  if ($13 != phi[$3] || $14 != z[$3]) bad = "row " k ": porosity/coordination not those of inc " $3
	  pi = atan2(0, -1); nu = 0.2; mu = 70e9 / (2 * (1 + nu))
	  c = $14 * $14 * (1 - $13) ^ 2 * mu * mu * $5 / (pi * pi * (1 - nu) ^ 2)
	  K = (c / 18) ^ (1 / 3); Gr = (5 - 4 * nu) / (5 * (2 - nu)) * (1.5 * c) ^ (1 / 3)
	  if ((($15 - K) / K) ^ 2 > 1e-18 || (($16 - Gr) / Gr) ^ 2 > 1e-18 || (($17 - 0.6 * K) / K) ^ 2 > 1e-18) bad = "row " k ": K_emt " $15 " (" K ") G_rough " $16 " (" Gr ")" }
	END { if (FNR != 6) bad = FNR " rows"; if (bad) { print bad; exit 1 } }' curve.rows - >why &&
    pass "--emt glass: Hertz-Mindlin K and G at the interval's sigma_c, porosity, coordination" || fail "--emt glass: Hertz-Mindlin K and G at the interval's sigma_c, porosity, coordination" "$(cat why)"
moduli --emt quartz curve.tsv >q.tsv 2>/dev/null
expect_num "--emt quartz: stiffer grains, larger K_emt" "$(col q.tsv 1 15)" ">" "$(col emt.tsv 1 15)"

# --- hand-made tables from a known material -----------------------------------------------------
# K = 1.234567e9, G = 0.7654321e9.  Segment 1: uniaxial strain along z, de 1e-4 per row:
# dsig_xx = dsig_yy = (K - 2G/3) de, dsig_zz = (K + 4G/3) de.  Segment 2: a general strain
# increment (2e-5, -3e-5, 1e-4): dsig_ll = lambda tr + 2 G de_ll.  Segment 3: isotropic 1e-4.
K=1.234567e9
G=0.7654321e9
awk -v K=$K -v G=$G 'BEGIN {
	printf "# inc\tseg\teps_xx\teps_yy\teps_zz\tsig_xx[Pa]\tsig_yy[Pa]\tsig_zz[Pa]\tsigma_c[Pa]\tsig_lat[Pa]\n"
	l = K - 2 * G / 3; e[1] = e[2] = 0.002; e[3] = 0.01; s[1] = s[2] = 5e6; s[3] = 8e6
	out(0, 0)
	for (k = 1; k <= 6; k++) step(k, 1, 0, 0, 1e-4)
	for (k = 7; k <= 9; k++) step(k, 2, 2e-5, -3e-5, 1e-4)
	for (k = 10; k <= 12; k++) step(k, 3, 1e-4, 1e-4, 1e-4)
}
function step(k, sg, a, b, c,   tr) {
	tr = a + b + c; d[1] = a; d[2] = b; d[3] = c
	for (i = 1; i <= 3; i++) { e[i] += d[i]; s[i] += l * tr + 2 * G * d[i] }
	out(k, sg)
}
function out(k, sg) {
	printf "%d\t%d\t%.17g\t%.17g\t%.17g\t%.17g\t%.17g\t%.17g\t%.17g\t%.17g\n", k, sg, e[1], e[2], e[3], s[1], s[2], s[3], (s[1] + s[2] + s[3]) / 3, (s[1] + s[2]) / 2
}' >synth.tsv
expect_ok "moduli reads the hand-made table" moduli synth.tsv
mv ok.out syn1.tsv
expect_num "hand-made, --window 1: 12 rows" "$(rows syn1.tsv | wc -l)" "==" 12
rows syn1.tsv | awk -F '\t' -v K=$K -v G=$G '
	function bad_rel(a, b) { return ((a - b) / b) ^ 2 > 1e-12 }	# 6 digits
	{ l = K - 2 * G / 3; E = 9 * K * G / (3 * K + G); nu = (3 * K - 2 * G) / (2 * (3 * K + G)) }
	$1 < 3 && (bad_rel($7, K) || bad_rel($8, G) || bad_rel($9, l) || bad_rel($10, E) || bad_rel($11, nu) || !($12 < 1e-6)) {
		bad = "row " NR " (seg " $1 "): K " $7 " G " $8 " lambda " $9 " E " $10 " nu " $11 " fit_rel " $12 }
	$1 == 3 && (bad_rel($7, K) || $8 != "nan") { bad = "row " NR " (isotropic): K " $7 " G " $8 }
	END { if (bad) { print bad; exit 1 } }' >why &&
    pass "hand-made: K and G back to 6 digits in every interval (G nan when isotropic)" || fail "hand-made: K and G back to 6 digits in every interval (G nan when isotropic)" "$(cat why)"
expect_ok "hand-made, --window 6" moduli --window 6 synth.tsv
mv ok.out syn6.tsv
if [ "$(rows syn6.tsv | cut -f 1-4 | tr '\t\n' ', ')" = "1,0,6,6 2,6,9,3 3,9,12,3 " ]; then pass "hand-made, --window 6: one interval per segment"; else fail "hand-made, --window 6: one interval per segment" "$(rows syn6.tsv | cut -f 1-4 | tr '\t\n' ', ')"; fi
expect_num "hand-made, --window 6: K of the uniaxial segment" "$(rel "$(col syn6.tsv 1 7)" $K)" "<" 1e-6
expect_num "hand-made, --window 6: G of the uniaxial segment" "$(rel "$(col syn6.tsv 1 8)" $G)" "<" 1e-6
expect_num "hand-made, --window 6: G of the general segment" "$(rel "$(col syn6.tsv 2 8)" $G)" "<" 1e-6
expect_num "hand-made, --window 6: sigma_c is the mean of the end rows" "$(rel "$(col syn6.tsv 1 5)" "$(awk -v a="$(col synth.tsv 1 9)" -v b="$(col synth.tsv 7 9)" 'BEGIN { printf "%.17g", (a + b) / 2 }')")" "<" 1e-12
# the columns are found by name: other columns, in another order, change nothing
awk -F '\t' -v OFS='\t' '{ if (NR == 1) $1 = "inc"; x = $1; $1 = $8; $8 = x; print (NR == 1 ? "# " : "") $0 "\t" (NR == 1 ? "extra" : NR) }' synth.tsv >shuffled.tsv
expect_ok "columns in another order" moduli shuffled.tsv
rows ok.out >shuf.rows
rows syn1.tsv >syn1.rows
expect_same "columns in another order: the same moduli" syn1.rows shuf.rows

# --pool-segments: a probe's uniaxial segments along x, y and z fitted as one interval.  A
# hand-made anisotropic material (transversely isotropic about z: each axis's uniaxial
# increment gives a different one-axis G) whose one-axis fits give G_x = G_y and G_z; pooled,
# the least squares over the three gives the mean of the three (equal strain steps: the
# normal equations weight each axis's deviatoric part equally).  Lateral responses keep K.
awk 'BEGIN {
	printf "# inc\tseg\teps_xx\teps_yy\teps_zz\tsig_xx[Pa]\tsig_yy[Pa]\tsig_zz[Pa]\tsigma_c[Pa]\tsig_lat[Pa]\n"
	K = 1e9; Gx = 0.5e9; Gz = 0.2e9
	for (i = 1; i <= 3; i++) { e[i] = 0; s[i] = 4e6 }
	out(0, 0)
	k = 0
	for (a = 1; a <= 3; a++) for (q = 1; q <= 3; q++) {
		G = a == 3 ? Gz : Gx
		for (i = 1; i <= 3; i++) s[i] += (i == a ? K + 4 * G / 3 : K - 2 * G / 3) * 1e-4
		e[a] += 1e-4
		out(++k, a)
	}
}
function out(k, sg) { printf "%d\t%d\t%.17g\t%.17g\t%.17g\t%.17g\t%.17g\t%.17g\t%.17g\t%.17g\n", k, sg, e[1], e[2], e[3], s[1], s[2], s[3], (s[1] + s[2] + s[3]) / 3, (s[2] + s[3]) / 2 }' >probe.tsv
expect_ok "--pool-segments on a three-axis probe" moduli --window 9 --pool-segments probe.tsv
mv ok.out pool.tsv
v=$(rows pool.tsv | cut -f 2-4 | tr '\t\n' ', ')
if [ "$v" = "0,9,9 " ]; then pass "--pool-segments: one interval of 9 increments"; else fail "--pool-segments: one interval of 9 increments" "$v"; fi
expect_num "--pool-segments: G the mean of the axes' (0.4 GPa)" "$(rel "$(col pool.tsv 1 8)" 0.4e9)" "<" 1e-9
expect_num "--pool-segments: K unchanged (1 GPa)" "$(rel "$(col pool.tsv 1 7)" 1e9)" "<" 1e-9
expect_num "without it: three intervals, one per axis" "$(moduli --window 9 probe.tsv 2>/dev/null | rows /dev/stdin | wc -l)" "==" 3
expect_num "without it: G of the z probe is the z one (0.2 GPa)" "$(rel "$(moduli --window 9 probe.tsv 2>/dev/null | col /dev/stdin 3 8)" 0.2e9)" "<" 1e-9

# a negative G is no modulus: written as nan (with lambda, E, nu), K kept, and said on stderr
awk -F '\t' -v OFS='\t' 'NR == 1 { print; next } { k = $1; s = 4e6 + k * 1e-4 * (1e9 - 4 * 0.1e9 / 3); l = 4e6 + k * 1e-4 * (1e9 + 2 * 0.1e9 / 3)
	print k, 1, 0, 0, k * 1e-4, l, l, s, (2 * l + s) / 3, l }' probe.tsv >negG.tsv
moduli --window 9 negG.tsv >neg.tsv 2>neg.err
v="$(col neg.tsv 1 8) $(col neg.tsv 1 9) $(col neg.tsv 1 10) $(col neg.tsv 1 11)"
if [ "$v" = "nan nan nan nan" ]; then pass "negative G: G lambda E nu written as nan"; else fail "negative G: G lambda E nu written as nan" "$v"; fi
expect_num "negative G: K kept (1 GPa)" "$(rel "$(col neg.tsv 1 7)" 1e9)" "<" 1e-9
v="$(col neg.tsv 1 13) $(col neg.tsv 1 14)"
if is_number "${v% *}" && [ "${v#* }" = nan ]; then pass "negative G: G_se nan with G, K_se kept ($v)"; else fail "negative G: G_se nan with G, K_se kept" "$v"; fi
if grep -q '^moduli: negG\.tsv:11: increments 0-9: G = -1e+08 Pa is negative: no modulus, written as nan$' neg.err; then
	pass "negative G: one line on stderr"; else fail "negative G: one line on stderr" "$(cat neg.err)"; fi

# --- standard errors ----------------------------------------------------------------------------
# ls_ref TABLE WINDOW PREFIX: per interval, "K G K_se G_se" of the least squares of
# ds_ll = K tr(de) + 2 G (de_ll - tr(de)/3) done here from the table's eps_ and PREFIX_ columns,
# by the 2x2 normal equations (no orthogonality assumed): s^2 = chisq / (3m - p) and
# se_j = sqrt(s^2 [(X^T X)^-1]_jj); a column whose sum of squares is below 1e-18 of the other's
# is left out (moduli's rule), its modulus and standard error nan.  Intervals: WINDOW
# increments within a segment, the increment into a row in that row's segment (moduli(1)).
ls_ref() {
	awk -F '\t' -v W="$2" -v P="$3" '
	/^# / { sub(/^# /, ""); for (i = 1; i <= NF; i++) { c = $i; sub(/\[.*\]$/, "", c); ix[c] = i }; next }
	/^#/ { next }
	{ r++; sg[r] = ("seg" in ix) ? $ix["seg"] : 0
	  for (a = 1; a <= 3; a++) { e[r, a] = $ix["eps_" ax(a)]; s[r, a] = $ix[P "_" ax(a)] } }
	function ax(a) { return a == 1 ? "xx" : a == 2 ? "yy" : "zz" }
	END { m = 0
	  for (q = 2; q <= r; q++) {
		m++; for (a = 1; a <= 3; a++) { de[m, a] = e[q, a] - e[q - 1, a]; ds[m, a] = s[q, a] - s[q - 1, a] }
		if (m == W || q == r || sg[q + 1] != sg[q]) { fit(m); m = 0 }
	  } }
	function fit(m,   k, a, tr, x1, x2, A11, A12, A22, b1, b2, det, K, G, chi, y, big, hk, hg, p, s2, Kse, Gse) {
		for (k = 1; k <= m; k++) { tr = de[k, 1] + de[k, 2] + de[k, 3]
			for (a = 1; a <= 3; a++) { x1 = tr; x2 = 2 * (de[k, a] - tr / 3); y = ds[k, a]
				A11 += x1 * x1; A12 += x1 * x2; A22 += x2 * x2; b1 += x1 * y; b2 += x2 * y } }
		big = A11 > A22 ? A11 : A22; hk = A11 > 1e-18 * big; hg = A22 > 1e-18 * big
		K = G = Kse = Gse = "nan"
		if (hk && hg) { det = A11 * A22 - A12 * A12; K = (A22 * b1 - A12 * b2) / det; G = (A11 * b2 - A12 * b1) / det; p = 2 }
		else if (hk) { K = b1 / A11; p = 1 } else { G = b2 / A22; p = 1 }
		for (k = 1; k <= m; k++) { tr = de[k, 1] + de[k, 2] + de[k, 3]
			for (a = 1; a <= 3; a++) { y = ds[k, a] - (hk ? K * tr : 0) - (hg ? G * 2 * (de[k, a] - tr / 3) : 0); chi += y * y } }
		s2 = chi / (3 * m - p)
		if (hk && hg) { Kse = sqrt(s2 * A22 / det); Gse = sqrt(s2 * A11 / det) }
		else if (hk) Kse = sqrt(s2 / A11); else Gse = sqrt(s2 / A22)
		printf "%.17g\t%.17g\t%.17g\t%.17g\n", K, G, Kse, Gse }' "$1"
}
# se_cmp NAME MODULI_TABLE REF: columns K G K_se G_se (7 8 13 14) of every row against ls_ref's,
# to 1e-9 relative (both are double least squares of the same numbers: their round-off differs
# by far less, and a standard error off by a factor sqrt((3m - 1)/(3m - 2)) or more, a wrong
# degree-of-freedom count, is 2 % at m = 9); nan must match nan
se_cmp() {
	rows "$2" | cut -f 7,8,13,14 | paste - "$3" | awk -F '\t' '
	function off(a, b) { if (a == "nan" || b == "nan") return a != b; return ((a - b) / b) ^ 2 > 1e-18 }
	{ for (j = 1; j <= 4; j++) if (off($j, $(j + 4))) bad = "row " NR ": " $0 }
	END { if (NR == 0) bad = "no rows"; if (bad) { print bad; exit 1 } }' >why &&
	    pass "$1" || fail "$1" "$(cat why)"
}
# (a) a hand-made table off Hooke's law by a known perturbation: K = 1.234567e9, G = 0.7654321e9,
# each stress component moved by 2e3 sin(3k + l) Pa (the increments are about 1e5 Pa).  Segment 1:
# 6 general strain increments (all components varying); segment 2: 4 isotropic ones (K only).
awk -v K=$K -v G=$G 'BEGIN {
	printf "# inc\tseg\teps_xx\teps_yy\teps_zz\tsig_xx[Pa]\tsig_yy[Pa]\tsig_zz[Pa]\tsigma_c[Pa]\tsig_lat[Pa]\n"
	l = K - 2 * G / 3; e[1] = e[2] = 0.002; e[3] = 0.01; s[1] = s[2] = 5e6; s[3] = 8e6
	out(0, 0)
	for (k = 1; k <= 6; k++) step(k, 1, 1e-5 * k, -2e-5 + 1e-5 * (k % 3), 1e-4 - 5e-6 * k)
	for (k = 7; k <= 10; k++) step(k, 2, 1e-4, 1e-4, 1e-4)
}
function step(k, sg, a, b, c,   tr) {
	tr = a + b + c; d[1] = a; d[2] = b; d[3] = c
	for (i = 1; i <= 3; i++) { e[i] += d[i]; s[i] += l * tr + 2 * G * d[i] + 2e3 * sin(3 * k + i) }
	out(k, sg)
}
function out(k, sg) {
	printf "%d\t%d\t%.17g\t%.17g\t%.17g\t%.17g\t%.17g\t%.17g\t%.17g\t%.17g\n", k, sg, e[1], e[2], e[3], s[1], s[2], s[3], (s[1] + s[2] + s[3]) / 3, (s[1] + s[2]) / 2
}' >pert.tsv
for w in 1 3 6; do
	moduli --window $w pert.tsv >pert$w.tsv 2>/dev/null
	ls_ref pert.tsv $w sig >pert$w.ref
	se_cmp "perturbed hand-made, --window $w: K, G, K_se, G_se = least squares in awk (1e-9)" pert$w.tsv pert$w.ref
done
# the perturbation shows: standard errors well above round-off, K's below K
expect_num "perturbed, --window 6: K_se of the general segment, above round-off (K 1.23e9)" "$(col pert6.tsv 1 13)" ">" 1e3
expect_num "perturbed, --window 6: G_se of the general segment, above round-off" "$(col pert6.tsv 1 14)" ">" 1e3
expect_num "perturbed, --window 6: K_se below 5 % of K" "$(col pert6.tsv 1 13)" "<" "$(awk -v K=$K 'BEGIN { print 0.05 * K }')"
v=$(rows pert3.tsv | awk -F '\t' '$1 == 2 { printf "%s,", $14 }')
if [ "$v" = "nan,nan," ]; then pass "perturbed, isotropic segment: G_se nan (no G)"; else fail "perturbed, isotropic segment: G_se nan (no G)" "$v"; fi
# (b) increments exactly on Hooke's law (synth.tsv): standard errors at round-off, below 1e-9
# of K (the stresses are differenced from values near 5e6 Pa: 1e-9 Pa of round-off in a 1e5 Pa
# increment gives a standard error near 1e-14 of K)
rows syn1.tsv | awk -F '\t' -v K=$K '
	$13 == "nan" || !($13 >= 0 && $13 < 1e-9 * K) { bad = "row " NR ": K_se " $13 }
	$1 < 3 && ($14 == "nan" || !($14 >= 0 && $14 < 1e-9 * K)) { bad = "row " NR ": G_se " $14 }
	$1 == 3 && $14 != "nan" { bad = "row " NR " (isotropic): G_se " $14 }
	END { if (NR != 12) bad = NR " rows"; if (bad) { print bad; exit 1 } }' >why &&
    pass "exactly on Hooke's law: K_se, G_se below 1e-9 of K (G_se nan when isotropic)" ||
    fail "exactly on Hooke's law: K_se, G_se below 1e-9 of K (G_se nan when isotropic)" "$(cat why)"
v=$(rows syn6.tsv | awk -F '\t' '{ printf "%s:%.3g:%.3g ", $1, $13 / '"$K"', $14 / '"$K"' }')
rows syn6.tsv | awk -F '\t' -v K=$K '!($13 < 1e-9 * K) || ($1 < 3 && !($14 < 1e-9 * K)) { bad = 1 } END { exit bad }' &&
    pass "exactly on Hooke's law, --window 6: K_se, G_se below 1e-9 of K ($v)" ||
    fail "exactly on Hooke's law, --window 6: K_se, G_se below 1e-9 of K" "$v"
# (c) the loadtest curve of the frictional pack: K_se and G_se the same least squares of its
# volume-averaged stresses, finite and positive (the pack is no isotropic Hooke's solid: its
# lateral stresses differ, fit_rel about 1 %) and well below K and G (under 5 %: about 1 %
# measured with one increment per interval, one degree of freedom)
for w in 1 3; do
	moduli --window $w curve.tsv >real$w.tsv 2>/dev/null
	ls_ref curve.tsv $w sig_lw >real$w.ref
	se_cmp "loadtest curve, --window $w: K, G, K_se, G_se = least squares in awk (1e-9)" real$w.tsv real$w.ref
	rows real$w.tsv | awk -F '\t' '!($13 > 0 && $13 < 0.05 * $7 && $14 > 0 && $14 < 0.05 * $8) { bad = "row " NR ": K " $7 " K_se " $13 " G " $8 " G_se " $14 }
	    END { if (NR == 0) bad = "no rows"; if (bad) { print bad; exit 1 } }' >why &&
	    pass "loadtest curve, --window $w: 0 < K_se < 5 % of K, 0 < G_se < 5 % of G" ||
	    fail "loadtest curve, --window $w: 0 < K_se < 5 % of K, 0 < G_se < 5 % of G" "$(cat why)"
done

# --- errors -----------------------------------------------------------------------------------
# expect_fail NAME STATUS REGEX ARGS...: moduli ARGS -o nothing.tsv, as expect_error, and no
# nothing.tsv nor a temporary file left
expect_fail() {
	n=$1 st=$2 re=$3
	shift 3
	expect_refused "no output file" nothing.tsv "$n" "$st" "$re" moduli "$@" -o nothing.tsv
}
cut -f 1-6,8- synth.tsv >nosigyy.tsv
expect_fail "a missing column" 1 "^moduli: nosigyy\.tsv: no column 'sig_yy'" nosigyy.tsv
cp synth.tsv in.tsv
expect_error "-o the input" 2 "^moduli: -o 'in.tsv' is the input" moduli -o in.tsv in.tsv
expect_same "-o the input: the input untouched" in.tsv synth.tsv
expect_error "-o in a missing directory" 2 "^moduli: -o: cannot write in directory 'no-such-dir'" moduli -o no-such-dir/x.tsv synth.tsv
awk 'NR == 4 { held = $0; next } { print } NR == 5 { print held }' synth.tsv >order.tsv
expect_fail "rows out of order" 1 '^moduli: order\.tsv:5: rows out of order' order.tsv
# a pack where a table belongs is named as such (it said only "no header line"; issue 19)
packgen -n 20 --seed 1 -o apack.pack 2>/dev/null
expect_fail "a pack instead of a table" 1 "^moduli: apack\.pack:1: a qusgm pack, not a table" apack.pack
awk -F '\t' -v OFS='\t' 'NR == 6 { $4 = "0.00.1" } { print }' synth.tsv >malformed.tsv
expect_fail "a malformed number" 1 "^moduli: malformed\.tsv:6: column eps_yy: '0\.00\.1' is not a number" malformed.tsv
awk -F '\t' -v OFS='\t' 'NR == 6 { $6 = "nan" } { print }' synth.tsv >nan.tsv
expect_fail "a nan stress" 1 '^moduli: nan\.tsv:6: .*finite' nan.tsv
awk -F '\t' -v OFS='\t' 'NR == 6 { NF = 9 } { print }' synth.tsv >short.tsv
expect_fail "a short row" 1 '^moduli: short\.tsv:6: ' short.tsv
head -n 2 synth.tsv >onerow.tsv
expect_fail "one row" 1 '^moduli: onerow\.tsv: .*at least two' onerow.tsv
tail -n +2 synth.tsv >nohdr.tsv
expect_fail "no header" 1 '^moduli: nohdr\.tsv:1: ' nohdr.tsv
printf '%s' "$(cat synth.tsv)" >nonl.tsv
expect_fail "last line without newline" 1 '^moduli: nonl\.tsv:14: ' nonl.tsv
# a header with no columns ('# ') and rows under it: refused at the first row (257 empty rows
# used to grow the row store to size 0 and abort with a double free)
{ printf '# \n'; awk 'BEGIN { for (i = 0; i < 300; i++) print "" }'; } >nocols.tsv
expect_fail "rows under a header with no columns" 1 '^moduli: nocols\.tsv:2: a row under a header with no columns$' nocols.tsv
expect_fail "--emt without porosity column" 1 '^moduli: synth\.tsv: --emt needs the porosity' --emt glass synth.tsv
expect_fail "missing input file" 1 '^moduli: .*no-such\.tsv' no-such.tsv
# a table written with spaces for tabs: say the columns are TAB-separated, not quote the whole
# header as one column name (issue 19)
tr '\t' ' ' <synth.tsv >spaces.tsv
expect_fail "spaces for tabs" 1 '^moduli: spaces\.tsv:[0-9]+: .*columns are TAB-separated$' spaces.tsv
# a window longer than the table is refused with both numbers, not fitted as one interval
nr=$(rows synth.tsv | wc -l)
expect_fail "--window longer than the table" 1 "^moduli: synth\.tsv: --window 1000 is longer than the table's $((nr - 1)) increments \($nr rows\)$" --window 1000 synth.tsv
expect_fail "--window 0" 2 '^moduli: --window' --window 0 synth.tsv
expect_fail "--window nan" 2 '^moduli: --window' --window nan synth.tsv
expect_fail "--stress bogus" 2 '^moduli: --stress' --stress bogus synth.tsv
expect_fail "--emt unobtainium" 2 '^moduli: --emt' --emt unobtainium synth.tsv
expect_fail "unknown option" 2 "^moduli: unknown option '--bogus'" --bogus synth.tsv
# a failed run leaves an existing -o file alone
echo keep >old.tsv
moduli -o old.tsv order.tsv >/dev/null 2>&1
moduli --window 0 -o old.tsv synth.tsv >/dev/null 2>&1
if [ "$(cat old.tsv)" = keep ] && ! ls -a | grep -q '^\.old'; then pass "failed runs do not clobber -o"; else fail "failed runs do not clobber -o" "changed or temp left"; fi

# --- help, version ------------------------------------------------------------------------------
expect_help_version moduli --window --emt
