# SPDX-License-Identifier: GPL-3.0-or-later
# readers: the C reader (packinfo) and the Python package's reader (share/python/qusgm) accept
# and refuse the same inputs with the same words (issue 59): every file of the shared corpus
# tests/corpus/packs (made by tests/corpus/make-packs.sh: Unicode digits and blanks, a CR
# inside a line, CR line endings, a byte-order mark, xz, bzip2 and zstd, a NUL, counts of
# 10^9, a hexadecimal overflow, a pair twice, the value rules, the glued column, gzip members,
# truncated, corrupt and followed by text) gives packinfo's line of
# tests/corpus/packs.expected, and the Python reader the same message (without the program's
# name) or the same number of packs, by its fast path and its line-by-line one alike; the
# fuzz corpus tests/fuzz/corpus/fuzz_pack likewise, packinfo against Python.  Memory: a header
# that declares 10^9 contacts over 37 lines, and a table of 30000 rows with one cell of 20000
# characters, are read within a few megabytes (they took 63 GiB and 2.3 GB).
. "$TOP/tests/tools/lib.sh"

python_with_numpy || exit 0

# NAME<TAB>the C reader's message (packinfo's, its "packinfo: " dropped), or "ok N" for N packs
c_outcomes() {
	for f in *; do
		if msg=$(packinfo "$f" 2>&1 >/dev/null); then
			printf '%s\tok %s\n' "$f" "$(packinfo "$f" 2>/dev/null | grep -c '^grains ')"
		else
			printf '%s\t%s\n' "$f" "${msg#packinfo: }"
		fi
	done
}
cat >outcomes.py <<'PY'
import sys
import qusgm
# NAME<TAB>the Python reader's outcome, as c_outcomes writes the C reader's; a line
# "DIFFER NAME" where the fast path and the line-by-line reader disagree
for path in sys.argv[1:]:
    outs = []
    for fast in (True, False):
        try:
            outs.append("ok %d" % len(list(qusgm.read_packs(path, fast=fast))))
        except qusgm.FormatError as e:
            outs.append(str(e))
        except Exception as e:  # anything but a FormatError is a failure of its own
            outs.append("%s: %s" % (type(e).__name__, e))
    if outs[0] != outs[1]:
        print("DIFFER %s: fast '%s', line by line '%s'" % (path, outs[0], outs[1]))
    sys.stdout.buffer.write(("%s\t%s\n" % (path, outs[0])).encode("utf-8", "surrogateescape"))
PY

rm -rf packs fuzz
cp -R "$TOP/tests/corpus/packs" packs
(cd packs && c_outcomes) >c.txt
n=$(wc -l <c.txt)
if cmp -s c.txt "$TOP/tests/corpus/packs.expected"; then
	pass "packinfo: the $n files of tests/corpus/packs as tests/corpus/packs.expected"
else
	fail "packinfo: the $n files of tests/corpus/packs as tests/corpus/packs.expected" "$(diff "$TOP/tests/corpus/packs.expected" c.txt | head -n 6)"
fi
# The Python reader's side is the optimised build's: it does not depend on the build, and in
# the sanitizer build's run it doubled this test's time (28 s of CPU) to check it again; that
# build's packinfo has the corpus above.
if [ "${BIN#*build-san}" != "$BIN" ]; then
	exit 0
fi
(cd packs && "$py" ../outcomes.py *) >py.txt 2>py.err
if grep -q '^DIFFER' py.txt; then
	fail "tests/corpus/packs: the Python reader's fast path and line-by-line reader agree" "$(grep '^DIFFER' py.txt | head -n 3)"
else
	pass "tests/corpus/packs: the Python reader's fast path and line-by-line reader agree ($n files)"
fi
grep -v '^DIFFER' py.txt >py.out
refused=$(grep -vc '	ok ' c.txt)
if cmp -s c.txt py.out; then
	pass "tests/corpus/packs: the Python reader accepts and refuses as packinfo, the same message ($n files, $refused refused)"
else
	fail "tests/corpus/packs: the Python reader accepts and refuses as packinfo, the same message" "$(diff c.txt py.out | head -n 8) $(head -c 300 py.err)"
fi

# the fuzz corpus: packinfo's own refusals after a pack was read (no FILE:LINE:, e.g. a
# periodic box too short for its grain grid) are the reader's acceptance
cp -R "$TOP/tests/fuzz/corpus/fuzz_pack" fuzz
(cd fuzz && c_outcomes) | awk -F '\t' '{ m = $2; l = length($1)
	if (m !~ /^ok / && !(substr(m, 1, l + 1) == $1 ":" && substr(m, l + 2) ~ /^[0-9]+: /)) m = "ok"; print $1 "\t" m }' >fc.txt
(cd fuzz && "$py" ../outcomes.py *) >fpy.txt 2>fpy.err
if grep -q '^DIFFER' fpy.txt; then
	fail "the fuzz corpus: fast path and line-by-line reader agree" "$(grep '^DIFFER' fpy.txt | head -n 3)"
else
	pass "the fuzz corpus: fast path and line-by-line reader agree"
fi
grep -v '^DIFFER' fpy.txt | awk -F '\t' 'NR == FNR { c[$1] = $2; next } { m = $2; if (c[$1] == "ok" && m ~ /^ok /) m = "ok"; print $1 "\t" m }' fc.txt - >fpy.out
nf=$(wc -l <fc.txt)
if [ "$nf" -gt 100 ] && cmp -s fc.txt fpy.out; then
	pass "the fuzz corpus: the Python reader accepts and refuses as packinfo, the same message ($nf files, $(grep -vc '	ok' fc.txt) refused)"
else
	fail "the fuzz corpus: the Python reader accepts and refuses as packinfo, the same message" "$nf files; $(diff fc.txt fpy.out | head -n 8)"
fi

# memory: what a header declares is no allocation; a long cell is no table-wide width
"$py" - "$TOP/tests/corpus/packs/huge-contacts.pack" <<'PY'
import sys, tracemalloc
import qusgm

def check(name, ok, why=""):
    print(("PASS %s" % name) if ok else ("FAIL %s: %s" % (name, why)))

tracemalloc.start()
try:
    qusgm.read_pack(sys.argv[1])
    check("contacts 1000000000 over 37 lines: refused", False, "accepted")
except qusgm.FormatError as e:
    peak = tracemalloc.get_traced_memory()[1]
    check("contacts 1000000000 over 37 lines: refused at the end of input, %.1f MB at most (%s)" % (peak / 1e6, e),
          "1000000000 contacts declared, 37 found" in str(e) and peak < 20e6, "peak %d bytes" % peak)
except MemoryError as e:
    check("contacts 1000000000 over 37 lines: refused", False, "MemoryError")
tracemalloc.stop()

with open("long.tsv", "w") as f:
    f.write("# stage\tx[m]\n")
    for k in range(29999):
        f.write("grow\t%d\n" % k)
    f.write("x" * 20000 + "\t1\n")
tracemalloc.start()
t = qusgm.read_table("long.tsv")
peak = tracemalloc.get_traced_memory()[1]
tracemalloc.stop()
check("a table of 30000 rows, one cell of 20000 characters: read in %.0f MB (the file is 0.3 MB)" % (peak / 1e6),
      len(t) == 30000 and t["stage"][-1] == "x" * 20000 and t["stage"][0] == "grow" and t.text_columns == ["stage"]
      and t["x"][-1] == 1 and peak < 60e6, "peak %d bytes, %d rows" % (peak, len(t)))
PY
