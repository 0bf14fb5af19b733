# SPDX-License-Identifier: GPL-3.0-or-later
# frictionalize as a user runs it: a small dense pack (200 grains, densify --stress 4e6) is
# frictionalized and checked with packinfo (contact history, sliding ratio, residual), the log
# (columns, one row per increment, saturation), determinism, --mu 0, the iteration and
# increment limits, atomic -o, and the history checks of share/doc/friction.md (a line far
# above mu P0 is refused, a stale line is dropped with a warning, a pack kept with --allow-limit
# far from equilibrium reads back).  About a second in all.
. "$TOP/tests/tools/lib.sh"

small_pack dense "densify makes the dense pack"
packinfo dense.pack >dense.txt 2>/dev/null

# --- a normal run -------------------------------------------------------------------------
frictionalize --log f.tsv -o f.pack dense.pack >f.out 2>f.err
rc=$?
if [ "$rc" -eq 0 ] && [ -s f.pack ] && [ ! -s f.out ]; then
	pass "frictionalize saturates: exit 0, the pack in -o, nothing on stdout"
else
	fail "frictionalize saturates: exit 0, the pack in -o, nothing on stdout" "exit $rc: $(head -c 300 f.err)"
fi
if packinfo f.pack >f.txt 2>f.txt.err; then pass "packinfo reads the frictional pack"; else fail "packinfo reads the frictional pack" "$(cat f.txt.err)"; fi
expect_num "the pack has contact history" "$(info_value f.txt history_contacts)" ">" 100
expect_num "packinfo sliding_ratio > 0" "$(info_value f.txt sliding_ratio)" ">" 0
expect_num "the dense pack had sliding_ratio 0" "$(info_value dense.txt sliding_ratio)" "==" 0
# the frictional pack records a trial slip ratio, the dense one none: packinfo --tsv on both
# still gives every row the header's columns (nan where a pack has no record)
packinfo --tsv dense.pack f.pack >both.tsv 2>/dev/null
expect_num "packinfo --tsv, a frictionless and a frictional pack: one field count" "$(awk -F '\t' '{ print NF }' both.tsv | sort -u | wc -l)" "==" 1
expect_num "packinfo reports mu 0.3 (the default --mu)" "$(info_value f.txt mu)" "==" 0.3
if grep -q '^friction 0.3$' f.pack && grep -q '^walls .* 0.3$' f.pack; then
	pass "friction 0.3 and wall mu 0.3 in the header"
else
	fail "friction 0.3 and wall mu 0.3 in the header" "$(grep -E '^(friction|walls)' f.pack | tr '\n' ' ')"
fi
# the commit stores the equilibrium's forces: the pack is in balance with its own history
expect_num "packinfo residual of the written pack" "$(info_value f.txt residual)" "<=" 1e-4
expect_num "no stale history in the written pack" "$(info_value f.txt stale_history)" "==" 0
awk '/^end$/ { on = 1; next } on && NF == 7 && ($4 != 0 || $5 != 0 || $6 != 0) { q++ } END { exit !(q > 100) }' f.pack &&
    pass "contact lines carry tangential forces Q0" || fail "contact lines carry tangential forces Q0" "fewer than 100 lines with Q0 != 0"
expect_num "uniaxial loading raised sigma_c" "$(info_value f.txt sigma_c)" ">" "$(info_value dense.txt sigma_c)"
if grep -q '^history frictionalize ' f.pack; then pass "history line"; else fail "history line" "none"; fi

