#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# make validate (part): the simple shear of frictional spheres against published DEM.  1000
# spheres made by the plate engine (packgen --shape spheroplate --platyness 0: the
# platy-particle paper's law, mu = 0.58, kappa 1e4) sheared by `shear` to gamma 2.5 at I = 1e-2;
# over the steady state, gamma 1.5-2.5:
#   - tau_w / sigma_w within 0.2-0.4.  The platy-particle paper (Boton et al. 2013, Fig. 7)
#     finds q/p of about 0.3 for its spheres (eta = 0) with this law at I about 1e-3; we take
#     its value with a band of +-0.1 for the tenfold rate, the smaller box and the fluctuation.
#   - q/p of the pair stress (P eq. 7) within 0.1 of tau_w / sigma_w (both measure the same
#     strength, one at the wall, one in the bulk);
#   - the velocity profile linear: R^2 above 0.98 over the bins between the glued layers
#     (P Fig. 6: sheared in the whole bulk, no localisation).
# SEED overrides the seed; RESULTS=FILE writes the report elsewhere (validate/shear.md).
# Exits 1 when a check fails; the report is written either way.
set -u
bin=${1:-build/bin}
case $bin in /*) ;; *) bin=$(pwd)/$bin ;; esac
top=$(cd "$(dirname "$0")/.." && pwd)
res=${RESULTS:-$top/validate/shear.md}
case $res in /*) ;; *) res=$(pwd)/$res ;; esac
work=$top/validate/work-shear
seed=${SEED:-1}
export LC_ALL=C
mkdir -p "$work"
rm -f "$work"/*
cd "$work" || exit 1
cols() { sh "$top/pipelines/cols.sh" "$@"; }
t0=$(date +%s)
"$bin/packgen" --shape spheroplate --platyness 0 -n 1000 --seed "$seed" -o s.pack || exit 1
"$bin/shear" --strain 2.5 --inertial 1e-2 --every 0.01 --profile prof.tsv --profile-from 1.5 -o sheared.pack s.pack >shear.tsv || exit 1
t1=$(date +%s)
read -r tau tsd qp <<EOF
$(cols shear.tsv gamma tau_sigma qp | awk -F '\t' '$1 >= 1.5 { n++; t += $2; tt += $2 * $2; q += $3 } END { m = t / n; printf "%.4f %.4f %.4f", m, sqrt(tt / n - m * m), q / n }')
EOF
r2=$(cols prof.tsv y_over_yw vx_over_vw | awk -F '\t' '$2 != "nan" { n++; x[n] = $1; y[n] = $2 }
	END { for (k = 2; k < n; k++) { m++; sx += x[k]; sy += y[k] } mx = sx / m; my = sy / m
	      for (k = 2; k < n; k++) { sxx += (x[k] - mx)^2; sxy += (x[k] - mx) * (y[k] - my); syy += (y[k] - my)^2 }
	      b = sxy / sxx; a = my - b * mx; for (k = 2; k < n; k++) { e = y[k] - a - b * x[k]; ss += e * e }
	      printf "%.4f", 1 - ss / syy }')
fails=0
checks=""
check() {	# DESCRIPTION CONDITION
	if awk "BEGIN { exit !($2) }"; then checks="$checks
- PASS: $1"; else checks="$checks
- FAIL: $1"; fails=$((fails + 1)); fi
}
check "tau_w/sigma_w = $tau within 0.2-0.4 (the platy-particle paper: q/p about 0.3 for spheres)" "$tau >= 0.2 && $tau <= 0.4"
check "q/p of the pair stress = $qp within 0.1 of tau_w/sigma_w" "($qp - $tau) < 0.1 && ($tau - $qp) < 0.1"
check "velocity profile linear: R^2 = $r2 above 0.98" "$r2 > 0.98"
{
	echo "# Simple shear of frictional spheres (make validate)"
	echo
	echo "$(date -u '+%Y-%m-%d %H:%M UTC'), commit $(cd "$top" && git rev-parse --short HEAD 2>/dev/null), $((t1 - t0)) s on one core."
	echo "1000 spheres (packgen --shape spheroplate --platyness 0 --seed $seed: mu 0.58, k_n = k_t = 1.5e3 N/m, e 0.6, kappa 1e4),"
	echo "sheared by \`shear --strain 2.5 --inertial 1e-2\`; means over gamma 1.5-2.5 (tests/validate-shear.sh)."
	echo
	echo "| quantity | this run | reference |"
	echo "| --- | --- | --- |"
	echo "| tau_w / sigma_w | $tau +- $tsd | q/p about 0.3 (Boton et al. 2013, Fig. 7, eta = 0) |"
	echo "| q/p (pair stress, xy plane) | $qp | the same |"
	echo "| packing fraction | $(cols shear.tsv gamma phi | awk -F '\t' '$1 >= 1.5 { n++; s += $2 } END { printf "%.4f", s / n }') | |"
	echo "| Z | $(cols shear.tsv gamma Z | awk -F '\t' '$1 >= 1.5 { n++; s += $2 } END { printf "%.2f", s / n }') | 3.6 (Fig. 12, at I about 1e-3) |"
	echo "| velocity profile R^2 | $r2 | linear (Fig. 6) |"
	echo
	echo "Checks:$checks"
	echo
	echo "Velocity profile (y / y_w, <v_x> / v_w):"
	echo
	echo '| y/y_w | v_x/v_w |'
	echo '| --- | --- |'
	cols prof.tsv y_over_yw vx_over_vw | awk -F '\t' '{ printf "| %.3f | %s |\n", $1, $2 }'
} >"$res.tmp" && mv "$res.tmp" "$res"
echo "wrote $res ($fails failed)"
[ "$fails" -eq 0 ]
