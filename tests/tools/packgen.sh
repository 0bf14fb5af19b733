# SPDX-License-Identifier: GPL-3.0-or-later
# packgen as a user runs it: a valid loose pack, same seed same bytes, the loose-pack
# properties the issue asks for, and every usage error.
#
# The sanitizer build makes its loose packs of 200 grains instead of 400 (4 s of CPU each
# there at 400), leaves the one check that needs the larger pack (the coordination of a
# loose pack) to the optimised build, and does not repeat a command only to compare the
# bytes (same seed, same bytes): the sanitizers see the same run the second time, and the
# optimised build checks the determinism.  Every other check runs in both builds.
. "$TOP/tests/tools/lib.sh"

san=0 N=400
if [ "${BIN#*build-san}" != "$BIN" ]; then san=1 N=200; fi
expect_ok "packgen -n $N writes a pack" packgen -n $N --seed 3 -o a.pack
if [ $san = 0 ]; then
	expect_ok "packgen again with the same seed" packgen -n $N --seed 3 -o b.pack
	expect_same "same seed, same bytes" a.pack b.pack
fi
packgen -n $N --seed 4 -o c.pack 2>/dev/null
if cmp -s a.pack c.pack; then fail "another seed gives another pack" "identical"; else pass "another seed gives another pack"; fi
packgen -n $N --seed 3 >d.pack 2>/dev/null
expect_same "stdout and -o give the same bytes" a.pack d.pack
packgen -n $N --seed 3 -o e.pack.gz 2>/dev/null
gzip -dc e.pack.gz >e.pack 2>/dev/null
expect_same ".gz output decompresses to the same pack" a.pack e.pack

expect_ok "packinfo reads the pack" packinfo a.pack
packinfo a.pack >info.txt
expect_num "grains" "$(info_value info.txt grains)" == $N
# A loose pack: grains touch (contacts exist) without significant overlap...
expect_num "largest overlap / R below 1e-3" "$(info_value info.txt overlap_max)" "<" 1e-3
# (400 grains: 2.45; the walls' share grows in a smaller box, and 200 grains of seeds 3-6
# gave 2.07-2.34, 150 grains 1.75-2.15, so the sanitizer build's 200 leave it out)
if [ $san = 0 ]; then
	expect_num "grains touch their neighbours (coordination)" "$(info_value info.txt coordination)" ">" 2
fi
# ...and many have fewer than 4 contacts, which densify will fix.
expect_num "many grains under 4 contacts" "$(info_value info.txt under4)" ">" $((N / 10))
# Porosity of a loose random pack in a small box with walls: well above random close
# packing (0.36) and below a random sequential placement (0.7: phi0 = 0.3).
expect_num "porosity above close packing" "$(info_value info.txt porosity)" ">" 0.38
expect_num "porosity below the initial placement" "$(info_value info.txt porosity)" "<" 0.6
# Radii inside the default uniform distribution 0.07-0.13 mm.
expect_num "smallest radius" "$(info_value info.txt r_min)" ">=" 7e-5
expect_num "largest radius" "$(info_value info.txt r_max)" "<=" 1.3e-4
grep -q '^history packgen ' a.pack && pass "history line recorded" || fail "history line recorded" "none"
grep -q -- '--seed=3' a.pack && pass "history records the seed" || fail "history records the seed" "no --seed=3"
awk '$1 == "walls" && $2 == 7e12 && $3 == 0.495 && $4 == 0.3 { ok = 1 } END { exit !ok }' a.pack && pass "walls 100 E_glass, 0.495, mu 0.3" || fail "walls 100 E_glass, 0.495, mu 0.3" "$(grep ^walls a.pack)"

# Moduli drawn with a 10 % spread around glass (70 GPa, 0.2): sample mean and spread.
awk '/^end$/ { on = 1; next } on && NF == 8 { n++; s += $6; s2 += $6 * $6; t += $7 }
     END { m = s / n; sd = sqrt(s2 / n - m * m); print m, sd / m, t / n }' a.pack >mod.txt
