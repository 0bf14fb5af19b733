# SPDX-License-Identifier: GPL-3.0-or-later
# densify as a user runs it: a loose packgen pack compacted frictionlessly to 1 and 4 MPa,
# checked with packinfo (which finds the contacts and forces itself, so its residual and
# stresses are an independent check), the log, determinism, the FIRE minimiser, and every
# error the issue lists.  Small packs (300 grains): a few seconds per run.
#
# The sanitizer build runs every check on packs of 150 grains, as its errors (memory, undefined
# behaviour) show on small packs as on large ones, at two thirds of the cost (its packgen of
# the wide size distribution took 11 s of CPU at 300 grains, 2 s at 150), but for the
# coordination floor of a jammed pack, which depends on the size (check_dense): that check is
# the optimised build's.
. "$TOP/tests/tools/lib.sh"

san=0 N=300
if [ "${BIN#*build-san}" != "$BIN" ]; then san=1 N=150; fi
expect_ok "packgen makes the loose pack" packgen -n $N --seed 2 -o loose.pack
packinfo loose.pack >loose.txt

# check_dense NAME PACK TARGET: the equilibrium properties every densified pack must have.
check_dense() {
	n=$1 pk=$2 target=$3
	if packinfo "$pk" >"$pk.txt" 2>"$pk.err"; then pass "$n: packinfo reads it"; else fail "$n: packinfo reads it" "$(cat "$pk.err")"; fi
	expect_num "$n: sigma_c within --stress-tol (0.01) of $target" "$(rel "$(info_value "$pk.txt" sigma_c)" "$target")" "<=" 0.01
	# packinfo computes every force from the positions: an independent residual
	expect_num "$n: packinfo residual" "$(info_value "$pk.txt" residual)" "<=" 1e-4
	# in equilibrium the volume average of the contact forces (Love-Weber) equals the
	# stress on the walls, axis by axis
	for ax in xx yy zz; do
		expect_num "$n: Love-Weber sig_$ax equals the wall stress" \
		    "$(rel "$(info_value "$pk.txt" sig_lw_$ax)" "$(info_value "$pk.txt" sig_$ax)")" "<" 1e-3
	done
	expect_num "$n: no grain under 4 contacts" "$(info_value "$pk.txt" under4)" == 0
	expect_num "$n: no rattlers" "$(info_value "$pk.txt" rattlers)" == 0
	expect_num "$n: porosity below the loose pack's" "$(info_value "$pk.txt" porosity)" "<" "$(info_value loose.txt porosity)"
	# Frictionless spheres jam isostatic: 3 force unknowns per contact pair balance 3
	# equations per grain, so the mean coordination is near 6 (more under load).  Wall
	# contacts count once and grains at the walls have fewer neighbours, which lowers a
	# 300-grain pack's mean a little: 5.5 is a safe floor, a loose pack is near 2.4.  The
	# optimised build's only: at 150 grains (the sanitizer build's packs) the walls' share
	# is larger and lowers the mean below it (5.41 at 1 MPa).
	if [ $san = 0 ]; then
		expect_num "$n: coordination of a jammed frictionless pack" "$(info_value "$pk.txt" coordination)" ">=" 5.5
	fi
	if grep -q '^refbox ' "$pk"; then pass "$n: refbox line"; else fail "$n: refbox line" "none"; fi
	awk '$1 == "contacts" && !on { m = $2 } /^end$/ { on = 1; next }
	     on && NF == 7 { k++; if (!($3 > 0)) bad++ }
	     END { exit !(m > 0 && k == m && bad == 0) }' "$pk" &&
	    pass "$n: contact lines, all with P0 > 0" || fail "$n: contact lines, all with P0 > 0" "$(grep '^contacts' "$pk")"
}

# 1 MPa and 4 MPa, with logs
expect_ok "densify --stress 1e6" densify --stress 1e6 --log d1.tsv -o d1.pack loose.pack
check_dense "1 MPa" d1.pack 1e6
densify --stress 4e6 --log d4.tsv loose.pack >d4.pack 2>d4.err
rc=$?
if [ "$rc" -eq 0 ]; then pass "densify --stress 4e6 (stdout)"; else fail "densify --stress 4e6 (stdout)" "exit $rc: $(head -c 300 d4.err)"; fi
check_dense "4 MPa" d4.pack 4e6
# Hertz overlaps grow as (sigma/E)^(2/3): about 1 % of R at 4 MPa for glass (70 GPa)
expect_num "4 MPa: largest overlap / R small" "$(info_value d4.pack.txt overlap_max)" "<" 0.05

