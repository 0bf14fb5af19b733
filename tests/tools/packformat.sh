# SPDX-License-Identifier: GPL-3.0-or-later
# packformat: the pack reader (lib/pack/packio.c) as a user meets it, through packinfo.
# One check for every error the reader reports (share/doc/pack-format.md, "Errors"), each
# with exit status 1, an empty stdout and exactly one "packinfo: FILE:LINE: what" line on
# stderr, and the positive cases: plain, gzip, stdin, '-', several packs in one stream, -o;
# then the same for the lines of format version 2 (columns, boundary), its shape columns and
# its phase column, which every tool that writes a pack keeps.
. "$TOP/tests/tools/lib.sh"

# Line numbers of good.pack, used by the error checks below:
#  1 magic   2 history   3 comment   4 meta   5 units   6 box   7 refbox   8 walls
#  9 friction   10 grains   11 contacts   12 end   13-15 grains   16-18 contacts
cat >good.pack <<'EOF'
qusgm-pack 1
history packgen 0.1.0: packgen -n 3 ; --n=3
# a comment is allowed in the header
meta note three grains in a row
units SI
box 0 0 0 3e-4 2e-4 2e-4
refbox 0 0 0 3e-4 2e-4 2e-4
walls 7e12 0.495 0.3
friction 0.3
grains 3
contacts 3
end
1 1e-4 1e-4 1e-4 1.0001e-4 7e10 0.2 2420
2 2e-4 1e-4 1e-4 1.0001e-4 7e10 0.2 2420
3 1.5e-4 1.5e-4 1.5e-4 2e-5 7e10 0.2 2420
1 2 0.01 0 0 0 0
1 xlo 0.01 0 1e-4 0 0
2 xhi 0.01 0 0 0 0
EOF

# bad NAME LINE REGEX SED-SCRIPT: a copy of good.pack edited by SED-SCRIPT must be refused
# at line LINE with a message matching REGEX.
bad() {
	name=$1 line=$2 re=$3
	sed "$4" good.pack >"$name.pack"
	expect_error "$name" 1 "^packinfo: $name\\.pack:$line: .*$re" packinfo "$name.pack"
}

# --- the first line ---
bad wrong-magic 1 'not a qusgm pack' '1s/.*/qusgm-pak 1/'
bad missing-version 1 'version' '1s/.*/qusgm-pack/'
bad newer-version 1 'version 3 is newer than this qusgm reads \(2\)' '1s/.*/qusgm-pack 3/'
bad older-version 1 'version' '1s/.*/qusgm-pack 0/'
bad malformed-version 1 'version' '1s/.*/qusgm-pack 1.0/'
bad much-newer-version 1 'version 30 is newer' '1s/.*/qusgm-pack 30/'

# --- the header: every required keyword exactly once (the error is at the 'end' line) ---
for k in units box walls friction grains contacts; do
	bad "missing-$k" 11 "missing '$k'" "/^$k /d"
done
bad missing-end 12 "unknown header keyword '1'" '/^end$/d'
bad duplicate-box 7 "duplicate 'box'" '6p'
bad duplicate-refbox 8 "duplicate 'refbox'" '7p'
bad duplicate-friction 10 "duplicate 'friction'" '9p'
bad duplicate-meta-key 5 "duplicate key" '4p'
bad unknown-keyword 6 "unknown header keyword 'colour'" '5a\
colour red'
bad empty-header-line 6 'empty line' '5a\
'
bad units-not-si 5 'units' '5s/.*/units mm/'
bad box-short 6 'expected 6 numbers' '6s/ 2e-4$//'
bad box-inverted 6 'not above' '6s/.*/box 0 0 0 -3e-4 2e-4 2e-4/'
bad refbox-inverted 7 'not above' '7s/.*/refbox 0 0 2e-4 3e-4 2e-4 2e-4/'
bad walls-E 8 "Young's modulus" '8s/.*/walls 0 0.495 0.3/'
bad walls-nu 8 'Poisson' '8s/.*/walls 7e12 0.5 0.3/'
bad walls-mu 8 'negative' '8s/.*/walls 7e12 0.495 -0.1/'
bad friction-negative 9 'negative' '9s/.*/friction -0.3/'
# values outside the range where the tools' physics holds, named with the range (the
# options cap mu at 10; a header's friction 1e300 was taken)
bad friction-above-10 9 'friction: coefficient 1e\+300 is outside \[0, 10\] \(the range of the tools. --mu\)$' '9s/.*/friction 1e300/'
bad walls-mu-above-10 8 'walls: friction coefficient 11 is outside \[0, 10\]' '8s/.*/walls 7e12 0.495 11/'
bad walls-E-too-stiff 8 "walls: Young's modulus 1e\+16 Pa is outside \[1000, 1e\+15\] Pa$" '8s/.*/walls 1e16 0.495 0.3/'
bad walls-E-too-soft 8 "walls: Young's modulus 1 Pa is outside \[1000, 1e\+15\] Pa$" '8s/.*/walls 1 0.495 0.3/'
bad grains-zero 10 'not a valid count' '10s/.*/grains 0/'
bad grains-not-integer 10 'not a valid count' '10s/.*/grains 3.5/'
bad end-extra 12 'after .end.' '12s/.*/end now/'
bad comment-after-header 13 'expected 8 columns' '12a\
# comment'

