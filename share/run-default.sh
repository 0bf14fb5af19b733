#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# make run: the main job on built-in defaults, the papers' whole chain on a G2740-style glass
# pack: packgen -> densify (4 MPa, frictionless) -> frictionalize (mu 0.3) -> loadtest
# (uniaxial strain to 20 MPa) -> moduli (K, G, lambda, E, nu per 10 increments), printed at
# the end; every stage's output stays in out/ for inspection, with its wall time in
# out/times.tsv, and out/moduli.png plots K and G against sigma_c and out/forces.png draws the
# force network of a slab of the final pack when gnuplot is installed; out/pack.html shows the
# final pack in 3D (packview).
set -e
bin=${1:-build/bin}
# OpenMP threads that wait at a barrier spin for a while before they sleep: GNU OpenMP's
# default spin makes two threads beside one other busy process 4x slower than alone (packgen
# 2740: 7.5 s alone, 32.7 s beside a busy loop; 13.6 s on one thread).  A short spin keeps
# the time alone (7.2 s) and bounds the loss (18.6 s); the bytes do not depend on it.
export GOMP_SPINCOUNT="${GOMP_SPINCOUNT:-1000}"
mkdir -p out
printf '# stage\tseconds\n' >out/times.tsv
stage() {
	name=$1
	shift
	echo "== $name: $*" >&2
	t0=$(date +%s.%N)
	"$@"
	t1=$(date +%s.%N)
	awk -v n="$name" -v a="$t0" -v b="$t1" 'BEGIN { printf "%s\t%.1f\n", n, b - a }' >>out/times.tsv
}
stage packgen "$bin/packgen" -n 2740 --seed 1 --material glass -o out/loose.pack.gz
stage densify "$bin/densify" --stress 4e6 --log out/densify.tsv -o out/dense.pack.gz out/loose.pack.gz
stage frictionalize "$bin/frictionalize" --mu 0.3 --log out/frictionalize.tsv -o out/frictional.pack.gz out/dense.pack.gz
stage loadtest sh -c "'$bin/loadtest' --path uniaxial --to-stress 20e6 -o out/final.pack.gz out/frictional.pack.gz >out/curve.tsv"
stage moduli "$bin/moduli" --window 10 -o out/moduli.tsv out/curve.tsv
# the effective-medium comparison like for like: an isotropic probe of the final pack (3
# increments of 1e-4), its K from the volume-averaged stress, Walton's K from the bulk
# porosity and coordination (moduli(1))
stage probe sh -c "'$bin/loadtest' --path isotropic --steps 3 out/final.pack.gz | '$bin/moduli' --window 3 --emt glass -o out/probe.tsv"
# the final pack in 3D, one page to open in a browser (packview(1))
stage packview "$bin/packview" -o out/pack.html out/final.pack.gz
echo "== packinfo out/frictional.pack.gz" >&2
"$bin/packinfo" out/frictional.pack.gz | grep -E '^(grains|porosity|coordination|under4|sigma_c|residual|sliding_ratio) '
if command -v gnuplot >/dev/null 2>&1; then
	gnuplot -e "in='out/moduli.tsv'; out='out/moduli.png'" share/plot/moduli.gp && echo "wrote out/moduli.png" >&2
	BIN=$bin sh share/plot/packpic.sh out/final.pack.gz out/forces.png contacts "final pack at 20 MPa" &&
	    echo "wrote out/forces.png (the force network of a slab of the final pack)" >&2
else
	echo "gnuplot not installed (apt-get install gnuplot-nox): no figure" >&2
fi
echo "== stage times (s)"
cat out/times.tsv
echo "== moduli (out/moduli.tsv): sigma_c, K, G, E in MPa"
awk -F'\t' 'NR > 1 { printf "%8.3f %9.1f %9.1f %9.1f  nu %.3f\n", $5 / 1e6, $7 / 1e6, $8 / 1e6, $10 / 1e6, $11 }' out/moduli.tsv
echo "== isotropic probe of the final pack (out/probe.tsv) against effective-medium theory (bulk porosity, coordination)"
awk -F'\t' 'NR > 1 { printf "sigma_c %.3f MPa  K %.1f MPa  K_emt %.1f MPa  K / K_emt %.3f  (bulk porosity %.4f, coordination %.3f)\n", $5 / 1e6, $7 / 1e6, $15 / 1e6, $7 / $15, $13, $14 }' out/probe.tsv
