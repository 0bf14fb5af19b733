# python: share/python/qusgm.py reads packs (plain and .gz, versions 1 and 2, streams) and
# tables into numpy arrays with the exact doubles the tools wrote: every grain and contact
# number equals the file's token read by float(), the radii extremes equal packinfo's to the
# bit, the porosity recomputed in numpy equals packinfo's to 1e-12, a table's columns, units,
# rows and values are those of pipelines/cols.sh; malformed input is a FormatError naming
# file:line (issue 18).  Skipped without a python3 that has numpy.
. "$TOP/tests/tools/lib.sh"

py=
for p in ${PYTHON:-} python3 /usr/bin/python3; do
	if command -v "$p" >/dev/null 2>&1 && "$p" -c 'import numpy' 2>/dev/null; then py=$p; break; fi
done
if [ -z "$py" ]; then
	echo "SKIP python reader (no python3 with numpy; Debian: apt-get install python3-numpy)"
	exit 0
fi
PYTHONPATH=$TOP/share/python
export PYTHONPATH

# The packs: version 1 (densify's, with contact lines; frictionalize's, with Q0 and M0), its
# gzip, version 2 with the phase column and with the shape columns; a stream of two.
small_pack frictional
gzip -c dense.pack >dense.pack.gz
packgen -n 60 --seed 3 --hydrate-volume 0.15 -o hyd.pack 2>/dev/null
packgen --shape spheroplate -n 27 --seed 3 -o plates.pack 2>/dev/null
cat dense.pack hyd.pack >two.pack
for f in dense.pack dense.pack.gz fr.pack hyd.pack plates.pack; do
	packinfo "$f" >"$f.info" 2>/dev/null
done
# the tables: a short frictional uniaxial curve and its moduli
loadtest --path uniaxial --steps 2 fr.pack >curve.tsv 2>/dev/null
moduli curve.tsv >moduli.tsv 2>/dev/null
sh "$TOP/pipelines/cols.sh" curve.tsv sig_zz porosity >curve.cols
sh "$TOP/pipelines/cols.sh" moduli.tsv K nu >moduli.cols

"$py" - <<'EOF'
import gzip, math, sys
import numpy as np
import qusgm

def check(name, ok, why=""):
    print(("PASS %s" % name) if ok else ("FAIL %s: %s" % (name, why)))

def info(path):
    return dict(l.split(None, 1) for l in open(path + ".info").read().splitlines())

def tokens(path):
    """The grain and contact lines of a single pack file, split: the reference, read
    without the module."""
    op = gzip.open if open(path, "rb").read(2) == b"\x1f\x8b" else open
    lines = op(path, "rt").read().splitlines()
    head = dict((l.split()[0], l.split()[1:]) for l in lines[:lines.index("end")] if l.split())
    ng, nc = int(head["grains"][0]), int(head["contacts"][0])
    k = lines.index("end") + 1
    return head, [l.split() for l in lines[k:k + ng]], [l.split() for l in lines[k + ng:k + ng + nc]]

def same_numbers(p, path):
    """Every field of every grain and contact is the file's token, read by float() (int for
    id and phase): exactly, bit for bit."""
    head, g, c = tokens(path)
    bad = []
    for k, col in enumerate(p.columns):
        ref = [int(t[k]) if col in ("id", "phase") else float(t[k]) for t in g]
        a = p.grains[col].tolist()
        if a != ref:
            bad.append(col)
    for k, col in enumerate(("P0", "Q0x", "Q0y", "Q0z", "M0")):
        if p.contacts[col].tolist() != [float(t[2 + k]) for t in c]:
            bad.append(col)
    walls = {w: -1 - k for k, w in enumerate(qusgm.WALLS)}
    if p.contacts["i"].tolist() != [int(t[0]) for t in c]:
        bad.append("i")
    if p.contacts["j"].tolist() != [walls[t[1]] if t[1] in walls else int(t[1]) for t in c]:
        bad.append("j")
    if p.contacts["j_wall"].tolist() != [t[1] if t[1] in walls else "" for t in c]:
        bad.append("j_wall")
    if p.box.tolist() != [float(t) for t in head["box"]]:
        bad.append("box")
    return bad

def porosity(p):
    return 1 - (4 / 3 * math.pi * p.grains["r"] ** 3).sum() / p.volume