# --- the log -----------------------------------------------------------------------------
hdr=$(printf '# inc\tseg\teps_xx\teps_yy\teps_zz\tsig_xx[Pa]\tsig_yy[Pa]\tsig_zz[Pa]\tsig_lw_xx[Pa]\tsig_lw_yy[Pa]\tsig_lw_zz[Pa]\tsigma_c[Pa]\tsig_lat[Pa]\tporosity\tcoordination\tsliding_ratio\ttrial_slip_ratio\titerations\tresidual\tres_mean\tbulk_porosity\tbulk_coordination\tK[Pa]\tG[Pa]\telapsed[s]')
if [ "$(head -n 1 f.tsv)" = "$hdr" ]; then pass "log header"; else fail "log header" "$(head -n 1 f.tsv)"; fi
# the starting row (inc 0, seg 0, K and G nan), then increments 1..n of segment 1, 21 columns,
# compression along z only (the default --axis), K and G positive
awk -F '\t' 'NR == 1 { next }
     { k = NR - 2; if (NF != 25) bad = "row " NR " has " NF " columns" }
     k > 0 && !($25 >= el) { bad = "row " NR ": elapsed " $25 " after " el }
     { el = $25 }
     $1 != k { bad = "row " NR ": inc " $1 ", wanted " k }
     k == 0 && !($2 == 0 && $23 == "nan" && $24 == "nan" && $18 == 0) { bad = "start row: seg " $2 ", K " $23 ", G " $24 }
     k > 0 && $2 != 1 { bad = "row " NR ": seg " $2 }
     k > 0 && !($23 > 0 && $24 > 0 && $18 > 0) { bad = "row " NR ": K " $23 ", G " $24 ", iterations " $18 }
     k > 0 && !($19 <= 1e-4) { bad = "row " NR ": residual " $19 }
     k > 0 && !($5 > z && $3 == x && $4 == y) { bad = "row " NR ": not uniaxial along z" }
     { x = $3; y = $4; z = $5 }
     END { if (bad) { print bad; exit 1 } }' f.tsv >why && pass "log: start row, then one row per increment" || fail "log: start row, then one row per increment" "$(cat why)"
n=$(($(wc -l <f.tsv) - 2))
expect_num "at least two windows (20) of increments" "$n" ">=" 20
expect_num "below --max-inc (1000) increments" "$n" "<" 1000
expect_num "strain step 1e-4 per increment" "$(awk -F '\t' 'NR == 2 { a = $5 } END { print ($5 - a) / (NR - 2) }' f.tsv)" "==" 1e-4
# sliding develops: it ends well above its first increments and never drops by much
awk -F '\t' 'NR > 2 { r[NR - 2] = $16 } END {
	n = NR - 2; for (k = 2; k <= n; k++) if (r[k - 1] - r[k] > d) d = r[k - 1] - r[k]
	if (!(r[n] > 2 * r[1] && d < 0.02)) { print "first " r[1] ", last " r[n] ", largest drop " d; exit 1 } }' f.tsv >why &&
    pass "sliding ratio grows, nondecreasing-ish" || fail "sliding ratio grows, nondecreasing-ish" "$(cat why)"
# saturation as documented: with W the window that -v reports (--window 10 widened to cover
# --window-overlap 0.25 x the mean overlap / radius in strain), the mean sliding ratio of the
# last W increments differs from that of the W before by less than --sat-tol (0.05) times itself
W=$(frictionalize -v --max-inc 1000 -o /dev/null dense.pack 2>&1 | sed -n 's/.*saturation window \([0-9]*\) increments.*/\1/p')
expect_num "saturation window at least --window" "${W:-0}" ">=" 10
# the first increment K at which the window means agree (column C: 16 sliding ratio, 24 G)
cat >sat.awk <<'AWK'
NR > 2 { v[++n] = $C }
END {
	for (k = 2 * W; k <= n; k++) {
		m1 = m0 = 0
		for (q = k - W + 1; q <= k; q++) { m1 += v[q]; m0 += v[q - W] }
		if (C == 16) { d = m1 - m0; if (d < 0) d = -d; ok = d <= 0.05 * m1 } else ok = m1 > m0
		if (ok) { first = k; break }
	}
	if (first != n) { print "criterion first met at increment " first ", stopped at " n; exit 1 }
}
AWK
awk -F '\t' -v W="$W" -v C=16 -f sat.awk f.tsv >why && pass "stops at the first increment where the window means agree" ||
    fail "stops at the first increment where the window means agree" "$(cat why)"
