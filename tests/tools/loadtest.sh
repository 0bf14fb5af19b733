# SPDX-License-Identifier: GPL-3.0-or-later
# loadtest as a user runs it, on a small frictional pack (200 grains: packgen, densify --stress
# 4e6, frictionalize): the table's header and rows, a test split in two runs through the -o
# pack against one run (the friction history must survive), a loading-unloading cycle with
# hysteresis, the isotropic, triaxial (held lateral stress), polyaxial paths, --mu 0,
# --to-stress, a target out of reach, and the errors.  A few seconds in all.
. "$TOP/tests/tools/lib.sh"

# columns: 1 inc, 2 seg, 3-5 eps, 6-8 sig, 9-11 sig_lw, 12 sigma_c, 13 sig_lat, 14 porosity,
# 15 coordination, 16 sliding_ratio, 17 trial_slip_ratio, 18 iterations, 19 residual, 20 res_mean, 21 bulk_porosity, 22 bulk_coordination

small_pack frictional "frictionalize makes the frictional pack"
packinfo fr.pack >fr.txt 2>/dev/null
s0=$(info_value fr.txt sigma_c)

# --- one run of 6 increments ---------------------------------------------------------------
loadtest --steps 6 -o six.pack fr.pack >six.tsv 2>six.err
rc=$?
if [ "$rc" -eq 0 ] && [ ! -s six.err ]; then pass "loadtest --steps 6: exit 0, quiet"; else fail "loadtest --steps 6: exit 0, quiet" "exit $rc: $(head -c 300 six.err)"; fi
grep -q '^## path: uniaxial .*step=0.0001 steps=6$' six.tsv && pass "## path line" || fail "## path line" "$(grep '^## path' six.tsv)"
grep -q '^## equilibrium: residual <= 0.0001 .*method lbfgs' six.tsv && pass "## equilibrium line" || fail "## equilibrium line" "$(grep '^## equil' six.tsv)"
grep -q '^## friction: mu 0.3, wall_mu 0.3, rule return-map$' six.tsv && pass "## friction line" || fail "## friction line" "$(grep '^## fric' six.tsv)"
hdr=$(printf '# inc\tseg\teps_xx\teps_yy\teps_zz\tsig_xx[Pa]\tsig_yy[Pa]\tsig_zz[Pa]\tsig_lw_xx[Pa]\tsig_lw_yy[Pa]\tsig_lw_zz[Pa]\tsigma_c[Pa]\tsig_lat[Pa]\tporosity\tcoordination\tsliding_ratio\ttrial_slip_ratio\titerations\tresidual\tres_mean\tbulk_porosity\tbulk_coordination')
if [ "$(grep -v '^##' six.tsv | head -n 1)" = "$hdr" ]; then pass "column header"; else fail "column header" "$(grep -v '^##' six.tsv | head -n 1)"; fi
if [ "$(grep -c '^##' six.tsv)" -ge 3 ] && [ "$(head -n 1 six.tsv | cut -c 1-2)" = "##" ] && [ "$(grep -c '^# ' six.tsv)" -eq 1 ]; then
	pass "## lines first, one column header"
else
	fail "## lines first, one column header" "$(head -n 3 six.tsv)"
fi
# the starting row (inc 0, seg 0, 0 iterations: the pack as read), then 6 increments of
# segment 1, 19 columns, 1e-4 more eps_zz each, lateral strains fixed
expect_num "--steps 6: start row + 6 rows" "$(rows six.tsv | wc -l)" "==" 7
rows six.tsv | awk -F '\t' '{ k = NR - 1; if (NF != 22) bad = "row " NR ": " NF " columns"
	if (!($21 < $14 && $22 > $15)) bad = "row " NR ": bulk porosity " $21 " (box " $14 "), bulk coordination " $22 " (box " $15 ")" }
     $1 != k { bad = "row " NR ": inc " $1 }
     k == 0 && !($2 == 0 && $18 == 0) { bad = "start row: seg " $2 ", iterations " $18 }
     k > 0 && !($2 == 1 && $18 > 0 && $19 <= 1e-4) { bad = "row " NR ": seg " $2 ", iterations " $18 ", residual " $19 }
     k > 0 { d = $5 - z; if (d < 0.99e-4 || d > 1.01e-4 || $3 != x || $4 != y) bad = "row " NR ": not a 1e-4 uniaxial z step" }
     k > 0 && !($8 > sz && $12 > sc) { bad = "row " NR ": stress did not grow" }
     { x = $3; y = $4; z = $5; sz = $8; sc = $12 }
     END { if (bad) { print bad; exit 1 } }' >why && pass "rows: uniaxial z steps of 1e-4, stress grows" || fail "rows: uniaxial z steps of 1e-4, stress grows" "$(cat why)"