for path, version in (("dense.pack", 1), ("dense.pack.gz", 1), ("fr.pack", 1), ("hyd.pack", 2), ("plates.pack", 2)):
    try:
        p = qusgm.read_pack(path)
    except Exception as e:
        check("%s: read_pack" % path, False, repr(e))
        continue
    i = info(path)
    check("%s: version %d" % (path, version), p.version == version, p.version)
    check("%s: grains as packinfo (%s)" % (path, i["grains"]), len(p.grains) == int(i["grains"]), len(p.grains))
    bad = same_numbers(p, path)
    check("%s: every number is the file's, exactly (%d grains, %d contact lines, columns %s)"
          % (path, len(p.grains), len(p.contacts), " ".join(p.columns)), not bad, "differ: %s" % bad)
    r = p.grains["r"]
    check("%s: r_min and r_max are packinfo's to the bit" % path,
          r.min() == float(i["r_min"]) and r.max() == float(i["r_max"]), (repr(r.min()), i["r_min"], repr(r.max()), i["r_max"]))
    check("%s: r_mean as packinfo's to 1e-15" % path, abs(r.mean() / float(i["r_mean"]) - 1) < 1e-15, (repr(r.mean()), i["r_mean"]))
    if path != "plates.pack":
        phi = porosity(p)
        check("%s: porosity recomputed = packinfo's to 1e-12" % path, abs(phi / float(i["porosity"]) - 1) < 1e-12, (repr(phi), i["porosity"]))
    check("%s: history lines" % path, len(p.history) >= 1 and p.history[0].startswith("packgen "), p.history)
    check("%s: units" % path, p.units == "SI" and p.units_of["E"] == "Pa" and p.units_of["rho"] == "kg/m^3" and p.units_of["P0"] == "N", p.units_of)

d = qusgm.read_pack("dense.pack")
z = qusgm.read_pack("dense.pack.gz")
check("plain and .gz read the same", all(np.array_equal(d.grains[f], z.grains[f]) for f in d.columns)
      and np.array_equal(d.contacts, z.contacts) and d.meta == z.meta and d.history == z.history)
check("dtypes: id int64, x float64", d.grains.dtype["id"] == np.int64 and d.grains.dtype["x"] == np.float64, d.grains.dtype)
fr = qusgm.read_pack("fr.pack")
check("fr.pack: walls, friction and history", fr.walls["mu"] >= 0 and fr.friction == 0.3 and fr.history[-1].startswith("frictionalize "),
      (fr.walls, fr.friction, fr.history[-1:]))
w = fr.contacts[fr.contacts["j"] < 0]
check("fr.pack: wall contacts: j = -1 - index of j_wall (%d)" % len(w),
      len(w) > 0 and all(qusgm.WALLS[-1 - j] == n for j, n in zip(w["j"].tolist(), w["j_wall"].tolist())))
h = qusgm.read_pack("hyd.pack")
check("hyd.pack: phase column int8, hydrate grains as packinfo (%s)" % info("hyd.pack").get("hydrate_grains"),
      h.grains.dtype["phase"] == np.int8 and int((h.grains["phase"] == 1).sum()) == int(info("hyd.pack")["hydrate_grains"]))
pl = qusgm.read_pack("plates.pack")
check("plates.pack: shape columns", pl.columns[-5:] == ("side", "qw", "qx", "qy", "qz") and (pl.grains["side"] > 0).any())
check("plates.pack: side_max as packinfo's", pl.grains["side"].max() == float(info("plates.pack")["side_max"]))

# streams
ps = list(qusgm.read_packs("two.pack"))
check("read_packs: two packs of a stream, versions 1 and 2", [p.version for p in ps] == [1, 2] and len(ps[1].grains) == 60
      and ps[1].line == len(open("dense.pack").read().splitlines()) + 1, [(p.version, p.line) for p in ps])
try:
    qusgm.read_pack("two.pack")
    check("read_pack refuses a stream of two", False, "no error")
except qusgm.FormatError as e:
    check("read_pack refuses a stream of two (%s)" % e, "two.pack:%d: a second pack follows" % ps[1].line in str(e), str(e))

# errors: FILE:LINE: what
text = open("dense.pack").read().splitlines(True)
k = text.index("end\n") + 3
def refused(name, body, where):
    open("bad.pack", "w").write(body)
    try:
        qusgm.read_pack("bad.pack")
        check(name, False, "no error")
    except ValueError as e:
        check("%s (%s)" % (name, e), isinstance(e, qusgm.FormatError) and str(e).startswith("bad.pack:%d: " % where), str(e))
