# SPDX-License-Identifier: GPL-3.0-or-later
# packview: the tool's contract, the page's content, and the page in a real browser: headless
# Chromium opens four views of two packs in one window, with no JavaScript error, and the
# screenshot's pixels show the grains in their phase colours, fewer grains in a slab, and
# the force chains when asked, none otherwise.
. "$TOP/tests/tools/lib.sh"

# --- the tool ----------------------------------------------------------------------------
expect_ok "--help" packview --help
grep -q -- '--three' ok.out && pass "--help names --three" || fail "--help names --three" "$(head -c 200 ok.out)"
expect_ok "--version" packview --version

small_pack dense
packgen -n 200 --seed 5 --hydrate-volume 0.2 -o hyd.pack 2>/dev/null
expect_ok "a dense pack" packview -o dense.html dense.pack
expect_ok "a pack with hydrate grains" packview -o hyd.html hyd.pack
if ls -a | grep -q '^\.dense'; then fail "no temporary files left" "$(ls -a)"; else pass "no temporary files left"; fi
# the title is the input's name ('<' written \u003c in the page's data): the rest is the same
packview <dense.pack | sed 's/\\u003cstdin>/dense.pack/g' >stdin.html
expect_same "stdin and FILE give the same page" stdin.html dense.html
gzip -c dense.pack >dense.pack.gz
packview dense.pack.gz >gz.html
sed 's/dense\.pack\.gz/dense.pack/g' gz.html >gz2.html
expect_same "a .gz input gives the same page" gz2.html dense.html
packview -o again.html dense.pack
expect_same "the page is a function of the pack" again.html dense.html

# self-contained: three.js and OrbitControls inlined, nothing fetched
if grep -Eiq '<(script|img|iframe|link|object|embed)[^>]*(src|href|data)=' dense.html; then
	fail "the page loads nothing" "$(grep -Eio '<(script|img|iframe|link|object|embed)[^>]*(src|href|data)=[^>]*' dense.html | head -n 1)"
else
	pass "the page loads nothing"
fi
grep -q 'THREE.OrbitControls\|exports.OrbitControls' dense.html && grep -q 'REVISION' dense.html &&
	pass "three.js and OrbitControls inlined" || fail "three.js and OrbitControls inlined" "not found in the page"
packview --controls '' -o own.html dense.pack
echo 'THREE: this is not JavaScript' >broken.js
packview --three broken.js -o broken.html dense.pack
if grep -q 'exports.OrbitControls' own.html; then fail "--controls '': the page's own orbit" "OrbitControls inlined"; else pass "--controls '': the page's own orbit"; fi

# errors: one line, nothing written
printf 'qusgm-pack 1\nunits SI\nbox 0 0 0 1 1 1\nwalls 1e9 0.3 0.3\nfriction 0.3\ngrains 2\ncontacts 0\nend\n1 0.5 0.5 0.5 0.1 1e9 0.3 2500\n' >short.pack
expect_error "a truncated pack: one line" 1 '^packview: short\.pack:[0-9]+: ' packview -o bad.html short.pack
[ -e bad.html ] && fail "nothing written on bad input" "bad.html exists" || pass "nothing written on bad input"
expect_error "no three.js: one line" 1 '^packview: /nonexistent/three\.js: .*--three' packview --three /nonexistent/three.js -o bad.html dense.pack
[ -e bad.html ] && fail "nothing written without three.js" "bad.html exists" || pass "nothing written without three.js"
expect_error "-o in a missing directory" 2 '^packview: ' packview -o /nonexistent/dir/p.html dense.pack

# the inlined scripts (issue 59): "</script" in any case and "<!--" cannot end or hide the
# script element; an empty, special, huge or foreign file is refused; -o is not --three
printf 'var THREE = {REVISION: "0"}; var a = "</SCRIPT>", b = "</Script >", c = "<!--<script>";\n' >tricky.js
packview --three tricky.js --controls '' -o tricky.html dense.pack 2>/dev/null
printf 'var THREE = {REVISION: "0"};\n' >plain.js
packview --three plain.js --controls '' -o plain.html dense.pack 2>/dev/null
n_end=$(grep -oi '</script' tricky.html | wc -l) n_end0=$(grep -oi '</script' plain.html | wc -l)
n_com=$(grep -o '<!--' tricky.html | wc -l) n_com0=$(grep -o '<!--' plain.html | wc -l)
if [ -s tricky.html ] && [ "$n_end" -eq "$n_end0" ] && [ "$n_com" -eq "$n_com0" ] &&
   grep -qF 'var a = "<\/SCRIPT>", b = "<\/Script >", c = "<\!--<script>";' tricky.html; then
	pass "</SCRIPT, </Script and <!-- of an inlined script are neutralised (<\\/SCRIPT, <\\!--; $n_end0 real ends)"
else
	fail "</SCRIPT, </Script and <!-- of an inlined script are neutralised" "$n_end/$n_end0 ends, $n_com/$n_com0 <!--: $(grep -o 'var a = [^;]*' tricky.html)"
