#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Hydrate dissociation in a hydrate-bearing quartz sand, the frictionless paper's model.  The
# smallest grains of a quartz pack are hydrate (packgen --hydrate-volume), the pack is
# compacted to an effective stress of 21 MPa (densify), and its stiffness is probed: three
# increments of 1e-5 strain along x, then y, then z (loadtest --path 'probe steps=3'),
# fitted together (moduli --pool-segments).  Then part of the hydrate dissociates: its
# saturation S falls by DS while the released gas and water raise the pore pressure by PEX
# (dissociate), and the probe is repeated.  It shows the effective stress and the moduli
# falling: the hydrate grains shrink out of their contacts and the pore pressure expands the
# skeleton, which unloads it.
#
#   sh hydrate.sh [N [DIR]]     N grains (default 1000; seconds),
#                               every file in DIR (default hydrate/)
#   DS=-0.02 PEX=1e6 sh hydrate.sh   the change of saturation and the excess pore pressure (Pa)
#   BIN=DIR                     the tools from DIR instead of PATH
# Outputs: loose.pack.gz, dense.pack.gz and diss.pack.gz (after dissociation), the probes'
# tables probe-dense.tsv and probe-diss.tsv and their moduli moduli-dense.tsv, moduli-diss.tsv.
set -eu
n=${1:-1000} dir=${2:-hydrate}
ds=${DS:--0.02} pex=${PEX:-1e6}
bin=${BIN:+$BIN/}
mkdir -p "$dir"
cd "$dir"
"${bin}packgen" -n "$n" --material quartz --hydrate-volume 0.13 -o loose.pack.gz
"${bin}densify" --stress 21e6 -o dense.pack.gz loose.pack.gz
"${bin}dissociate" --mu 0 --dS "$ds" --pex "$pex" -o diss.pack.gz dense.pack.gz
for p in dense diss; do
	"${bin}loadtest" --mu 0 --path 'probe steps=3' --strain-step 1e-5 $p.pack.gz >probe-$p.tsv
	"${bin}moduli" --pool-segments --window 9 -o moduli-$p.tsv probe-$p.tsv
done
# before and after: the saturation and the stress of the pack (packinfo), K and G of its probe
for p in dense diss; do
	"${bin}packinfo" $p.pack.gz | awk -v p=$p '
		$1 == "hydrate_saturation" { S = $2 } $1 == "sigma_c" { s = $2 }
		END { printf "%-6s S %.4f  sigma_c %7.3f MPa", p, S, s / 1e6 }'
	awk -F '\t' '/^##/ { next }
		/^# / { sub(/^# /, ""); for (i = 1; i <= NF; i++) { c = $i; sub(/\[.*\]$/, "", c); col[c] = i }; next }
		{ printf "  K %7.1f MPa  G %6.1f MPa\n", $col["K"] / 1e6, $col["G"] / 1e6 }' moduli-$p.tsv
done
