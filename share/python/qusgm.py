"""Read qusgm packs and tables into numpy arrays.

A pure-Python reader of the two kinds of file the qusgm tools write (numpy required,
pandas optional):

- packs, qusgm-pack versions 1 and 2 (share/doc/pack-format.md, qusgm-pack(5)), plain or
  gzip-compressed (told by the magic bytes 1f 8b, not by the name), one pack or several
  back to back in one stream;
- tables, the TSV of packinfo --tsv, loadtest, moduli and frictionalize --log
  (share/doc/tables.md): '##' metadata lines, one '# ' header of TAB-separated names with
  their units in brackets (sig_zz[Pa]), rows of numbers, 'nan' for a missing value.

    import qusgm
    p = qusgm.read_pack("dense.pack.gz")
    g = p.grains                         # numpy structured array, fields p.columns
    phi = 1 - (4 / 3 * np.pi * g["r"] ** 3).sum() / p.volume
    t = qusgm.read_table("curve.tsv")
    t["sig_zz"], t.units["sig_zz"]       # a column (float64 array) and its unit, 'Pa'
    df = t.to_dataframe()                # with pandas

Every number is converted by Python's float(), which rounds correctly, so a value reads as
the exact double the tool wrote (the writers print the shortest decimal that reads back to
it).  Units are SI: m, Pa, kg/m^3, N, N m.

Pack (read_pack, read_packs): attributes version (1 or 2), history (list of the history
lines' text, oldest first), meta (dict), units ('SI'), box and refbox (numpy arrays
xlo ylo zlo xhi yhi zhi, m; refbox None when the pack has none), boundary (three of
'walls'/'periodic', x y z), walls (dict E, nu, mu), friction (grain-grain mu), columns
(the grain columns, in file order), grains (structured array, one record per grain line, in
file order: id int64; x y z r E nu rho and, where present, side qw qx qy qz float64; phase
int8, 0 mineral 1 hydrate), contacts (structured array: i int64, the first grain's id; j
int64, the second grain's id, or for a wall -1 - w with w the wall's index in WALLS, so
xlo -1 ... zhi -6; j_wall the wall's name, '' for a grain; P0 Q0x Q0y Q0z M0 float64),
units_of (dict: column -> unit, '' for a dimensionless one or a count), name and line (where
the pack starts).  pack.to_dataframe() and pack.to_dataframe("contacts") need pandas.

Table (read_table): names (column names without their units), units (dict name -> unit,
'' without brackets), meta (the '##' lines, without '## '), data (structured array, every
field float64, nan for 'nan'), t[name] a column, len(t) the rows, t.to_dataframe().

Malformed input raises FormatError (a ValueError) "FILE:LINE: what is wrong", as the tools
report it.  This reader checks the structure of a pack (header keywords, counts, columns,
numbers, ids and wall names of the contacts), not every rule of qusgm's own reader
(overlapping centres, radius ranges...): packinfo(1) is the full check.
"""

import gzip
import io
import math
import sys

import numpy as np

__all__ = ["read_pack", "read_packs", "read_table", "Pack", "Table", "FormatError", "WALLS", "UNITS"]
__version__ = "0.2.0"

WALLS = ("xlo", "xhi", "ylo", "yhi", "zlo", "zhi")
VERSIONS = (1, 2)

# The unit of every column a pack can hold ('' dimensionless or a count).
UNITS = {
    "id": "", "x": "m", "y": "m", "z": "m", "r": "m", "E": "Pa", "nu": "", "rho": "kg/m^3",
    "side": "m", "qw": "", "qx": "", "qy": "", "qz": "", "phase": "",
    "i": "", "j": "", "j_wall": "", "P0": "N", "Q0x": "N", "Q0y": "N", "Q0z": "N", "M0": "N m",
}