# --- grain lines ---
bad missing-column 14 'expected 8 columns' '14s/ 2420$//'
bad extra-column 14 'expected 8 columns' '14s/$/ 7/'
bad non-number 14 "'abc' is not a finite number" '14s/^2 2e-4/2 abc/'
bad nan 14 "'nan' is not a finite number" '14s/^2 2e-4/2 nan/'
bad inf 14 "'inf' is not a finite number" '14s/1.0001e-4/inf/'
bad overflow 14 'not a finite number' '14s/1.0001e-4/1e999/'
bad id-not-integer 14 'not an integer' '14s/^2 /2.5 /'
bad id-negative 14 'negative' '14s/^2 /-2 /;16s/^1 2 /1 -2 /'
bad radius-zero 14 'radius 0 is not positive' '14s/1.0001e-4/0/'
bad radius-negative 14 'radius -0.0001 is not positive' '14s/1.0001e-4/-1e-4/'
bad E-zero 14 "Young's modulus 0 is not positive" '14s/7e10/0/'
bad E-negative 14 "Young's modulus" '14s/7e10/-7e10/'
# E = 1e-300 was taken (densify then squeezed the grain by 0.47 R), and a grain larger than
# its box (packinfo printed porosity -inf)
bad E-tiny 14 "grain 2: Young's modulus 1e-300 Pa is outside \[1000, 1e\+13\] Pa$" '14s/7e10/1e-300/'
bad E-huge 14 "grain 2: Young's modulus 1e\+14 Pa is outside \[1000, 1e\+13\] Pa$" '14s/7e10/1e14/'
bad grain-larger-than-box 14 'grain 2: radius 1 m is larger than the box along x \(0.0003 m\): the radius must be at most the box length$' '14s/1.0001e-4/1/'
bad nu-half 14 'Poisson ratio 0.5 is outside' '14s/ 0.2 / 0.5 /'
bad nu-minus-one 14 'Poisson ratio -1 is outside' '14s/ 0.2 / -1 /'
bad density-zero 14 'density 0 is not positive' '14s/2420$/0/'
bad density-negative 14 'density' '14s/2420$/-2420/'
bad centre-outside 14 'centre x = 0.0004 is outside the box' '14s/^2 2e-4/2 4e-4/'
bad centre-below 15 'centre z' '15s/ 1.5e-4 2e-5/ -1e-6 2e-5/'
# two grains at one centre: no direction between them, so packinfo once said overlap_max 0
# and no contact between them; refused at the later line, for every tool that reads a pack
bad same-centre 15 'grains 1 and 3 have the same centre$' '15s/^3 1.5e-4 1.5e-4 1.5e-4/3 1e-4 1e-4 1e-4/'
bad same-centre-first-pair 14 'grains 1 and 2 have the same centre$' '14s/^2 2e-4/2 1e-4/;15s/^3 1.5e-4 1.5e-4 1.5e-4/3 1e-4 1e-4 1e-4/'
for t in densify frictionalize loadtest; do
	expect_error "same-centre-$t" 1 "^$t: same-centre\\.pack:15: grains 1 and 3 have the same centre$" $t same-centre.pack
done
# the later line of the two is named
bad duplicate-id 15 'duplicate grain id 1' '15s/^3 /1 /;16,18d;11s/3/0/'

# --- contact lines ---
bad contact-missing-grain 16 'grain 7, which is not in the pack' '16s/^1 2 /1 7 /'
bad contact-missing-first 17 'grain 9, which is not in the pack' '17s/^1 xlo /9 xlo /'
bad contact-wall-name 17 "'xmid' is neither a grain id nor a wall" '17s/xlo/xmid/'
bad contact-wall-first 17 "'xlo' is neither a grain id nor a wall" '17s/^1 xlo /xlo 1 /'
bad contact-self 16 'with itself' '16s/^1 2 /1 1 /'
bad contact-twice 18 'listed twice' '18s/.*/2 1 0.01 0 0 0 0/'
bad contact-wall-twice 18 'listed twice' '18s/.*/1 xlo 0.02 0 0 0 0/'
bad contact-missing-column 16 'expected 7 columns' '16s/ 0$//'
bad contact-extra-column 16 'expected 7 columns' '16s/$/ 0/'
bad contact-nan 16 "'nan' is not a finite number" '16s/0.01 0 0 0 0/0.01 nan 0 0 0/'
bad contact-negative-P0 16 'P0 = -0.01 is negative' '16s/0.01/-0.01/'
# a contact force past Hertz's at an overlap as large as the contact's radius (a P0 of 1e300 N
# was taken); a pack of the plate engine's linear law is not held to Hertz's bound
bad contact-P0-huge 16 'contact: normal force P0 = 1e\+300 N is outside \[0, [0-9.e+]+\] N, the Hertz force at an overlap as large as the contact.s radius' '16s/0.01/1e300/'
bad contact-wall-P0-huge 17 'contact: normal force P0 = 1e\+06 N is outside' '17s/0.01/1e6/'
bad contact-Q0-huge 16 'contact: tangential force \|Q0\| = 1e\+300 N is outside' '16s/0.01 0 0 0 0/0.01 1e300 0 0 0/'
bad contact-M0-huge 16 'contact: couple \|M0\| = 1e\+300 N m is outside' '16s/0.01 0 0 0 0/0.01 0 0 0 -1e300/'
sed '4a\
meta contact-law linear
16s/0.01/1e3/' good.pack >linear-law.pack
expect_ok contact-P0-linear-law packinfo linear-law.pack

