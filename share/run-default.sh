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
# the grains of the pack: the papers' 2740 unless a second argument says (tests/tools/makerun.sh
# runs the chain small)
n=${2:-2740}
# Idle OpenMP threads sleep at once by default: a tool sets OMP_WAIT_POLICY=passive before
# its threads start unless OMP_WAIT_POLICY or GOMP_SPINCOUNT is set (qusgm(7), ENVIRONMENT).  This script used to set GOMP_SPINCOUNT=1000, which switched that
# off and cost 5 times the CPU of one thread beside other jobs (bench/threads.md).
mkdir -p out
printf '# stage\tseconds\n' >out/times.tsv
# the tools' directory as it can be typed: quoted only where it needs to be
case $bin in
*[!A-Za-z0-9_./+-]*) b="'$(printf '%s' "$bin" | sed "s/'/'\\\\''/g")'" ;;
*) b=$bin ;;
esac
# stage NAME COMMAND: COMMAND is one line of shell, printed as it runs, so that it can be
# pasted into a shell as it is (the directory it ran in is the current one)
stage() {
	name=$1 cmd=$2
	echo "== $name: $cmd" >&2
	t0=$(date +%s.%N)
	eval "$cmd"
	t1=$(date +%s.%N)
	awk -v n="$name" -v a="$t0" -v b="$t1" 'BEGIN { printf "%s\t%.1f\n", n, b - a }' >>out/times.tsv
}
stage packgen "$b/packgen -n $n --seed 1 --material glass -o out/loose.pack.gz"
stage densify "$b/densify --stress 4e6 --log out/densify.tsv -o out/dense.pack.gz out/loose.pack.gz"
stage frictionalize "$b/frictionalize --mu 0.3 --log out/frictionalize.tsv -o out/frictional.pack.gz out/dense.pack.gz"
stage loadtest "$b/loadtest --path uniaxial --to-stress 20e6 -o out/final.pack.gz out/frictional.pack.gz > out/curve.tsv"
stage moduli "$b/moduli --window 10 -o out/moduli.tsv out/curve.tsv"
# the effective-medium comparison like for like: an isotropic probe of the final pack (3
# increments of 1e-4), its K from the volume-averaged stress, Walton's K from the bulk
# porosity and coordination (moduli(1))
stage probe "$b/loadtest --path isotropic --steps 3 out/final.pack.gz | $b/moduli --window 3 --emt glass -o out/probe.tsv"
# the final pack in 3D, one page to open in a browser (packview(1))
stage packview "$b/packview -o out/pack.html out/final.pack.gz"
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
# the columns of a table by their names (qusgm-tables(5)): c["K"] is K[Pa]'s position
names='/^##/ { next } /^# / { sub(/^# /, ""); for (i = 1; i <= NF; i++) { k = $i; sub(/\[.*\]$/, "", k); c[k] = i }; next }'
echo "== moduli (out/moduli.tsv): sigma_c, K, G, E in MPa"
awk -F'\t' "$names"' { printf "%8.3f %9.1f %9.1f %9.1f  nu %.3f\n", $c["sigma_c"] / 1e6, $c["K"] / 1e6, $c["G"] / 1e6, $c["E"] / 1e6, $c["nu"] }' out/moduli.tsv
echo "== isotropic probe of the final pack (out/probe.tsv) against effective-medium theory (bulk porosity, coordination)"
awk -F'\t' "$names"' { printf "sigma_c %.3f MPa  K %.1f MPa  K_emt %.1f MPa  K / K_emt %.3f  (bulk porosity %.4f, coordination %.3f)\n",
	$c["sigma_c"] / 1e6, $c["K"] / 1e6, $c["K_emt"] / 1e6, $c["K"] / $c["K_emt"], $c["porosity"], $c["coordination"] }' out/probe.tsv
