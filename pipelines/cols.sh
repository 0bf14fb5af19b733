#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# cols.sh FILE NAME...: print the named columns of a qusgm table (loadtest, frictionalize --log,
# densify --log, moduli; share/doc/tables.md), tab-separated, without the header.  Units in
# brackets are ignored in the names ("sigma_c" finds "sigma_c[Pa]"); '##' lines are skipped.
# A missing column is an error: a figure must not silently plot the wrong thing.
f=$1
shift
awk -F'\t' -v want="$*" '
BEGIN { n = split(want, w, " ") }
/^##/ { next }
/^# / && !hdr {
	sub(/^# /, "")
	for (i = 1; i <= NF; i++) { c = $i; sub(/\[.*\]$/, "", c); idx[c] = i }
	for (k = 1; k <= n; k++)
		if (!(w[k] in idx)) { print "cols.sh: " FILENAME ": no column " w[k] > "/dev/stderr"; bad = 1; exit 2 }
	hdr = 1
	next
}
/^#/ { next }
hdr { s = $(idx[w[1]]); for (k = 2; k <= n; k++) s = s "\t" $(idx[w[k]]); print s }
END { if (!hdr && !bad) { print "cols.sh: " FILENAME ": no header line" > "/dev/stderr"; exit 2 } }' "$f"
