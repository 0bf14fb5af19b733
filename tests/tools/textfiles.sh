# SPDX-License-Identifier: GPL-3.0-or-later
# textfiles: the small text inputs read through the line reader (lib/base/lines.c): a
# material preset file (packgen --material FILE), a size table (packgen --psd
# table:FILE), and packimport's "x y z r" lines.  Their readers used 512- and 256-byte fgets buffers, which split a longer
# line in two and read the second half as a line of its own; lines of any length must now
# be read whole, or refused as one line with its right number.
. "$TOP/tests/tools/lib.sh"

# long N: N characters "0"
long() { head -c "$1" /dev/zero | tr '\0' 0; }
z600=$(long 600)
z300=$(long 300)

# --- material preset files ---------------------------------------------------------------
{
	echo "# a comment of 1000 characters: $(long 1000)"
	echo "E 5e9"
	echo "nu        $(printf '%600s' '')0.3"
	echo "rho 1000.$z600"
	echo "spread 0"
} >long.mat
expect_ok "material file with 1000- and 600-character lines" packgen -n 20 --seed 1 --material ./long.mat -o long.pack
# spread 0: every grain has exactly the file's E and nu, and rho 1000.000...0 is 1000
awk '/^end$/ { on = 1; next } on && NF == 8 && ($6 != 5e9 || $7 != 0.3 || $8 != 1000) { bad = 1 }
    on && NF == 8 { n++ } END { exit bad || n != 20 }' long.pack &&
    pass "material file with long lines: E, nu, rho of every grain as written" ||
    fail "material file with long lines: E, nu, rho of every grain as written" "$(sed -n '/^end$/,$p' long.pack | head -3)"
printf 'E 5e9\nnu 0.3\nrho 1000\nspread 0\n' >short.mat
packgen -n 20 --seed 1 --material ./short.mat -o short.pack 2>/dev/null
sed '/^history /d; /^meta material /d' long.pack >long.body
sed '/^history /d; /^meta material /d' short.pack >short.body
expect_same "material file with long lines: the same pack as the short file" long.body short.body
{ echo "# $(long 2000)"; echo "E 5e9"; echo "nu 0.3 $(long 700)"; echo "rho 1000"; } >extra.mat
expect_error "material file: a third field after 700 characters is refused at its line" 2 \
    "^packgen: --material: \./extra\.mat:3: expected 'key value' with a finite number \\(try" \
    packgen -n 20 --material ./extra.mat
{ echo "# $(long 700)"; echo "E 5e9"; echo "k$z600 1"; } >key.mat
expect_error "material file: a 601-character key is refused whole, at its line" 2 \
    "^packgen: --material: \./key\.mat:3: unknown key: k0{600} \\(the keys: E, nu, rho, spread\\) \\(try" \
    packgen -n 20 --material ./key.mat
printf 'E 5e9\nnu 0.3\r\nrho 1000\r\n' >crlf.mat
expect_ok "material file with CRLF lines" packgen -n 20 --seed 1 --material ./crlf.mat -o crlf.pack
printf 'E 5e9\nnu 0.\0003\nrho 1000\n' >nul.mat
expect_error "material file: a NUL byte" 2 '^packgen: --material: \./nul\.mat:2: binary data \(NUL byte\)' \
    packgen -n 20 --material ./nul.mat
# a key given twice (the second E replaced the first without a word), and E out of the range a
# pack takes (E = 1e-300 made grains that densify squeezed by 0.47 R)
printf 'E 5e9\nnu 0.3\nE 7e10\nrho 1000\n' >twice.mat
expect_error "material file: E given twice" 2 '^packgen: --material: \./twice\.mat:3: E given twice \(each key once\)' \
    packgen -n 20 --material ./twice.mat
printf 'E 5e9\nnu 0.3\nrho 1000\nspread 0.1\nspread 0\n' >spread2.mat
expect_error "material file: spread given twice" 2 '^packgen: --material: \./spread2\.mat:5: spread given twice' \
    packgen -n 20 --material ./spread2.mat
printf 'E 1e-300\nnu 0.3\nrho 1000\n' >tiny.mat
expect_error "material file: E 1e-300" 2 '^packgen: --material: \./tiny\.mat:1: E 1e-300 Pa is outside \[1000, 1e\+13\] Pa' \
    packgen -n 20 --material ./tiny.mat

# --- size tables -------------------------------------------------------------------------
{
	echo "# a comment of 1000 characters: $(long 1000)"
	echo "1.${z300}e-4 1"
	echo "1.2e-4      $(printf '%400s' '')2"
} >long.txt
expect_ok "size table with 1000-, 300- and 400-character lines" packgen -n 40 --seed 1 --psd table:long.txt -o tl.pack
printf '1e-4 1\n1.2e-4 2\n' >short.txt
packgen -n 40 --seed 1 --psd table:short.txt -o ts.pack 2>/dev/null
sed '/^history /d' tl.pack >tl.body
sed '/^history /d' ts.pack >ts.body
expect_same "size table with long lines: the same pack as the short table" tl.body ts.body
{ echo "1e-4 1"; echo "# $(long 900)"; echo "1.2e-4 2 $(long 300)"; } >extra.txt
expect_error "size table: a third field after 300 characters is refused at its line" 2 \
    "^packgen: extra\.txt:3: expected 'radius \[weight\]'" packgen -n 40 --psd table:extra.txt
printf '1e-4 1\r\n1.2e-4 2\r\n' >crlf.txt
packgen -n 40 --seed 1 --psd table:crlf.txt -o tc.pack 2>/dev/null
sed '/^history /d' tc.pack >tc.body
expect_same "size table with CRLF lines: the same pack" tc.body ts.body
: >empty.txt
expect_error "size table: empty" 2 '^packgen: empty\.txt: the size table is empty \(try' packgen --psd table:empty.txt
expect_error "size table: missing" 2 '^packgen: none\.txt: cannot open size table \(try' packgen --psd table:none.txt
# weights all 0 were taken (a distribution of nothing); an overflowing sum is no distribution
printf '1e-4 0\n1.2e-4 0\n' >zero.txt
expect_error "size table: every weight 0" 2 '^packgen: zero\.txt: the weights are all 0: at least one must be positive \(try' \
    packgen -n 40 --psd table:zero.txt
printf '1e-4 1e308\n1.2e-4 1e308\n' >huge.txt
expect_error "size table: weights past a double" 2 '^packgen: huge\.txt: the weights sum to inf, more than a double holds' \
    packgen -n 40 --psd table:huge.txt

# --- packimport's x y z r lines ------------------------------------------------------------
printf '0.001 0.001 0.001 0.0005\n0.002 0.002 0.002 0.0005\n' >short.xyzr
{ echo "0.001 0.001 0.001 0.0005"; echo "0.002 $(printf '%70000s' '')0.002 0.002 0.0005$(printf '%70000s' '')"; } >wide.xyzr
packimport short.xyzr >short-imp.pack 2>/dev/null
packimport wide.xyzr >wide-imp.pack 2>wide.err
sed '/^history /d' short-imp.pack >short-imp.body
sed '/^history /d' wide-imp.pack >wide-imp.body
expect_same "x y z r: a 140000-character line is one sphere" wide-imp.body short-imp.body
{ echo "# $(long 70000)"; echo "0.001 0.001 0.001 0.0005 $(long 70000)"; } >wide5.xyzr
expect_error "x y z r: five columns after a 70000-character comment, refused at line 2" 1 \
    '^packimport: wide5\.xyzr:2: expected 4 columns \(x y z r\), found 5$' packimport wide5.xyzr