_REQUIRED = ("id", "x", "y", "z", "r", "E", "nu", "rho")
_VALID_COLUMNS = (
    _REQUIRED,
    _REQUIRED + ("side", "qw", "qx", "qy", "qz"),
    _REQUIRED + ("phase",),
    _REQUIRED + ("side", "qw", "qx", "qy", "qz", "phase"),
)
_DTYPES = {"id": np.int64, "phase": np.int8}
_CONTACT_DTYPE = np.dtype([("i", np.int64), ("j", np.int64), ("j_wall", "U3"), ("P0", np.float64),
                           ("Q0x", np.float64), ("Q0y", np.float64), ("Q0z", np.float64),
                           ("M0", np.float64)])


class FormatError(ValueError):
    """A malformed pack or table: the message is "FILE:LINE: what is wrong"."""


def _open(source):
    """(binary stream, display name, whether to close it) for a path, '-' or a file object.
    gzip is told by its magic bytes, as the tools tell it."""
    if source is None or source == "-":
        fp, name, own = sys.stdin.buffer, "<stdin>", False
    elif hasattr(source, "read"):
        fp = source.buffer if isinstance(source, io.TextIOBase) else source
        name, own = getattr(source, "name", "<stream>"), False
    else:
        fp, name, own = open(source, "rb"), str(source), True
    if not hasattr(fp, "peek"):
        fp = io.BufferedReader(fp)
    if fp.peek(2)[:2] == b"\x1f\x8b":
        fp = gzip.GzipFile(fileobj=fp, mode="rb")
    return fp, name, own


class _Lines:
    """Numbered text lines, each of which must end in '\\n' (one '\\r' before it dropped)."""

    def __init__(self, source):
        self.raw, self.name, self.own = _open(source)
        self.text = io.TextIOWrapper(self.raw, encoding="utf-8", errors="surrogateescape", newline="\n")
        self.lineno = 0
        self.pushed = None

    def error(self, msg, lineno=None):
        return FormatError("%s:%d: %s" % (self.name, self.lineno if lineno is None else lineno, msg))

    def next(self):
        """The next line without its end, or None at the end of input."""
        if self.pushed is not None:
            s, self.pushed = self.pushed, None
            self.lineno += 1
            return s
        try:
            s = self.text.readline()
        except (OSError, EOFError, gzip.BadGzipFile) as e:
            raise self.error("corrupt or truncated input (%s)" % e, self.lineno + 1) from None
        if not s:
            return None
        self.lineno += 1
        if not s.endswith("\n"):
            raise self.error("truncated: the last line has no newline")
        s = s[:-1]
        if s.endswith("\r"):
            s = s[:-1]
        if "\0" in s:
            raise self.error("binary data (NUL byte) in a text file")
        return s

    def push(self, s):
        self.pushed = s
        self.lineno -= 1

    def close(self):
        self.text.detach()
        if self.own:
            self.raw.close()


def _float(tok, what, lines):
    """A finite double, exactly as strtod reads it (decimal or hexadecimal)."""
    try:
        if "_" in tok:
            raise ValueError
        v = float.fromhex(tok) if "x" in tok or "X" in tok else float(tok)
    except ValueError:
        raise lines.error("%s: '%s' is not a number" % (what, tok)) from None
    if not math.isfinite(v):
        raise lines.error("%s: '%s' is not a finite number" % (what, tok))
    return v


def _int(tok, what, lines):
    if not tok.lstrip("+-").isdigit():
        raise lines.error("%s: '%s' is not an integer" % (what, tok))
    return int(tok)