expect_num "start row is the pack as read: sigma_c" "$(rel "$(col six.tsv 1 12)" "$s0")" "<" 1e-9
expect_num "start row is the pack as read: sliding_ratio" "$(col six.tsv 1 16)" "==" "$(info_value fr.txt sliding_ratio)"
expect_num "friction slides in the rows" "$(col six.tsv 7 16)" ">" 0
expect_num "start row is the pack as read: trial_slip_ratio" "$(col six.tsv 1 17)" "==" "$(info_value fr.txt trial_slip_ratio)"
# most contacts slip a little while their normal force rises; few end at their limit
expect_num "the trial slips outnumber the contacts at their limit" "$(col six.tsv 7 17)" ">" "$(col six.tsv 7 16)"
packinfo six.pack >six.txt 2>/dev/null
expect_num "-o pack: packinfo residual" "$(info_value six.txt residual)" "<=" 1e-4
expect_num "-o pack: its sigma_c is the last row's" "$(rel "$(info_value six.txt sigma_c)" "$(col six.tsv 7 12)")" "<" 1e-9
expect_num "-o pack: its sliding_ratio is the last row's" "$(info_value six.txt sliding_ratio)" "==" "$(col six.tsv 7 16)"
grep -q '^meta increments 6$' six.pack && pass "-o pack: meta increments 6" || fail "-o pack: meta increments 6" "$(grep '^meta' six.pack | tr '\n' ' ')"
grep -q '^history loadtest ' six.pack && pass "-o pack: history line" || fail "-o pack: history line" "none"

# the same command gives the same bytes
loadtest --steps 6 fr.pack >six2.tsv 2>/dev/null
loadtest --steps 6 fr.pack >six3.tsv 2>/dev/null
expect_same "same input, same table" six2.tsv six3.tsv
rows six.tsv >six.rows
rows six2.tsv >six2.rows
expect_same "-o does not change the rows" six.rows six2.rows
cat fr.pack | loadtest --steps 6 >six4.tsv 2>/dev/null
expect_same "stdin gives the same table" six2.tsv six4.tsv

# --- a split run repeats one run to the last digit -----------------------------------------
loadtest --steps 3 -o a.pack fr.pack >a.tsv 2>a.err
rc1=$?
loadtest --steps 3 a.pack >b.tsv 2>b.err
rc2=$?
if [ "$rc1" -eq 0 ] && [ "$rc2" -eq 0 ]; then pass "split run: both halves exit 0"; else fail "split run: both halves exit 0" "exit $rc1, $rc2: $(cat a.err b.err | head -c 300)"; fi
grep -q '^meta increments 3$' a.pack && pass "split run: a.pack records 3 increments" || fail "split run: a.pack records 3 increments" "$(grep '^meta' a.pack | tr '\n' ' ')"
packinfo a.pack >a.txt 2>/dev/null
expect_num "split run: a.pack carries sliding history" "$(info_value a.txt sliding_ratio)" ">" 0
# the second run starts with a row repeating the state reached (seg 0, inc 3), then inc 4..6
expect_num "split run: second half has start row + 3 rows" "$(rows b.tsv | wc -l)" "==" 4
if [ "$(col b.tsv 1 1)" = 3 ] && [ "$(col b.tsv 1 2)" = 0 ]; then pass "split run: second half starts at inc 3, seg 0"; else fail "split run: second half starts at inc 3, seg 0" "inc $(col b.tsv 1 1) seg $(col b.tsv 1 2)"; fi
if [ "$(col b.tsv 1 1)-$(rows b.tsv | cut -f 3-17 | head -n 1)" = "$(col a.tsv 4 1)-$(rows a.tsv | cut -f 3-17 | sed -n 4p)" ]; then
	pass "split run: the start row repeats the state the first half ended in"