# --- counts and the end of the stream ---
bad fewer-grains 16 '4 grains declared, 3 found' '10s/3/4/;11s/3/0/;16,$d'
bad fewer-contacts 19 '4 contacts declared, 3 found' '11s/3/4/'
bad trailing-garbage 19 'unexpected line after the last contact' '$a\
garbage'
bad trailing-empty-line 19 'unexpected line after the last contact' '$a\
'
bad second-pack-bad 19 'newer' '$a\
qusgm-pack 3'
bad nul-byte 14 'NUL' '14s/2420/24\x0020/'
# a \r other than the one before the \n (a history line ending in CR CR LF once kept one \r,
# wrote it back and lost it on the next read)
bad history-cr-cr-lf 2 'a carriage return \(\\r\) inside a line' '2s/$/\r\r/'
bad meta-cr-inside 4 'carriage return' '4s/three/three\r/'
bad grain-cr-cr-lf 14 'carriage return' '14s/$/\r\r/'

# --- a plain pack cut without its final newline (once read: the last rho 2420 became 24) ---
sed '11s/3/0/;16,$d' good.pack >nocontacts.pack
printf '%s' "$(sed '$s/2420$/24/' nocontacts.pack)" >cut-last-field.pack
expect_error cut-last-field 1 '^packinfo: cut-last-field\.pack:15: truncated: the last line has no newline$' packinfo cut-last-field.pack
printf '%s' "$(cat good.pack)" >no-final-newline.pack
expect_error no-final-newline 1 '^packinfo: no-final-newline\.pack:18: truncated: the last line has no newline$' \
    packinfo no-final-newline.pack
printf '%s' "$(cat good.pack)" | gzip -c >no-final-newline.pack.gz
expect_error no-final-newline-gz 1 '^packinfo: no-final-newline\.pack\.gz:18: truncated' packinfo no-final-newline.pack.gz

# --- a huge declared count over one grain line: the plain end-of-input error, fast, and no
# room reserved for 10^9 grains (64 GB, refused under a 1 GB address-space limit) ---
# (a sanitizer build cannot start under that limit: there the message alone is checked)
sed '10s/3/1000000000/;11s/3/0/;14,$d' good.pack >huge-count.pack
vlimit='ulimit -v 1000000 &&'
ldd "$BIN/packinfo" 2>/dev/null | grep -q 'libasan\|libtsan' && vlimit=
expect_error huge-grain-count 1 '^packinfo: huge-count\.pack:14: unexpected end of input: 1000000000 grains declared, 1 found$' \
    sh -c "$vlimit exec packinfo huge-count.pack"

# --- truncated gzip, empty input ---
gzip -c good.pack >good.pack.gz
size=$(wc -c <good.pack.gz)
for cut in 20 $((size / 2)) $((size - 4)); do
	head -c "$cut" good.pack.gz >trunc.pack.gz
	expect_error "truncated-gz-$cut-of-$size" 1 '^packinfo: trunc\.pack\.gz:[0-9]+: corrupt or truncated' \
	    packinfo trunc.pack.gz
done
: >empty.pack
expect_error empty-file 1 '^packinfo: empty\.pack:1: empty input' packinfo empty.pack
expect_error empty-stdin 1 '^packinfo: <stdin>:1: empty input' packinfo <empty.pack
expect_error missing-file 1 '^packinfo: no-such\.pack: ' packinfo no-such.pack

# --- usage ---
expect_error unknown-option 2 "^packinfo: unknown option '--no-such-option'" packinfo --no-such-option good.pack
expect_error unknown-short-option 2 "^packinfo: unknown option '-x'" packinfo -x good.pack
# several FILEs, as the README writes it: one row (--tsv) or one block per pack, the same
# as the packs concatenated on standard input (issue 19; two operands were a usage error)
gzip -c good.pack >good2.pack.gz
expect_ok two-operands-tsv packinfo --tsv good.pack good2.pack.gz
# the last column, file, names each input: the rest is the stream's
nofile() { awk -F '\t' 'BEGIN { OFS = "\t" } { NF--; print }' "$1"; }
nofile ok.out >two.tsv
cat good.pack good.pack | packinfo --tsv >cat.out 2>/dev/null
nofile cat.out >cat.tsv
expect_same two-operands-tsv-as-a-stream two.tsv cat.tsv
expect_ok two-operands packinfo good.pack good.pack
mv ok.out two.info
cat good.pack good.pack | packinfo >cat.info 2>/dev/null
expect_same two-operands-as-a-stream two.info cat.info
expect_error two-operands-empty-second 1 '^packinfo: empty\.pack:1: empty input' packinfo good.pack empty.pack

# --- what reads ---
expect_ok good packinfo good.pack
packinfo good.pack >good.info 2>/dev/null
if [ "$(info_value good.info grains)" = 3 ] && [ "$(info_value good.info contacts_gg)" = 3 ] &&
    [ "$(info_value good.info history_contacts)" = 3 ] && [ "$(info_value good.info mu)" = 0.3 ]; then
	pass good-values
else
	fail good-values "grains/contacts_gg/history_contacts/mu: $(tr '\n' ' ' <good.info | head -c 300)"
