# SPDX-License-Identifier: GPL-3.0-or-later
# packimport: x y z r text to a pack; the exact round trip through packexport --xyzr;
# materials, walls, box, seed; every reader error as one file:line message.
. "$TOP/tests/tools/lib.sh"

# Numbers as num_format writes them, so that the round trip can be byte-exact.
cat >in.xyzr <<'EOF'
0.001 0.0012 0.0015 0.0005
0.0019 0.0012 0.0015 0.00045
0.0014 0.0021 0.0011 0.00051234567890123
1.2345678901234568e-05 0.0025 0.0018 0.0006
EOF

expect_ok "import" packimport -o a.pack in.xyzr
sed 1,2d a.pack >a.body	# all but the magic and the history line, which holds argv
expect_num "grains line" "$(awk '$1 == "grains" { print $2 }' a.pack)" == 4
if [ "$(awk 'f { printf "%s ", $1 } $1 == "end" { f = 1 }' a.pack)" = "1 2 3 4 " ]; then
	pass "ids 1..N in file order"
else
	fail "ids 1..N in file order" "$(awk 'f { printf "%s ", $1 } $1 == "end" { f = 1 }' a.pack)"
fi
packexport --xyzr a.pack >back.xyzr
# two points at one centre: refused, as the pack reader would refuse the pack
printf '1e-4 1e-4 1e-4 1e-4\n2e-4 1e-4 1e-4 1e-4\n1e-4 1e-4 1e-4 2e-5\n' >same.xyzr
expect_error "two points at one centre" 1 '^packimport: same\.xyzr: grains 1 and 3 have the same centre$' packimport --fit-box same.xyzr
# an argument with a carriage return (here the file name): the history line gets a space for
# it, so the pack reads back and a second tool writes the history back byte for byte
crname=$(printf 'in\r.xyzr')
cp in.xyzr "$crname"
expect_ok "import a file whose name has a \\r" packimport -o cr.pack "$crname"
if ! grep -q "$(printf '\r')" cr.pack && grep -q "^history packimport .* 'in .xyzr'" cr.pack; then
	pass "the history line has a space for the \\r"
else
	fail "the history line has a space for the \\r" "$(grep '^history' cr.pack | od -c | head -3)"
fi
packexport --xyzr cr.pack >/dev/null 2>cr.err && pass "the pack with that history reads back" ||
    fail "the pack with that history reads back" "$(cat cr.err)"
expect_same "xyzr -> packimport -> packexport --xyzr is exact" back.xyzr in.xyzr
if grep -q '^history packimport .*--seed=1 .*--wall-E=7000000000000 ' a.pack; then
	pass "history line with resolved options"
else
	fail "history line" "$(grep '^history' a.pack)"
fi
if [ "$(awk '$1 == "walls"' a.pack)" = "walls 7000000000000 0.495 0.3" ] &&
    [ "$(awk '$1 == "friction"' a.pack)" = "friction 0.3" ]; then
	pass "wall E = 100 x glass E, wall nu 0.495, friction 0.3 for grains and walls"
else
	fail "wall and friction defaults" "$(grep -E '^(walls|friction)' a.pack | tr '\n' '|')"
fi
# E and nu drawn around glass (70 GPa, 0.2, 10 % spread), density 2420.
if awk 'f { if ($6 < 4e10 || $6 > 1e11 || $7 < 0.1 || $7 > 0.3 || $8 != 2420) bad = 1; n++ }
    $1 == "end" { f = 1 } END { exit bad || n != 4 }' a.pack; then
	pass "E, nu, rho drawn from glass"
else
	fail "E, nu, rho drawn from glass" "$(tail -n 4 a.pack | tr '\n' '|')"
fi
packimport in.xyzr >s1.pack
packimport in.xyzr >s2.pack
expect_same "same inputs and seed, same bytes" s1.pack s2.pack
if sed 1,2d s1.pack | cmp -s - a.body; then pass "-o FILE and stdout give the same pack"; else fail "-o FILE and stdout" "differ"; fi
packimport --seed 2 in.xyzr >c.pack
if cmp -s c.pack a.pack; then fail "another seed draws other moduli" "identical"; else pass "another seed draws other moduli"; fi
packimport --material quartz --friction 0.5 --wall-E 2e11 --wall-nu 0.3 --wall-friction 0.1 in.xyzr >q.pack
if [ "$(awk '$1 == "walls"' q.pack)" = "walls 200000000000 0.3 0.1" ] &&
    [ "$(awk '$1 == "friction"' q.pack)" = "friction 0.5" ] &&
    [ "$(awk 'f { print $8; exit } $1 == "end" { f = 1 }' q.pack)" = 2650 ]; then
	pass "--material --friction --wall-E --wall-nu --wall-friction"