# --until shear: the first increment at which the mean G of the last window exceeds the one before
expect_ok "--until shear runs" frictionalize --until shear --log sh.tsv -o sh.pack dense.pack
awk -F '\t' -v W="$W" -v C=24 -f sat.awk sh.tsv >why && pass "--until shear stops once G has passed its minimum" ||
    fail "--until shear stops once G has passed its minimum" "$(cat why)"
expect_error "--until bad" 2 '^frictionalize: --until: must be sliding or shear' frictionalize --until never dense.pack
last=$(tail -n 1 f.tsv)
expect_num "log's last sliding_ratio is packinfo's" "$(echo "$last" | cut -f 16)" "==" "$(info_value f.txt sliding_ratio)"
expect_num "log's last trial_slip_ratio is packinfo's" "$(echo "$last" | cut -f 17)" "==" "$(info_value f.txt trial_slip_ratio)"
# the log's K and G are those of the volume-averaged stress (moduli's default): moduli on
# the log, one increment per interval, gives the same numbers
expect_num "log's last G is moduli's of its last increment (volume-averaged stress)" \
    "$(rel "$(echo "$last" | cut -f 24)" "$(moduli f.tsv 2>/dev/null | tail -n 1 | cut -f 8)")" "<" 1e-9
expect_num "log's last sigma_c is packinfo's" "$(rel "$(echo "$last" | cut -f 12)" "$(info_value f.txt sigma_c)")" "<" 1e-9

# --- determinism --------------------------------------------------------------------------
# the same command line (the history line records it) in another directory
mkdir again && cp dense.pack again/ && (cd again && frictionalize --log f.tsv -o f.pack dense.pack 2>/dev/null)
expect_same "same input, same pack" f.pack again/f.pack
cut -f 1-24 f.tsv >f.tsv.noel
cut -f 1-24 again/f.tsv >again/f.tsv.noel
expect_same "same input, same log (elapsed[s] aside)" f.tsv.noel again/f.tsv.noel
cat dense.pack | frictionalize >f3.pack 2>/dev/null
grep -v '^history frictionalize ' f.pack >f.nohist
grep -v '^history frictionalize ' f3.pack >f3.nohist
expect_same "stdin and stdout give the same pack as file and -o" f.nohist f3.nohist

# --- --mu 0 (grain-grain friction off; --wall-mu follows --mu unless given) ----------------
expect_ok "--mu 0 runs" frictionalize --mu 0 --wall-mu 0.3 --log m0.tsv -o m0.pack dense.pack
if grep -q '^friction 0$' m0.pack; then pass "--mu 0: friction 0 in the pack"; else fail "--mu 0: friction 0 in the pack" "$(grep '^friction' m0.pack)"; fi
awk '/^end$/ { on = 1; next } on && NF == 7 && $2 !~ /^[xyz](lo|hi)$/ && ($4 != 0 || $5 != 0 || $6 != 0) { q++ }
     END { exit q > 0 }' m0.pack && pass "--mu 0: no grain-grain tangential force" || fail "--mu 0: no grain-grain tangential force" "found some"
awk '/^end$/ { on = 1; next } on && NF == 7 && $2 ~ /^[xyz](lo|hi)$/ && ($4 != 0 || $5 != 0 || $6 != 0) { q++ }
     END { exit !(q > 0) }' m0.pack && pass "--mu 0: wall contacts keep friction (--wall-mu 0.3)" || fail "--mu 0: wall contacts keep friction (--wall-mu 0.3)" "no wall Q0"
expect_ok "--mu 0 --wall-mu 0 runs" frictionalize --mu 0 --wall-mu 0 --log m00.tsv -o m00.pack dense.pack
grep -q '^frictionalize: .*nothing can slide' ok.err && pass "--mu 0 --wall-mu 0: warns that nothing can slide" ||
    fail "--mu 0 --wall-mu 0: warns that nothing can slide" "$(cat ok.err)"
