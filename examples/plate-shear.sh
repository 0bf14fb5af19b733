#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Simple shear of platy grains, the platy-particle paper's test.  A pack of spheroplates
# (square plates with rounded edges, platyness ETA = (R - r) / R) is compacted isotropically
# (packgen --shape spheroplate) and sheared between rough walls at a constant normal stress
# and a constant inertial number I (shear), to the shear strain STRAIN.  It shows the stress
# ratio q/p, the packing fraction and the coordination over the strain, the velocity profile
# across the layer over the second half of the run (0 at the bottom wall, 1 at the top), and
# the descriptors of the final pack: the plates' nematic order and the anisotropies of the
# contact network and forces that carry q/p (packinfo).
#
#   sh plate-shear.sh [N [DIR]]  N plates (default 1000; about a minute on one core),
#                                every file in DIR (default plate-shear/)
#   ETA=0.5 STRAIN=1 I=1e-2 sh plate-shear.sh   platyness, shear strain, inertial number
#                                (the paper's: I = 1e-3 to a strain of 2.5, 25 times longer)
#   BIN=DIR                      the tools from DIR instead of PATH
# Outputs: pack.pack.gz, the shear's table shear.tsv (a row per 0.05 of strain), the velocity
# profile profile.tsv, the final pack final.pack.gz and its descriptors descriptors.txt.
set -eu
n=${1:-1000} dir=${2:-plate-shear}
eta=${ETA:-0.5} strain=${STRAIN:-1} inertial=${I:-1e-2}
bin=${BIN:+$BIN/}
mkdir -p "$dir"
cd "$dir"
"${bin}packgen" --shape spheroplate --platyness "$eta" -n "$n" -o pack.pack.gz
"${bin}shear" --strain "$strain" --inertial "$inertial" --every 0.05 --profile profile.tsv \
	--profile-from "$(awk -v g="$strain" 'BEGIN { print g / 2 }')" --profile-bins 10 \
	-o final.pack.gz pack.pack.gz >shear.tsv
"${bin}packinfo" -o descriptors.txt final.pack.gz
echo "# gamma	q/p	phi	Z"
awk -F '\t' '/^##/ { next }
	/^# / { sub(/^# /, ""); for (i = 1; i <= NF; i++) { c = $i; sub(/\[.*\]$/, "", c); col[c] = i }; next }
	{ printf "%.2f\t%.3f\t%.4f\t%.2f\n", $col["gamma"], $col["qp"], $col["phi"], $col["Z"] }' shear.tsv
echo "# y/y_w	v_x/v_w"
awk -F '\t' '/^##/ { next }
	/^# / { sub(/^# /, ""); for (i = 1; i <= NF; i++) { c = $i; sub(/\[.*\]$/, "", c); col[c] = i }; next }
	{ printf "%.2f\t%.3f\n", $col["y_over_yw"], $col["vx_over_vw"] }' profile.tsv
grep -E '^(packing_fraction|coordination|nematic_order|qp|a_n|a_fn|a_ft) ' descriptors.txt
