#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# packpic.sh PACK OUT.png [COLOUR] [TITLE]: a picture of a sphere pack's force network, drawn
# by gnuplot from packexport's tables: the slab of grains whose centres lie within one mean
# radius of the box's middle plane y = y_c, seen along y (x across, z up), each grain the
# disc where the plane cuts it, filled by COLOUR, a column of packexport --tsv-grains
# (contacts, the default: the grain's contacts with grains and walls; phase; r; E ...),
# and each contact between two grains of the slab (or a grain and a wall) a black line from
# centre to centre whose width follows its normal force: eight classes, 0.5 pt per half mean
# force (P / P_mean < 0.5: 0.5 pt, ... 4 pt from 3.5 P_mean up).
# Needs packexport on PATH or BIN, and gnuplot (gnuplot-nox).
set -e
pack=$1 out=$2 colour=${3:-contacts} title=${4:-}
bin=${BIN:+$BIN/}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"${bin}packexport" --tsv-grains "$pack" >"$tmp/g.tsv"
if head -n 1 "$tmp/g.tsv" | grep -q 'side\[m\]'; then
	# spheroplates (no force network: their interactions are the plate engine's): the plates
	# centred within half a plate width of the middle plane z = z_c, seen along z (x across,
	# y, the shear test's gradient, up), each the trace of its mid-plane, n x e_z, as wide as
	# the plate (L + 2 r), coloured by COLOUR (a grain column; |ny| by default, a normal's
	# component taken by its size)
	[ "$colour" = contacts ] && colour=ny
	set -- $(awk -F '\t' '!/^#/ { n++; s += $9 / 2 + $5; if (n == 1 || $4 < lo) lo = $4; if (n == 1 || $4 > hi) hi = $4 }
		END { printf "%.17g %.17g", (lo + hi) / 2, s / n }' "$tmp/g.tsv")
	awk -F '\t' -v zc="$1" -v w="$2" -v col="$colour" '
		/^# / { sub(/^# /, ""); for (i = 1; i <= NF; i++) { c = $i; sub(/\[.*\]$/, "", c); idx[c] = i }
			if (!(col in idx)) { print "packpic.sh: no grain column " col > "/dev/stderr"; exit 2 }; next }
		{ d = $4 - zc; if (d < 0) d = -d; if (d >= w) next
		  ux = $(idx["ny"]); uy = -$(idx["nx"]); u = sqrt(ux * ux + uy * uy); h = $9 / 2 + $5
		  if (u < 1e-9) { ux = 1; uy = 0; u = 1 }
		  ux *= h / u; uy *= h / u
		  v = $(idx[col]); if (col ~ /^n[xyz]$/ && v < 0) v = -v	# n and -n: one orientation
		  printf "%.9g\t%.9g\t%.9g\t%.9g\t%s\n", $2 - ux, $3 - uy, 2 * ux, 2 * uy, v }' "$tmp/g.tsv" >"$tmp/segs.tsv"
	case $colour in n[xyz]) colour="|$colour|" ;; esac
	set -- $(gzip -dcf "$pack" | awk '$1 == "box" { print $2, $3, $5, $6; exit }')
	nseg=$(wc -l <"$tmp/segs.tsv")
	gnuplot -e "segs='$tmp/segs.tsv'; out='$out'; colour='$colour'; x0=$1; z0=$2; x1=$3; z1=$4; \
		ttl='${title:+$title: }plates centred within half a plate width of z_c ($nseg), seen along z'" \
		"$(dirname "$0")/pack.gp"
	exit 0
fi
"${bin}packexport" --tsv-contacts "$pack" >"$tmp/c.tsv"
# the slab: centre and half-width, from the grains
set -- $(awk -F '\t' '!/^#/ { n++; s += $5; if (n == 1 || $3 < lo) lo = $3; if (n == 1 || $3 > hi) hi = $3 }
	END { printf "%.17g %.17g", (lo + hi) / 2, s / n }' "$tmp/g.tsv")
yc=$1 w=$2
# discs: x z section-radius colour, of the grains cut by the plane and centred in the slab
awk -F '\t' -v yc="$yc" -v w="$w" -v col="$colour" '
	/^# / { sub(/^# /, ""); for (i = 1; i <= NF; i++) { c = $i; sub(/\[.*\]$/, "", c); idx[c] = i }
		if (!(col in idx)) { print "packpic.sh: no grain column " col > "/dev/stderr"; exit 2 }; next }
	{ d = $3 - yc; if (d < 0) d = -d; if (d < w && d < $5) { print $1 "\t" $2 "\t" $4 "\t" sqrt($5 * $5 - d * d) "\t" $(idx[col]) } }' \
	"$tmp/g.tsv" >"$tmp/discs.tsv"
# lines: x1 z1 dx dz class, for contacts whose two grains are discs (or a disc and a wall)
awk -F '\t' 'FNR == NR { in_slab[$1] = 1; next }
	/^#/ { next }
	($1 in in_slab) && ($2 < 0 || ($2 in in_slab)) { n++; P[n] = $9; x[n] = $3; z[n] = $5; dx[n] = $6 - $3; dz[n] = $8 - $5; s += $9 }
	END { m = n ? s / n : 1; for (k = 1; k <= n; k++) { c = int(2 * P[k] / m) + 1; if (c > 8) c = 8
		printf "%.9g\t%.9g\t%.9g\t%.9g\t%d\n", x[k], z[k], dx[k], dz[k], c } }' "$tmp/discs.tsv" "$tmp/c.tsv" >"$tmp/lines.tsv"
# the box, from the pack's header (plain or gzip)
set -- $(gzip -dcf "$pack" | awk '$1 == "box" { print $2, $4, $5, $7; exit }')
box="x0=$1; z0=$2; x1=$3; z1=$4"
ndisc=$(wc -l <"$tmp/discs.tsv")
nline=$(wc -l <"$tmp/lines.tsv")
gnuplot -e "discs='$tmp/discs.tsv'; lines='$tmp/lines.tsv'; out='$out'; colour='$colour'; $box; \
	ttl='${title:+$title: }slab |y - y_c| < r_mean ($ndisc grains, $nline contacts), line width ~ normal force'" \
	"$(dirname "$0")/pack.gp"