refused("a radius that is not a number", "".join(text[:k]) + text[k].replace(text[k].split()[4], "1e-4x", 1) + "".join(text[k + 1:]), k + 1)
refused("a truncated pack", "".join(text[:k]), k + 1)
refused("a last line without newline", "".join(text)[:-1], len(text))
refused("version 3", "qusgm-pack 3\n", 1)
refused("a grain line with a column missing", "".join(text[:k]) + text[k].rsplit(None, 1)[0] + "\n" + "".join(text[k + 1:]), k + 1)
try:
    open("bad.gz", "wb").write(gzip.compress("".join(text).encode())[:-200])
    qusgm.read_pack("bad.gz")
    check("a truncated .gz", False, "no error")
except qusgm.FormatError as e:
    check("a truncated .gz (%s)" % e, str(e).startswith("bad.gz:"), str(e))

# tables
for path, names, units, colfile in (("curve.tsv", ("sig_zz", "porosity"), ("Pa", ""), "curve.cols"),
                                    ("moduli.tsv", ("K", "nu"), ("Pa", ""), "moduli.cols")):
    t = qusgm.read_table(path)
    raw = [l for l in open(path).read().splitlines()]
    header = [l for l in raw if l.startswith("# ")][0][2:].split("\t")
    rows = [l for l in raw if not l.startswith("#")]
    check("%s: column names without units (%d)" % (path, len(t.names)),
          t.names == [h.split("[")[0] for h in header] and list(t.data.dtype.names) == t.names, t.names)
    check("%s: units" % path, [t.units[n] for n in names] == list(units), t.units)
    check("%s: %d rows" % (path, len(rows)), len(t) == len(rows) and len(rows) > 0, len(t))
    cols = [l.split("\t") for l in open(colfile).read().splitlines()]
    ok = all(t[n].tolist() == [float(c[k]) for c in cols] for k, n in enumerate(names))
    check("%s: %s equal pipelines/cols.sh's, exactly" % (path, " ".join(names)), ok, (t[names[0]].tolist(), cols))
    check("%s: every value the row's token" % path,
          all(t.data[r].tolist() == tuple(float(x) for x in rows[r].split("\t")) or
              all((a == b) or (math.isnan(a) and math.isnan(b)) for a, b in zip(t.data[r].tolist(), (float(x) for x in rows[r].split("\t"))))
              for r in range(len(rows))))
t = qusgm.read_table("curve.tsv")
check("curve.tsv: the ## lines in meta", len(t.meta) == 5 and t.meta[0].startswith("qusgm loadtest "), t.meta)
open("bad.tsv", "w").write("# a\tb[Pa]\n1\t2\n3\n")
try:
    qusgm.read_table("bad.tsv")
    check("a table row short of a field", False, "no error")
except qusgm.FormatError as e:
    check("a table row short of a field (%s)" % e, str(e).startswith("bad.tsv:3: "), str(e))

try:
    import pandas
except ImportError:
    print("SKIP to_dataframe (no pandas)")
else:
    df = d.to_dataframe()
    check("Pack.to_dataframe: the grains, units in attrs", list(df.columns) == list(d.columns) and len(df) == len(d.grains)
          and df["r"].tolist() == d.grains["r"].tolist() and df.attrs["units"]["x"] == "m")
    dc = fr.to_dataframe("contacts")
    check("Pack.to_dataframe('contacts')", len(dc) == len(fr.contacts) and (dc["j_wall"] != "").sum() == len(w))
    tf = qusgm.read_table("moduli.tsv").to_dataframe()
    check("Table.to_dataframe", tf["K"].tolist() == qusgm.read_table("moduli.tsv")["K"].tolist() and tf.attrs["units"]["K"] == "Pa")
EOF
rc=$?
if [ "$rc" -ne 0 ]; then fail "the python checks ran" "exit $rc"; fi
# the module reads standard input too, and is what make install copies
if "$py" -c 'import qusgm, sys; p = qusgm.read_pack("-"); print(len(p.grains))' <dense.pack.gz | grep -qx 200; then
	pass "read_pack('-'): gzip on standard input"
else
	fail "read_pack('-'): gzip on standard input" "$("$py" -c 'import qusgm; qusgm.read_pack("-")' <dense.pack.gz 2>&1 | tail -n 1)"
fi