fi
packinfo good.pack.gz >gz.info 2>/dev/null
expect_same gzip-same-output good.info gz.info
packinfo <good.pack >stdin.info 2>/dev/null
expect_same stdin-same-output good.info stdin.info
packinfo - <good.pack >dash.info 2>/dev/null
expect_same dash-same-output good.info dash.info
packinfo - <good.pack.gz >gzstdin.info 2>/dev/null
expect_same gzip-stdin-same-output good.info gzstdin.info

sed 's/$/\r/' good.pack >crlf.pack
packinfo crlf.pack >crlf.info 2>/dev/null
expect_same crlf-same-output good.info crlf.info

# packs back to back: one TSV header line and one row per pack
cat good.pack good.pack >two.pack
packinfo --tsv two.pack >two.tsv 2>two.err
if [ $? -eq 0 ] && [ "$(wc -l <two.tsv)" -eq 3 ] && [ "$(grep -c '^#' two.tsv)" -eq 1 ] &&
    [ "$(sed -n 2p two.tsv)" = "$(sed -n 3p two.tsv)" ] && [ "$(sed -n 2p two.tsv | cut -f1)" = 3 ]; then
	pass two-packs-tsv
else
	fail two-packs-tsv "$(head -c 300 two.err) $(head -c 200 two.tsv)"
fi
packinfo two.pack >two.info 2>/dev/null
{ cat good.info; echo; cat good.info; } >two.want
expect_same two-packs-keys two.info two.want
cat good.pack.gz good.pack.gz >two.pack.gz
packinfo --tsv two.pack.gz >twogz.out 2>/dev/null
nofile twogz.out >twogz.tsv
nofile two.tsv >two.nofile
expect_same two-gzip-members twogz.tsv two.nofile
# a plain pack appended to a .gz one (gzip -t: "trailing garbage"): refused, never dropped
# without a word; the same bytes on standard input
cat good.pack.gz good.pack >gz-then-plain.pack.gz
expect_error gzip-trailing-plain 1 '^packinfo: gz-then-plain\.pack\.gz:19: trailing data after the end of the gzip stream \(not a gzip member' \
    packinfo gz-then-plain.pack.gz
expect_error gzip-trailing-plain-stdin 1 '^packinfo: <stdin>:19: trailing data after the end of the gzip stream' \
    packinfo <gz-then-plain.pack.gz
expect_error gzip-trailing-plain-one-pack 1 '^densify: gz-then-plain\.pack\.gz:19: trailing data after the end of the gzip stream' \
    densify --stress 1e6 -o nothing.pack gz-then-plain.pack.gz
# what is not a pack of LF lines says what it is, at line 1
tr '\n' '\r' <good.pack >cr-only.pack
expect_error cr-only 1 "^packinfo: cr-only\\.pack:1: CR line endings \\(old Mac\\): convert them \\(tr '\\\\r' '\\\\n' < FILE\\)\$" \
    packinfo cr-only.pack
printf '\357\273\277' | cat - good.pack >bom.pack
expect_error utf8-bom 1 '^packinfo: bom\.pack:1: a UTF-8 byte-order mark \(bytes EF BB BF\) starts the file' packinfo bom.pack
for z in xz bzip2 zstd lz4; do
	command -v $z >/dev/null 2>&1 || continue
	$z -c <good.pack >good.pack.$z 2>/dev/null
	expect_error "$z-input" 1 "^packinfo: good\\.pack\\.$z:1: $z-compressed: decompress it first \\($z -d FILE" \
	    packinfo "good.pack.$z"
done

# a header of 160000 meta lines, and one of 160000 history lines: read in time linear in
# the lines.  Each meta key was looked for among those before it (160000 lines: over 2
# minutes, 40000: 10 s) and each history line cost a realloc of the whole array (50000
# lines: 280 s and 1.5 GB in the sanitizer build); now well under a second, so a 30 s limit
# tells the two apart on any machine.  The last meta line repeats the first key: the hash
# that finds duplicates finds it, at its line.
awk 'NR == 1 { print; for (k = 1; k <= 160000; k++) print "meta key" k " value " k; next } { print }' good.pack >meta160k.pack
if timeout 30 packinfo meta160k.pack >meta160k.info 2>meta160k.err && [ "$(info_value meta160k.info grains)" = 3 ]; then
	pass "160000 meta lines read in linear time"
else
	fail "160000 meta lines read in linear time" "exit $? (124: over 30 s) $(head -c 200 meta160k.err)"
fi
awk 'NR == 1 { print; for (k = 1; k <= 160000; k++) print "history tool " k; next } { print }' good.pack >hist160k.pack
if timeout 30 packinfo hist160k.pack >hist160k.info 2>hist160k.err && [ "$(info_value hist160k.info grains)" = 3 ]; then
	pass "160000 history lines read in linear time"
else
	fail "160000 history lines read in linear time" "exit $? (124: over 30 s) $(head -c 200 hist160k.err)"
fi
awk 'NR == 1 { print; for (k = 1; k <= 160000; k++) print "meta key" k " value " k; print "meta key1 again"; next } { print }' \
    good.pack >meta160kdup.pack
expect_error "160000 meta lines: the key repeated at the end" 1 "^packinfo: meta160kdup\\.pack:160002: meta: duplicate key 'key1'\$" \
    timeout 30 packinfo meta160kdup.pack

