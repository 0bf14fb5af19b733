#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# platy.sh RUNS FROM ETA...: the platy study's summary table (pipelines/Makefile), one row per
# platyness: the means and standard deviations over the steady state (gamma >= FROM) of the
# shear's rows (RUNS/platy-etaETA/shear.tsv: tau_sigma, qp, phi, Z) and of the descriptors
# of its snapshots (descriptors.tsv, packinfo --tsv, over the free grains: floating_fraction_free
# as chi, the anisotropies, K_s, eq. 28, and beside them the 3D nematic measures and the direct
# tangential anisotropies).  Standard deviations are of the values in the window, so they
# show the fluctuation, not the error of the mean.
set -e
runs=$1 from=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
cols="sh $here/cols.sh"
SHEAR="tau_sigma qp phi Z"
DESC="floating_fraction_free a_m theta_m a_n theta_n a_ln theta_ln a_lt a_fn theta_fn a_ft K_s qp_harmonic theta_sigma
 coordination_free a_m_3d M1_M3 nematic_S a_lt_direct theta_lt_direct a_ft_direct theta_ft_direct qp_harmonic_direct"
# mean and sd of each column of a cols.sh stream, as "m1 s1 m2 s2 ..."
msd() { awk -F '\t' '{ for (k = 1; k <= NF; k++) { s[k] += $k; q[k] += $k * $k }; n++; nf = NF }
	END { for (k = 1; k <= nf; k++) { m = s[k] / n; v = q[k] / n - m * m; printf "%s%.6g\t%.6g", (k > 1 ? "\t" : ""), m, (v > 0 ? sqrt(v) : 0) }; if (!n) printf "nan"; printf "\n" }'; }
printf '# eta\trows\tsnapshots'
for c in $SHEAR $DESC; do printf '\t%s\t%s_sd' "$c" "$c"; done
printf '\n'
for eta in "$@"; do
	d=$runs/platy-eta$eta
	s=$($cols "$d/shear.tsv" gamma $SHEAR | awk -F '\t' -v f="$from" '$1 >= f' | cut -f2- | msd)
	r=$($cols "$d/shear.tsv" gamma | awk -v f="$from" '$1 >= f' | wc -l)
	g=$($cols "$d/descriptors.tsv" $DESC | msd)
	n=$($cols "$d/descriptors.tsv" grains | wc -l)
	printf '%s\t%s\t%s\t%s\t%s\n' "$eta" "$r" "$n" "$s" "$g"
done
