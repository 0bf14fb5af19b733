#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# tests/bench-threads.sh [BINDIR]: densify of a 2740-grain pack (packgen -n 2740 --seed 1) to
# 4 MPa beside a competing job (`yes >/dev/null`, one core busy), with the default threads,
# with --threads 1, and with --threads 2 (idle threads waiting passively, the tools' default
# policy) and --threads 2 with OMP_WAIT_POLICY=active (libgomp's spinning, what the tools did
# before); wall, user and system seconds of each (/usr/bin/time), and whether the packs are
# the same bytes (history lines aside).  Prints rows for bench/threads.md.  BENCH_ACTIVE=0
# leaves out the spinning run (minutes on a busy machine).
set -u
bin=${1:-build/bin}
case $bin in /*) ;; *) bin=$(pwd)/$bin ;; esac
w=${TMPDIR:-/tmp}/bench-threads.$$
mkdir -p "$w" && cd "$w" || exit 2
"$bin/packgen" -q -n 2740 --seed 1 -o loose.pack.gz || exit 1
yes >/dev/null &
y=$!
trap 'kill $y 2>/dev/null; rm -rf "$w"' EXIT
echo "| run | threads used | wall s | user s | sys s | load (1 min) at start | same pack |"
echo "| --- | --- | --- | --- | --- | --- | --- |"
# run NAME ENV ARGS...: densify with ENV (VAR=value, or - for none) and ARGS
run() {
	name=$1 e=$2
	shift 2
	[ "$e" = - ] && e=QUSGM_BENCH=1
	load=$(cut -d' ' -f1 /proc/loadavg)
	/usr/bin/time -f '%e %U %S' -o t.txt env "$e" "$bin/densify" -v "$@" --stress 4e6 -o "$name.pack" loose.pack.gz 2>"$name.err"
	th=$(sed -n 's/^densify: \([0-9]*\) threads\{0,1\} (--threads)$/\1/p' "$name.err" | head -n 1)
	grep -v '^history' "$name.pack" >"$name.body"
	same=no
	cmp -s "$name.body" one.body 2>/dev/null && same=yes
	[ "$name" = one ] && same=reference
	read -r wall user sys <t.txt
	echo "| $name | $th | $wall | $user | $sys | $load | $same |"
}
run one - --threads 1
run default -
run two-passive - --threads 2
[ "${BENCH_ACTIVE:-1}" = 0 ] || run two-spinning OMP_WAIT_POLICY=active --threads 2