else
	fail "material and wall options" "$(grep -E '^(walls|friction)' q.pack | tr '\n' '|')"
fi

# The fitted box holds every sphere, touches the extreme ones, and makes no wall contact.
# Each bound within 1e-18 m of the extreme sphere surface, and outside it.
if awk 'NR == FNR { for (a = 1; a <= 3; a++) { lo = $a - $4; hi = $a + $4
	if (NR == 1 || lo < min[a]) min[a] = lo; if (NR == 1 || hi > max[a]) max[a] = hi }; next }
    $1 == "box" { for (a = 1; a <= 3; a++) { d = min[a] - $(a + 1); e = $(a + 4) - max[a]
	if (d < 0 || d > 1e-18 || e < 0 || e > 1e-18) bad = 1 }; seen = 1 }
    END { exit bad || !seen }' in.xyzr a.pack; then
	pass "fit-box holds every sphere"
else
	fail "fit-box holds every sphere" "$(grep '^box' a.pack)"
fi
# x - r and x + r round: 0.4 - 0.1 and 0.28 + 0.1 would leave a sphere overlapping a wall by an ulp.
printf '0.4 0.5 0.4 0.1\n0.28 0.5 0.4 0.1\n' >touch.xyzr
packimport touch.xyzr | packinfo >touch.info
expect_num "fitted box gives no wall contacts" "$(info_value touch.info contacts_gw)" == 0
packimport --fit-box -o fit.pack in.xyzr
sed 1,2d fit.pack >fit.body
expect_same "--fit-box is the default" fit.body a.body

packimport --box 0,0,0,0.003,0.003,0.003 in.xyzr >box.pack
if grep -q '^box 0 0 0 0.003 0.003 0.003$' box.pack; then pass "--box is used as given"; else fail "--box" "$(grep '^box' box.pack)"; fi

# Comments, blank lines, CRLF, the YADE cell line, gzip: the same spheres.
{ echo '##PERIODIC:: 0.003 0.003 0.003'; echo '# a comment'; echo; sed 's/$/\r/' in.xyzr; echo '   '; } >commented.xyzr
packimport commented.xyzr | packexport --xyzr >commented.out
expect_same "comments, blank lines, CRLF are skipped; the spheres after a ##PERIODIC:: line as they were" commented.out in.xyzr

# YADE's periodic cell: ##PERIODIC:: makes a periodic pack of those box lengths, and the
# --periodic round trip, which packimport(1) calls exact, gives back the same bytes (the line
# was skipped: the cell lost, the lengths of a fitted box written back, issue 59)
if packimport commented.xyzr 2>/dev/null | grep -qx 'boundary periodic periodic periodic'; then
	pass "##PERIODIC:: makes every axis periodic"
else
	fail "##PERIODIC:: makes every axis periodic" "$(packimport commented.xyzr 2>&1 | grep -E '^(boundary|box)')"
fi
if packimport commented.xyzr 2>/dev/null | grep -qx 'box 0 0 0 0.003 0.003 0.003'; then
	pass "##PERIODIC:: the cell [0, L] that holds the centres"
else
	fail "##PERIODIC:: the cell [0, L] that holds the centres" "$(packimport commented.xyzr 2>&1 | grep '^box')"
fi
packgen -n 60 --seed 3 -o walled.pack 2>/dev/null
# per: a cell at the origin, as YADE writes it
{ echo '##PERIODIC:: 0.003 0.0031 0.0032'; cat in.xyzr; } >per.xyzr
packexport --xyzr --periodic walled.pack >walled.xyzr 2>/dev/null
for f in walled per; do
	packimport "$f.xyzr" 2>/dev/null | packexport --xyzr --periodic >"$f.back" 2>/dev/null
	if [ -s "$f.xyzr" ] && cmp -s "$f.back" "$f.xyzr"; then
		pass "$f: packexport --xyzr --periodic | packimport | packexport --xyzr --periodic: the same bytes ($(head -n 1 "$f.xyzr"))"
	else
		fail "$f: the --periodic round trip is byte-exact" "$(cmp "$f.back" "$f.xyzr" 2>&1)"
	fi
