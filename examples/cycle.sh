#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A load-unload cycle in uniaxial strain (an oedometer) of a frictional glass pack, the
# frictional paper's setting: compacted without friction to 4 MPa (densify), friction
# switched on (frictionalize), then one loadtest path of two segments, loading along z to
# TOP and unloading to BOTTOM, and moduli fitted to every ten increments of each segment.
# It shows the hysteresis friction makes: the pack unloads stiffer than it loaded (contacts
# that slid stick again when the load reverses, so G of the first unloading interval is
# above the last loading one), and it keeps a permanent strain: on the way down it passes
# the stress it started from at a larger axial strain.
#
#   sh cycle.sh [N [DIR]]       N grains (default 1000; under half a minute of one core),
#                               every file in DIR (default cycle/)
#   TOP=20e6 BOTTOM=4e6 MU=0.3 sh cycle.sh   the turning stresses sigma_c (Pa), friction
#   BIN=DIR                     the tools from DIR instead of PATH
# Outputs: the packs, frictionalize's log fric.tsv, the cycle's table curve.tsv (segment 1
# loading, 2 unloading; qusgm-tables(5)), its moduli moduli.tsv and its last pack final.pack.gz.
set -eu
n=${1:-1000} dir=${2:-cycle}
top=${TOP:-20e6} bottom=${BOTTOM:-4e6} mu=${MU:-0.3}
bin=${BIN:+$BIN/}
mkdir -p "$dir"
cd "$dir"
"${bin}packgen" -n "$n" --material glass -o loose.pack.gz
"${bin}densify" --stress 4e6 -o dense.pack.gz loose.pack.gz
"${bin}frictionalize" --mu "$mu" --log fric.tsv -o fric.pack.gz dense.pack.gz
"${bin}loadtest" --path "uniaxial step=1e-4 to-stress=$top; uniaxial step=-1e-4 to-stress=$bottom" \
	-o final.pack.gz fric.pack.gz >curve.tsv
"${bin}moduli" --window 10 -o moduli.tsv curve.tsv
# the turning points, the permanent strain (the unloading's axial strain where sigma_c
# comes back to its starting value, interpolated, less the starting strain) and G either
# side of the turn
awk -F '\t' '
FNR == 1 { f++ }
/^##/ { next }
/^# / { sub(/^# /, ""); delete col; for (i = 1; i <= NF; i++) { c = $i; sub(/\[.*\]$/, "", c); col[c] = i }; next }
f == 1 { e = $col["eps_zz"]; s = $col["sigma_c"]
	if (!n++) { e0 = e; s0 = s }
	if ($col["seg"] == 1) { etop = e; stop = s }
	if ($col["seg"] == 2 && s <= s0 && !eback) eback = pe + (e - pe) * (s0 - ps) / (s - ps)
	pe = e; ps = s; elast = e; slast = s }
f == 2 { if ($col["seg"] == 1) gload = $col["G"]; else if (!gunload) gunload = $col["G"] }
END {
	printf "start       eps_zz %.5f  sigma_c %.3f MPa\n", e0, s0 / 1e6
	printf "top         eps_zz %.5f  sigma_c %.3f MPa\n", etop, stop / 1e6
	printf "end         eps_zz %.5f  sigma_c %.3f MPa\n", elast, slast / 1e6
	if (eback) printf "permanent   eps_zz %.5f  at sigma_c %.3f MPa on the way down\n", eback - e0, s0 / 1e6
	printf "G loading   %.1f MPa (last interval)\nG unloading %.1f MPa (first interval)\n", gload / 1e6, gunload / 1e6
}' curve.tsv moduli.tsv
