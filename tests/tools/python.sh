# SPDX-License-Identifier: GPL-3.0-or-later
# python: the package share/python/qusgm reads packs (plain and .gz, versions 1 and 2,
# streams) and tables into numpy arrays with the exact doubles the tools wrote: every grain
# and contact number equals the file's token read by float(), the radii extremes equal
# packinfo's to the bit, the porosity recomputed in numpy equals packinfo's to 1e-12; the fast
# path (numpy's C parser) gives the same bytes as the line-by-line reader, and accepts and
# refuses what it does, with the same message; every kind of table (packinfo --tsv, loadtest,
# moduli, frictionalize's and densify's logs, shear's table and profile) reads with its
# columns, units, rows, values and text columns, and through the pandas call that
# share/doc/tables.md gives; malformed input is a FormatError naming file:line; pyproject.toml
# builds a wheel of the package (issues 18, 46).  Run with Debian's python3 (the one make
# check installs python3-numpy and python3-pandas for): without numpy it fails, never skips.
. "$TOP/tests/tools/lib.sh"
# The optimised build's: the package is Python, the same whatever build wrote its inputs, and
# the tools that write them are the sanitizer build's own tests' (17 s of CPU there).
if [ "${BIN#*build-san}" != "$BIN" ]; then
	echo "SKIP python (the package does not depend on the build)"
	exit 0
fi

python_with_numpy || exit 0

# The packs: version 1 (densify's, with contact lines; frictionalize's, with Q0 and M0), its
# gzip, version 2 with the phase column and with the shape columns; a stream of two.
small_pack dense
frictionalize --log frlog.tsv -o fr.pack dense.pack 2>/dev/null
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
# every other kind: packinfo --tsv, densify's log (a text column), shear's table and profile
packinfo --tsv dense.pack fr.pack hyd.pack >info.tsv 2>/dev/null
densify --stress 1e6 --log dlog.tsv -o hyd-dense.pack hyd.pack 2>/dev/null
packgen --shape spheroplate --platyness 0.5 -n 125 --seed 2 -o shear.pack 2>/dev/null
# (--relax-tol 0: no relaxation at sigma_w before the strain, which took nine tenths of the
# run, ten seconds in the sanitizer build; the table and profile have the same rows and
# columns without it, and shear.sh tests the relaxation)
shear --strain 0.004 --relax-tol 0 --every 0.002 --profile shear.prof --profile-bins 3 --profile-from 0 -o /dev/null shear.pack \
	>shear.tsv 2>/dev/null
for f in info.tsv dlog.tsv frlog.tsv shear.tsv shear.prof; do
	[ -s "$f" ] || fail "the table $f written" "empty or missing"
done

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
        ref = [int(t[k]) if col in ("id", "phase") else t[k] if col == "shape" else float(t[k]) for t in g]
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
    kinds = p.kinds.tolist()
    check("%s: kinds, one of SHAPES, spheroplate where side > 0" % path,
          set(kinds) <= set(qusgm.SHAPES) and ("side" not in p.columns or
          kinds == ["spheroplate" if s > 0 else "sphere" for s in p.grains["side"].tolist()]), kinds[:3])
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
    kinds = p.kinds.tolist()
    check("%s: kinds, one of SHAPES, spheroplate where side > 0" % path,
          set(kinds) <= set(qusgm.SHAPES) and ("side" not in p.columns or
          kinds == ["spheroplate" if s > 0 else "sphere" for s in p.grains["side"].tolist()]), kinds[:3])
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

# every kind of table: names, units, rows, each value the token read by float() (nan too),
# text columns (densify's stage) as str; and the pandas call of share/doc/tables.md
try:
    import pandas as pd
except ImportError:
    pd = None
    check("pandas installed (make check installs python3-pandas)", False, "import pandas failed")
def same(a, b):
    return a == b or (isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b))