done
# a box away from the origin: the lengths exactly, the centres as they were
packimport walled.xyzr 2>/dev/null >wp.pack
packinfo wp.pack >wp.info 2>wp.err
if [ -s wp.info ] && grep -qx 'boundary periodic periodic periodic' wp.pack; then
	pass "the periodic import of a box away from the origin reads back (packinfo)"
else
	fail "the periodic import of a box away from the origin reads back" "$(head -c 300 wp.err)"
fi
{ echo '##PERIODIC:: 0.003 0.003'; cat in.xyzr; } >cell2.xyzr
expect_error "##PERIODIC:: with two lengths" 1 '^packimport: cell2\.xyzr:1: ##PERIODIC:: expected 3 cell lengths \(Lx Ly Lz\), found 2$' packimport cell2.xyzr
{ echo '##PERIODIC:: 0.003 -1 0.003'; cat in.xyzr; } >cellneg.xyzr
expect_error "##PERIODIC:: a negative length" 1 "^packimport: cellneg\\.xyzr:1: ##PERIODIC:: cell length '-1' is not a positive number$" packimport cellneg.xyzr
{ cat commented.xyzr; echo '##PERIODIC:: 0.003 0.003 0.003'; } >celltwice.xyzr
expect_error "a second ##PERIODIC:: line" 1 '^packimport: celltwice\.xyzr:[0-9]+: a second ##PERIODIC:: line \(the first is line 1\)$' packimport celltwice.xyzr
expect_error "##PERIODIC:: and --box of other lengths" 1 "^packimport: commented\\.xyzr:1: ##PERIODIC:: cell length 0\\.003 along x differs from --box's 0\\.004$" \
    packimport --box 0,0,0,0.004,0.003,0.003 commented.xyzr
if packimport --box 0,0,0,0.003,0.003,0.003 commented.xyzr 2>/dev/null | grep -qx 'boundary periodic periodic periodic'; then
	pass "##PERIODIC:: with --box of its lengths: periodic, the box given"
else
	fail "##PERIODIC:: with --box of its lengths" "$(packimport --box 0,0,0,0.003,0.003,0.003 commented.xyzr 2>&1 | tail -n 1)"
fi
gzip -c in.xyzr >in.xyzr.gz
packimport in.xyzr.gz >gz.pack
sed 1,2d gz.pack >gz.body
expect_same ".gz input gives the same pack but for its history line" gz.body a.body
packimport <in.xyzr | packexport --xyzr >stdin.out
expect_same "stdin input" stdin.out in.xyzr
packimport -o out.pack.gz in.xyzr
if gzip -dc out.pack.gz | sed 1,2d | cmp -s - a.body; then pass "-o NAME.gz writes gzip"; else fail "-o NAME.gz" "differs"; fi