read -r Em Esd num <mod.txt
# 150 draws: standard error of the mean 0.1/sqrt(150) = 0.8 % of E; 4 sigma = 3.3 % (at 200
# and 400 draws, the packs here, 3.3 % is 4.7 and 6.6 standard errors).
expect_num "mean E within 4 standard errors of 70 GPa" "$(awk -v e="$Em" 'BEGIN { print (e > 70e9 ? e - 70e9 : 70e9 - e) / 70e9 }')" "<" 0.033
expect_num "spread of E about 10 %" "$Esd" ">" 0.07
expect_num "spread of E about 10 % (upper)" "$Esd" "<" 0.13

expect_ok "quartz preset" packgen -n 40 --seed 1 --material quartz -o q.pack
awk '$1 == "walls" && $2 == 1e13 { ok = 1 } END { exit !ok }' q.pack && pass "quartz walls 100 x 100 GPa" || fail "quartz walls" "$(grep ^walls q.pack)"
printf 'E 5e9\nnu 0.3\nrho 1000\n' >soft.mat
expect_ok "material file" packgen -n 40 --seed 1 --material ./soft.mat -o s.pack
printf '1e-4 1\n1.2e-4 2\n' >sizes.txt
expect_ok "size table" packgen -n 40 --seed 1 --psd table:sizes.txt -o t.pack
awk '/^end$/ { on = 1; next } on && NF == 8 && $5 != 1e-4 && $5 != 1.2e-4 { bad = 1 } END { exit bad }' t.pack &&
    pass "size table radii only" || fail "size table radii only" "other radii"
expect_ok "lognormal sizes" packgen -n 40 --seed 1 --psd lognormal:1e-4,0.2 -o l.pack
expect_ok "elongated box" packgen -n 60 --seed 1 --aspect 1,1,2 -o z.pack
packinfo z.pack >z.txt
expect_num "aspect 1,1,2 gives a taller box" "$(awk '$1=="lz"{z=$2} $1=="lx"{x=$2} END{print z/x}' z.txt)" ">" 1.6

expect_error "unknown option" 2 '^packgen: unknown option' packgen --bogus
expect_error "non-numeric grains" 2 '^packgen: --grains' packgen -n ten
expect_error "zero grains" 2 '^packgen: --grains' packgen -n 0
expect_error "bad psd" 2 '^packgen: --psd' packgen --psd uniform:2,1
expect_error "unknown material" 2 "^packgen: --material: unknown material 'steel'" packgen --material steel
expect_error "negative friction" 2 '^packgen: --friction' packgen --friction -1
expect_error "bad aspect" 2 '^packgen: --aspect' packgen --aspect 1,0,1
# a starting box that cannot hold the largest grain (--aspect 1e300,1,1 ended in "the time
# step is too long" with a stress of -nan), refused before the DEM with the side named
expect_error "aspect 1e300,1,1" 2 '^packgen: --aspect 1e300,1,1: the starting box would be [0-9.e+-]+ m along y, less than the largest grain.s diameter' \
    packgen -n 30 --aspect 1e300,1,1 -o nothing.pack
expect_error "aspect underflowing" 2 "^packgen: --aspect: expected three positive numbers" packgen -n 30 --aspect 1e-300,1e-300,1e-300
expect_error "wall-E past the range" 2 '^packgen: --wall-E: 1e\+20 Pa is outside \[1000, 1e\+15\] Pa' packgen -n 30 --wall-E 1e20
expect_error "operand not allowed" 2 '^packgen: too many operands' packgen extra.pack
expect_error "NaN option" 2 'not a finite number' packgen --overlap nan
# -o that cannot be written, or a file packgen reads, refused before the compaction (it was
# found only when the pack was done: hours at 1e6 grains)
expect_error "-o in a missing directory" 2 "^packgen: -o: cannot write in directory 'no-such-dir': No such file or directory" \
    packgen -n 30 -o no-such-dir/x.pack