for path in ("info.tsv", "curve.tsv", "moduli.tsv", "frlog.tsv", "dlog.tsv", "shear.tsv", "shear.prof"):
    try:
        t = qusgm.read_table(path)
    except Exception as e:
        check("%s: read_table" % path, False, repr(e))
        continue
    raw = open(path).read().splitlines()
    header = [l for l in raw if l.startswith("# ")][0][2:].split("\t")
    rows = [l.split("\t") for l in raw if not l.startswith("#")]
    text = [k for k in range(len(header)) if not all(r[k].lstrip("+-").replace(".", "", 1).replace("e", "", 1).replace("-", "").replace("+", "").isdigit() or r[k] == "nan" for r in rows)]
    ok = t.names == [h.split("[")[0] for h in header] and all(t.units[h.split("[")[0]] == (h.split("[")[1][:-1] if "[" in h else "") for h in header)
    check("%s: %d columns, their units" % (path, len(header)), ok, (t.names, t.units))
    vals = [tuple(r[k] if k in text else float(r[k]) for k in range(len(header))) for r in rows]
    ok = len(t) == len(rows) > 0 and all(all(same(a, b) for a, b in zip(t.data[i].tolist(), vals[i])) for i in range(len(rows)))
    check("%s: %d rows, every value the file's token%s" % (path, len(rows), ", text columns %s" % [header[k] for k in text] if text else ""), ok)
    check("%s: text columns as str, the others float64" % path,
          t.text_columns == [t.names[k] for k in text] and all(t.data.dtype[n] == np.float64 for n in t.names if n not in t.text_columns))
    if pd is not None:
        with open(path) as f:
            hdr = next(line for line in f if not line.startswith("##"))
        df = pd.read_csv(path, sep="\t", comment="#", header=None, names=hdr[2:].rstrip("\n").split("\t"),
                         float_precision="round_trip")
        ok = list(df.columns) == header and len(df) == len(rows) and all(
            all(same(a, b) for a, b in zip(df.iloc[i].tolist(), vals[i])) for i in range(len(rows)))
        check("%s: pandas.read_csv(sep='\\t', comment='#', names=the header's, float_precision='round_trip'): the same values" % path, ok)
        d2 = t.to_dataframe()
        check("%s: Table.to_dataframe, the same values, units in attrs" % path,
              list(d2.columns) == t.names and all(all(same(a, b) for a, b in zip(d2.iloc[i].tolist(), vals[i])) for i in range(len(rows)))
              and d2.attrs["units"] == t.units)
t = qusgm.read_table("dlog.tsv")
check("dlog.tsv: densify's stages, relax first (%s)" % " ".join(sorted(set(t["stage"].tolist()))),
      t["stage"][0] == "relax" and set(t["stage"].tolist()) <= {"relax", "grow", "retry", "compact"})

# the fast path: the same arrays, byte for byte, as the line-by-line reader; taken on every
# pack a tool writes (the line-by-line reader made to fail); and on damaged packs the same
# acceptance and the same message
for path in ("dense.pack", "dense.pack.gz", "fr.pack", "hyd.pack", "plates.pack"):
    a, b = qusgm.read_pack(path), qusgm.read_pack(path, fast=False)
    check("%s: fast and line-by-line the same bytes (%d grains, %d contacts)" % (path, len(a.grains), len(a.contacts)),
          a.grains.dtype == b.grains.dtype and a.grains.tobytes() == b.grains.tobytes()
          and a.contacts.dtype == b.contacts.dtype and a.contacts.tobytes() == b.contacts.tobytes())
a, b = list(qusgm.read_packs("two.pack")), list(qusgm.read_packs("two.pack", fast=False))
check("two.pack: fast and line-by-line the same bytes, a stream", [x.grains.tobytes() + x.contacts.tobytes() for x in a]
      == [x.grains.tobytes() + x.contacts.tobytes() for x in b] and [x.line for x in a] == [x.line for x in b])
slow = qusgm._grains_slow, qusgm._contacts_slow
def no_slow(*args):
    raise RuntimeError("the line-by-line reader")
qusgm._grains_slow = qusgm._contacts_slow = no_slow
try:
    for path in ("dense.pack", "dense.pack.gz", "fr.pack", "hyd.pack", "plates.pack", "two.pack"):
        list(qusgm.read_packs(path))
    check("the fast path reads every pack here alone", True)
except RuntimeError as e:
    check("the fast path reads every pack here alone", False, "%s: %s" % (path, e))
qusgm._grains_slow, qusgm._contacts_slow = slow

def outcome(text, fast):
    open("mut.pack", "w").write(text)
    try:
        p = qusgm.read_pack("mut.pack", fast=fast)
        return "ok", p.grains.dtype.descr, p.grains.tobytes(), p.contacts.tobytes()
    except qusgm.FormatError as e:
        return "error", str(e)
def mutate(path, line, old, new, count=1):
    L = open(path).read().splitlines(True)
    k = L.index("end\n") + 1 + line
    L[k] = L[k].replace(old, new, count) if old is not None else new
    return "".join(L)