# -o FILE: written atomically; nothing at all when the input is bad
expect_ok output-file packinfo -o out.info good.pack
expect_same output-file-content out.info good.info
sed '14s/7e10/0/' good.pack >bad.pack
expect_error output-bad-input 1 '^packinfo: bad\.pack:14: ' packinfo -o bad.info bad.pack
if [ -e bad.info ] || ls -a | grep -q '^\.bad\.info\.'; then
	fail output-bad-leaves-nothing "$(ls -a | tr '\n' ' ')"
else
	pass output-bad-leaves-nothing
fi
cat good.pack bad.pack >goodbad.pack
expect_error output-second-pack-bad 1 '^packinfo: goodbad\.pack:32: ' packinfo -o goodbad.info goodbad.pack
if [ -e goodbad.info ] || ls -a | grep -q '^\.goodbad\.info\.'; then
	fail output-second-bad-leaves-nothing "$(ls -a | tr '\n' ' ')"
else
	pass output-second-bad-leaves-nothing
fi

# --- format version 2: the columns and boundary lines --------------------------------------
# Line numbers of good2.pack:
#  1 magic   2 history   3 comment   4 meta   5 units   6 box   7 boundary   8 refbox
#  9 walls   10 friction   11 grains   12 contacts   13 columns   14 end   15-17 grains
#  18-20 contacts (x is periodic: no contact with xlo or xhi)
cat >good2.pack <<'EOF'
qusgm-pack 2
history packgen 0.1.0: packgen -n 3 ; --n=3
# a comment is allowed in the header
meta note three grains in a row
units SI
box 0 0 0 7e-4 2e-4 2e-4
boundary periodic walls walls
refbox 0 0 0 7e-4 2e-4 2e-4
walls 7e12 0.495 0.3
friction 0.3
grains 3
contacts 3
columns id x y z r E nu rho
end
1 1e-4 1e-4 1e-4 1.0001e-4 7e10 0.2 2420
2 2e-4 1e-4 1e-4 1.0001e-4 7e10 0.2 2420
3 1.5e-4 1.5e-4 1.5e-4 2e-5 7e10 0.2 2420
1 2 0.01 0 0 0 0
1 ylo 0.01 0 1e-4 0 0
2 zhi 0.01 0 0 0 0
EOF

# bad2 NAME LINE REGEX SED-SCRIPT: as bad, on good2.pack.
bad2() {
	name=$1 line=$2 re=$3
	sed "$4" good2.pack >"$name.pack"
	expect_error "$name" 1 "^packinfo: $name\\.pack:$line: .*$re" packinfo "$name.pack"
}

expect_ok v2-good packinfo good2.pack
gzip -c good2.pack >good2.pack.gz
packinfo good2.pack >good2.info 2>/dev/null
packinfo good2.pack.gz >good2gz.info 2>/dev/null
expect_same v2-gzip-same-output good2.info good2gz.info
sed 's/$/\r/' good2.pack >crlf2.pack
packinfo crlf2.pack >crlf2.info 2>/dev/null
expect_same v2-crlf-same-output good2.info crlf2.info
# version 2 spelling out what version 1 implies: the same pack
sed '1s/1$/2/;6a\
boundary walls walls walls
11a\
columns id x y z r E nu rho' good.pack >std2.pack
packinfo std2.pack >std2.info 2>/dev/null
expect_same v2-standard-is-v1 good.info std2.info
# every axis periodic (a periodic axis must hold three interaction distances, 2 r_max
# each: the enumerator's cell grid); the columns line early in the header
sed '6s/.*/box 0 0 0 7e-4 7e-4 7e-4/;8s/.*/refbox 0 0 0 7e-4 7e-4 7e-4/;7s/.*/boundary periodic periodic periodic/;19,20d;12s/3/1/' good2.pack >allper.pack
expect_ok v2-all-periodic packinfo allper.pack
sed '13d;4a\
columns id x y z r E nu rho' good2.pack >colsfirst.pack
expect_ok v2-columns-early packinfo colsfirst.pack
# a version-1 and a version-2 pack in one stream
cat good.pack good2.pack >mixed.pack
packinfo --tsv mixed.pack >mixed.tsv 2>mixed.err
if [ $? -eq 0 ] && [ "$(wc -l <mixed.tsv)" -eq 3 ]; then pass v2-after-v1-in-a-stream; else fail v2-after-v1-in-a-stream "$(head -c 300 mixed.err)"; fi

