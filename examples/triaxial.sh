#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# A conventional triaxial test of a quartz pack.  The grains are compacted without friction
# to an isotropic stress (densify), friction is switched on by uniaxial strain increments
# until the share of sliding contacts saturates (frictionalize), and the pack is then
# compressed along z while the side walls are moved to hold their mean stress where it was
# (loadtest --path 'triaxial hold').  It shows the deviatoric stress q = sig_zz - sig_lat
# rising with the axial strain at a nearly constant lateral stress, the volumetric strain
# (compaction positive), and the friction angle the pack mobilises, sin(phi) = q / (sig_zz +
# sig_lat); the last row of its table has the largest strain.
#
#   sh triaxial.sh [N [DIR]]    N grains (default 1000; under half a minute of one core),
#                               every file in DIR (default triaxial/)
#   STRESS=10e6 MU=0.5 STEPS=200 sh triaxial.sh   the compaction stress (Pa), the friction
#                               coefficient, the test's increments of 1e-4 axial strain
#   BIN=DIR                     the tools from DIR instead of PATH
# Outputs: loose, dense and frictional packs, frictionalize's log fric.tsv, the test's table
# curve.tsv (a row per increment, qusgm-tables(5)) and its last pack final.pack.gz.
set -eu
n=${1:-1000} dir=${2:-triaxial}
stress=${STRESS:-10e6} mu=${MU:-0.5} steps=${STEPS:-200}
bin=${BIN:+$BIN/}
mkdir -p "$dir"
cd "$dir"
"${bin}packgen" -n "$n" --material quartz -o loose.pack.gz
"${bin}densify" --stress "$stress" -o dense.pack.gz loose.pack.gz
"${bin}frictionalize" --mu "$mu" --log fric.tsv -o fric.pack.gz dense.pack.gz
"${bin}loadtest" --path 'triaxial hold' --steps "$steps" -o final.pack.gz fric.pack.gz >curve.tsv
# about ten rows of the curve: strains from the test's start, stresses in MPa
awk -F '\t' -v every="$(( (steps + 9) / 10 ))" '
/^##/ { next }
/^# / { sub(/^# /, ""); for (i = 1; i <= NF; i++) { c = $i; sub(/\[.*\]$/, "", c); col[c] = i }
	print "# d_eps_axial\td_eps_vol\tsig_lat[MPa]\tq[MPa]\tsin_phi\tsliding_ratio"; next }
{ ez = $col["eps_zz"]; ev = $col["eps_xx"] + $col["eps_yy"] + ez
  if (k++ == 0) { ez0 = ez; ev0 = ev }
  lat = $col["sig_lat"]; q = $col["sig_zz"] - lat
  row = sprintf("%.5f\t%.5f\t%.3f\t%.3f\t%.4f\t%.3f", ez - ez0, ev - ev0, lat / 1e6, q / 1e6,
	q / ($col["sig_zz"] + lat), $col["sliding_ratio"])
  if ((k - 1) % every == 0) print row; else pending = row }
END { if ((k - 1) % every != 0) print pending }' curve.tsv