class Pack:
    """One pack of a qusgm-pack stream (see the module's docstring for the attributes)."""

    def __init__(self):
        self.version = None
        self.history = []
        self.meta = {}
        self.units = None
        self.box = None
        self.refbox = None
        self.boundary = ("walls", "walls", "walls")
        self.walls = None
        self.friction = None
        self.columns = _REQUIRED
        self.grains = None
        self.contacts = None
        self.name = None
        self.line = None

    @property
    def n(self):
        """The number of grains."""
        return len(self.grains)

    @property
    def periodic(self):
        """Per axis x y z, whether it is periodic."""
        return tuple(b == "periodic" for b in self.boundary)

    @property
    def volume(self):
        """The box's volume (m^3)."""
        b = self.box
        return float((b[3] - b[0]) * (b[4] - b[1]) * (b[5] - b[2]))

    @property
    def units_of(self):
        """Column -> unit of the grain and contact columns ('' dimensionless)."""
        return {c: UNITS[c] for c in self.columns + _CONTACT_DTYPE.names}

    def to_dataframe(self, which="grains"):
        """The grains (or with "contacts", the contact lines) as a pandas DataFrame, one
        column per field, the units in df.attrs["units"]."""
        import pandas as pd

        if which not in ("grains", "contacts"):
            raise ValueError("to_dataframe: 'grains' or 'contacts', not %r" % (which,))
        a = self.grains if which == "grains" else self.contacts
        df = pd.DataFrame({f: a[f] for f in a.dtype.names})
        df.attrs["units"] = {f: UNITS[f] for f in a.dtype.names}
        return df

    def __repr__(self):
        return "<qusgm.Pack version %s: %d grains, %d contacts, from %s:%s>" % (
            self.version, len(self.grains), len(self.contacts), self.name, self.line)


_ONCE = ("units", "box", "refbox", "walls", "friction", "grains", "contacts", "boundary", "columns")
_REQUIRED_KEYS = ("units", "box", "walls", "friction", "grains", "contacts")


def _read_header(lines, magic):
    p = Pack()
    p.name, p.line = lines.name, lines.lineno
    tok = magic.split()
    if not tok or tok[0] != "qusgm-pack":
        raise lines.error("not a qusgm pack")
    if len(tok) != 2 or not tok[1].lstrip("+-").isdigit():
        raise lines.error("pack format version missing or not an integer")
    p.version = int(tok[1])
    if p.version > VERSIONS[-1]:
        raise lines.error("pack format version %d is newer than this reader reads (%d); upgrade qusgm"
                          % (p.version, VERSIONS[-1]))
    if p.version < VERSIONS[0]:
        raise lines.error("unknown pack format version %d" % p.version)
    seen = {}
    while True:
        s = lines.next()
        if s is None:
            raise lines.error("input ends before 'end'", lines.lineno + 1)
        if s.startswith("#"):
            continue
        if s.startswith("history ") or s.startswith("history\t"):
            p.history.append(s[8:])
            continue
        tok = s.split()
        if not tok:
            raise lines.error("empty header line")
        key, args = tok[0], tok[1:]
        if key == "end":
            if args:
                raise lines.error("text after 'end'")
            break
        if key == "meta":
            if len(args) < 2:
                raise lines.error("meta: expected a key and a value")
            k = args[0]
            if k in p.meta:
                raise lines.error("meta: duplicate key '%s'" % k)
            p.meta[k] = s.split(None, 2)[2].rstrip(" \t")
            continue
        if key not in _ONCE:
            raise lines.error("unknown header keyword '%s'" % key)
        if key in seen:
            raise lines.error("%s: the header must contain exactly one" % key)
        if key in ("boundary", "columns") and p.version == 1:
            raise lines.error("%s: not in version 1 of the format" % key)
        seen[key] = lines.lineno
        want = {"units": 1, "box": 6, "refbox": 6, "walls": 3, "friction": 1, "grains": 1,
                "contacts": 1, "boundary": 3}.get(key)
        if want is not None and len(args) != want:
            raise lines.error("%s: expected %d values, found %d" % (key, want, len(args)))
        if key == "units":
            if args[0] != "SI":
                raise lines.error("units: '%s' is not SI" % args[0])
            p.units = "SI"
        elif key in ("box", "refbox"):
            v = np.array([_float(t, key, lines) for t in args])
            if not (v[3:] > v[:3]).all():
                raise lines.error("%s: an upper bound not above the lower one" % key)
            setattr(p, key, v)
        elif key == "walls":
            E, nu, mu = (_float(t, "walls", lines) for t in args)
            p.walls = {"E": E, "nu": nu, "mu": mu}
        elif key == "friction":
            p.friction = _float(args[0], "friction", lines)
        elif key in ("grains", "contacts"):
            v = _int(args[0], key, lines)
            if not (key == "contacts" or v >= 1) or v < 0 or v > 10 ** 9:
                raise lines.error("%s: '%s' is not a valid count" % (key, args[0]))
            seen[key + "_n"] = v
        elif key == "boundary":
            for a, b in zip("xyz", args):
                if b not in ("walls", "periodic"):
                    raise lines.error("boundary: '%s' for axis %s is neither 'walls' nor 'periodic'" % (b, a))
            p.boundary = tuple(args)
        elif key == "columns":
            if tuple(args) not in _VALID_COLUMNS:
                raise lines.error("columns: '%s' is not one of the valid column lists (pack-format.md)"
                                  % " ".join(args))
            p.columns = tuple(args)
    for key in _REQUIRED_KEYS + (("boundary", "columns") if p.version == 2 else ()):
        if key not in seen:
            raise lines.error("%s: the header must contain exactly one" % key)
    return p, seen["grains_n"], seen["contacts_n"]


