#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# hydrate.sh BIN RUN...: the hydrate study's summary table (pipelines/Makefile, s-fig5), one
# row per run directory (RUN/diss.pack.gz from dissociate, RUN/moduli.tsv from the three-axis
# probe that followed): the dissociation applied (dS, p_ex, from the pack's meta lines), the
# hydrate saturation after (packinfo), the effective stress before and after and the total
# stress (dissociate's meta; the pack's own volume-averaged stress for the run that changes
# nothing), and the probe's sigma_c, K, G and fit_rel (moduli(1): the share of the stress
# change the isotropic fit leaves unexplained; near 1 when the pack rearranged in the probe), and
# last the standard errors K_se and G_se of K and G.
set -e
bin=$1
shift
here=$(cd "$(dirname "$0")" && pwd)
cols="sh $here/cols.sh"
# meta KEY of a pack, or the default given
meta() { gzip -dc "$1" | awk -v k="$2" -v d="$3" '$1 == "meta" && $2 == k { v = $3 } /^end/ { exit } END { print (v == "" ? d : v) }'; }
printf '# run\tdS\tpex[Pa]\tS\tsigma_before[Pa]\tsigma_after[Pa]\tsigma_total[Pa]\tsigma_c[Pa]\tK[Pa]\tG[Pa]\tfit_rel\tK_se[Pa]\tG_se[Pa]\n'
for d in "$@"; do
	p=$d/diss.pack.gz
	info=$("$bin/packinfo" "$p")
	lw=$(echo "$info" | awk '$1 ~ /^sig_lw_(xx|yy|zz)$/ { s += $2 } END { printf "%.17g", s / 3 }')
	S=$(echo "$info" | awk '$1 == "hydrate_saturation" { print $2 }')
	printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$(basename "$d")" "$(meta "$p" dissociation_dS 0)" "$(meta "$p" dissociation_pex 0)" \
	    "$S" "$(meta "$p" effective_stress_before "$lw")" "$(meta "$p" effective_stress_after "$lw")" \
	    "$(meta "$p" total_stress_after "$lw")" "$($cols "$d/moduli.tsv" sigma_c K G fit_rel | head -n 1)" \
	    "$($cols "$d/moduli.tsv" K_se G_se | head -n 1)"
done
