# SPDX-License-Identifier: GPL-3.0-or-later
# dissociate on a small hydrate-bearing quartz pack (packgen --hydrate-volume 0.15, 200 grains,
# densify --stress 4e6), frictionless unless said: nothing asked changes nothing; the probe's K
# against loadtest's isotropic unloading step; p_ex alone lowers the effective stress by about
# alpha_b p_ex; dS alone lowers S by dS exactly; a frictional pack; the refusals.  The rules
# against hand-computed radii and the box against alpha_b p_ex / K are test_dissociate's.
# About 5 s.
. "$TOP/tests/tools/lib.sh"

packgen -n 200 --seed 5 --material quartz --hydrate-volume 0.15 -o loose.pack 2>/dev/null
expect_ok "densify the hydrate pack" densify --stress 4e6 -o hyd.pack loose.pack
meta() { awk -v k="$2" '$1 == "meta" && $2 == k { print $3 } /^end/ { exit }' "$1"; }
lw_mean() { packinfo "$1" | awk '$1 ~ /^sig_lw_(xx|yy|zz)$/ { s += $2 } END { printf "%.17g", s / 3 }'; }

# --- nothing asked, nothing changed --------------------------------------------------------
expect_ok "dS 0, p_ex 0" dissociate -o same.pack hyd.pack
grep -v '^history' hyd.pack >a.txt
grep -v '^history' same.pack >b.txt
expect_same "dS 0 and p_ex 0: the pack byte for byte but the history" a.txt b.txt
expect_num "... and one history line more" "$(grep -c '^history' same.pack)" "==" "$(($(grep -c '^history' hyd.pack) + 1))"
grep -q '^history dissociate' same.pack && pass "the history line is dissociate's" || fail "the history line is dissociate's" "$(grep '^history' same.pack | tail -n 1)"