def _read_body(lines, p, ng, nc):
    ncol = len(p.columns)
    cols = [[] for _ in p.columns]
    ids = {}
    for n in range(ng):
        s = lines.next()
        if s is None:
            raise lines.error("%d grain lines, the header says %d" % (n, ng), lines.lineno + 1)
        tok = s.split()
        if len(tok) != ncol:
            raise lines.error("grain line with %d columns, expected %d" % (len(tok), ncol))
        for k, c in enumerate(p.columns):
            if c == "id":
                v = _int(tok[k], "id", lines)
                if v < 0:
                    raise lines.error("grain id %d is negative" % v)
                if v in ids:
                    raise lines.error("duplicate grain id %d" % v)
                ids[v] = n
            elif c == "phase":
                if tok[k] not in ("0", "1"):
                    raise lines.error("grain %s: phase '%s' is neither 0 (mineral) nor 1 (hydrate)"
                                      % (tok[0], tok[k]))
                v = int(tok[k])
            else:
                v = _float(tok[k], c, lines)
            cols[k].append(v)
    dt = np.dtype([(c, _DTYPES.get(c, np.float64)) for c in p.columns])
    g = np.empty(ng, dtype=dt)
    for k, c in enumerate(p.columns):
        g[c] = cols[k]
    walls = {w: -1 - k for k, w in enumerate(WALLS)}
    c = np.zeros(nc, dtype=_CONTACT_DTYPE)
    for n in range(nc):
        s = lines.next()
        if s is None:
            raise lines.error("%d contact lines, the header says %d" % (n, nc), lines.lineno + 1)
        tok = s.split()
        if len(tok) != 7:
            raise lines.error("contact line with %d columns, expected 7" % len(tok))
        i = _int(tok[0], "i", lines)
        if i not in ids:
            raise lines.error("contact: no grain %d" % i)
        if tok[1] in walls:
            if p.periodic["xyz".index(tok[1][0])]:
                raise lines.error("contact: wall %s of a periodic axis" % tok[1])
            j, jw = walls[tok[1]], tok[1]
        else:
            j, jw = _int(tok[1], "j", lines), ""
            if j not in ids:
                raise lines.error("contact: no grain %d" % j)
            if j == i:
                raise lines.error("contact: grain %d with itself" % i)
        v = [_float(t, f, lines) for t, f in zip(tok[2:], ("P0", "Q0x", "Q0y", "Q0z", "M0"))]
        if v[0] < 0:
            raise lines.error("contact: P0 %s is negative" % tok[2])
        c[n] = (i, j, jw, *v)
    p.grains, p.contacts = g, c
    return p