else
	fail "split run: the start row repeats the state the first half ended in" "rows differ"
fi
{ rows a.tsv; rows b.tsv; } | awk -F '\t' '$2 != 0' >split.rows
rows six.tsv | awk -F '\t' '$2 != 0' >one.rows
expect_same "split run (3 + 3) gives the rows of one run (6), every digit" one.rows split.rows
# the control: the same continuation with the tangential history erased differs, so the
# check above sees the history
awk '/^end$/ { on = 1; print; next } on && NF == 7 { $4 = $5 = $6 = $7 = 0 } { print }' a.pack >nohist.pack
loadtest --steps 3 nohist.pack 2>/dev/null | awk -F '\t' '!/^#/ && $2 != 0' >nohist.rows
rows b.tsv | awk -F '\t' '$2 != 0' >b.rows
if [ -s nohist.rows ] && ! cmp -s nohist.rows b.rows; then pass "control: without its Q0, M0 history the continuation differs"; else fail "control: without its Q0, M0 history the continuation differs" "same rows"; fi

# --- a loading-unloading cycle in one command ----------------------------------------------
cycle='uniaxial steps=3; uniaxial step=-1e-4 steps=3'
expect_ok "cycle runs" loadtest --path "$cycle" fr.pack
mv ok.out cyc.tsv
grep -q '^## path: uniaxial .*step=0.0001 steps=3; uniaxial .*step=-0.0001 steps=3$' cyc.tsv && pass "cycle: ## path names both segments" || fail "cycle: ## path names both segments" "$(grep '^## path' cyc.tsv)"
rows cyc.tsv | awk -F '\t' '{ k = NR - 1; want = k == 0 ? 0 : k <= 3 ? 1 : 2; if ($1 != k || $2 != want) bad = "row " NR ": inc " $1 " seg " $2 } END { if (NR != 7) bad = NR " rows"; if (bad) { print bad; exit 1 } }' >why &&
    pass "cycle: rows 1-3 segment 1, 4-6 segment 2" || fail "cycle: rows 1-3 segment 1, 4-6 segment 2" "$(cat why)"
expect_num "cycle: eps_zz back at its start" "$(awk -v a="$(col cyc.tsv 7 5)" -v b="$(col cyc.tsv 1 5)" 'BEGIN { d = a - b; print d < 0 ? -d : d }')" "<" 1e-12
expect_num "cycle: eps_zz turned at +3e-4" "$(awk -v a="$(col cyc.tsv 4 5)" -v b="$(col cyc.tsv 1 5)" 'BEGIN { print a - b }')" ">" 2.99e-4
# hysteresis: at the same strain, the stress on unloading is below the stress on loading
expect_num "cycle: hysteresis, sig_zz unloading < loading at eps +2e-4" "$(col cyc.tsv 5 8)" "<" "$(col cyc.tsv 3 8)"
expect_num "cycle: hysteresis, sig_zz unloading < loading at eps +1e-4" "$(col cyc.tsv 6 8)" "<" "$(col cyc.tsv 2 8)"
expect_num "cycle: hysteresis, sig_zz back at eps 0 below the start" "$(col cyc.tsv 7 8)" "<" "$(col cyc.tsv 1 8)"
expect_num "cycle: the loop is wide (gap / stress at +1e-4)" "$(rel "$(col cyc.tsv 6 8)" "$(col cyc.tsv 2 8)")" ">" 1e-3
# frictionless the same cycle is elastic: the dense pack, --mu 0, comes back on its path
loadtest --mu 0 --path "$cycle" dense.pack >cyc0.tsv 2>/dev/null
expect_num "frictionless cycle: no loop (gap / stress at +1e-4)" "$(rel "$(col cyc0.tsv 6 8)" "$(col cyc0.tsv 2 8)")" "<" 1e-4