# nothing can slide: the ratio stays 0 and the run saturates after two windows
expect_num "--mu 0 --wall-mu 0: saturates after two windows" "$(($(wc -l <m00.tsv) - 2))" "==" $((2 * W))
expect_ok "--mu 0 alone runs" frictionalize --mu 0 -o m0b.pack dense.pack
if grep -q '^walls .* 0$' m0b.pack; then pass "--mu 0: --wall-mu follows it"; else fail "--mu 0: --wall-mu follows it" "$(grep '^walls' m0b.pack)"; fi
expect_num "--mu 0 --wall-mu 0: sliding ratio stays 0" "$(awk -F '\t' 'NR > 1 && ($16 != 0 || $17 != 0) { n++ } END { print n + 0 }' m00.tsv)" "==" 0
awk '/^end$/ { on = 1; next } on && NF == 7 && ($4 != 0 || $5 != 0 || $6 != 0) { q++ } END { exit q > 0 }' m00.pack &&
    pass "--mu 0 --wall-mu 0: no tangential force at all" || fail "--mu 0 --wall-mu 0: no tangential force at all" "found some"

# --- help, version ------------------------------------------------------------------------
expect_help_version frictionalize --mu --sat-tol

# --- errors: exit status, nothing on stdout, one stderr line, no output file, no log -------
# expect_fail NAME STATUS REGEX ARGS...: frictionalize ARGS --log nothing.tsv -o nothing.pack
expect_fail() {
	n=$1 st=$2 re=$3
	shift 3
	expect_refused "no output file, no log" "nothing.pack nothing.tsv" "$n" "$st" "$re" frictionalize "$@" --log nothing.tsv -o nothing.pack
}
expect_fail "--mu -1" 2 '^frictionalize: --mu' --mu -1 dense.pack
expect_fail "--mu nan" 2 '^frictionalize: --mu' --mu nan dense.pack
expect_fail "--wall-mu NaN" 2 '^frictionalize: --wall-mu' --wall-mu NaN dense.pack
expect_fail "--strain-step nan" 2 '^frictionalize: --strain-step' --strain-step nan dense.pack
expect_fail "--strain-step 0" 2 '^frictionalize: --strain-step' --strain-step 0 dense.pack
expect_fail "--axis w" 2 '^frictionalize: --axis' --axis w dense.pack
expect_fail "--rule bogus" 2 '^frictionalize: --rule' --rule bogus dense.pack
expect_fail "unknown option" 2 "^frictionalize: unknown option '--bogus'" --bogus dense.pack
expect_fail "missing input file" 1 '^frictionalize: .*no-such\.pack' no-such.pack
expect_fail "pack without reference box" 1 '^frictionalize: loose\.pack: no reference box' loose.pack
# a run that fails once it has begun keeps its log (the header and every row so far) and writes no pack
expect_run_fail() {
	n=$1 st=$2 re=$3
	shift 3
	expect_refused "no output file" nothing.pack "$n" "$st" "$re" frictionalize "$@" --log nothing.tsv -o nothing.pack
	if [ "$(head -n 1 nothing.tsv 2>/dev/null)" = "$hdr" ] && [ "$(rows nothing.tsv | cut -f 1 | head -n 1)" = 0 ]; then
		pass "$n: the log kept, from its start row"
	else
		fail "$n: the log kept, from its start row" "$(head -c 200 nothing.tsv 2>&1)"
	fi
}
expect_run_fail "increment limit" 1 '^frictionalize: .*did not saturate in 3 increments.*--allow-limit' --max-inc 3 --window 2 --window-overlap 0 dense.pack
expect_num "increment limit: the log has the start row and the 3 increments" "$(rows nothing.tsv | wc -l)" == 4
expect_run_fail "iteration limit" 1 '^frictionalize: .*iteration limit.*--allow-limit' --max-iter 3 dense.pack
# the log and the pack over each other or over the input, refused before any work; a log that
# cannot be written, before the run with its own error and no pack
expect_refused "no output file" nothing.pack "--log the output" 2 "^frictionalize: -o and --log name the same file 'nothing.pack'" \
    frictionalize --log nothing.pack -o nothing.pack dense.pack
