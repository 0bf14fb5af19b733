# SPDX-License-Identifier: GPL-3.0-or-later
# Progress (lib/base/cli.h): on a terminal a status line redrawn in place, with a bar and an
# ETA where the run has a target, fitted to the terminal's width, ended when the tool is
# killed, and a closing line at success; in a pipe nothing without -v, and with -v plain lines.
# A tool that reads a terminal's standard input says so.  The terminal is a pseudo-terminal
# made by script(1) (util-linux), 200 columns wide unless a check says otherwise.
. "$TOP/tests/tools/lib.sh"

packgen -n 300 --seed 3 -o loose.pack 2>/dev/null
# on_tty FILE CMD: run CMD with its standard error on a pseudo-terminal, the terminal's bytes into FILE
on_tty() {
	f=$1
	shift
	script -qfec "stty cols 200 2>/dev/null; $*" /dev/null >"$f" 2>&1 </dev/null
}
if ! command -v script >/dev/null 2>&1; then
	fail "script(1) is there (util-linux: bsdutils)" "not found"
else
	on_tty d.tty densify --stress 4e6 -o d.pack loose.pack
	# the line of a compaction step: stage, iterations, residual, elapsed, bar, ETA
	if tr '\r' '\n' <d.tty | grep -aEq '^densify: compact [0-9]+  it [0-9]+  res [0-9.e+-]+  [0-9:]+s?  \[[#.]{20}\] +[0-9]+% ETA '; then
		pass "densify on a terminal: stage, iterations, residual, elapsed, bar and ETA"
	else
		fail "densify on a terminal: stage, iterations, residual, elapsed, bar and ETA" "$(tr '\r' '\n' <d.tty | tail -n 3 | cut -c 1-200)"
	fi
	if tr '\r' '\n' <d.tty | grep -aEq '^densify: grow [0-9]+  it [0-9]+  res '; then
		pass "densify on a terminal: the growth rounds, without a target"
	else
		fail "densify on a terminal: the growth rounds, without a target" "$(tr '\r' '\n' <d.tty | head -n 3 | cut -c 1-200)"
	fi
	if grep -aq "$(printf '\033')\[K" d.tty && [ "$(tr -cd '\r' <d.tty | wc -c)" -ge 2 ]; then
		pass "densify on a terminal: the line is redrawn in place (CR, erase to the end)"
	else
		fail "densify on a terminal: the line is redrawn in place (CR, erase to the end)" "$(od -c d.tty | head -n 3)"
	fi
	on_tty l.tty loadtest -n 4 -o l.pack d.pack ">l.tsv"
	if tr '\r' '\n' <l.tty | grep -aEq '^loadtest: segment 1 increment [0-9]+ .*\[[#.]{20}\] +[0-9]+% ETA '; then
		pass "loadtest on a terminal: bar and ETA of the increments"
	else
		fail "loadtest on a terminal: bar and ETA of the increments" "$(tr '\r' '\n' <l.tty | tail -n 2 | cut -c 1-200)"
	fi
	if [ "${BIN#*build-san}" = "$BIN" ]; then	# a whole densify to see nothing: the optimised build's
		on_tty q.tty densify -q --stress 4e6 -o q.pack loose.pack
		expect_num "densify -q on a terminal: nothing" "$(wc -c <q.tty)" == 0
	fi
	# a run that succeeds ends with one line: its time and its last summary in full
	if [ "$(tr '\r' '\n' <d.tty | grep -av '^$' | tail -n 1)" != "" ] &&
	    tr '\r' '\n' <d.tty | grep -av '^$' | tail -n 1 | grep -aEq '^densify: done in [0-9:]+s?: compact [0-9]+: sigma_c .* residual [0-9.e+-]+$'; then
		pass "densify on a terminal: a closing line at success"
	else
		fail "densify on a terminal: a closing line at success" "$(tr '\r' '\n' <d.tty | tail -n 2 | cut -c 1-200)"
	fi
	# a run that fails has none: the error is the last line
	on_tty f.tty densify --stress 4e6 --max-rounds 1 -o f.pack loose.pack
	if grep -aq 'done in' f.tty || ! tr '\r' '\n' <f.tty | grep -av '^$' | tail -n 1 | grep -aq 'did not finish'; then
		fail "densify on a terminal, failing: no closing line" "$(tr '\r' '\n' <f.tty | tail -n 2 | cut -c 1-200)"
	else
		pass "densify on a terminal, failing: no closing line"
	fi

	# The line fits the terminal (it was cut at the width: at 80 columns the ETA's number went):
	# every line drawn is under the width, and each of the compaction's ends with a whole ETA;
	# the window's width, else COLUMNS (a terminal that reports none), else 80.
	# fits FILE WIDTH NAME
	fits() {
		tr '\r' '\n' <"$1" | sed "s/$(printf '\033')\[K//g" | grep -a '^densify: ' | grep -av 'done in' >fit.lines
		long=$(awk -v w="$2" 'length($0) >= w' fit.lines | head -n 1)
		# the status before the summary ("  | "), where it shows the target (a bar or a percentage)
		grep -a '^densify: compact' fit.lines | sed 's/  | .*//' | grep -aE '\[|%' >fit.target
		compact=$(wc -l <fit.target)
		cut=$(grep -avE '% ETA ([0-9]+s|[0-9]+:[0-9][0-9](:[0-9][0-9])?|\?)$' fit.target | head -n 1)
		if [ -n "$long" ]; then
			fail "$3: every line under $2 columns" "$long"
		elif [ "$compact" -lt 1 ] || [ -n "$cut" ]; then
			fail "$3: the compaction's lines end with a whole ETA" "$compact lines; $cut"
		else
			pass "$3: every line under $2 columns, each compaction line with a whole ETA ($compact)"
		fi
	}
	# The widths and the kill below are the optimised build's: under the sanitizers they took
	# 75 of this test's 90 s of CPU (densify's runs at 3 widths, a 2000-grain pack killed), to
	# draw the same line with the same code that the terminal runs above have just checked.
	if [ "${BIN#*build-san}" = "$BIN" ]; then
	for c in 80 40; do
		script -qfec "stty cols $c 2>/dev/null; densify --stress 4e6 -o w.pack loose.pack" /dev/null >w$c.tty 2>&1 </dev/null
		fits w$c.tty $c "densify on $c columns"
	done
	script -qfec "stty cols 0 rows 0 2>/dev/null; COLUMNS=50 densify --stress 4e6 -o w.pack loose.pack" /dev/null >wc.tty 2>&1 </dev/null
	fits wc.tty 50 "densify on a terminal of no width, COLUMNS=50"

	# Killed (TERM) while its line is up: the line is ended, so the shell writes below it.
	packgen -q -n 2000 --seed 1 -o big.pack
	rm -f k.pid
	script -qfec "stty cols 200 2>/dev/null; densify --threads 1 --stress 4e6 -o k.pack big.pack & echo \$! >k.pid; wait \$!; echo \"exit \$?\"" \
		/dev/null >k.tty 2>&1 </dev/null &
	spid=$!
	i=0
	while [ $i -lt 1000 ] && ! grep -aq 'densify: grow' k.tty 2>/dev/null; do
		sleep 0.01
		i=$((i + 1))
	done
	[ -s k.pid ] && kill -TERM "$(cat k.pid)" 2>/dev/null
	wait $spid
	if ! grep -aq 'exit 143' k.tty || ! grep -aq 'densify: grow' k.tty; then
		fail "densify killed by TERM on a terminal" "not killed while its line was up: $(tr '\r' '\n' <k.tty | tail -n 2 | cut -c 1-200)"
	elif ! grep -aq '^exit 143' k.tty; then
		fail "densify killed by TERM on a terminal: the status line ended" "$(tr '\r' '\n' <k.tty | tail -n 1 | cut -c 1-200)"
	else
		pass "densify killed by TERM on a terminal: the status line ended before the shell's next line"
	fi
	fi	# the optimised build's