# --- other paths ---------------------------------------------------------------------------
expect_ok "isotropic path" loadtest --path isotropic --steps 3 fr.pack
mv ok.out iso.tsv
grep -q '^## path: isotropic ratio=1:1:1 step=0.0001 steps=3$' iso.tsv && pass "isotropic: ## path line" || fail "isotropic: ## path line" "$(grep '^## path' iso.tsv)"
rows iso.tsv | awk -F '\t' 'NR > 1 { for (a = 3; a <= 5; a++) { d = $a - e[a]; if (d < 0.99e-4 || d > 1.01e-4) bad = "row " NR ": d" a " = " d }
	if (!($12 > s)) bad = "row " NR ": sigma_c did not grow" }
     { for (a = 3; a <= 5; a++) e[a] = $a; s = $12 } END { if (NR != 4) bad = NR " rows"; if (bad) { print bad; exit 1 } }' >why &&
    pass "isotropic: 1e-4 on every axis, sigma_c grows" || fail "isotropic: 1e-4 on every axis, sigma_c grows" "$(cat why)"

# strain_steps FILE NROWS XLO XHI YLO YHI ZLO ZHI: FILE has NROWS rows, and from one row to the
# next eps_xx changes by XLO to XHI, eps_yy by YLO to YHI, eps_zz by ZLO to ZHI; else the first
# row that does not, on stdout, and a failing exit
strain_steps() {
	rows "$1" | awk -F '\t' -v nr="$2" -v xlo="$3" -v xhi="$4" -v ylo="$5" -v yhi="$6" -v zlo="$7" -v zhi="$8" 'NR > 1 { dx = $3 - x; dy = $4 - y; dz = $5 - z
	if (dx < xlo || dx > xhi || dy < ylo || dy > yhi || dz < zlo || dz > zhi) bad = "row " NR ": " dx " " dy " " dz }
     { x = $3; y = $4; z = $5 } END { if (NR != nr) bad = NR " rows"; if (bad) { print bad; exit 1 } }'
}
expect_ok "polyaxial ratio=1:2:4" loadtest --path 'polyaxial ratio=1:2:4' --steps 3 fr.pack
mv ok.out poly.tsv
strain_steps poly.tsv 4 0.2499e-4 0.2501e-4 0.4999e-4 0.5001e-4 0.9999e-4 1.0001e-4 >why &&
    pass "polyaxial: strain steps 0.25e-4 0.5e-4 1e-4 (the largest ratio takes the step)" || fail "polyaxial: strain steps 0.25e-4 0.5e-4 1e-4 (the largest ratio takes the step)" "$(cat why)"

expect_ok "triaxial lateral=0.5" loadtest --path 'triaxial lateral=0.5' --steps 2 fr.pack
mv ok.out tl.tsv
strain_steps tl.tsv 3 0.4999e-4 0.5001e-4 0.4999e-4 0.5001e-4 0.9999e-4 1.0001e-4 >why &&
    pass "triaxial lateral=0.5: lateral steps half the axial" || fail "triaxial lateral=0.5: lateral steps half the axial" "$(cat why)"

# Triaxial with the mean lateral stress held at its starting value by the servo (loadpath.h:
# each increment's lateral strain is predicted from a model learnt along the segment; the
# stress reached is off by a fraction of an increment's stress change, and the damped secant
# closes in: the last row within a quarter of it, measured 1 %).  The first increment is
# uniaxial.
expect_ok "triaxial hold" loadtest --path 'triaxial hold' --steps 8 fr.pack
mv ok.out th.tsv
grep -q '^## path: triaxial .* hold=-1 steps=8$' th.tsv && pass "triaxial hold: ## path line" || fail "triaxial hold: ## path line" "$(grep '^## path' th.tsv)"
target=$(col th.tsv 1 13)
dsz=$(awk -v a="$(col th.tsv 2 8)" -v b="$(col th.tsv 1 8)" 'BEGIN { print a - b }')
rows th.tsv | awk -F '\t' 'NR > 1 { d = $5 - z; if (d < 0.99e-4 || d > 1.01e-4) bad = "row " NR ": axial step " d } { z = $5 }
     END { if (NR != 9) bad = NR " rows"; if (bad) { print bad; exit 1 } }' >why &&
    pass "triaxial hold: axial steps of 1e-4" || fail "triaxial hold: axial steps of 1e-4" "$(cat why)"