# The log: the documented header, then one row per stage: relax 0, grow (or retry) 1..k, compact 1..m,
# eleven columns each, the last the elapsed seconds, growing; the last row is the pack written.
hdr=$(printf '# stage\tround\tsigma_c[Pa]\tporosity\tcoordination\tunder4\tgrowth\titerations\tresidual\tresidual_mean\telapsed[s]')
for lg in d1.tsv d4.tsv; do
	if [ "$(head -n 1 $lg)" = "$hdr" ]; then pass "$lg: header"; else fail "$lg: header" "$(head -n 1 $lg)"; fi
	awk -F '\t' 'NR == 1 { next }
	     $1 == "retry" { $1 = "grow" }	# an undone growth round counts as one
	     { n++; if (NF != 11) bad = "row " NR " has " NF " columns" }
	     n > 1 && !($11 >= el) { bad = "row " NR ": elapsed " $11 " after " el }
	     { el = $11 }
	     n == 1 && !($1 == "relax" && $2 == 0) { bad = "first row is not relax 0" }
	     n > 1 && $1 == "grow" && !(prev == "relax" || prev == "grow") { bad = "grow after " prev }
	     n > 1 && $1 == "compact" && !(prev == "grow" || prev == "compact" || prev == "relax") { bad = "compact after " prev }
	     n > 1 && $1 != "grow" && $1 != "compact" { bad = "stage " $1 }
	     n > 1 { want = ($1 == prev) ? r + 1 : 1; if ($2 != want) bad = "row " NR ": round " $2 ", wanted " want }
	     { prev = $1; r = $2 }
	     END { if (bad) { print bad; exit 1 } if (prev != "compact") { print "last stage " prev; exit 1 } }' \
	    $lg >log.why && pass "$lg: one row per stage, in order" || fail "$lg: one row per stage, in order" "$(cat log.why)"
