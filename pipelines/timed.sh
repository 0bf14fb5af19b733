#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# timed.sh LOG NAME OUT CMD [ARG...]: run CMD with its standard output to OUT (- keeps it),
# then append "NAME<tab>seconds" to LOG when it succeeded.  The studies' reports add up the
# times of the stages they need (report.sh), so a study's cost is known however make -j
# interleaved it.
log=$1 name=$2 out=$3
shift 3
t0=$(date +%s.%N)
if [ "$out" = - ]; then "$@"; else "$@" >"$out"; fi
rc=$?
t1=$(date +%s.%N)
[ "$rc" -eq 0 ] && awk -v n="$name" -v a="$t0" -v b="$t1" 'BEGIN { printf "%s\t%.1f\n", n, b - a }' >>"$log"
exit "$rc"