expect_num "triaxial hold: the lateral walls moved out" "$(col th.tsv 9 3)" "<" "$(col th.tsv 1 3)"
rows th.tsv | awk -F '\t' 'NR > 2 && $3 == x { bad = bad " " $1 } { x = $3 } END { if (bad) { print "no lateral strain in increment" bad; exit 1 } }' >why &&
    pass "triaxial hold: the servo moves the lateral walls in every increment after the first" ||
    fail "triaxial hold: the servo moves the lateral walls in every increment after the first" "$(cat why)"
expect_num "triaxial hold: largest |sig_lat - start| after the first increment, within one increment's axial stress change ($dsz Pa)" \
    "$(rows th.tsv | awk -F '\t' -v t="$target" 'NR > 2 { d = $13 - t; if (d < 0) d = -d; if (d > m) m = d } END { print m + 0 }')" "<" "$dsz"
expect_num "triaxial hold: the last row's sig_lat within a quarter of it" \
    "$(awk -v a="$(col th.tsv 9 13)" -v t="$target" 'BEGIN { d = a - t; print d < 0 ? -d : d }')" "<" "$(awk -v d="$dsz" 'BEGIN { print d / 4 }')"
# hold=PA, 3 % below the starting lateral stress: after the first (uniaxial) increment the
# rows stay, on average, much closer to PA than the start was (the start, if PA were ignored)
pa=$(awk -v t="$target" 'BEGIN { printf "%.0f", t * 0.97 }')
expect_ok "triaxial hold=PA" loadtest --path "triaxial hold=$pa" --steps 6 fr.pack
mv ok.out thp.tsv
grep -q "^## path: triaxial .* hold=$(awk -v p="$pa" 'BEGIN { printf "%g", p }') steps=6\$" thp.tsv && pass "triaxial hold=PA: ## path line" || fail "triaxial hold=PA: ## path line" "$(grep '^## path' thp.tsv)"
expect_num "triaxial hold=PA: mean |sig_lat - PA| after the first increment / |start - PA|" \
    "$(rows thp.tsv | awk -F '\t' -v p="$pa" -v t="$target" 'NR > 2 { s += $13; n++ } END { d = s / n - p; if (d < 0) d = -d; print d / (t - p) }')" "<" 0.5

# --- --mu 0 -----------------------------------------------------------------------------------
expect_ok "--mu 0 runs" loadtest --mu 0 --steps 3 -o mu0.pack fr.pack
mv ok.out mu0.tsv
grep -q '^## friction: none (mu 0)$' mu0.tsv && pass "--mu 0: ## friction none" || fail "--mu 0: ## friction none" "$(grep '^## fric' mu0.tsv)"
expect_num "--mu 0: nothing slides" "$(rows mu0.tsv | awk -F '\t' 'NR > 1 && ($16 != 0 || $17 != 0) { n++ } END { print n + 0 }')" "==" 0
grep -q '^friction 0$' mu0.pack && pass "--mu 0: the -o pack has friction 0" || fail "--mu 0: the -o pack has friction 0" "$(grep '^friction' mu0.pack)"
awk '/^end$/ { on = 1; next } on && NF == 7 && ($4 != 0 || $5 != 0 || $6 != 0) { q++ } END { exit q > 0 }' mu0.pack &&
    pass "--mu 0: no tangential history written" || fail "--mu 0: no tangential history written" "Q0 != 0"