# --- the probe's K: loadtest's isotropic extension of 1e-5 per axis from the same pack -------
# loadtest's step is against the reference lengths, the probe's against the current ones:
# per axis de / (1 - eps), eps the pack's strain against its reference box.  Tolerance 2 %:
# the two steps differ by those factors (0.1-0.3 %), each stress is an equilibrium to 1e-4 of
# the forces, and an error of convention is a factor (3 for a linear strain, 20-50 % for the
# wall stress)
expect_ok "p_ex 2e5 (probe)" dissociate --mu 0 --pex 2e5 -o p.pack hyd.pack
loadtest --mu 0 --path isotropic --strain-step -1e-5 --steps 1 hyd.pack >iso.tsv 2>/dev/null
kiso=$(sh "$TOP/pipelines/cols.sh" iso.tsv eps_xx eps_yy eps_zz sig_lw_xx sig_lw_yy sig_lw_zz | awk '
	{ m = ($4 + $5 + $6) / 3 }
	NR == 1 { m0 = m; for (a = 1; a <= 3; a++) e0[a] = $a }
	NR == 2 { d = 0; for (a = 1; a <= 3; a++) d += (e0[a] - $a) / (1 - e0[a]); printf "%.17g", (m0 - m) / d }')
expect_num "probe K against loadtest's isotropic step (rel. difference < 0.02)" "$(rel "$(meta p.pack dissociation_K)" "$kiso")" "<" 0.02
[ "$(meta p.pack dissociation_K_from)" = probe ] && pass "meta dissociation_K_from probe" || fail "meta dissociation_K_from probe" "$(meta p.pack dissociation_K_from)"
# the box: eps_kk = alpha_b p_ex / K with the K recorded
expect_num "eps_kk = 0.8 p_ex / K" "$(rel "$(meta p.pack dissociation_eps_kk)" "$(awk -v k="$(meta p.pack dissociation_K)" 'BEGIN { printf "%.17g", 0.8 * 2e5 / k }')")" "<" 1e-12
# the effective stress: before is the pack's, after the written pack's
expect_num "effective stress before = the pack's volume-averaged stress" "$(rel "$(meta p.pack effective_stress_before)" "$(lw_mean hyd.pack)")" "<" 1e-9
expect_num "effective stress after = the written pack's" "$(rel "$(meta p.pack effective_stress_after)" "$(lw_mean p.pack)")" "<" 1e-9
# drop / (alpha_b p_ex) in [0.98, 1.10]: Hertz unloading is softer than the tangent K by about
# drop / (6 sigma) (0.7 % here) and the probe is good to about 1 %, which bound it below; the
# grains' own compression adds up to K / (alpha_b K_i) of the softest (hydrate: 7.8 %) above
drop=$(awk -v a="$(meta p.pack effective_stress_before)" -v b="$(meta p.pack effective_stress_after)" 'BEGIN { printf "%.6g", (a - b) / (0.8 * 2e5) }')
expect_num "p_ex alone: drop / (alpha_b p_ex) >= 0.98" "$drop" ">=" 0.98
expect_num "p_ex alone: drop / (alpha_b p_ex) <= 1.10" "$drop" "<=" 1.10
expect_num "total stress after = effective after + alpha_b p_ex" \
    "$(rel "$(meta p.pack total_stress_after)" "$(awk -v s="$(meta p.pack effective_stress_after)" 'BEGIN { printf "%.17g", s + 0.8 * 2e5 }')")" "<" 1e-12
expect_num "p_ex: the written pack is an equilibrium (packinfo residual <= 1e-4)" \
    "$(packinfo p.pack | awk '$1 == "residual" { print $2 }')" "<=" 1e-4
expect_ok "--K given: no probe" dissociate --mu 0 --pex 2e5 --K 4e8 -o k.pack hyd.pack
[ "$(meta k.pack dissociation_K_from)" = given ] && pass "meta dissociation_K_from given" || fail "meta dissociation_K_from given" "$(meta k.pack dissociation_K_from)"

# --- dS alone: S falls by dS exactly (box and mineral unchanged) -----------------------------
S0=$(packinfo hyd.pack | awk '$1 == "hydrate_saturation" { print $2 }')
expect_num "the pack has hydrate (S > 0.1)" "$S0" ">" 0.1
expect_ok "dS -0.01" dissociate --mu 0 --dS -0.01 -o s.pack hyd.pack
S1=$(packinfo s.pack | awk '$1 == "hydrate_saturation" { print $2 }')
expect_num "dS alone: S' = S + dS (packinfo)" "$(rel "$S1" "$(awk -v s="$S0" 'BEGIN { printf "%.17g", s - 0.01 }')")" "<" 1e-9
expect_num "dS alone: the effective stress falls" "$(lw_mean s.pack)" "<" "$(lw_mean hyd.pack)"
# the mineral grains keep their radii; the hydrate grains' volumes all fall by dS / S
awk '/^end/ { g = 1; next } g && NF == 9 { print $1, $5, $9 }' hyd.pack | sort -n >r0
awk '/^end/ { g = 1; next } g && NF == 9 { print $1, $5, $9 }' s.pack | sort -n >r1
bad=$(join r0 r1 | awk -v f="$(awk -v s="$S0" 'BEGIN { printf "%.17g", 1 - 0.01 / s }')" '
	$3 == 0 && $2 != $4 { n++ }
	$3 == 1 { q = ($4 / $2) ^ 3 / f - 1; if (q < 0) q = -q; if (q > 1e-13) n++ }
	END { print n + 0 }')
expect_num "dS alone: mineral radii unchanged, hydrate volumes times 1 + dS/S" "$bad" "==" 0
expect_ok "from stdin to stdout" sh -c 'dissociate --mu 0 --dS -0.01 <hyd.pack >s2.pack'
expect_same "stdin and FILE give the same pack but the history" "$(grep -v '^history' s.pack >s1.txt; echo s1.txt)" "$(grep -v '^history' s2.pack >s2.txt; echo s2.txt)"

# --- frictional: the pack's friction and history -------------------------------------------
frictionalize --max-inc 10 --min-inc 10 --window 2 --window-overlap 0 --allow-limit -o fr.pack hyd.pack 2>/dev/null
expect_ok "dissociate a frictional pack (dS -0.01, p_ex 2e5)" dissociate --dS -0.01 --pex 2e5 -o frd.pack fr.pack
expect_num "frictional: the effective stress falls" "$(meta frd.pack effective_stress_after)" "<" "$(meta frd.pack effective_stress_before)"
expect_num "frictional: the written pack is an equilibrium of its history (packinfo residual <= 1e-4)" \
    "$(packinfo frd.pack | awk '$1 == "residual" { print $2 }')" "<=" 1e-4

# --- refusals --------------------------------------------------------------------------------
expect_error "dS > 0 refused" 2 '^dissociate: --dS: must be <= 0' dissociate --dS 0.01 hyd.pack
expect_error "p_ex < 0 refused" 2 '^dissociate: --pex: must be >= 0' dissociate --pex -1 hyd.pack
cp hyd.pack in.pack
# -o the input: the pack updated in place (read whole, then renamed over it)
dissociate --mu 0 -o ref.pack in.pack 2>/dev/null
expect_ok "-o the input: allowed" dissociate --mu 0 -o in.pack in.pack
expect_same "-o the input: the pack updated in place, as -o another file" in.pack ref.pack
expect_error "dS <= -S refused, naming the file and S" 1 "^dissociate: hyd.pack: --dS -0.9: the pack's hydrate saturation is 0\\.[0-9]+; dS must be above -S" \
    dissociate --mu 0 --dS -0.9 hyd.pack
packgen -n 200 --seed 5 --material quartz -o plain.loose 2>/dev/null
densify --stress 4e6 -o plain.pack plain.loose 2>/dev/null
expect_error "dS < 0 without hydrate refused" 1 '^dissociate: plain.pack: --dS -0.01: the pack has no hydrate grains' dissociate --mu 0 --dS -0.01 plain.pack
expect_error "a loose pack (no reference box) refused" 1 '^dissociate: loose.pack: no reference box' dissociate --pex 1e5 loose.pack
rm -f none.pack
dissociate --mu 0 --dS -0.9 -o none.pack hyd.pack 2>/dev/null
[ ! -e none.pack ] && pass "a refused run writes no -o" || fail "a refused run writes no -o" "none.pack exists"
expect_ok "p_ex alone on a pack without hydrate" dissociate --mu 0 --pex 2e5 -o plainp.pack plain.pack