printf '1e-4 1\n' >sizes.txt
expect_error "-o the --psd table" 2 "^packgen: -o 'sizes.txt' is the --psd table" packgen -n 30 --psd table:sizes.txt -o sizes.txt
printf 'E 7e10\nnu 0.2\nrho 2420\n' >g.mat
expect_error "-o the --material file" 2 "^packgen: -o './g.mat' is the --material file" packgen -n 30 --material ./g.mat -o ./g.mat
rm -f fail.pack
packgen -n 40 --max-steps 10 -o fail.pack 2>fail.err
rc=$?
if [ "$rc" -eq 1 ] && [ ! -e fail.pack ] && ! ls .fail.pack.* >/dev/null 2>&1; then
	pass "a run that fails leaves no output and no temporary file"
else
	fail "a run that fails leaves no output and no temporary file" "rc $rc, $(ls -a | tr '\n' ' ')"
fi

# -o onto something that is not a regular file is written into, never replaced by the
# temporary file's rename: a FIFO stays a FIFO and its reader gets the pack (as root, -o
# /dev/null used to turn /dev/null into a regular file)
mkfifo out.fifo
cat out.fifo >from.fifo &
if packgen -n 20 --seed 3 -o out.fifo 2>fifo.err; then pass "-o FIFO: exit 0"; else fail "-o FIFO: exit 0" "$(cat fifo.err)"; fi
wait
if [ -p out.fifo ]; then pass "-o FIFO: still a FIFO"; else fail "-o FIFO: still a FIFO" "$(ls -l out.fifo)"; fi
packgen -n 20 --seed 3 >direct.pack 2>/dev/null
expect_same "-o FIFO: the reader got the pack" from.fifo direct.pack
# a few grains that do not fit at random: the message names --phi0 (issue 19), and a lower
# one places them
expect_error "-n 2: names --phi0" 1 '^packgen: cannot place grain 2 of 2 at random: .*\(--phi0, now 0\.3\)$' packgen -n 2 -o nothing.pack
expect_ok "-n 2 --phi0 0.05" packgen -n 2 --phi0 0.05 -o two.pack
# packgen reads no input: its --help does not say it does
if packgen --help | grep -q 'standard input'; then fail "--help: no standard input" "$(packgen --help | grep 'standard input')"; else pass "--help: no standard input"; fi

# Spheroplates (issue 13): 27 plates of platyness 0.5, a static pack in a couple of seconds.
expect_ok "spheroplates: packgen --shape spheroplate -n 27" packgen --shape spheroplate --platyness 0.5 -n 27 --seed 2 -o p.pack
if [ $san = 0 ]; then
	expect_ok "spheroplates: again with the same seed" packgen --shape spheroplate --platyness 0.5 -n 27 --seed 2 -o p2.pack
	expect_same "spheroplates: same seed, same bytes" p.pack p2.pack
fi
packinfo p.pack >pinfo.txt 2>/dev/null
expect_num "spheroplates: 27 plates" "$(info_value pinfo.txt plates)" == 27
expect_num "spheroplates: platyness read back 0.5" "$(info_value pinfo.txt platyness)" == 0.5
# r = 30 nm and side 2 (R - r) = 2 r at eta 0.5 (the edge reading): R = 60 nm
expect_num "spheroplates: side 60 nm" "$(rel "$(info_value pinfo.txt side_mean)" 6e-8)" "<" 1e-12
# a static pack of frictional plates: denser than the grid (0.14) and than a loose
# random placement, looser than close packing of spheres
expect_num "spheroplates: packing above 0.35" "$(info_value pinfo.txt packing_fraction)" ">" 0.35
expect_num "spheroplates: packing below 0.64" "$(info_value pinfo.txt packing_fraction)" "<" 0.64
grep -q '^columns id x y z r E nu rho shape side qw qx qy qz$' p.pack && pass "spheroplates: shape columns" || fail "spheroplates: shape columns" "$(grep ^columns p.pack)"
for k in plate-radius contact-law kn kt restitution sigma0 kappa; do
	grep -q "^meta $k " p.pack && pass "spheroplates: meta $k" || fail "spheroplates: meta $k" "missing"