fi
: >empty.js
expect_error "--three an empty file" 1 '^packview: empty\.js: empty, not three\.js \(--three\)$' packview --three empty.js -o bad.html dense.pack
expect_error "--three /dev/null" 1 '^packview: /dev/null: not a regular file ' packview --three /dev/null -o bad.html dense.pack
expect_error "--three /dev/zero (read without limit before)" 1 '^packview: /dev/zero: not a regular file ' packview --three /dev/zero -o bad.html dense.pack
expect_error "--controls /dev/null" 1 '^packview: /dev/null: not a regular file \(--controls ' packview --controls /dev/null -o bad.html dense.pack
echo 'var x = 1;' >other.js
expect_error "--three a script that is not three.js" 1 "^packview: other\\.js: not three\\.js \\(no 'THREE' or 'REVISION' in it; --three FILE\\)$" packview --three other.js -o bad.html dense.pack
expect_error "--controls a script that is not OrbitControls" 1 "^packview: other\\.js: not OrbitControls \\(no 'OrbitControls' in it; --controls FILE\\)$" packview --controls other.js -o bad.html dense.pack
head -c 16777217 /dev/zero | tr '\0' ' ' >huge.js
expect_error "--three over 16 MiB" 1 '^packview: huge\.js: 16777217 bytes, more than the 16 MiB a script may have' packview --three huge.js -o bad.html dense.pack
rm -f huge.js
[ -e bad.html ] && fail "nothing written for a refused script" "bad.html exists" || pass "nothing written for a refused script"
cp plain.js keep.js
expect_error "-o over the --three file" 2 "^packview: -o 'keep\\.js' is the --three file: " packview --three keep.js -o keep.js dense.pack
ln -s keep.js link.js
expect_error "-o over the --three file through a link (device and inode)" 2 "^packview: -o 'keep\\.js' is the --three file: " packview --three link.js -o keep.js dense.pack
expect_same "the --three file is left as it was" keep.js plain.js
expect_error "-o over the input" 2 '^packview: ' packview -o dense.pack dense.pack
expect_error "an unknown option" 2 '^packview: ' packview --no-such-option dense.pack

# --- in the browser ------------------------------------------------------------------------
# One Chromium run: a 600x450 window of four 300x225 frames, each a view of a page driven by
# its query (panel=0: the 3D view alone).
#   top left:     the hydrate pack coloured by phase (box=0: the walls' faint faces would tint
#                 the grains behind them)
#   top right:    the same in the slab 0.45 < x/Lx < 0.55
#   bottom left:  the dense pack's force chains, grains hidden
#   bottom right: the same without the force chains (the box alone)
# and below them a fifth, a page made with a three.js that is no script, which must report
# its error: the check that errors are seen at all.
# The optimised build's: the page is the same bytes from either build (checked above and in
# the optimised build's run), so the sanitizer build's Chromium run (15 s of CPU) drew it again.
if [ "${BIN#*build-san}" != "$BIN" ]; then
	exit 0
fi
if ! command -v chromium >/dev/null 2>&1; then
	fail "headless Chromium" "chromium not installed (make check installs it as root: apt-get install chromium)"
	exit 0
fi
if ! command -v python3 >/dev/null 2>&1; then
	fail "the screenshot's pixels" "python3 not installed"
	exit 0
fi
here=$(pwd)
cat >frames.html <<EOF
<!DOCTYPE html><html><head><style>body { margin: 0; } iframe { border: 0; width: 300px; height: 225px; float: left; }</style></head><body>
<iframe src="file://$here/hyd.html?panel=0&box=0&field=phase"></iframe><iframe src="file://$here/hyd.html?panel=0&box=0&field=phase&slab=x,0.45,0.55"></iframe><iframe src="file://$here/dense.html?panel=0&forces=1&grains=0"></iframe><iframe src="file://$here/dense.html?panel=0&grains=0"></iframe>
<iframe src="file://$here/broken.html?panel=0" style="width: 100px; height: 100px"></iframe>
<pre id="titles"></pre>
<script>
window.addEventListener('load', function () {
	var t = [];
	document.querySelectorAll('iframe').forEach(function (f) { t.push(f.contentDocument ? f.contentDocument.title : 'no access'); });
	document.getElementById('titles').textContent = t.join('\n');
});
</script></body></html>
EOF
# No D-Bus here (it would wait for one); the WebGL of the CPU (SwiftShader), as on a machine
# without a GPU; file access across the frames, for their titles.
mkdir -p profile
DBUS_SESSION_BUS_ADDRESS=disabled: timeout 120 chromium --headless --no-sandbox --user-data-dir="$here/profile" \
	--use-angle=swiftshader --enable-unsafe-swiftshader --allow-file-access-from-files \
	--no-first-run --disable-extensions --disable-background-networking --hide-scrollbars \
	--enable-logging=stderr --v=0 --window-size=600,560 --virtual-time-budget=5000 \
	--screenshot="$here/shot.png" --dump-dom "file://$here/frames.html" >dom.html 2>chromium.log
rc=$?
if [ "$rc" -ne 0 ] || [ ! -s shot.png ]; then
	fail "headless Chromium ran" "exit $rc: $(grep -v dbus chromium.log | tail -n 3)"
	exit 0