# --- stops ------------------------------------------------------------------------------------
tgt=$(awk -v s="$s0" 'BEGIN { printf "%.0f", s + 3e5 }')
expect_ok "--to-stress $tgt" loadtest --to-stress "$tgt" fr.pack
mv ok.out ts.tsv
n=$(rows ts.tsv | wc -l)
expect_num "--to-stress: stops at the first row at or above it" "$(col ts.tsv "$n" 12)" ">=" "$tgt"
expect_num "--to-stress: the row before is below it" "$(col ts.tsv $((n - 1)) 12)" "<" "$tgt"
expect_ok "--to-strain" loadtest --to-strain "$(awk -v e="$(col six.tsv 1 5)" 'BEGIN { printf "%.10g", e + 2.5e-4 }')" fr.pack
expect_num "--to-strain: 3 increments to pass 2.5e-4" "$(rows ok.out | wc -l)" "==" 4

# a target out of reach: one line, exit 1, the rows computed are kept, -o is not written
echo keep >far.pack
loadtest --to-stress 1e9 --max-steps 4 -o far.pack fr.pack >far.tsv 2>far.err
rc=$?
if [ "$rc" -eq 1 ] && [ "$(wc -l <far.err)" -eq 1 ] && grep -q '^loadtest: .*4 increments without reaching its target.*rows computed so far are kept' far.err; then
	pass "target out of reach: exit 1, one line"
else
	fail "target out of reach: exit 1, one line" "exit $rc: $(head -c 300 far.err)"
fi
expect_num "target out of reach: start row + 4 rows kept" "$(rows far.tsv | wc -l)" "==" 5
rows far.tsv | head -n 5 >far.rows
rows six.tsv | head -n 5 >six5.rows
expect_same "target out of reach: the rows kept are the rows computed" six5.rows far.rows
if [ "$(cat far.pack)" = keep ] && ! ls -a | grep -q '^\.far'; then pass "target out of reach: -o not written"; else fail "target out of reach: -o not written" "far.pack changed or temp left"; fi
loadtest --to-stress 1e9 --max-strain "$(awk -v e="$(col six.tsv 1 5)" 'BEGIN { printf "%.10g", e + 2.5e-4 }')" fr.pack >fs.tsv 2>fs.err
rc=$?
if [ "$rc" -eq 1 ] && [ "$(wc -l <fs.err)" -eq 1 ] && grep -q 'passed the limit' fs.err && [ "$(rows fs.tsv | wc -l)" -eq 4 ]; then
	pass "--max-strain stops: exit 1, one line, rows kept"
else
	fail "--max-strain stops: exit 1, one line, rows kept" "exit $rc, $(rows fs.tsv | wc -l) rows: $(head -c 300 fs.err)"
fi
loadtest --to-stress 1e9 --max-steps 2 --allow-limit -o far2.pack fr.pack >far2.tsv 2>far2.err
rc=$?
if [ "$rc" -eq 0 ] && [ -s far2.pack ] && [ "$(wc -l <far2.err)" -eq 1 ] && grep -q 'allow-limit' far2.err; then
	pass "--allow-limit: exit 0, the pack, one warning"
else
	fail "--allow-limit: exit 0, the pack, one warning" "exit $rc: $(head -c 300 far2.err)"
fi

# --- help, version ---------------------------------------------------------------------------
expect_help_version loadtest --path --to-stress

# probe: uniaxial along x, y, z in turn, N increments each, as three segments
expect_ok "probe steps=2 (frictionless)" loadtest --mu 0 --path 'probe steps=2' dense.pack
rows ok.out | awk -F '\t' 'NR > 1 { k = NR - 1; a = int((k - 1) / 2) + 1
	if ($2 != a) bad = "row " NR ": seg " $2 " (want " a ")"
	for (i = 1; i <= 3; i++) { d = $(2 + i) - p[i]; if ((i == a) != (d > 0.99e-4 && d < 1.01e-4) || (i != a && d != 0)) bad = "row " NR ": eps " i " moved by " d } }
	{ for (i = 1; i <= 3; i++) p[i] = $(2 + i) }
	END { if (NR != 7) bad = NR " rows"; if (bad) { print bad; exit 1 } }' >why &&
    pass "probe: 2 increments of 1e-4 along x (seg 1), y (seg 2), z (seg 3)" || fail "probe: 2 increments of 1e-4 along x (seg 1), y (seg 2), z (seg 3)" "$(cat why)"