done
# the frictional history: one contact line per touching interaction
expect_num "spheroplates: contact lines written" "$(awk '$1 == "contacts" { print $2 }' p.pack)" ">" 10
# --kappa sets the compaction stress: sigma0 = kn / (kappa r) = 1.5e3 / (1e3 3e-8) = 5e7 Pa
expect_ok "spheroplates: packgen --kappa 1e3" packgen --shape spheroplate --platyness 0.5 -n 27 --seed 2 --kappa 1e3 -o pk.pack
expect_num "spheroplates: --kappa 1e3 gives sigma0 5e7 Pa" "$(rel "$(awk '$1 == "meta" && $2 == "sigma0" { print $3 }' pk.pack)" 5e7)" "<" 1e-12
expect_error "spheroplates: --stress and --kappa" 2 '^packgen: --stress and --kappa: give one' packgen --shape spheroplate -n 27 --stress 1e6 --kappa 1e3
# packinfo's interactions (measure_plates) against packgen's own: one contact line per interaction
expect_num "spheroplates: packinfo finds an interaction per contact line" \
	"$(awk '$1 == "contacts_gg" { g = $2 } $1 == "contacts_gw" { w = $2 } END { print g + w }' pinfo.txt)" == "$(info_value pinfo.txt history_contacts)"
# packinfo's Z (measure_plates, in SI) against the DEM's own count at rest (packgen -v, scaled
# units, 3 decimals), and against (2 gg + gw) / N
packgen --shape spheroplate --platyness 0.5 -n 27 --seed 2 -v -o pv.pack 2>pv.log
zdem=$(sed -n 's/.*at rest after .*, \([0-9.]*\) interactions per grain.*/\1/p' pv.log)
expect_num "spheroplates: packinfo's Z is the DEM's" "$(rel "$(info_value pinfo.txt coordination)" "$zdem")" "<" 2e-4
expect_num "spheroplates: coordination Z = (2 gg + gw) / N" "$(awk '$1 == "contacts_gg" { g = $2 } $1 == "contacts_gw" { w = $2 } $1 == "coordination" { z = $2 } END { d = z - (2 * g + w) / 27; print d < 0 ? -d : d }' pinfo.txt)" "<" 1e-12
expect_num "spheroplates: some interactions" "$(info_value pinfo.txt contacts_gg)" ">" 10
# the pack's stresses from the element forces (meta kn) against the servo's target: packgen
# stops with every wall within 5 % of sigma0 (platepack.c), and with frictionless walls
# (--dem-wall-friction 0) the grains' Love-Weber stress is the wall stress up to the
# unbalanced forces, mean|F_i| < 1e-3 of the mean interaction force (the rest criterion,
# over all grains and counting the dashpots; packinfo's residual_mean is over the grains with
# an interaction and elastic, so it may show up to twice it): that moves a diagonal
# component by well under 1 %
s0=$(awk '$1 == "meta" && $2 == "sigma0" { print $3 }' p.pack)
for a in xx yy zz; do
	expect_num "spheroplates: sig_$a within 5 % of sigma0" "$(rel "$(info_value pinfo.txt sig_$a)" "$s0")" "<" 0.05
	expect_num "spheroplates: sig_lw_$a within 1 % of sig_$a" "$(rel "$(info_value pinfo.txt sig_lw_$a)" "$(info_value pinfo.txt sig_$a)")" "<" 0.01
