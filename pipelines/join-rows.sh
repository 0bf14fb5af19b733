#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# join-rows.sh FILE...: one table of the rows of several qusgm tables with the same columns
# (share/doc/tables.md), e.g. the platy study's summaries of one platyness each
# (validate/platy-8000/summary-eta*.tsv): the first file's '##' lines and header once, then
# every file's rows sorted by the first column, numerically.  A file whose header differs
# from the first's, or that has none, is an error (its rows would land under the wrong names):
# one line "join-rows.sh: FILE: what is wrong", exit 2, nothing on stdout.
set -e
[ $# -gt 0 ] || { echo "join-rows.sh: usage: join-rows.sh FILE..." >&2; exit 2; }
export LC_ALL=C
tab=$(printf '\t')
hdr=
for f in "$@"; do
	[ -f "$f" ] && [ -r "$f" ] || { echo "join-rows.sh: $f: cannot read it" >&2; exit 2; }
	h=$(grep -m 1 '^# ' "$f") || { echo "join-rows.sh: $f: no header line" >&2; exit 2; }
	[ -z "$hdr" ] && hdr=$h first=$f
	[ "$h" = "$hdr" ] || { echo "join-rows.sh: $f: header differs from $first's" >&2; exit 2; }
done
grep '^##' "$1" || true
printf '%s\n' "$hdr"
cat "$@" | grep -v '^#' | sort -s -t "$tab" -k 1,1g