# --- errors: exit status, nothing on stdout, one stderr line, no -o file --------------------
# expect_fail NAME STATUS REGEX ARGS...: loadtest ARGS -o nothing.pack
expect_fail() {
	n=$1 st=$2 re=$3
	shift 3
	expect_refused "no output file" nothing.pack "$n" "$st" "$re" loadtest "$@" -o nothing.pack
}
expect_fail "path 'uniaxal'" 2 "^loadtest: --path: segment 1: unknown path 'uniaxal'" --path uniaxal --steps 3 fr.pack
expect_fail "path 'uniaxial steps=x'" 2 "^loadtest: --path: segment 1: bad value in 'steps=x'" --path 'uniaxial steps=x' fr.pack
expect_fail "path 'uniaxial step=nan steps=3'" 2 "^loadtest: --path: segment 1: bad value in 'step=nan'" --path 'uniaxial step=nan steps=3' fr.pack
expect_fail "second segment bad" 2 "^loadtest: --path: segment 2: " --path 'uniaxial steps=2; uniaxial stepz=1' fr.pack
expect_fail "polyaxial without ratio" 2 '^loadtest: --path: segment 1: .*ratio' --path polyaxial --steps 3 fr.pack
expect_fail "hold and lateral together" 2 '^loadtest: --path: segment 1: .*exclusive' --path 'triaxial hold lateral=0.5' --steps 3 fr.pack
expect_fail "empty path" 2 '^loadtest: --path: ' --path '' --steps 3 fr.pack
expect_fail "probe with axis=" 2 '^loadtest: --path: segment 1: a probe loads x, y and z in turn: no axis= ' --path 'probe axis=z steps=2' fr.pack
expect_fail "probe with to-stress=" 2 "^loadtest: --path: segment 1: a probe stops by steps=N \\(per axis\\), not 'to-stress=9e6' " --path 'probe to-stress=9e6' fr.pack
expect_fail "probe without steps" 2 '^loadtest: --path: segment 1: a probe needs steps=N' --path probe --to-stress 9e6 fr.pack
# a bare loadtest (the pipe of the README) runs 100 increments; a path without a stop in a
# segment and with a stop option for another kind still fails to parse
loadtest fr.pack >bare.tsv 2>/dev/null
expect_num "bare loadtest: 100 increments and the start row" "$(grep -vc '^#' bare.tsv)" "==" 101
expect_fail "unknown option" 2 "^loadtest: unknown option '--bogus'" --bogus --steps 3 fr.pack
expect_fail "--strain-step nan" 2 "^loadtest: --strain-step: 'nan' is not a finite number" --strain-step nan --steps 3 fr.pack
expect_fail "--strain-step NaN" 2 "^loadtest: --strain-step: 'NaN'" --strain-step NaN --steps 3 fr.pack
expect_fail "--strain-step 0" 2 '^loadtest: --strain-step' --strain-step 0 --steps 3 fr.pack
expect_fail "--strain-step 0.1" 2 '^loadtest: --strain-step' --strain-step 0.1 --steps 3 fr.pack
expect_fail "--mu -1" 2 '^loadtest: --mu' --mu -1 --steps 3 fr.pack
expect_fail "--to-stress 0" 2 '^loadtest: --to-stress' --to-stress 0 fr.pack
expect_fail "--axis w" 2 '^loadtest: --axis' --axis w --steps 3 fr.pack
expect_fail "missing input file" 1 '^loadtest: .*no-such\.pack' --steps 3 no-such.pack
expect_fail "pack without reference box" 1 '^loadtest: loose\.pack: no reference box' --steps 3 loose.pack
# a stop already passed where the test starts ran no increment: it wrote a header and exited 0
# without a word; now one line that names the stop and the start, and nothing on stdout
expect_fail "--to-stress below the start" 1 '^loadtest: segment 1 \(uniaxial\): to-stress 100000 Pa is already passed at its start \(sigma_c [0-9.e+]+ Pa, which a step of 0.0001 raises\): nothing to load' \
    --to-stress 1e5 fr.pack
