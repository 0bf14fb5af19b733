#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A conventional triaxial test of a quartz pack, as a laboratory runs one.  The grains are
# compacted without friction to an isotropic stress (densify), and friction is switched on by
# uniaxial strain increments until the share of sliding contacts saturates (frictionalize),
# which leaves the pack loaded far more along z than across (at STRESS=10e6 about 50 MPa
# against 15 MPa).  The pack is then consolidated to the cell pressure, as a sample is before
# its test: the axis unloads while the side walls hold their mean stress at the cell pressure,
# until the mean stress is the cell pressure too (loadtest --path 'triaxial hold=P step=-1e-4
# to-stress=P').  Then the test: the pack is compressed along z while the side walls hold
# their mean stress at the cell pressure ('triaxial hold=P').  It shows the deviatoric stress
# q = sig_zz - sig_lat rising from about 0 with the axial strain at a constant lateral
# stress, the volumetric strain (compaction positive), and the friction angle the pack
# mobilises, sin(phi) = q / (sig_zz + sig_lat); the summary's first row is the consolidated
# state, its last the largest strain.
#
#   sh triaxial.sh [N [DIR]]    N grains (default 1000; under half a minute of one core),
#                               every file in DIR (default triaxial/)
#   STRESS=10e6 MU=0.5 STEPS=200 sh triaxial.sh   the compaction stress (Pa), the friction
#                               coefficient, the test's increments of 1e-4 axial strain
#   CELL=PA                     the cell pressure (Pa) [STRESS]
#   BIN=DIR                     the tools from DIR instead of PATH
# Outputs: loose, dense and frictional packs, frictionalize's log fric.tsv, the table
# curve.tsv of the consolidation (seg 1) and the test (seg 2), a row per increment
# (qusgm-tables(5)), and the last pack final.pack.gz.
set -eu
n=${1:-1000} dir=${2:-triaxial}
stress=${STRESS:-10e6} mu=${MU:-0.5} steps=${STEPS:-200}
cell=${CELL:-$stress}
bin=${BIN:+$BIN/}
mkdir -p "$dir"
cd "$dir"
"${bin}packgen" -n "$n" --material quartz -o loose.pack.gz
"${bin}densify" --stress "$stress" -o dense.pack.gz loose.pack.gz
"${bin}frictionalize" --mu "$mu" --log fric.tsv -o fric.pack.gz dense.pack.gz
"${bin}loadtest" --path "triaxial hold=$cell step=-1e-4 to-stress=$cell; triaxial hold=$cell steps=$steps" \
	-o final.pack.gz fric.pack.gz >curve.tsv
# about ten rows of the test: the consolidated state (the last row of seg 1), then rows of
# seg 2; strains from the consolidated state, stresses in MPa
awk -F '\t' -v every="$(( (steps + 9) / 10 ))" '
function row(   ez, ev, lat, q) {
	ez = $col["eps_zz"]; ev = $col["eps_xx"] + $col["eps_yy"] + ez
	lat = $col["sig_lat"]; q = $col["sig_zz"] - lat
	if (k == 0) { ez0 = ez; ev0 = ev }
	return sprintf("%.5f\t%.5f\t%.3f\t%.3f\t%.4f\t%.3f", ez - ez0, ev - ev0, lat / 1e6, q / 1e6,
	    q / ($col["sig_zz"] + lat), $col["sliding_ratio"])
}
/^##/ { next }
/^# / { sub(/^# /, ""); for (i = 1; i <= NF; i++) { c = $i; sub(/\[.*\]$/, "", c); col[c] = i }
	print "# d_eps_axial\td_eps_vol\tsig_lat[MPa]\tq[MPa]\tsin_phi\tsliding_ratio"; next }
$col["seg"] < 2 { last = $0; next }
k == 0 { line = $0; $0 = last; print row(); k++; $0 = line }
{ r = row(); if (k++ % every == 0) print r; else pending = r }
END { if ((k - 1) % every != 0) print pending }' curve.tsv
