#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# make-packs.sh: writes the shared corpus tests/corpus/packs/ (issue 59) from packs of the
# fuzz corpus: each file a pack, or an input that is not one, that the C reader (packinfo)
# and the Python package's reader must accept or refuse alike, with the same words
# (tests/tools/corpus.sh).  Their expected outcomes, checked by hand once, are in
# tests/corpus/packs.expected; run from the top of the tree, then review the diff.
set -eu
src=tests/fuzz/corpus/fuzz_pack
out=tests/corpus/packs
rm -rf "$out"
mkdir -p "$out"
f12=$src/f12.pack
# line N of f12.pack replaced by TEXT (printf's escapes), into NAME
subst() { awk -v n="$2" -v t="$3" 'NR == n { printf "%s\n", t; next } { print }' "$f12" >"$out/$1"; }

cp "$f12" "$out/ok-v1.pack"
cp "$src/multi.pack" "$out/ok-stream.pack"
cp "$src/plates.pack" "$out/ok-plates.pack"
: >"$out/empty.pack"
printf '\357\273\277' | cat - "$f12" >"$out/bom.pack"
tr '\n' '\r' <"$f12" >"$out/cr-only.pack"
sed 's/$/\r/' "$f12" >"$out/ok-crlf.pack"
sed '5s/glass/gl\rass/' "$f12" >"$out/cr-inside.pack"
sed '20s/ 2420$/ 24@0/' "$f12" | tr '@' '\000' >"$out/nul.pack"
xz -c "$f12" >"$out/xz.pack.xz"
bzip2 -c "$f12" >"$out/bzip2.pack.bz2"
zstd -q -c "$f12" >"$out/zstd.pack.zst"
# numbers: Unicode digits and blanks, what Python's float() and str.split() take and
# strtod and the C reader's split do not
sed '16s/ 2420$/ \xd9\xa2\xd9\xa4\xd9\xa2\xd9\xa0/' "$f12" >"$out/unicode-digits.pack"
sed '16s/ 2420$/\xc2\xa02420/' "$f12" >"$out/nbsp.pack"
sed '16s/ 2420$/ 2_420/' "$f12" >"$out/underscore.pack"
sed '16s/ 2420$/ 0x1p99999/' "$f12" >"$out/hex-overflow.pack"
sed '16s/ 2420$/ 0x1.2ep11/' "$f12" >"$out/ok-hex.pack"
sed '16s/ 2420$/ nan/' "$f12" >"$out/nan.pack"
sed '16s/ 2420$/\t\v2420/' "$f12" >"$out/ok-tab-vt.pack"
# counts: a header's count is no allocation
sed 's/^contacts 37$/contacts 1000000000/' "$f12" >"$out/huge-contacts.pack"
sed 's/^grains 12$/grains 1000000000/' "$f12" >"$out/huge-grains.pack"
sed 's/^contacts 37$/contacts 1000000001/' "$f12" >"$out/count-too-large.pack"
# contacts: a pair twice (as it was, and with its grains swapped), an unknown grain, a wall
# of a periodic axis, a force past Hertz's bound
sed '28p; s/^contacts 37$/contacts 38/' "$f12" >"$out/contact-twice.pack"
awk 'NR == 28 { print; split($0, f, " "); printf "%s %s", f[2], f[1]; for (k = 3; k <= 7; k++) printf " %s", f[k]; print ""; next }
     /^contacts 37$/ { print "contacts 38"; next } { print }' "$f12" >"$out/contact-twice-swapped.pack"