# --- version 2: every error of the new lines ---
bad2 v2-missing-columns 13 "missing 'columns' line" '/^columns /d'
bad2 v2-missing-boundary 13 "missing 'boundary' line" '/^boundary /d'
bad2 v2-duplicate-columns 14 "duplicate 'columns' line" '13p'
bad2 v2-duplicate-boundary 8 "duplicate 'boundary' line" '7p'
bad2 v2-columns-no-names 13 'columns: expected the names of the grain columns' '13s/.*/columns/'
bad2 v2-unknown-column 13 "columns: unknown column 'type'" '13s/$/ type/'
bad2 v2-unknown-column-first 13 "columns: unknown column 'ID'" '13s/ id / ID /'
bad2 v2-column-twice 13 "columns: column 'x' named twice" '13s/$/ x/'
bad2 v2-column-twice-long 13 "columns: column 'id' named twice" '13s/$/ id x y z r E nu rho id x y z r E nu rho/'
bad2 v2-missing-required-column 13 "columns: the required column 'rho' is missing" '13s/ rho$//'
bad2 v2-missing-first-column 13 "columns: the required column 'id' is missing" '13s/ id / /'
bad2 v2-column-order 13 "columns: column 2 must be 'x'" '13s/ x y / y x /'
bad2 v2-column-order-last 13 "columns: column 7 must be 'nu'" '13s/ nu rho$/ rho nu/'
bad2 v2-boundary-two-words 7 'boundary: expected 3 words .*found 2' '7s/ walls$//'
bad2 v2-boundary-four-words 7 'boundary: expected 3 words .*found 4' '7s/$/ walls/'
bad2 v2-boundary-no-words 7 'boundary: expected 3 words .*found 0' '7s/.*/boundary/'
bad2 v2-boundary-unknown-word 7 "boundary: 'wall' for axis y is neither 'walls' nor 'periodic'" '7s/periodic walls/periodic wall/'
bad2 v2-boundary-case 7 "boundary: 'Periodic' for axis x" '7s/periodic/Periodic/'
bad2 v2-boundary-shear 7 "boundary: 'lees-edwards' for axis z" '7s/walls$/lees-edwards/'
bad2 v2-periodic-wall-contact 19 "contact: wall 'xlo' on axis x, which is periodic" '19s/ylo/xlo/'
bad2 v2-periodic-wall-contact-z 20 "contact: wall 'zhi' on axis z, which is periodic" '7s/.*/boundary periodic walls periodic/'
bad2 v2-grain-columns 16 'grain line: expected 8 columns \(id x y z r E nu rho\), found 7' '16s/ 2420$//'
bad2 v2-unknown-keyword 6 "unknown header keyword 'shape'" '5a\
shape sphere'
# the new lines do not exist in version 1
bad columns-in-v1 12 "columns: not in version 1 of the format \(a pack with a columns line starts 'qusgm-pack 2'\)" '11a\
columns id x y z r E nu rho'
bad boundary-in-v1 7 "boundary: not in version 1 of the format" '6a\
boundary walls walls walls'
# a directory as input is named as one, not as a corrupt stream (issue 19)
mkdir -p adir
expect_error dir-input-packinfo 1 '^packinfo: adir: is a directory$' packinfo adir
expect_error dir-input-densify 1 '^densify: adir: is a directory$' densify --stress 1e6 -o x.pack adir
expect_error dir-input-moduli 1 '^moduli: adir: is a directory$' moduli adir

# --- version 2: the shape columns side qw qx qy qz -----------------------------------------
# Line numbers of good3.pack:
#  1 magic   2 history   3 units   4 box   5 boundary   6 walls   7 friction   8 grains
#  9 contacts   10 columns   11 end   12-14 grains (13 columns)   15 contact
cat >good3.pack <<'EOF2'
qusgm-pack 2
history hand-written: three plates
units SI
box 0 0 0 1e-3 1e-3 1e-3
boundary walls walls walls
walls 7e12 0.495 0.3
friction 0.3
grains 3
contacts 1
columns id x y z r E nu rho side qw qx qy qz
end
1 2e-4 2e-4 2e-4 2e-5 7e10 0.2 2420 1e-4 1 0 0 0
2 5e-4 5e-4 5e-4 2e-5 7e10 0.2 2420 1e-4 0.7071067811865476 0.7071067811865476 0 0
3 8e-4 8e-4 8e-4 2e-5 7e10 0.2 2420 1e-4 0.5 0.5 0.5 0.5
1 2 0.01 0 0 0 0
EOF2

bad3() {
	name=$1 line=$2 re=$3
	sed "$4" good3.pack >"$name.pack"
	expect_error "$name" 1 "^packinfo: $name\\.pack:$line: .*$re" packinfo "$name.pack"
}

expect_ok shapes-good packinfo good3.pack
packinfo good3.pack >good3.info 2>/dev/null
gzip -c good3.pack >good3.pack.gz
packinfo good3.pack.gz >good3gz.info 2>/dev/null
expect_same shapes-gzip-same-output good3.info good3gz.info
sed 's/$/\r/' good3.pack >crlf3.pack
packinfo crlf3.pack >crlf3.info 2>/dev/null
expect_same shapes-crlf-same-output good3.info crlf3.info
# a quaternion typed by hand: %g's 6 significant digits (norm 1 + 3e-7) read, 4 do not
sed '13s/0.7071067811865476 0.7071067811865476/0.707107 0.707107/' good3.pack >six-digits.pack
expect_ok shapes-quaternion-six-digits packinfo six-digits.pack
bad3 shapes-quaternion-four-digits 13 "grain 2: \(qw, qx, qy, qz\) = \(0.7071, 0.7071, 0, 0\) is not a unit quaternion \(norm 0.99999041, off 1 by more than 1e-06\)$" \
    '13s/0.7071067811865476 0.7071067811865476/0.7071 0.7071/'