done
last=$(tail -n 1 d4.tsv | cut -f 3)
expect_num "log's last sigma_c is packinfo's" "$(rel "$last" "$(info_value d4.pack.txt sigma_c)")" "<" 1e-9
last=$(tail -n 1 d1.tsv | cut -f 6)
expect_num "log's last under4 is 0" "$last" == 0
# Phase (a) ends with the first growth round that carries the onset (1e5 Pa by default; a
# tenth of --stress below 1 MPa): the pack has jammed, and the compaction seats the grains
# still under 4 contacts, its last step at the full --tol (1e-4) with none left.  The history
# line records the onset used.
for lg in d1.tsv d4.tsv; do
	set -- $(awk -F '\t' '$1 == "grow" { if (s >= 1e5) early++; s = $3 } $1 == "compact" { u = $6; r = $9 }
	    END { print s + 0, early + 0, u + 0, r + 0 }' $lg)
	expect_num "$lg: the last growth round carries the onset" "$1" ">=" 1e5
	expect_num "$lg: no growth round before it does" "$2" == 0
	expect_num "$lg: the last compaction step has no grain under 4" "$3" == 0
	expect_num "$lg: the last compaction step is at the full --tol" "$4" "<=" 1e-4
done
grep -q '^history densify .*--onset=100000' d4.pack && pass "history records --onset=100000" ||
    fail "history records --onset=100000" "$(grep '^history densify' d4.pack)"
densify --stress 5e5 -o half.pack loose.pack 2>/dev/null
grep -q '^history densify .*--onset=50000 ' half.pack && pass "--stress 5e5: the onset is a tenth of it" ||
    fail "--stress 5e5: the onset is a tenth of it" "$(grep '^history densify' half.pack)"

# --min-coord 0 turns growth off: the pack is only compressed to the target, and grains left
# with fewer than 4 contacts (rattlers) do not hold the end.  Until 2026-12-05 the compaction
# waited for them whatever --min-coord was, and failed after 1000 steps.
densify --min-coord 0 --stress 4e6 --log mc0.tsv -o mc0.pack loose.pack 2>mc0.err
rc=$?
if [ "$rc" -eq 0 ]; then pass "--min-coord 0: exit 0"; else fail "--min-coord 0: exit 0" "exit $rc: $(head -c 300 mc0.err)"; fi
set -- $(awk -F '\t' '!/^#/ { g = $7; s = $3; r = $9 } END { print g + 0, s + 0, r + 0 }' mc0.tsv 2>/dev/null)
expect_num "--min-coord 0: no grain grew" "${1:-x}" == 0
expect_num "--min-coord 0: sigma_c within 1 % of 4 MPa" "$(rel "${2:-0}" 4e6)" "<=" 0.01
expect_num "--min-coord 0: the last step is at the full --tol" "${3:-x}" "<=" 1e-4

# Determinism: the same command gives the same bytes; stdin and -o give the same pack as a
# file operand and stdout, apart from the history line that records the command line.
densify --stress 4e6 --log d4.tsv loose.pack >d4b.pack 2>/dev/null
expect_same "same input, same bytes" d4.pack d4b.pack
cat loose.pack | densify --stress 4e6 -o d4c.pack 2>/dev/null
grep -v '^history densify ' d4.pack >d4.nohist
grep -v '^history densify ' d4c.pack >d4c.nohist 2>/dev/null
expect_same "pipe and -o give the same pack as file and stdout" d4.nohist d4c.nohist

# An already dense pack is only compacted: no growth rounds, and the reference box stays.
expect_ok "densify a dense pack further" densify --stress 4e6 --log re.tsv -o re.pack d1.pack
if ! grep -q '^grow' re.tsv; then pass "dense pack: no growth rounds"; else fail "dense pack: no growth rounds" "$(grep -c '^grow' re.tsv) rows"; fi
if [ "$(grep '^refbox' re.pack)" = "$(grep '^refbox' d1.pack)" ]; then pass "dense pack: reference box kept"; else fail "dense pack: reference box kept" "changed"; fi
check_dense "1 -> 4 MPa" re.pack 4e6
# Separate runs from the loose pack may grow grains differently, so compare the same pack
# compressed further: compaction must lower the porosity.
expect_num "1 MPa pack compressed to 4 MPa is denser" "$(info_value re.pack.txt porosity)" "<" "$(info_value d1.pack.txt porosity)"

# FIRE reaches the same target and residual
expect_ok "densify --method fire" densify --stress 4e6 --method fire -o fire.pack loose.pack
check_dense "fire" fire.pack 4e6

# Releasing unbraced grains (grains with 1-3 contacts moved to just touching between
# minimiser chunks) must not change what an equilibrium is: with a release every 50
# iterations, and with none, the pack passes the same independent checks.
expect_ok "densify --release-after 50" densify --stress 4e6 --release-after 50 -o rel50.pack loose.pack
check_dense "release every 50 iterations" rel50.pack 4e6
expect_ok "densify --release-after 0" densify --stress 4e6 --release-after 0 -o rel0.pack loose.pack
check_dense "no release" rel0.pack 4e6

# Compaction steps that move the box stop at --grow-tol (or --grow-max-iter); only a step at
# the target, minimised to the full --tol, ends the compaction.  --full-steps takes every
# step to --tol.  Either way the pack passes the same independent checks.
expect_num "d4.tsv: a compaction step stopped short of --tol (loose)" \
    "$(awk -F '\t' '$1 == "compact" && $9 > 1e-4 { k++ } END { print k + 0 }' d4.tsv)" ">=" 1
expect_ok "densify --full-steps" densify --stress 4e6 --full-steps --log full.tsv -o full.pack loose.pack
check_dense "every step to --tol" full.pack 4e6
expect_num "full.tsv: every compaction step at --tol" \
    "$(awk -F '\t' '$1 == "compact" && !($9 <= 1e-4) { k++ } END { print k + 0 }' full.tsv)" == 0

# Checkpoints: a run stopped after every stage (--time-limit far below one stage) and rerun
# until it finishes must give the uninterrupted run's pack and log, to the byte (the history
# line records the command, so it is left out, and the log's elapsed seconds); each stop exits
# 75 with one line and no pack, and keeps the log with a row for every stage so far (the call
# number: each runs one stage); the finished run removes the checkpoint.
# resume_all NAME INPUT ARGS...: reruns densify until it stops stopping; sets runs, rc.
resume_all() {
	n=$1 in=$2
	shift 2
	runs=0 stops_ok=1
	rm -f "$n.ck" "$n.pack" "$n.tsv"
	while :; do
		# one thread and two in turn: a checkpoint does not depend on the count
		densify "$@" --threads $((runs % 2 + 1)) --checkpoint "$n.ck" --time-limit 1e-9 --log "$n.tsv" -o "$n.pack" "$in" >"$n.out" 2>"$n.err"
		rc=$?
		runs=$((runs + 1))
		[ "$rc" -eq 75 ] && [ "$runs" -lt 200 ] || break
		if [ -e "$n.pack" ] || [ "$(rows "$n.tsv" | wc -l)" -ne "$runs" ] || [ -s "$n.out" ] || [ ! -s "$n.ck" ] || [ "$(wc -l <"$n.err")" -ne 1 ] ||
		    ! grep -q "^densify: stopped after [a-z]* [0-9]* at the time limit .*goes on from $n.ck\$" "$n.err"; then
			stops_ok=0
			echo "stop $runs: $(cat "$n.err")" >"$n.why"
		fi
	done
}
resume_all ck4 loose.pack --stress 4e6
expect_num "checkpoint: the run ends (exit 0) after its stops" "$rc" == 0
expect_num "checkpoint: one run per stage of the log" "$runs" == "$(rows d4.tsv | wc -l)"
if [ "$stops_ok" -eq 1 ]; then pass "checkpoint: every stop exits 75, one line, the checkpoint, no pack, the log so far"; else fail "checkpoint: every stop exits 75, one line, the checkpoint, no pack, the log so far" "$(cat ck4.why)"; fi
# stage_cols LOG: the log without its elapsed seconds (the one column that differs between runs)
stage_cols() { cut -f 1-10 "$1" >"$1.stages"; }
stage_cols d4.tsv
stage_cols ck4.tsv
grep -v '^history densify ' ck4.pack >ck4.nohist 2>/dev/null
expect_same "checkpoint: the resumed pack is the uninterrupted one" d4.nohist ck4.nohist
expect_same "checkpoint: the resumed log is the uninterrupted one (elapsed aside)" d4.tsv.stages ck4.tsv.stages
if [ ! -e ck4.ck ]; then pass "checkpoint: removed when the run is done"; else fail "checkpoint: removed when the run is done" "ck4.ck left"; fi
# a dense pack compacted further (it carries a reference box and contact lines)
resume_all ckre d1.pack --stress 4e6
grep -v '^history densify ' re.pack >re.nohist
grep -v '^history densify ' ckre.pack >ckre.nohist 2>/dev/null
expect_same "checkpoint: dense pack further, resumed, is the uninterrupted one" re.nohist ckre.nohist
# A wide size distribution (the smallest grains grow, so the skin taken from the radii of a
# resumed run would be larger) with a release every 10 iterations (the release's longest
# move is a quarter of the skin): the resumed run must still be the uninterrupted one.
expect_ok "packgen, a wide psd" packgen -n $N --seed 3 --psd uniform:2e-5,1.5e-4 -o wide.pack
densify --stress 4e6 --release-after 10 --log wide.tsv -o wide.pack.d wide.pack 2>/dev/null
resume_all ckwide wide.pack --stress 4e6 --release-after 10
grep -v '^history densify ' wide.pack.d >wide.nohist
grep -v '^history densify ' ckwide.pack >ckwide.nohist 2>/dev/null
expect_same "checkpoint: wide psd, releases every 10 iterations, resumed" wide.nohist ckwide.nohist
stage_cols wide.tsv
stage_cols ckwide.tsv
expect_same "checkpoint: wide psd, the log (elapsed aside)" wide.tsv.stages ckwide.tsv.stages
# an uninterrupted run with --checkpoint is the run without it
densify --stress 4e6 --checkpoint once.ck -o once.pack loose.pack 2>/dev/null
grep -v '^history densify ' once.pack >once.nohist 2>/dev/null
expect_same "checkpoint: --checkpoint alone changes nothing" d4.nohist once.nohist
# What a checkpoint is refused for: another run's options or input, a pack that is not a
# checkpoint, a damaged one.  The checkpoint is kept (it may be the only copy of hours of work).
rm -f other.ck al.ck
densify --stress 4e6 --checkpoint other.ck --time-limit 1e-9 -o other.pack loose.pack 2>/dev/null
cp other.ck other.keep
expect_error "checkpoint of other options" 1 '^densify: other.ck: the checkpoint of another run \(other options or another input\): remove it to start afresh$' \
    densify --stress 3e6 --checkpoint other.ck -o other.pack loose.pack
expect_same "checkpoint of other options: kept" other.keep other.ck
expect_error "checkpoint of another input" 1 '^densify: other.ck: the checkpoint of another run' \
    densify --stress 4e6 --checkpoint other.ck -o other.pack d1.pack
cp loose.pack plain.ck
expect_error "a pack that is no checkpoint" 1 '^densify: plain.ck: not a densify checkpoint' \
    densify --stress 4e6 --checkpoint plain.ck -o other.pack loose.pack
# bad_ck NAME SED REGEX: the checkpoint edited by SED is refused with one line matching REGEX
bad_ck() {
	sed "$2" other.keep >bad.ck
	if cmp -s bad.ck other.keep; then fail "$1" "the edit '$2' changed nothing"; return; fi
	expect_error "$1" 1 "$3" densify --stress 4e6 --checkpoint bad.ck -o other.pack loose.pack
}
bad_ck "a checkpoint of another version" 's/^meta densify-checkpoint 3 /meta densify-checkpoint 9 /' \
    '^densify: bad.ck: meta densify-checkpoint: not a densify checkpoint of version 3$'
bad_ck "a checkpoint without its stage" '/^meta densify-stage /d' \
    '^densify: bad.ck: meta densify-stage: missing, malformed or out of range$'
bad_ck "a checkpoint with a negative under4" 's/^\(meta densify-stage [a-z]* [^ ]* [^ ]* [^ ]*\) [0-9]* /\1 -1 /' \
    '^densify: bad.ck: meta densify-stage: missing, malformed or out of range$'
bad_ck "a checkpoint with a round beyond any" 's/^\(meta densify-checkpoint 3 [0-9]\) [0-9]* /\1 9223372036854775807 /' \
    '^densify: bad.ck: meta densify-checkpoint: malformed or out of range$'
bad_ck "a checkpoint with an infinite scale" 's/^\(meta densify-checkpoint 3 [0-9] [0-9]*\) [^ ]* /\1 inf /' \
    '^densify: bad.ck: meta densify-checkpoint: malformed or out of range$'
bad_ck "a checkpoint missing a log row" '/^meta densify-log-1 /d' \
    '^densify: bad.ck: meta densify-log-1: missing \(densify-checkpoint says 1 rows\)$'
bad_ck "a checkpoint with a row too many" 's/^\(meta densify-log-1 .*\)$/\1\nmeta densify-log-2 x/' \
    '^densify: bad.ck: meta densify-log-2: one row too many'
bad_ck "a checkpoint with a phase beyond int" 's/^meta densify-checkpoint 3 0 /meta densify-checkpoint 3 4294967296 /' \
    '^densify: bad.ck: meta densify-checkpoint: malformed or out of range$'
bad_ck "a checkpoint whose stage is not its phase's" 's/^meta densify-stage relax /meta densify-stage compact /' \
    "^densify: bad.ck: meta densify-stage: stage 'compact' after phase 0$"
bad_ck "a checkpoint whose skin is not the input's" 's/^\(meta densify-checkpoint 3 0 0 1 [^ ]*\) [^ ]* /\1 1e-300 /' \
    "^densify: bad.ck: the checkpoint's radii sum or skin is not the input's$"
bad_ck "a checkpoint whose under4 the positions do not give" 's/^\(meta densify-stage relax [^ ]* [^ ]* [^ ]*\) [0-9]* /\1 5 /' \
    "^densify: bad.ck \\(resumed\\): the checkpoint's positions give [0-9]+ grains under 4 contacts, its stage 5$"
# --allow-limit is not part of the run: a stopped run may be finished with it
densify --stress 4e6 --checkpoint al.ck --time-limit 1e-9 -o al.pack loose.pack 2>/dev/null
expect_ok "checkpoint: finished with --allow-limit added" densify --stress 4e6 --allow-limit --checkpoint al.ck -o al.pack loose.pack
grep -v '^history densify ' al.pack >al.nohist 2>/dev/null
expect_same "checkpoint: finished with --allow-limit, the same pack" d4.nohist al.nohist
if [ ! -e other.pack ]; then pass "refused checkpoints: no output"; else fail "refused checkpoints: no output" "other.pack written"; fi

# Errors: exit status, nothing on stdout, one line on stderr, no output file.
# expect_fail NAME STATUS REGEX ARGS...: densify ARGS -o nothing.pack, as expect_error, and
# neither nothing.pack nor a temporary file is left.
expect_fail() {
	n=$1 st=$2 re=$3
	shift 3
	rm -f nothing.pack
	expect_error "$n" "$st" "$re" densify "$@" -o nothing.pack
	if [ ! -e nothing.pack ] && ! ls .nothing.pack* >/dev/null 2>&1; then
		pass "$n: no output file"
	else
		fail "$n: no output file" "$(ls -a | tr '\n' ' ')"
	fi
}

# hand-made packs: 4 grains; 5 grains in a box 0.15 mm thick, thinner than a 0.2 mm grain
mkpack() {	# FILE ZHI N
	{
		echo "qusgm-pack 1"
		echo "units SI"
		echo "box 0 0 0 1.5e-3 1e-3 $2"
		echo "walls 7e12 0.495 0.3"
		echo "friction 0.3"
		echo "grains $3"
		echo "contacts 0"
		echo "end"
		k=1
		while [ $k -le "$3" ]; do
			echo "$k $((k * 25))e-5 5e-4 7e-5 1e-4 7e10 0.2 2420"
			k=$((k + 1))
		done
	} >"$1"
}
mkpack four.pack 1e-3 4
mkpack thin.pack 1.5e-4 5
expect_ok "the hand-made packs are valid packs" packinfo four.pack
expect_fail "fewer than 5 grains" 1 '^densify: .*4 grains: densify needs at least 5' four.pack
expect_fail "box thinner than a grain" 1 '^densify: .*thinner than grain' thin.pack
expect_fail "--stress 0" 2 '^densify: --stress' --stress 0 loose.pack
expect_fail "--stress -1" 2 '^densify: --stress' --stress -1 loose.pack
expect_fail "--stress 1e12 (beyond E/100)" 2 '^densify: --stress .*small-strain' --stress 1e12 loose.pack
# against the softest grain, not the mean: one grain of E = 1e5 Pa among glass ones would be
# squeezed far past Hertz's small strains at 4 MPa (one of E = 1e-300 was squeezed by 0.47 R)
awk '/^end$/ { on = 1; print; next } on && NF == 8 && !done { $6 = 1e5; id = $1; done = 1 } { print }' loose.pack >soft.pack
expect_fail "a soft grain: --stress beyond its E/100" 2 "^densify: --stress 4e\\+06 Pa is beyond the small-strain range of Hertz contacts \\(E/100 = 1000 Pa, E of grain 1, the softest\\)$" \
    --stress 4e6 soft.pack
# a target absurdly far below the moduli is refused at once, not after a minute of rounds (issue 19)
expect_fail "--stress 1e-300 (below 1e-12 E)" 2 "^densify: --stress 1e-300 Pa is below 1e-12 E of the grains \\(1e-12 E = [0-9.e+-]+ Pa\\)$" --stress 1e-300 loose.pack
expect_fail "--stress below --onset" 2 '^densify: --stress .*--onset' --onset 1e4 --stress 5e3 loose.pack
expect_fail "--tol 2" 2 '^densify: --tol' --tol 2 loose.pack
expect_fail "--method bfgs" 2 "^densify: --method: no such method 'bfgs' \\(the methods: [a-z0-9]+(, [a-z0-9]+)*\\) \\(try 'densify --help'\\)$" --method bfgs loose.pack
# the message's list is the method table (lib/qs/minimize.h, QS_METHODS), as --method's help
# line is: every method it lists is in the help line and is accepted, and the list is no
# shorter than the four methods there were when it was written
methods=$(sed -n "s/.*(the methods: \([^)]*\)).*/\1/p" err.err | tr -d ,)
help_joined densify | grep -- '--method NAME' >mhelp.txt
bad="" count=0
for m in $methods; do
	count=$((count + 1))
	grep -q -- " $m (" mhelp.txt || bad="$bad $m:not-in-help"
	# --tol 2 stops the run at the usage check, which reports every bad option
	densify --method "$m" --tol 2 -o nothing.pack loose.pack 2>&1 | grep -q -- '--method' && bad="$bad $m:refused"
done
if [ "$count" -ge 4 ] && [ -z "$bad" ]; then pass "--method: the unknown name's list ($methods) is --help's and each is accepted"; else fail "--method: the unknown name's list is --help's and each is accepted" "'$methods' ($count):$bad"; fi
expect_fail "--cap 0" 2 '^densify: --cap' --cap 0 loose.pack
expect_fail "--release-after -1" 2 '^densify: --release-after' --release-after -1 loose.pack
expect_fail "--time-limit without --checkpoint" 2 '^densify: --time-limit needs --checkpoint' --time-limit 60 loose.pack
expect_fail "--checkpoint the output" 2 "^densify: --checkpoint: 'nothing.pack' is standard output, the input, the output or the log" --checkpoint nothing.pack loose.pack
expect_fail "--checkpoint the output by another path" 2 "^densify: --checkpoint: './nothing.pack' is" --checkpoint ./nothing.pack loose.pack
expect_fail "--checkpoint the log" 2 "^densify: --checkpoint: 'l.tsv' is" --checkpoint l.tsv --log ./l.tsv loose.pack
expect_fail "--checkpoint the input" 2 "^densify: --checkpoint: 'loose.pack' is" --checkpoint loose.pack loose.pack
ln -sf nothing.ck link.pack
expect_error "--checkpoint the output through a link: allowed (the rename replaces the link)" 75 '^densify: stopped after relax 0' \
    densify --checkpoint nothing.ck --time-limit 1e-9 -o link.pack loose.pack
if [ -L link.pack ] && [ -s nothing.ck ]; then pass "the link stays until the output replaces it"; else fail "the link stays until the output replaces it" "$(ls -l link.pack nothing.ck 2>&1)"; fi
rm -f nothing.ck link.pack
expect_error "-o in a missing directory" 2 "^densify: -o: cannot write in directory 'no-such-dir'" densify --checkpoint x.ck -o no-such-dir/x.pack loose.pack
expect_fail "--checkpoint in a missing directory" 2 "^densify: --checkpoint: cannot write in directory 'no-such-dir'" --checkpoint no-such-dir/x.ck loose.pack
expect_fail "--checkpoint -" 2 "^densify: --checkpoint: '-' is" --checkpoint - loose.pack
# the log and the pack over each other, or either over the input, refused before any work
# (--log X -o X exited 0 with the log as X and the pack lost); a log that cannot be written
# fails before the run, with its own error, and leaves no pack (--log /dev/full exited 1
# after committing -o, saying "No such file or directory")
expect_fail "--log the output" 2 "^densify: -o and --log name the same file 'nothing.pack': one would replace the other" --log nothing.pack loose.pack
expect_fail "--log the output by another path" 2 "^densify: -o and --log name the same file" --log ./nothing.pack loose.pack
cp loose.pack in.pack
expect_fail "--log the input" 2 "^densify: --log 'in.pack' is the input: write to another file" --log in.pack in.pack
# -o the input: the pack updated in place (read whole, then renamed over it)
# (the optimised build's: the in-place write is lib/base/fileio's, which the sanitizer
# build checks through loadtest's and dissociate's, at a fraction of this run's CPU)
if [ "${BIN#*build-san}" = "$BIN" ]; then
	densify --stress 4e6 -o ref.pack in.pack 2>/dev/null
	expect_ok "-o the input: allowed" densify --stress 4e6 -o in.pack in.pack
	expect_same "-o the input: the pack updated in place, as -o another file" in.pack ref.pack
fi
cp loose.pack in.pack
# a log through a symbolic link is written into the file the link names: refused when that
# is the input or -o (it exited 0 with the input, or the log, lost); /dev/stdout is stdout
ln -s in.pack in.link
expect_fail "--log a link to the input" 2 "^densify: --log 'in.link' is the input: write to another file \\(the input would be lost\\)" --log in.link in.pack
expect_same "--log a link to the input: the input untouched" in.pack loose.pack
ln -s nothing.pack out.link
expect_fail "--log a link to -o" 2 "^densify: -o and --log name the same file 'nothing.pack'" --log out.link loose.pack
ln -s later.pack dangling.link
expect_refused "no output file" later.pack "--log a link to -o not yet written" 2 "^densify: -o and --log name the same file 'later.pack'" \
    densify --log dangling.link -o later.pack loose.pack
rm -f in.link out.link dangling.link
expect_error "--log /dev/stdout with the pack on stdout" 2 "^densify: --log and -o both go to standard output" densify --log /dev/stdout loose.pack
if densify --stress 4e6 --log /dev/stdout -o ref2.pack loose.pack >stdout.log 2>/dev/null && [ "$(head -n 1 ref2.pack)" = "qusgm-pack 1" ] &&
    [ "$(rows stdout.log | wc -l)" -ge 2 ] && ! grep -q '^qusgm-pack' stdout.log; then
	pass "--log /dev/stdout with -o FILE: the log on stdout"
else
	fail "--log /dev/stdout with -o FILE: the log on stdout" "$(head -c 300 stdout.log)"
fi
expect_error "-o ''" 2 "^densify: -o: the file name is empty" densify -o '' loose.pack
expect_error "--log ''" 2 "^densify: --log: the file name is empty" densify --log '' -o x.pack loose.pack
expect_error "--log to standard output with the pack" 2 "^densify: --log and -o both go to standard output" densify --log - loose.pack
expect_fail "--log in a missing directory" 2 "^densify: --log: cannot write in directory 'no-such-dir'" --log no-such-dir/l.tsv loose.pack
expect_fail "--log /dev/full" 1 '^densify: /dev/full: write error: No space left on device$' --log /dev/full loose.pack
expect_fail "--time-limit -1" 2 '^densify: --time-limit' --checkpoint x.ck --time-limit -1 loose.pack
expect_fail "--max-iter 0" 2 '^densify: --max-iter' --max-iter 0 loose.pack
expect_fail "unknown option" 2 '^densify: unknown option' --bogus loose.pack
expect_fail "missing input file" 1 '^densify: ' no-such.pack
# a limit that every minimisation reaches yet lets phase (a) seat every grain: with 3 one grain
# of this pack stayed under 4 contacts for the 1000 rounds (5 to 50 all end at the limit)
expect_fail "iteration limit" 1 '^densify: .*iteration limit.*--allow-limit' --max-iter 10 --log lim.tsv loose.pack
# a failed run keeps its log, every stage it ran (the relaxation at least), as the run went
if [ -f lim.tsv ] && [ "$(head -n 1 lim.tsv)" = "$hdr" ] && [ "$(rows lim.tsv | wc -l)" -ge 1 ] && [ "$(tail -c 1 lim.tsv | od -An -c | tr -d ' ')" = '\n' ]; then
	pass "iteration limit: the log kept, header and complete rows"
else
	fail "iteration limit: the log kept, header and complete rows" "$(ls -l lim.tsv 2>&1)"
fi

# --allow-limit keeps the pack, exits 0 and warns in one line
densify --max-iter 10 --allow-limit -o lim.pack loose.pack >lim.out 2>lim.err
rc=$?
if [ "$rc" -eq 0 ] && [ -s lim.pack ] && [ ! -s lim.out ] && [ "$(wc -l <lim.err)" -eq 1 ] && grep -q 'iteration limit' lim.err; then
	pass "--allow-limit: exit 0, the pack, one warning"
else
	fail "--allow-limit: exit 0, the pack, one warning" "exit $rc, stderr: $(head -c 300 lim.err)"
fi