subst contact-no-grain.pack 28 "1 99 0.1 0 0 0 0"
subst contact-hertz.pack 28 "1 2 1e9 0 0 0 0"
subst contact-self.pack 28 "3 3 0.1 0 0 0 0"
# grains: the value rules of the C reader, two at one centre, an id twice
subst grain-radius.pack 16 "1 0.00010584563995346208 0.00029273637370322 0.00010970892723918507 -1e-5 65293086641.32453 0.1713623712368082 2420"
subst grain-E.pack 16 "1 0.00010584563995346208 0.00029273637370322 0.00010970892723918507 7.5e-5 1e14 0.1713623712368082 2420"
subst grain-outside.pack 16 "1 0.1 0.00029273637370322 0.00010970892723918507 7.5e-5 65293086641.32453 0.1713623712368082 2420"
subst grain-same-centre.pack 17 "2 0.00010584563995346208 0.00029273637370322 0.00010970892723918507 1e-4 64740894703.998604 0.18311215839721895 2420"
subst grain-id-twice.pack 17 "1 0.00016036255301307852 0.00012196256093359707 0.00014173593401163419 0.00010786963598454836 64740894703.998604 0.18311215839721895 2420"
# version 2: the glued column (its words, a wall of a periodic axis), a bad quaternion
awk '/^columns / { print $0 " glued"; next } /^end$/ { print; on = 1; next }
     on && NF == 8 { print $0 " " ($1 == 1 ? "zlo" : "-"); next } { print }' "$src/v2_walls.pack" >"$out/ok-glued.pack"
sed 's/ zlo$/ zmid/' "$out/ok-glued.pack" >"$out/glued-word.pack"
sed 's/^boundary walls walls walls$/boundary walls walls periodic/' "$out/ok-glued.pack" >"$out/glued-periodic.pack"
sed '14s/ 0.7071067811865476 0.7071067811865476 0 0$/ 0.7 0.7 0 0/' "$src/plates.pack" >"$out/plate-quaternion.pack"
# gzip: two members, a truncated stream, a corrupt one, a plain pack appended
head -n 14 "$f12" | gzip -n >"$out/ok-two-members.pack.gz"
tail -n +15 "$f12" | gzip -n >>"$out/ok-two-members.pack.gz"
gzip -n -c "$f12" >"$out/truncated.pack.gz"
size=$(wc -c <"$out/truncated.pack.gz")
head -c $((size - 40)) "$out/truncated.pack.gz" >"$out/t.tmp" && mv "$out/t.tmp" "$out/truncated.pack.gz"
gzip -n -c "$f12" >"$out/crc.pack.gz"
# the CRC-32 of the trailer: every byte decodes, then the check fails
size=$(wc -c <"$out/crc.pack.gz")
printf '\377' | dd of="$out/crc.pack.gz" bs=1 seek=$((size - 8)) conv=notrunc 2>/dev/null
{ gzip -n -c "$f12"; cat "$f12"; } >"$out/trailing.pack.gz"
# the rules of no sense (issue 59 H9): a box beyond 1 km, a plate larger than the box, grains
# whose volumes exceed the box
sed 's/^box 3.1153668307431874e-05 /box -2000 /' "$f12" >"$out/box-km.pack"
sed '13s/ 1e-4 1 0 0 0$/ 1 1 0 0 0/' "$src/plates.pack" >"$out/plate-side.pack"
subst grain-volume.pack 16 "1 0.00010584563995346208 0.00029273637370322 0.00010970892723918507 0.0005 65293086641.32453 0.1713623712368082 2420"
# other streams inside a gzip (issue 59 H10): a gzip twice, zlib, xz within gzip; gzip's zero
# padding (read, as gzip -d reads it), then something after it (refused)
gzip -n -c "$f12" | gzip -n >"$out/gzip-twice.pack.gz"
python3 -c 'import sys, zlib; sys.stdout.buffer.write(zlib.compress(sys.stdin.buffer.read()))' <"$f12" >"$out/zlib.pack.z"
xz -c "$f12" | gzip -n >"$out/xz-in-gzip.pack.gz"
{ gzip -n -c "$f12"; head -c 512 /dev/zero; } >"$out/ok-zero-padding.pack.gz"
{ gzip -n -c "$f12"; head -c 512 /dev/zero; printf 'x'; } >"$out/zero-padding-then.pack.gz"
# the end of the stream: a line without a newline, text after the last contact
head -c -1 "$f12" >"$out/no-newline.pack"
{ cat "$f12"; echo "extra"; } >"$out/after-last.pack"