bad3 shapes-quaternion-zero 14 'grain 3: .* is not a unit quaternion \(norm 0,' '14s/0.5 0.5 0.5 0.5$/0 0 0 0/'
bad3 shapes-quaternion-long 12 'is not a unit quaternion \(norm 2,' '12s/1 0 0 0$/2 0 0 0/'
bad3 shapes-quaternion-nan 12 "'nan' is not a finite number" '12s/1 0 0 0$/nan 0 0 0/'
bad3 shapes-side-negative 12 'grain 1: side -0.0001 is negative$' '12s/1e-4 1 0 0 0$/-1e-4 1 0 0 0/'
bad3 shapes-side-nan 12 "'nan' is not a finite number" '12s/1e-4 1 0 0 0$/nan 1 0 0 0/'
bad3 shapes-side-inf 12 "'inf' is not a finite number" '12s/1e-4 1 0 0 0$/inf 1 0 0 0/'
bad3 shapes-side-overflow 12 "'1e999' is not a finite number" '12s/1e-4 1 0 0 0$/1e999 1 0 0 0/'
bad3 shapes-grain-short 12 'grain line: expected 13 columns \(id x y z r E nu rho side qw qx qy qz\), found 12$' '12s/ 0$//'
bad3 shapes-grain-sphere-line 12 'expected 13 columns .*found 8$' '12s/ 1e-4 1 0 0 0$//'
# all five or none, together and in order, after the eight required columns
bad3 shapes-only-four 10 "columns: only some of the shape columns \(side qw qx qy qz\): they come all 5 or none; 'qz' is missing$" '10s/ qz$//'
bad3 shapes-only-side 10 "only some of the shape columns .*'qw' is missing$" '10s/ qw qx qy qz$//'
bad3 shapes-only-quaternion 10 "only some of the shape columns .*'side' is missing$" '10s/ side / /'
bad3 shapes-order 10 "columns: column 9 must be 'side' \(the shape columns come together, in the order side qw qx qy qz\)$" '10s/side qw/qw side/'
bad3 shapes-order-quaternion 10 "columns: column 10 must be 'qw'" '10s/qw qx qy qz$/qx qy qz qw/'
bad3 shapes-before-rho 10 "columns: column 8 must be 'rho' \(the required columns come first" '10s/rho side qw qx qy qz$/side qw qx qy qz rho/'
bad3 shapes-side-twice 10 "columns: column 'side' named twice" '10s/$/ side/'
bad3 shapes-unknown 10 "columns: unknown column 'qs'" '10s/ qz$/ qs/'
# version 1 has no columns line, so no shape columns
bad3 shapes-in-v1 9 "columns: not in version 1 of the format" '1s/2$/1/;5d'
bad3 shapes-lines-in-v1 10 "grain line: expected 8 columns \(id x y z r E nu rho\), found 13; more columns need 'qusgm-pack 2' and a columns line$" '1s/2$/1/;5d;10d'

# --- version 2: the kind column 'shape', just before the shape columns ---------------------
# good3.pack has none: each grain's kind is its side's (side > 0: spheroplate); with it, the
# same pack reads to the same report, and a writer puts it there (packgen, shear)
sed '10s/ rho side / rho shape side /;12,14s/ 2420 / 2420 spheroplate /' good3.pack >kind3.pack
expect_ok shapes-kind-good packinfo kind3.pack
packinfo kind3.pack >kind3.info 2>/dev/null
expect_same shapes-kind-same-output good3.info kind3.info
bad_kind() {
	name=$1 line=$2 re=$3
	sed "$4" kind3.pack >"$name.pack"
	expect_error "$name" 1 "^packinfo: $name\\.pack:$line: .*$re" packinfo "$name.pack"
}
bad_kind shapes-kind-unknown 13 "grain 2: shape 'cube' is not a kind \(sphere, spheroplate\)$" '13s/ spheroplate / cube /'
bad_kind shapes-kind-sphere-side 12 "grain 1: a sphere cannot have side 0.0001 " '12s/ spheroplate / sphere /'
bad_kind shapes-kind-plate-side-0 14 "grain 3: a spheroplate cannot have side 0 " '14s/ spheroplate 1e-4 / spheroplate 0 /'
bad_kind shapes-kind-alone 10 "columns: 'shape' \(the grains' kinds\) needs the shape columns" '10s/ side qw qx qy qz$//;12,14s/ spheroplate .*$/ spheroplate/'
bad_kind shapes-kind-after-side 10 "columns: column 14 'shape': the kind columns come before the shape columns" '10s/ shape side qw qx qy qz$/ side qw qx qy qz shape/'

# --- version 2: the phase column (0 mineral, 1 hydrate) --------------------------------------
# The example of pack-format.md, "The phase column".  Line numbers of good4.pack:
#  1 magic   2 meta   3 units   4 box   5 boundary   6 walls   7 friction   8 grains
#  9 contacts   10 columns   11 end   12-15 grains (9 columns)
cat >good4.pack <<'EOF4'
qusgm-pack 2
meta material quartz
units SI
box 0 0 0 4e-4 2e-4 2e-4
boundary walls walls walls
walls 1e13 0.495 0.3
friction 0.3
grains 4
contacts 0
columns id x y z r E nu rho phase
end
1 1e-4 1e-4 1e-4 1e-4 1e11 0.15 2650 0
2 3e-4 1e-4 1e-4 1e-4 1e11 0.15 2650 0
3 2e-4 1e-4 1.9e-4 1e-5 1e11 0.15 2650 0
4 2e-4 1.75e-4 1e-4 2e-5 6.6e9 0.32 900 1
EOF4
awk '/^    qusgm-pack 2$/ { on = 0 } /^## The phase column/ { sec = 1 } sec && /^    qusgm-pack 2$/ { on = 1 } on && /^    / { print substr($0, 5) } on && /^$/ && n++ { exit }' \
    "$TOP/share/doc/pack-format.md" >doc4.pack