expect_fail "--to-strain below the start" 1 '^loadtest: segment 1 \(uniaxial\): to-strain -0.01 is already passed at its start' --to-strain -0.01 fr.pack
expect_fail "unloading to a stress above the start" 1 'to-stress 9e\+09 Pa is already passed at its start \(sigma_c [0-9.e+]+ Pa, which a step of -0.0001 lowers\)' \
    --path 'uniaxial step=-1e-4 to-stress=9e9' fr.pack
loadtest --path 'uniaxial steps=2; uniaxial to-stress=1e5' -o nothing.pack fr.pack >passed2.tsv 2>passed2.err
rc=$?
if [ "$rc" -eq 1 ] && [ "$(rows passed2.tsv | wc -l)" -eq 3 ] && [ ! -e nothing.pack ] &&
    grep -q '^loadtest: segment 2 (uniaxial): to-stress 100000 Pa is already passed at its start' passed2.err; then
	pass "a later segment's stop passed: exit 1, the rows so far, no pack"
else
	fail "a later segment's stop passed: exit 1, the rows so far, no pack" "exit $rc, $(rows passed2.tsv | wc -l) rows: $(head -c 300 passed2.err)"
fi
# -o that cannot be written, over the input or on the table's standard output: refused before
# the test (it was found only after the last increment)
expect_error "-o in a missing directory" 2 "^loadtest: -o: cannot write in directory 'no-such-dir'" loadtest --steps 3 -o no-such-dir/x.pack fr.pack
cp fr.pack in.pack
# -o the input: the pack updated in place (read whole, then renamed over it)
loadtest --steps 3 -o ref.pack in.pack >ref.tsv 2>/dev/null
expect_ok "-o the input: allowed" loadtest --steps 3 -o in.pack in.pack
expect_same "-o the input: the pack updated in place, as -o another file" in.pack ref.pack
expect_error "-o - with the table" 2 "^loadtest: the table and -o both go to standard output" loadtest --steps 3 -o - fr.pack
awk '/^end$/ { on = 1; print; next }
     on && NF == 7 && $2 !~ /^[xyz](lo|hi)$/ && !done { $4 = 1000 * $3 + 1; done = 1 } { print }' fr.pack >corrupt.pack
expect_fail "history far above mu P0 refused" 1 '^loadtest: corrupt\.pack: contact [0-9]+ [0-9]+: ' --steps 3 corrupt.pack
# the iteration limit stops the test like a target out of reach: rows kept, no pack
rm -f lim.pack
loadtest --max-iter 3 --steps 3 -o lim.pack fr.pack >lim.tsv 2>lim.err
rc=$?
if [ "$rc" -eq 1 ] && [ "$(wc -l <lim.err)" -eq 1 ] && grep -q '^loadtest: .*increment 1: the minimiser hit its iteration limit' lim.err &&
    [ "$(rows lim.tsv | wc -l)" -eq 2 ] && [ ! -e lim.pack ]; then
	pass "iteration limit: exit 1, one line, the rows so far, no pack"
else
	fail "iteration limit: exit 1, one line, the rows so far, no pack" "exit $rc, $(rows lim.tsv | wc -l) rows: $(head -c 300 lim.err)"
fi
# -o is atomic: a failed run does not clobber an existing file
echo keep >old.pack
loadtest --max-iter 3 --steps 3 -o old.pack fr.pack >/dev/null 2>&1
loadtest --path uniaxal --steps 3 -o old.pack fr.pack >/dev/null 2>&1
if [ "$(cat old.pack)" = keep ] && ! ls -a | grep -q '^\.old'; then pass "failed runs do not clobber -o"; else fail "failed runs do not clobber -o" "changed or temp left"; fi