def read_packs(source):
    """Every pack of a stream, in order (a generator): source is a path, '-' (stdin) or a
    binary file object, plain or gzip."""
    lines = _Lines(source)
    try:
        s = lines.next()
        if s is None:
            raise lines.error("empty input", 1)
        while s is not None:
            p, ng, nc = _read_header(lines, s)
            yield _read_body(lines, p, ng, nc)
            s = lines.next()
            if s is not None and not s.startswith("qusgm-pack"):
                raise lines.error("unexpected line after the last contact")
    finally:
        lines.close()


def read_pack(source):
    """Exactly one pack (as the tools that transform one pack read): see read_packs."""
    lines = _Lines(source)
    try:
        s = lines.next()
        if s is None:
            raise lines.error("empty input", 1)
        p, ng, nc = _read_header(lines, s)
        _read_body(lines, p, ng, nc)
        s = lines.next()
        if s is not None:
            raise lines.error("a second pack follows; use read_packs" if s.startswith("qusgm-pack")
                              else "unexpected line after the last contact")
        return p
    finally:
        lines.close()


class Table:
    """A qusgm table (see the module's docstring)."""

    def __init__(self, names, units, meta, data, name):
        self.names, self.units, self.meta, self.data, self.name = names, units, meta, data, name

    def __getitem__(self, name):
        return self.data[name]

    def __len__(self):
        return len(self.data)

    def __contains__(self, name):
        return name in self.units

    def to_dataframe(self):
        """The table as a pandas DataFrame, the units in df.attrs["units"]."""
        import pandas as pd

        df = pd.DataFrame({f: self.data[f] for f in self.names})
        df.attrs["units"] = dict(self.units)
        return df

    def __repr__(self):
        return "<qusgm.Table %s: %d rows, columns %s>" % (self.name, len(self.data), " ".join(self.names))


def _split_name(field):
    """'sig_zz[Pa]' -> ('sig_zz', 'Pa'); 'porosity' -> ('porosity', '')."""
    if field.endswith("]") and "[" in field:
        k = field.index("[")
        if k > 0:
            return field[:k], field[k + 1:-1]
    return field, ""


def read_table(source):
    """A table (path, '-' or binary file object; plain or gzip).  '##' lines anywhere are
    collected in meta, repeats of the header (concatenated tables) skipped, a different
    header refused, as the tools' table reader does."""
    lines = _Lines(source)
    header, names, meta, rows = None, [], [], []
    try:
        while True:
            s = lines.next()
            if s is None:
                break
            if s.startswith("##"):
                meta.append(s[3:] if s.startswith("## ") else s[2:])
                continue
            if s.startswith("#"):
                if header is None:
                    if not s.startswith("# ") or not s[2:]:
                        raise lines.error("bad header line (expected '# name\\tname...')")
                    header = s
                    fields = s[2:].split("\t")
                    names = [_split_name(f) for f in fields]
                    if len({n for n, _ in names}) != len(names) or not all(n for n, _ in names):
                        raise lines.error("bad header line: an empty or repeated column name")
                elif s != header:
                    raise lines.error("a second, different header line")
                continue
            if header is None:
                raise lines.error("no header line before the first row")
            tok = s.split("\t")
            if len(tok) != len(names):
                raise lines.error("%d fields, the header has %d" % (len(tok), len(names)))
            row = []
            for t, (n, _) in zip(tok, names):
                try:
                    if "_" in t or t != t.strip():
                        raise ValueError
                    row.append(float.fromhex(t) if "x" in t or "X" in t else float(t))
                except ValueError:
                    raise lines.error("column %s: '%s' is not a number" % (n, t)) from None
            rows.append(tuple(row))
        if header is None:
            raise FormatError("%s: empty (no header line)" % lines.name)
    finally:
        lines.close()
    data = np.array(rows, dtype=[(n, np.float64) for n, _ in names])
    return Table([n for n, _ in names], {n: u for n, u in names}, meta, data, lines.name)