expect_same "the phase example of pack-format.md" good4.pack doc4.pack

bad4() {
	name=$1 line=$2 re=$3
	sed "$4" good4.pack >"$name.pack"
	expect_error "$name" 1 "^packinfo: $name\\.pack:$line: .*$re" packinfo "$name.pack"
}

expect_ok phase-good packinfo good4.pack
packinfo good4.pack >good4.info 2>/dev/null
expect_num phase-hydrate-grains "$(info_value good4.info hydrate_grains)" == 1
bad4 phase-two 15 "grain 4: phase '2' is neither 0 \(mineral\) nor 1 \(hydrate\)$" '15s/ 1$/ 2/'
bad4 phase-minus-one 12 "grain 1: phase '-1' is neither 0 \(mineral\) nor 1 \(hydrate\)$" '12s/ 0$/ -1/'
bad4 phase-half 13 "grain 2: phase '0.5' is neither 0 \(mineral\) nor 1 \(hydrate\)$" '13s/ 0$/ 0.5/'
bad4 phase-real 15 "grain 4: phase '1.0' is neither 0 \(mineral\) nor 1 \(hydrate\)$" '15s/ 1$/ 1.0/'
bad4 phase-exponent 15 "grain 4: phase '1e0' is neither" '15s/ 1$/ 1e0/'
bad4 phase-nan 14 "grain 3: phase 'nan' is neither" '14s/ 0$/ nan/'
bad4 phase-word 15 "grain 4: phase 'hydrate' is neither" '15s/ 1$/ hydrate/'
bad4 phase-missing-field 15 'grain line: expected 9 columns \(id x y z r E nu rho phase\), found 8$' '15s/ 1$//'
bad4 phase-extra-field 15 'grain line: expected 9 columns \(id x y z r E nu rho phase\), found 10$' '15s/$/ 1/'
bad4 phase-without-column 12 'grain line: expected 8 columns \(id x y z r E nu rho\), found 9$' '10s/ phase$//'
bad4 phase-twice 10 "columns: column 'phase' named twice$" '10s/$/ phase/'
bad4 phase-before-rho 10 "columns: column 8 must be 'rho' \(the required columns come first" '10s/rho phase$/phase rho/'
bad4 phase-before-shapes 10 "columns: column 10 'side': the shape columns come before the phase columns$" \
    '10s/$/ side qw qx qy qz/;12,15s/$/ 0 1 0 0 0/'
bad4 phase-in-v1 9 "columns: not in version 1 of the format" '1s/2$/1/;5d'
bad4 phase-lines-in-v1 10 "grain line: expected 8 columns \(id x y z r E nu rho\), found 9; more columns need 'qusgm-pack 2' and a columns line$" '1s/2$/1/;5d;10d'
# with the shape columns: all four columns lines read
sed '10s/ phase$/ side qw qx qy qz phase/;12,15s/ \([01]\)$/ 0 1 0 0 0 \1/' good4.pack >shph.pack
expect_ok phase-after-shapes packinfo shph.pack
expect_num phase-after-shapes-hydrate-grains "$(packinfo shph.pack | awk '$1 == "hydrate_grains" { print $2 }')" == 1

# every tool that writes a pack keeps the tags: the same ids carry the same phase after
# densify, frictionalize and loadtest (each grain followed by its id), and packgen's
# renumbering keeps the hydrate's density with its tag
phase_of() { awk '/^end$/ { on = 1; next } on && NF == 9 { print $1, $9, $8 }' "$1" | sort -n; }
packgen -n 200 --seed 5 --material quartz --hydrate-volume 0.15 -o hy.pack 2>/dev/null
phase_of hy.pack >hy.ph
expect_num phase-packgen-tags-some "$(awk '$2 == 1' hy.ph | wc -l)" ">" 10
expect_num phase-packgen-density-with-tag "$(awk '($2 == 1) != ($3 == 900)' hy.ph | wc -l)" == 0
expect_ok phase-densify densify --stress 4e6 -o hyd.pack hy.pack
phase_of hyd.pack >hyd.ph
expect_same phase-densify-keeps-the-tags hy.ph hyd.ph
expect_ok phase-frictionalize frictionalize -o hyf.pack hyd.pack
phase_of hyf.pack >hyf.ph
expect_same phase-frictionalize-keeps-the-tags hy.ph hyf.ph
expect_ok phase-loadtest loadtest --steps 2 -o hyl.pack hyf.pack
phase_of hyl.pack >hyl.ph
expect_same phase-loadtest-keeps-the-tags hy.ph hyl.ph
grep -q '^columns id x y z r E nu rho phase$' hyl.pack && pass phase-loadtest-columns-line || fail phase-loadtest-columns-line "$(grep ^columns hyl.pack)"

# a periodic axis too short for the grains (found when the contacts are first enumerated) is
# the pack's fault: every tool names the file (it said only 'the box is too short ...'; issue 19)
cp "$TOP/tests/fuzz/corpus/fuzz_pack/v2_pz.pack" short.pack
for t in packinfo "packexport --vtk -o short.vtm" densify loadtest frictionalize "dissociate --pex 1e5"; do
	expect_error "$t: a periodic box too short names the file" 1 "^${t%% *}: short.pack: the box is too short along periodic axis z" $t short.pack
done