done
expect_num "spheroplates: residual_mean at rest" "$(info_value pinfo.txt residual_mean)" "<" 2e-3
# (the optimised build's: 216-grain compactions and a densify, 20 s of CPU in the sanitizer
# build, whose code, the plate pass and the linear law's densify, that build runs on the
# smaller packs here and in laws.sh)
if [ $san = 0 ]; then
# spheres by the plate engine (--platyness 0): on the grid's nodes they are a simple cubic
# crystal that the isotropic compaction keeps, every grain at 6 interactions (grains or
# walls); off the nodes (--jitter, default 1 for spheres) they are not
expect_ok "spheres by the plate engine on the nodes" packgen --shape spheroplate --platyness 0 --jitter 0 -n 216 --seed 2 -o s0.pack
expect_num "spheres on the nodes: a simple cubic crystal, Z = 6" "$(packinfo s0.pack | awk '$1 == "coordination" { print $2 }')" == 6
expect_ok "spheres by the plate engine off the nodes" packgen --shape spheroplate --platyness 0 -n 216 --seed 2 -o s1.pack
expect_num "spheres off the nodes: Z below 5.5" "$(packinfo s1.pack | awk '$1 == "coordination" { print $2 }')" "<" 5.5
expect_num "spheres by the plate engine: the linear law's report, residual at rest" "$(packinfo s1.pack | awk '$1 == "residual_mean" { print $2 }')" "<" 2e-3
# densify runs such a pack under its own law, the linear one at its meta kn: its output keeps
# the key, and packinfo measures it with that law's forces at densify's mean stress (densify
# stops within its --stress-tol, 1 %, of the target: the trace of the pairs' and walls'
# stress over 3)
expect_ok "densify a pack of the plate engine's spheres" densify --stress 4e6 s1.pack -o s1d.pack
grep -q '^meta contact-law linear$' s1d.pack && pass "densify: keeps meta contact-law linear" ||
	fail "densify: keeps meta contact-law linear" "$(grep contact-law s1d.pack)"
packinfo s1d.pack >s1d.info 2>/dev/null
sc=$(awk '$1 ~ /^sig_lw_(xx|yy|zz)$/ { s += $2 } END { print s / 3 }' s1d.info)
expect_num "densified: sigma_c of the linear law's forces at densify's 4 MPa ($sc Pa)" "$(rel "$sc" 4e6)" "<" 0.01
fi
expect_ok "spheroplates: corner reading" packgen --shape spheroplate --platyness 0.5 --plate-radius corner -n 8 --seed 2 -o pc.pack
# corner: side = sqrt(2) (R - r) = sqrt(2) r
expect_num "spheroplates: corner side sqrt(2) r" "$(rel "$(packinfo pc.pack | awk '$1 == "side_mean" { print $2 }')" 4.242640687119285e-8)" "<" 1e-12
expect_error "spheroplates: 27 plates are too few for a periodic axis" 1 '^packgen: the compacted box is .* too short for a periodic axis .*: use more grains$' packgen --shape spheroplate --platyness 0.5 -n 27 --seed 2 --periodic xz -o pp.pack
expect_ok "spheroplates: periodic x and z" packgen --shape spheroplate --platyness 0.5 -n 125 --seed 2 --periodic xz -o pp.pack
grep -q '^boundary periodic walls periodic$' pp.pack && pass "spheroplates: boundary periodic walls periodic" || fail "spheroplates: boundary line" "$(grep ^boundary pp.pack)"
expect_error "spheroplates: densify refuses plates" 1 'spheroplate.*densify handles spheres only' densify p.pack
expect_error "--shape unknown" 2 '^packgen: --shape: expected sphere or spheroplate' packgen --shape cube
expect_error "--platyness 1" 2 '^packgen: --platyness: must be in \[0, 1\)' packgen --shape spheroplate --platyness 1
expect_error "--plate-radius unknown" 2 '^packgen: --plate-radius: expected edge or corner' packgen --shape spheroplate --plate-radius mid
expect_error "--restitution 0.1" 2 '^packgen: --restitution' packgen --shape spheroplate --restitution 0.1
expect_error "--periodic xyz" 2 '^packgen: --periodic: one axis must keep its walls' packgen --shape spheroplate --periodic xyz
# the history line's resolved options, given back, make the same pack (spheres record the
# plate options at the values the sphere path has)
for args in "-n 40 --seed 4" "--shape spheroplate -n 8 --seed 3"; do
	packgen $args -o h1.pack 2>/dev/null
	packgen $(sed -n 's/^history packgen [^:]*: .* ; //p' h1.pack) -o h2.pack 2>/dev/null
	grep -v '^history' h1.pack >h1.body
	grep -v '^history' h2.pack >h2.body 2>/dev/null
	if [ -s h1.body ] && cmp -s h1.body h2.body; then
		pass "resolved options given back: same pack ($args)"
	else
		fail "resolved options given back ($args)" "the packs differ"
	fi