cp dense.pack in.pack
expect_error "--log the input" 2 "^frictionalize: --log 'in.pack' is the input" frictionalize --log in.pack in.pack
ln -s in.pack in.link
expect_error "--log a link to the input" 2 "^frictionalize: --log 'in.link' is the input" frictionalize --log in.link -o x.pack in.pack
expect_same "--log a link to the input: the input untouched" in.pack dense.pack
rm -f in.link
# -o the input: the pack updated in place (read whole, then renamed over it)
# (the optimised build's: the in-place write is lib/base/fileio's, which the sanitizer
# build checks through loadtest's and dissociate's, at a fraction of this run's CPU)
if [ "${BIN#*build-san}" = "$BIN" ]; then
	frictionalize -o ref.pack in.pack 2>/dev/null
	expect_ok "-o the input: allowed" frictionalize -o in.pack in.pack
	expect_same "-o the input: the pack updated in place, as -o another file" in.pack ref.pack
fi
expect_refused "no output file" nothing.pack "--log /dev/full" 1 '^frictionalize: /dev/full: write error: No space left on device$' \
    frictionalize --log /dev/full -o nothing.pack dense.pack
expect_refused "no log" nothing.tsv "-o in a missing directory" 2 "^frictionalize: -o: cannot write in directory 'no-such-dir'" \
    frictionalize --log nothing.tsv -o no-such-dir/x.pack dense.pack
# the same on stdout: a failing run writes no half pack
expect_error "increment limit, no -o: nothing on stdout" 1 'did not saturate' frictionalize --max-inc 3 --window 2 --window-overlap 0 dense.pack

# --allow-limit keeps the pack and the log, exits 0, warns in one line
frictionalize --max-inc 3 --window 2 --window-overlap 0 --allow-limit --log lim.tsv -o lim.pack dense.pack >lim.out 2>lim.err
rc=$?
if [ "$rc" -eq 0 ] && [ -s lim.pack ] && [ ! -s lim.out ] && [ "$(wc -l <lim.err)" -eq 1 ] && grep -q 'did not saturate' lim.err; then
	pass "--allow-limit: exit 0, the pack, one warning"
else
	fail "--allow-limit: exit 0, the pack, one warning" "exit $rc, stderr: $(head -c 300 lim.err)"
fi
expect_num "--allow-limit: log has the start row and 3 increments" "$(($(wc -l <lim.tsv) - 1))" "==" 4

# --allow-limit far from equilibrium: the grain nearest the top wall made 3 % larger overlaps
# its neighbours and the wall deeply; 20 iterations cannot relax that, so the normal forces
# fall by far more than an equilibrium's increment while the history stays at the start's
# limit.  The kept pack must still read back (fr_commit slips such lines to their limit;
# before, loadtest refused it: |Q0| or |M0| far above the limit of a committed pack).
awk 'NR == FNR { if (/^end$/) e = 1; else if (e && NF == 8 && (top == "" || $4 > zt)) { top = $1; zt = $4 } next }
     /^end$/ { e2 = 1 } e2 && NF == 8 && $1 == top { $5 = $5 * 1.03 } { print }' dense.pack dense.pack >infl.pack
frictionalize --max-iter 20 --max-inc 2 --window 2 --window-overlap 0 --allow-limit -o infl-f.pack infl.pack >/dev/null 2>infl-f.err
if [ -s infl-f.pack ] && loadtest -p uniaxial -n 1 --max-iter 20 --allow-limit infl-f.pack >infl.tsv 2>infl.err; then
	pass "--allow-limit far from equilibrium: loadtest reads the kept pack"
else
	fail "--allow-limit far from equilibrium: loadtest reads the kept pack" "$(head -c 300 infl.err)"