dl = open("dense.pack").read().splitlines(True)
ng = len(qusgm.read_pack("dense.pack").grains)
c0 = dl[dl.index("end\n") + 1 + ng].split()
wl = [l for l in dl[dl.index("end\n") + 1 + ng:] if l.split()[1] in qusgm.WALLS][0]
wk = dl.index(wl) - dl.index("end\n") - 1
hl = open("hyd.pack").read().splitlines(True)
cases = [("dense.pack", 0, "1 ", x) for x in ("1.0 ", "+1 ", "01 ", "1e0 ", "0x1 ", " 1 ", "-1 ", "2 ", "1_0 ", '"1" ')] + [
    ("dense.pack", 0, dl[dl.index("end\n") + 1].split()[1], x) for x in ("0x1p-12", "nan", "inf", "1e-4x", "", "1e400", "-0")] + [
    ("dense.pack", 1, " ", "\t"), ("dense.pack", 1, " ", "  "), ("dense.pack", 1, "\n", " \n"), ("dense.pack", 1, "\n", "\r\n"),
    ("dense.pack", 1, "\n", " 7\n"), ("dense.pack", 1, None, "\n"), ("dense.pack", 1, "\n", "#\n"),
    ("dense.pack", ng, c0[1] + " ", "-1 "), ("dense.pack", ng, c0[1] + " ", c0[0] + " "), ("dense.pack", ng, c0[1] + " ", "99999 "),
    ("dense.pack", ng, c0[1] + " ", "-1000000000000001 "), ("dense.pack", ng, c0[1] + " ", "xlo "), ("dense.pack", ng, c0[1] + " ", "XLO "),
    ("dense.pack", ng, c0[0] + " ", "0 "), ("dense.pack", ng, c0[2], "-" + c0[2]), ("dense.pack", ng, "\n", "\t\n"),
    ("dense.pack", wk, " " + wl.split()[1] + " ", "\t" + wl.split()[1] + " "), ("dense.pack", wk, " " + wl.split()[1] + " ", " xmid "),
    ("dense.pack", wk, " " + wl.split()[1] + " ", " xhx "), ("dense.pack", wk, " " + wl.split()[1] + " ", " zlo1 "),
    ("dense.pack", wk, " " + wl.split()[1] + " ", " " + ("yhi" if wl.split()[1] != "yhi" else "xlo") + " "),
    ("hyd.pack", 0, None, hl[hl.index("end\n") + 1].rsplit(" ", 1)[0] + " 2\n"),
    ("hyd.pack", 0, None, hl[hl.index("end\n") + 1].rsplit(" ", 1)[0] + " +1\n"),
    ("hyd.pack", 0, None, hl[hl.index("end\n") + 1].rsplit(" ", 1)[0] + " 01\n")]
for chunk in (qusgm._CHUNK, 37):  # the default (one chunk here), and chunks of 37 lines
    qusgm._CHUNK = chunk
    same_outcome, errors = [], 0
    for path, line, old, new in cases + [("dense.pack", k, None, "\n") for k in (36, 37, 38, ng + 36)]:
        t = mutate(path, line, old, new)
        f, s = outcome(t, True), outcome(t, False)
        errors += f[0] == "error"
        if f != s:
            same_outcome.append((path, line, old, new, f[:2], s[:2]))
    check("damaged packs, %d lines a chunk: the fast path accepts and refuses as the line-by-line reader, "
          "the same message (%d cases, %d refused)" % (chunk, len(cases) + 4, errors),
          not same_outcome and errors > len(cases) // 2, same_outcome[:3])
    ok = all(qusgm.read_pack(f).grains.tobytes() + qusgm.read_pack(f).contacts.tobytes() ==
             qusgm.read_pack(f, fast=False).grains.tobytes() + qusgm.read_pack(f, fast=False).contacts.tobytes()
             for f in ("dense.pack", "dense.pack.gz", "fr.pack", "plates.pack"))
    check("%d lines a chunk: fast and line-by-line the same bytes" % chunk, ok)

if pd is not None:
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
# the module reads standard input too
if "$py" -c 'import qusgm, sys; p = qusgm.read_pack("-"); print(len(p.grains))' <dense.pack.gz | grep -qx 200; then
	pass "read_pack('-'): gzip on standard input"
else
	fail "read_pack('-'): gzip on standard input" "$("$py" -c 'import qusgm; qusgm.read_pack("-")' <dense.pack.gz 2>&1 | tail -n 1)"
fi

# pyproject.toml: one version with the Makefile's and the module's, and a wheel of the package
# built by setuptools' backend (Debian python3-setuptools) from a copy of share/python
ver=$(awk '$1 == "VERSION" && $2 == "=" { print $3; exit }' "$TOP/Makefile")
pv=$(sed -n 's/^version = "\(.*\)"$/\1/p' "$TOP/share/python/pyproject.toml")
mv_=$("$py" -c 'import qusgm; print(qusgm.__version__)')
if [ "$pv" = "$ver" ] && [ "$mv_" = "$ver" ]; then pass "pyproject.toml and qusgm.__version__ say $ver"; else fail "pyproject.toml and qusgm.__version__ say $ver" "'$pv' '$mv_'"; fi
if "$py" -c 'import setuptools.build_meta' 2>/dev/null; then
	rm -rf pysrc wheel && cp -R "$TOP/share/python" pysrc && mkdir wheel
	if (cd pysrc && "$py" -c 'import sys, setuptools.build_meta as b; print(b.build_wheel(sys.argv[1]))' ../wheel) >wheel.log 2>&1 &&
	   "$py" -c 'import sys, zipfile; n = zipfile.ZipFile(sys.argv[1]).namelist(); sys.exit(not {"qusgm/__init__.py", "qusgm/py.typed"} <= set(n))' wheel/qusgm-"$ver"-py3-none-any.whl; then
		pass "pyproject.toml builds qusgm-$ver-py3-none-any.whl, with py.typed"
	else
		fail "pyproject.toml builds a wheel" "$(tail -n 3 wheel.log)"
	fi
else
	echo "SKIP the wheel (no setuptools; Debian: apt-get install python3-setuptools)"
fi