# --- data errors: exit 1, nothing on stdout, one line "packimport: FILE:LINE: ..." --------
printf '0.001 0.001 0.001 0.0005\n0.002 0.002 0.0005\n' >cols.xyzr
expect_error "malformed line" 1 '^packimport: cols.xyzr:2: expected 4 columns \(x y z r\), found 3$' packimport cols.xyzr
cp cols.xyzr same-io.xyzr
expect_error "-o the input" 2 "^packimport: -o 'same-io.xyzr' is the input" packimport -o same-io.xyzr same-io.xyzr
expect_same "-o the input: the input untouched" same-io.xyzr cols.xyzr
printf '0.001 0.001 0.001 0.0005 1\n' >cols5.xyzr
expect_error "five columns" 1 '^packimport: cols5.xyzr:1: expected 4 columns' packimport cols5.xyzr
printf '# c\n0.001 nan 0.001 0.0005\n' >nan.xyzr
expect_error "NaN" 1 "^packimport: nan.xyzr:2: 'nan' is not a finite number$" packimport nan.xyzr
printf '0.001 0.001 0.001 0.0005\n\n0.002 0.002 0.002 -0.0005\n' >neg.xyzr
expect_error "negative radius" 1 '^packimport: neg.xyzr:3: radius -0.0005 is not positive$' packimport neg.xyzr
printf '0.001 0.001 0.001 0\n' >zero.xyzr
expect_error "zero radius" 1 '^packimport: zero.xyzr:1: radius 0 is not positive$' packimport zero.xyzr
printf '0.001 0.001 0.001 0.0005x\n' >junk.xyzr
expect_error "trailing junk in a number" 1 "^packimport: junk.xyzr:1: '0.0005x' is not a finite number$" packimport junk.xyzr
printf '0.001 1e999 0.001 0.0005\n' >inf.xyzr
expect_error "overflow" 1 "^packimport: inf.xyzr:1: '1e999' is not a finite number$" packimport inf.xyzr
awk 'BEGIN { for (i = 1; i <= 3000; i++) printf "%d 0.5 0.25 0.125\n", i }' >big.xyzr
gzip -c big.xyzr | head -c 3000 >trunc.xyzr.gz
expect_error "truncated .gz" 1 '^packimport: trunc.xyzr.gz:[0-9]+: corrupt or truncated input' packimport trunc.xyzr.gz
gzip -c big.xyzr | head -c 20 >trunc20.gz
expect_error "truncated .gz header" 1 '^packimport: trunc20.gz:1: corrupt or truncated input' packimport trunc20.gz
: >empty.xyzr
expect_error "empty input" 1 '^packimport: empty.xyzr:1: empty input$' packimport empty.xyzr
printf '# only\n\n' >comments.xyzr
expect_error "comments only" 1 '^packimport: comments.xyzr:3: no spheres' packimport comments.xyzr
expect_error "empty stdin" 1 '^packimport: <stdin>:1: empty input$' packimport <empty.xyzr
printf '0.001 0.001 0.001 0.0005\n0.001 0.0\0001 0.001 0.0005\n' >nul.xyzr
expect_error "NUL byte" 1 '^packimport: nul.xyzr:2: binary data' packimport nul.xyzr
expect_error "centre outside --box" 1 '^packimport: in.xyzr:4: centre y = 0.0025 is outside the box \[0, 0.0022\]$' \
    packimport --box 0,0,0,0.003,0.0022,0.003 in.xyzr
expect_error "missing file" 1 '^packimport: nonexistent.xyzr: ' packimport nonexistent.xyzr
expect_error "bad material file" 1 '^packimport: ./none.mat: ' packimport --material ./none.mat in.xyzr
packimport -o never.pack neg.xyzr 2>/dev/null
if [ -e never.pack ] || ls -a | grep -q '^\.never'; then fail "failed import leaves no file" "$(ls -a)"; else pass "failed import leaves no file"; fi

# --- usage errors: exit 2 ---------------------------------------------------------------
expect_error "unknown option" 2 "unknown option '--bogus'" packimport --bogus in.xyzr
expect_error "--box with --fit-box" 2 'exclude' packimport --box 0,0,0,1,1,1 --fit-box in.xyzr
expect_error "--box with five numbers" 2 '^packimport: --box: ' packimport --box 0,0,0,1,1 in.xyzr
expect_error "--box with hi below lo" 2 '^packimport: --box: ' packimport --box 0,0,1,1,1,0 in.xyzr
expect_error "unknown material" 2 "^packimport: --material: unknown material 'unobtainium'" packimport --material unobtainium in.xyzr
expect_error "negative seed" 2 '^packimport: --seed: ' packimport --seed -1 in.xyzr
expect_error "negative friction" 2 '^packimport: --friction: ' packimport --friction -0.1 in.xyzr
expect_error "wall-E not positive" 2 '^packimport: --wall-E: ' packimport --wall-E 0 in.xyzr
expect_error "friction above 10" 2 '^packimport: --friction: 11 is outside \[0, 10\]' packimport --friction 11 in.xyzr
expect_error "wall-friction above 10" 2 "^packimport: --wall-friction: '1e300' is not a number in \[0, 10\]" packimport --wall-friction 1e300 in.xyzr
expect_error "wall-E past the range" 2 '^packimport: --wall-E: 1e20 Pa is outside \[1000, 1e\+15\] Pa' packimport --wall-E 1e20 in.xyzr
expect_error "wall-nu out of range" 2 '^packimport: --wall-nu: ' packimport --wall-nu 0.5 in.xyzr
expect_error "two input files" 2 'too many operands' packimport in.xyzr in.xyzr
