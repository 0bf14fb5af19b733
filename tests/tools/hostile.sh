# SPDX-License-Identifier: GPL-3.0-or-later
# Hostile input (issue 59): settings and packs of no sense, each of which a tool accepted
# (exit 0 with a pack of no sense) or ran on for minutes with no row; now refused before any
# work, in one line that names the option or the pack's line.  Every refusal runs under a
# timeout (60 s), so that a regression fails here rather than hanging the suite.
. "$TOP/tests/tools/lib.sh"

to() { timeout 60 "$@"; }

packgen --shape spheroplate --platyness 0.5 -n 125 --seed 2 -o s.pack 2>/dev/null
# meta KEY VALUE: s.pack with that meta line's value replaced, to m.pack
meta() { awk -v k="$1" -v v="$2" '$1 == "meta" && $2 == k { $3 = v } { print }' s.pack >m.pack; }

# --- shear: the stiffness, the stress and the wall's speed (H3) -------------------------------
# meta kn -1500, kt -1, sigma0 1e-300 and --kn 1e300 ran for minutes (kill at 20 s)
meta kn -1500
expect_error "shear: meta kn -1500" 1 '^shear: m\.pack: meta kn -1500 N/m: must be positive; give --kn$' to shear --strain 0.02 m.pack
meta kt -1
expect_error "shear: meta kt -1" 1 '^shear: m\.pack: meta kt -1 N/m: must be non-negative; give --kt$' to shear --strain 0.02 m.pack
meta sigma0 1e-300
expect_error "shear: meta sigma0 1e-300" 1 '^shear: m\.pack: the shear would need .* steps .*more than ten times --max-steps' \
    to shear --strain 0.02 m.pack
for o in "--stress 1e-300" "--velocity 1e-300" "--inertial 1e-300" "--kn 1e300"; do
	expect_error "shear $o" 1 '^shear: s\.pack: the shear would need .* steps .*out of any sensible range' \
	    to shear --strain 0.02 $o s.pack
done
expect_error "shear --velocity 1e300" 1 "^shear: s\\.pack: the top wall at v_w 1e\\+300 m/s would move more than a grain's radius" \
    to shear --strain 0.02 --velocity 1e300 s.pack
expect_error "shear --kn 1e-300" 2 '^shear: s\.pack: sigma_w .*\(stiffness number' to shear --strain 0.02 --kn 1e-300 s.pack
# the other settings (H9): beyond --strain, or without --checkpoint
expect_error "shear --profile-from beyond --strain" 2 '^shear: --profile-from: 0\.5 is not below --strain 0\.1' \
    shear --strain 0.1 --profile-from 0.5 s.pack
expect_error "shear --snapshots beyond --strain" 2 '^shear: --snapshots: 0\.5 is beyond --strain 0\.1' \
    shear --strain 0.1 --snapshots 0.05,0.5 s.pack
expect_error "shear --checkpoint-every without --checkpoint" 2 '^shear: --checkpoint-every needs --checkpoint' \
    shear --strain 0.1 --checkpoint-every 10 s.pack

# --- packgen: --kn, --stress and --spheroradius (H3, H9) ---------------------------------------
# --kn and --stress 1e-300 failed after 15-26 s without naming an option; --kn 1e300 and
# --spheroradius 1e-300 wrote a pack
expect_error "packgen --kn 1e-300" 2 '^packgen: --kn 1e-300 N/m: the compaction stress .* is outside \[1e-3 Pa, 10 GPa\]' \
    to packgen --shape spheroplate -n 27 --kn 1e-300
expect_error "packgen --kn 1e300" 2 '^packgen: --kn 1e\+300 N/m: the compaction stress' to packgen --shape spheroplate -n 27 --kn 1e300
expect_error "packgen --stress 1e-300" 2 '^packgen: --kn 1500 N/m and --stress 1e-300 Pa: the stiffness number .* must be in \[10, 1e9\]' \
    to packgen --shape spheroplate -n 27 --stress 1e-300
expect_error "packgen --kn and --stress 1e-300" 2 '^packgen: --stress: 1e-300 Pa is outside \[1e-3 Pa, 10 GPa\]' \
    to packgen --shape spheroplate -n 27 --kn 1e-300 --stress 1e-300
expect_error "packgen --spheroradius 1e-300" 2 '^packgen: --spheroradius: must be in \[1e-10, 1\] m, got 1e-300' \
    to packgen --shape spheroplate -n 27 --spheroradius 1e-300