fi
pass "headless Chromium ran"
# every frame says it is ready; no error of any frame in its title or on the console (the
# page's own handler turns errors and warnings into console errors and a title)
ready=$(grep -o 'packview: ready: ' dom.html | wc -l)
expect_num "all four frames ready" "$ready" == 4
broken=$(grep -o 'packview: error: [^<]*' dom.html | grep -c 'THREE\|not JavaScript\|Unexpected')
expect_num "the page with a broken three.js reports its error" "$broken" == 1
if grep 'CONSOLE' chromium.log | grep -v 'GL Driver Message' | grep -v 'broken\.html' >console.txt; then
	fail "no console message" "$(head -c 300 console.txt)"
else
	pass "no console message"
fi
if grep -o 'packview: error[^<]*' dom.html | grep -v 'THREE\|not JavaScript\|Unexpected' | grep -q .; then
	fail "no JavaScript error" "$(grep -o 'packview: error[^<]*' dom.html | head -c 300)"
else
	pass "no JavaScript error"
fi

# The pixels of each quadrant: a grain's colour times its shading keeps the ratios of its
# channels, so a pixel is of a colour when its channels' ratios match it within 0.04 (edges
# that blend with the background do not).  Mineral (0.80, 0.66, 0.42) and hydrate (0.30,
# 0.75, 0.95) as the page draws the phases; a force chain is red to orange (the force ramp
# from (0.99, 0.75, 0.30) to (0.50, 0, 0.05)): red above 100, blue below 0.45 red.
python3 - shot.png >pixels.txt <<'EOF'
import sys, zlib, struct
def png(path):
	d = open(path, 'rb').read()
	assert d[:8] == b'\x89PNG\r\n\x1a\n'
	pos, idat = 8, b''
	while pos < len(d):
		n, t = struct.unpack('>I4s', d[pos:pos + 8])
		c = d[pos + 8:pos + 8 + n]
		if t == b'IHDR':
			w, h, depth, ctype = struct.unpack('>IIBB', c[:10])
		elif t == b'IDAT':
			idat += c
		pos += 12 + n
	assert depth == 8 and ctype in (2, 6), (depth, ctype)
	bpp = 3 if ctype == 2 else 4
	raw, stride, rows, prev, o = zlib.decompress(idat), w * bpp, [], bytearray(w * bpp), 0
	for y in range(h):
		f, line = raw[o], bytearray(raw[o + 1:o + 1 + stride])
		o += 1 + stride
		for i in range(stride):
			a = line[i - bpp] if i >= bpp else 0
			b = prev[i]
			c = prev[i - bpp] if i >= bpp else 0
			if f == 1: line[i] = (line[i] + a) & 255
			elif f == 2: line[i] = (line[i] + b) & 255
			elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
			elif f == 4:
				p = a + b - c
				pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
				line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
		rows.append(line)
		prev = line
	return w, h, bpp, rows
w, h, bpp, rows = png(sys.argv[1])
h = 450	# the four frames; the broken page's below
def like(px, ref):
	m = max(px)
	if m < 40:
		return False
	k = ref.index(max(ref))
	return all(abs(px[i] / px[k] - ref[i] / ref[k]) < 0.04 for i in range(3))
mineral, hydrate = (0.80, 0.66, 0.42), (0.30, 0.75, 0.95)
for qy in range(2):
	for qx in range(2):
		n = {'mineral': 0, 'hydrate': 0, 'force': 0}
		for y in range(qy * h // 2, (qy + 1) * h // 2):
			r = rows[y]
			for x in range(qx * w // 2, (qx + 1) * w // 2):
				px = r[bpp * x:bpp * x + 3]
				if like(px, mineral): n['mineral'] += 1
				if like(px, hydrate): n['hydrate'] += 1
				if px[0] > 100 and px[2] < 0.45 * px[0] and px[1] < 0.85 * px[0]: n['force'] += 1
		print('q%d%d' % (qy, qx), n['mineral'], n['hydrate'], n['force'])
EOF
# q00 q01 q10 q11: mineral, hydrate and force pixels
q() { awk -v k="$1" -v c="$2" '$1 == k { print $c }' pixels.txt; }
echo "pixels (quadrant mineral hydrate force): $(tr '\n' ';' <pixels.txt)"
expect_num "full view: mineral grains drawn" "$(q q00 2)" '>' 3000
expect_num "full view: hydrate grains drawn" "$(q q00 3)" '>' 600
expect_num "full view: no force chain unasked" "$(q q00 4)" '<' 50
# a slab a tenth of the box wide shows a part of the grains
expect_num "slab: fewer mineral pixels" "$(q q01 2)" '<' "$(awk -v a="$(q q00 2)" 'BEGIN { print 0.6 * a }')"
expect_num "slab: some grains drawn" "$(q q01 2)" '>' 100
expect_num "slab: fewer hydrate pixels" "$(q q01 3)" '<' "$(q q00 3)"
expect_num "force chains drawn when asked" "$(q q10 4)" '>' 2000
expect_num "no force chains unasked" "$(q q11 4)" '<' 20
expect_num "box alone: no grain drawn" "$(q q11 2)" '<' 20
