# SPDX-License-Identifier: GPL-3.0-or-later
# Progress (lib/base/cli.h): on a terminal a status line redrawn in place, with a bar and an
# ETA where the run has a target; in a pipe nothing without -v, and with -v plain lines.
# The terminal is a pseudo-terminal made by script(1) (util-linux), 200 columns wide.
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
	on_tty q.tty densify -q --stress 4e6 -o q.pack loose.pack
	expect_num "densify -q on a terminal: nothing" "$(wc -c <q.tty)" == 0
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