done
expect_error "--dem-wall-friction for spheres" 2 '^packgen: --dem-wall-friction: only with --shape spheroplate' packgen --dem-wall-friction 0.3
expect_error "--jitter for spheres" 2 '^packgen: --jitter: only with --shape spheroplate' packgen --jitter 0.5
expect_error "--jitter 2" 2 '^packgen: --jitter: must be in \[0, 1\]' packgen --shape spheroplate --jitter 2
expect_error "--periodic for spheres" 2 '^packgen: --periodic: only with --shape spheroplate' packgen --periodic x
expect_error "--periodic bad" 2 '^packgen: --periodic: expected' packgen --shape spheroplate --periodic xq

# --- --hydrate-volume F (issue 20): the smallest grains hydrate ------------------------------
# The rule (packgen.1, "Hydrate"): grains by radius, ties by id order (packgen draws in id
# order, and ids are renumbered by position after the DEM, so the check orders by radius
# alone: uniform radii have no ties); the hydrate grains are the shortest prefix whose sum of
# r^3 reaches F of the total.  awk redoes it from the pack's own numbers.
expect_ok "--hydrate-volume 0.15" packgen -n 300 --seed 3 --material quartz --hydrate-volume 0.15 -o hy.pack
if [ $san = 0 ]; then
	expect_ok "--hydrate-volume 0.15 again" packgen -n 300 --seed 3 --material quartz --hydrate-volume 0.15 -o hy2.pack
	expect_same "--hydrate-volume: same seed, same bytes" hy.pack hy2.pack
fi
grep -q '^columns id x y z r E nu rho phase$' hy.pack && pass "--hydrate-volume: the phase column" || fail "--hydrate-volume: the phase column" "$(grep ^columns hy.pack)"
grep -q '^qusgm-pack 2$' hy.pack && pass "--hydrate-volume: version 2" || fail "--hydrate-volume: version 2" "$(head -n 1 hy.pack)"
for m in 'hydrate-volume 0.15' 'hydrate-material hydrate' 'material quartz'; do
	grep -q "^meta $m\$" hy.pack && pass "--hydrate-volume: meta $m" || fail "--hydrate-volume: meta $m" "$(grep ^meta hy.pack | tr '\n' ' ')"
done
grep -q -- ' --hydrate-volume=0.15 ' hy.pack && pass "--hydrate-volume: in the history's resolved options" || fail "--hydrate-volume: in the history" "none"
awk '/^end$/ { on = 1; next } on && NF == 9 { print $5, $9, $6, $7, $8 }' hy.pack | sort -g -k1,1 >hy.rows
awk -v F=0.15 '{ r[NR] = $1; ph[NR] = $2; v = $1 * $1 * $1; tot += v }
    END {
	# the prefix by the rule
	for (k = 1; k <= NR && !(s >= F * tot); k++) { s += r[k] ^ 3; m = k }
	bad = 0
	for (k = 1; k <= NR; k++) if ((k <= m) != (ph[k] == 1)) bad++
	printf "%d %d %.17g %.17g %.17g\n", bad, m, s / tot, (s - r[m] ^ 3) / tot, r[m]
    }' hy.rows >hy.rule