# --- the pack reader: grains larger than the box, a box of 1e300 m (H9) ------------------------
# g: the first grain line (after the 'end' of the header); its 10th field the side
g=$(($(grep -n '^end$' s.pack | head -n 1 | cut -d: -f1) + 1))
[ "$(grep '^columns' s.pack | cut -d' ' -f11)" = side ] || fail "hostile: s.pack's layout" "side is not the 10th column"
awk -v g=$g 'NR == g { $10 = 1 } { print }' s.pack >side.pack
expect_error "a plate side of 1 m (porosity -3.7e11)" 1 \
    "^packinfo: side\\.pack:$g: grain 1: bounding radius 0\\.707107 m \\(side 1 m\\) is larger than the box along x" packinfo side.pack
awk -v g=$g -v n=125 'NR >= g && NR < g + n { $10 = 5e-7 } { print }' s.pack >vol.pack
expect_error "grains whose volumes exceed the box" 1 "^packinfo: vol\\.pack:$g: the grains' volume .* m\\^3 exceeds the box's" \
    packinfo vol.pack
awk '$1 == "box" { $5 = "1e300" } { print }' s.pack >bigbox.pack
expect_error "a box of 1e300 m" 1 '^packinfo: bigbox\.pack:[0-9]+: box: bound 1e\+300 m is outside \[-1000, 1000\] m' packinfo bigbox.pack

# --- loadtest: a key twice in a path segment (H9) --------------------------------------------
expect_error "loadtest: steps=1 steps=2" 2 "^loadtest: --path: segment 1: 'steps' is given twice" \
    loadtest --path 'uniaxial steps=1 steps=2' s.pack

# --- input that is no text, and gzip's padding (H10) -------------------------------------------
# each was "binary data (NUL byte)"; now what it is, and that only gzip is read
gzip -c s.pack | gzip -c >twice.pack.gz
expect_error "a gzip inside a gzip" 1 '^packinfo: twice\.pack\.gz:1: a gzip inside a gzip \(compressed twice\): decompress it once' \
    packinfo twice.pack.gz
printf 'x\234\313H\315\311\311\007\000\006,\002\025' >z.pack
expect_error "zlib data" 1 '^packinfo: z\.pack:1: zlib-compressed data \(no gzip header\): only gzip is read' packinfo z.pack
printf '\3757zXZ\000\000\004\346\326\264F' | gzip -c >xz.pack.gz
expect_error "xz inside a gzip" 1 '^packinfo: xz\.pack\.gz:1: inside the gzip stream, xz-compressed: decompress it first' \
    packinfo xz.pack.gz
printf 'BZh91AY&SY\000\000\000' | gzip -c >bz.pack.gz
expect_error "bzip2 inside a gzip" 1 '^packinfo: bz\.pack\.gz:1: inside the gzip stream, bzip2-compressed' packinfo bz.pack.gz
# zero padding after the last member (a tape block), which gzip -d accepts: read
gzip -c s.pack >pad.pack.gz
head -c 1000 /dev/zero >>pad.pack.gz
packinfo s.pack >plain.info 2>/dev/null
expect_ok "gzip's zero padding is read" packinfo pad.pack.gz
expect_same "gzip's zero padding: the same pack" ok.out plain.info
printf 'x' >>pad.pack.gz
expect_error "zero padding, then other bytes" 1 '^packinfo: pad\.pack\.gz:[0-9]+: trailing data after the end of the gzip stream' \
    packinfo pad.pack.gz

# --- names and ranges said (H10) ---------------------------------------------------------------
expect_error "--psd table: (no file)" 2 '^packgen: --psd table: names no file' packgen -n 5 --psd table:
printf 'E 7e10\nnu 0.5\nrho 2500\n' >half.mat
expect_error "a material's nu 0.5: the range said" 2 '^packgen: --material: \./half\.mat:2: nu 0\.5: the Poisson ratio must be in \(-1, 0\.5\)' \
    packgen -n 5 --material ./half.mat
printf 'E 7e10\nnu 0.2\nrho 2500\n' >mymaterial
expect_error "a material file named without a slash" 2 \
    "^packgen: --material: unknown material 'mymaterial' \\(presets: .*\\): to read the file of that name, give its path as \\./mymaterial" \
    packgen -n 5 --material mymaterial
expect_error "-o ''" 2 "^packinfo: -o: the file name is empty" packinfo -o '' s.pack