fi
# and both say how many lines the commit slipped (a pack whose history was cut to its limits
# is not the state a converged increment would have left)
for t in infl-f infl; do
	if grep -Eq 'iteration limit .*; [1-9][0-9]* friction history lines slipped to their limit at the commit \(kept: --allow-limit\)' $t.err; then
		pass "--allow-limit far from equilibrium: $t.err counts the slipped lines"
	else
		fail "--allow-limit far from equilibrium: $t.err counts the slipped lines" "$(tail -n 2 $t.err)"
	fi
done

# -o is atomic: a failing run leaves an existing file as it was; the log is the run's own
echo keep >old.pack
echo keep >old.tsv
frictionalize --max-inc 3 --window 2 --window-overlap 0 --log old.tsv -o old.pack dense.pack >/dev/null 2>&1
if [ "$(cat old.pack)" = keep ] && [ "$(head -n 1 old.tsv)" = "$hdr" ]; then
	pass "failed run does not clobber -o; its --log holds the run"
else
	fail "failed run does not clobber -o; its --log holds the run" "changed"
fi
if ls -a | grep -q '^\.old'; then fail "failed run leaves no temporary file" "$(ls -a | tr '\n' ' ')"; else pass "failed run leaves no temporary file"; fi
frictionalize --mu -1 -o old.pack dense.pack >/dev/null 2>&1
if [ "$(cat old.pack)" = keep ]; then pass "usage error does not clobber -o"; else fail "usage error does not clobber -o" "changed"; fi

# --- contact history checks (share/doc/friction.md) ---------------------------------------
# A line whose |Q0| is far above mu (P0 + P_mean) is corrupt: refused, naming the contact.
awk '/^end$/ { on = 1; print; next }
     on && NF == 7 && $2 !~ /^[xyz](lo|hi)$/ && !done { $4 = 1000 * $3 + 1; done = 1 } { print }' f.pack >corrupt.pack
if [ "$(cmp corrupt.pack f.pack 2>&1 | wc -l)" -eq 1 ]; then pass "corrupted pack made"; else fail "corrupted pack made" "awk edit failed"; fi
expect_fail "history far above mu P0 refused" 1 '^frictionalize: corrupt\.pack: contact [0-9]+ [0-9]+: .*sliding limit' corrupt.pack
# a frictionless pack whose lines carry tangential force is refused by the same rule
sed 's/^friction 0.3$/friction 0/' f.pack >mu0hist.pack
expect_fail "friction 0 with tangential history refused" 1 '^frictionalize: mu0hist\.pack: contact ' mu0hist.pack

# A stale history line (two grains that do not touch: the leftmost and the rightmost grain)
# gives one warning and is dropped: the result is the pack made without it.
awk 'NR == FNR { if (/^end$/) e = 1; else if (e && NF == 8) { if (lo == "" || $2 < xl) { lo = $1; xl = $2 } if (hi == "" || $2 > xh) { hi = $1; xh = $2 } } next }
     /^contacts / { print "contacts", $2 + 1; next } { print }
     END { print lo, hi, 0.05, 0, 0, 0, 0 }' dense.pack dense.pack >stale.pack
packinfo stale.pack >stale.txt 2>/dev/null
expect_num "the stale pack has one stale history line" "$(info_value stale.txt stale_history)" "==" 1
frictionalize -o st.pack stale.pack >st.out 2>st.err
rc=$?
if [ "$rc" -eq 0 ] && [ "$(wc -l <st.err)" -eq 1 ] && grep -Eq '^frictionalize: stale\.pack: 1 history lines? .*not touch.*dropped' st.err; then
	pass "stale history: exit 0, one warning"
else
	fail "stale history: exit 0, one warning" "exit $rc, stderr: $(head -c 300 st.err)"
fi
packinfo st.pack >st.txt 2>/dev/null
expect_num "stale history dropped from the output" "$(info_value st.txt stale_history)" "==" 0
grep -v '^history frictionalize ' st.pack >st.nohist
expect_same "stale line dropped: same pack as without it" f.nohist st.nohist