fi
# in a pipe: nothing without -v; with -v plain lines (no CR, no escapes), one per stage
densify --stress 4e6 -o p.pack loose.pack 2>p.err
expect_num "densify in a pipe: nothing on stderr" "$(wc -c <p.err)" == 0
densify -v --stress 4e6 --log v.tsv -o v.pack loose.pack 2>v.err
if grep -q "$(printf '\r')" v.err || grep -q "$(printf '\033')" v.err; then
	fail "densify -v in a pipe: plain lines" "$(od -c v.err | head -n 2)"
else
	pass "densify -v in a pipe: plain lines"
fi
expect_num "densify -v in a pipe: a line per stage of the log" "$(grep -cE '^densify: (relax|grow|retry|compact) [0-9]+: ' v.err)" == "$(rows v.tsv | wc -l)"
if tail -n 1 v.err | grep -Eq '^densify: done in [0-9:]+s?: compact [0-9]+: '; then
	pass "densify -v in a pipe: the closing line last"
else
	fail "densify -v in a pipe: the closing line last" "$(tail -n 1 v.err)"
fi

# A tool given no file reads standard input; on a terminal it says so (it waited without a
# word), once, before it reads: every tool that reads one.  The terminal's end of input comes
# at once here (script's own input is /dev/null), so each then stops at the empty input.
if command -v script >/dev/null 2>&1; then
	for t in densify dissociate frictionalize loadtest moduli "packexport --xyzr" packimport packinfo packview shear; do
		name=${t%% *}
		on_tty s.tty "$t"
		case $name in
		moduli) what="a loadtest table" ;;
		packimport) what="'x y z r' lines" ;;
		*) what="a pack" ;;
		esac
		if [ "$(tr -d '\r' <s.tty | head -n 1)" = "$name: reading $what from standard input (Ctrl-D ends it)" ] &&
		    [ "$(grep -c 'from standard input' s.tty)" -eq 1 ]; then
			pass "$name on a terminal's standard input: says it reads $what"
		else
			fail "$name on a terminal's standard input: says it reads $what" "$(tr -d '\r' <s.tty | head -n 2 | tr '\n' '|')"
		fi
	done
	on_tty sq.tty "packinfo -q"
	if grep -q 'from standard input' sq.tty; then fail "packinfo -q: no word of standard input" "$(head -n 1 sq.tty)"; else pass "packinfo -q: no word of standard input"; fi
	on_tty sf.tty "packinfo loose.pack"
	if grep -q 'from standard input' sf.tty; then fail "packinfo FILE on a terminal: no word of standard input" "$(head -n 1 sf.tty)"; else pass "packinfo FILE on a terminal: no word of standard input"; fi
fi
# not a terminal: nothing said
packinfo <loose.pack >/dev/null 2>sp.err
expect_num "packinfo from a pipe: nothing on stderr" "$(wc -c <sp.err)" == 0