read -r hbad hm hF hFprev hrmax <hy.rule
expect_num "--hydrate-volume: the hydrate grains are exactly the smallest (grains off the rule)" "$hbad" == 0
expect_num "--hydrate-volume: some grains hydrate" "$hm" ">" 10
expect_num "--hydrate-volume: their volume fraction reaches F" "$hF" ">=" 0.15
expect_num "--hydrate-volume: one grain fewer does not (the first prefix >= F)" "$hFprev" "<" 0.15
expect_num "--hydrate-volume: hydrate grains counted" "$(awk '$2 == 1' hy.rows | wc -l)" == "$hm"
# uniform 0.07-0.13 mm: F = 0.15 below r_c with (r_c^4 - a^4) / (b^4 - a^4) = 0.15, 0.0892 mm;
# 300 grains move it by a few um
expect_num "--hydrate-volume: the largest hydrate radius near 0.089 mm" "$(rel "$hrmax" 8.92e-5)" "<" 0.05
# the hydrate's constants: rho 900 exactly, E and nu drawn around 6.6 GPa and 0.32 (spread
# 0.1: 4 standard deviations are 40 %; the quartz grains, 100 GPa and 0.15, are far out)
expect_num "--hydrate-volume: every hydrate grain rho 900" "$(awk '$2 == 1 && $5 != 900' hy.rows | wc -l)" == 0
expect_num "--hydrate-volume: every hydrate E within 40 % of 6.6 GPa" "$(awk '$2 == 1 && ($3 < 0.6 * 6.6e9 || $3 > 1.4 * 6.6e9)' hy.rows | wc -l)" == 0
expect_num "--hydrate-volume: every hydrate nu within 40 % of 0.32" "$(awk '$2 == 1 && ($4 < 0.6 * 0.32 || $4 > 1.4 * 0.32)' hy.rows | wc -l)" == 0
expect_num "--hydrate-volume: mean hydrate E within 5 % of 6.6 GPa" "$(awk '$2 == 1 { s += $3; n++ } END { print s / n }' hy.rows | xargs -I{} awk 'BEGIN { d = {} - 6.6e9; print (d < 0 ? -d : d) / 6.6e9 }')" "<" 0.05
expect_num "--hydrate-volume: the mineral grains quartz (rho 2650, E above 50 GPa)" "$(awk '$2 == 0 && ($5 != 2650 || $3 < 5e10)' hy.rows | wc -l)" == 0
# F = 0 is no option: no phase column, the same pack but for the command line in the history
packgen -n 60 --seed 3 -o h0a.pack 2>/dev/null
packgen -n 60 --seed 3 --hydrate-volume 0 -o h0b.pack 2>/dev/null
grep -v '^history' h0a.pack >h0a.body
grep -v '^history' h0b.pack >h0b.body
if [ -s h0a.body ] && cmp -s h0a.body h0b.body && ! grep -q phase h0b.pack && grep -q '^qusgm-pack 1$' h0b.pack; then
	pass "--hydrate-volume 0: the pack without the option (version 1, no phase column)"
else
	fail "--hydrate-volume 0: the pack without the option" "they differ"
fi
# the resolved options given back make the same hydrate pack
packgen $(sed -n 's/^history packgen [^:]*: .* ; //p' hy.pack) -o hy3.pack 2>/dev/null
grep -v '^history' hy.pack >hy.body
grep -v '^history' hy3.pack >hy3.body 2>/dev/null
if [ -s hy.body ] && cmp -s hy.body hy3.body; then pass "--hydrate-volume: resolved options given back, same pack"; else fail "--hydrate-volume: resolved options given back" "the packs differ"; fi
expect_error "--hydrate-volume 1" 2 '^packgen: --hydrate-volume: must be in \[0, 1\) \(the hydrate.s fraction of the grain volume\), got 1 ' packgen --hydrate-volume 1
expect_error "--hydrate-volume -0.1" 2 '^packgen: --hydrate-volume: must be in \[0, 1\)' packgen --hydrate-volume -0.1
expect_error "--hydrate-volume nan" 2 "^packgen: --hydrate-volume: 'nan' is not a finite number" packgen --hydrate-volume nan
expect_error "--hydrate-volume with spheroplates" 2 '^packgen: --hydrate-volume: spheres only \(not with --shape spheroplate\)' packgen --shape spheroplate --hydrate-volume 0.1
# friction coefficients in [0, 10] like every tool's --mu (1e300 was accepted; issue 19)
expect_error "--friction 11" 2 '^packgen: --friction: must be in \[0, 10\]' packgen --friction 11
expect_error "--wall-friction 1e300" 2 '^packgen: --wall-friction: must be at most 10' packgen --wall-friction 1e300
expect_error "--dem-friction 11" 2 '^packgen: --dem-friction: must be in \[0, 10\]' packgen --dem-friction 11
