# SPDX-License-Identifier: GPL-3.0-or-later
"""Read qusgm packs and tables into numpy arrays.

A reader, in Python and numpy, of the two kinds of file the qusgm tools write (numpy
required, pandas optional; share/doc/library.md, "Reading packs and tables in Python", says
where make install puts it):

- packs, qusgm-pack versions 1 and 2 (share/doc/pack-format.md, qusgm-pack(5)), plain or
  gzip-compressed (told by the magic bytes 1f 8b, not by the name), one pack or several
  back to back in one stream;
- tables, the TSV of packinfo --tsv, loadtest, moduli, frictionalize --log, densify --log and
  shear (share/doc/tables.md): '##' metadata lines, one '# ' header of TAB-separated names
  with their units in brackets (sig_zz[Pa]), rows of numbers, 'nan' for a missing value, and
  text columns (densify's stage).

    import qusgm
    p = qusgm.read_pack("dense.pack.gz")
    g = p.grains                         # numpy structured array, fields p.columns
    phi = 1 - (4 / 3 * np.pi * g["r"] ** 3).sum() / p.volume
    t = qusgm.read_table("curve.tsv")
    t["sig_zz"], t.units["sig_zz"]       # a column (float64 array) and its unit, 'Pa'
    df = t.to_dataframe()                # the way to pandas, units in df.attrs["units"]

Every number is converted by a correctly rounded parser (Python's float(), or numpy's
fromstring on the fast path), so a value reads as the exact double the tool wrote (the
writers print the shortest decimal that reads back to it).  Units are SI: m, Pa, kg/m^3, N,
N m.

The grain and contact lines of a pack go through numpy's C parser (the fast path, about half
the time of the line-by-line parser, whose cost is per line) after their shape and integer
columns are checked on the bytes; where anything is off, the lines go to
the line-by-line parser, which names the line that is wrong.  Both give the same arrays byte
for byte and accept the same input; read_pack(..., fast=False) is the line-by-line one.

Pack (read_pack, read_packs): attributes version (1 or 2), history (list of the history
lines' text, oldest first), meta (dict), units ('SI'), box and refbox (numpy arrays
xlo ylo zlo xhi yhi zhi, m; refbox None when the pack has none), boundary (three of
'walls'/'periodic', x y z), walls (dict E, nu, mu), friction (grain-grain mu), columns
(the grain columns, in file order), grains (structured array, one record per grain line, in
file order: id int64; x y z r E nu rho and, where present, side qw qx qy qz float64; shape
str, the grain's kind, one of SHAPES; phase int8, 0 mineral 1 hydrate), kinds (each grain's
kind, a str array: the shape column, or for a pack without it 'spheroplate' where side > 0
and 'sphere' elsewhere), contacts (structured array: i int64, the first grain's id; j
int64, the second grain's id, or for a wall -1 - w with w the wall's index in WALLS, so
xlo -1 ... zhi -6; j_wall the wall's name, '' for a grain; P0 Q0x Q0y Q0z M0 float64),
units_of (dict: column -> unit, '' for a dimensionless one or a count), name and line (where
the pack starts).  pack.to_dataframe() and pack.to_dataframe("contacts") need pandas.

Table (read_table): names (column names without their units), units (dict name -> unit,
'' without brackets), meta (the '##' lines, without '## '), data (structured array, every
field float64, nan for 'nan', but a text column, one whose first row is not a number, str),
text_columns (their names), t[name] a column, len(t) the rows, t.to_dataframe().

Malformed input raises FormatError (a ValueError) "FILE:LINE: what is wrong", as the tools
report it.  This reader checks the structure of a pack (header keywords, counts, columns,
numbers, ids and wall names of the contacts), not every rule of qusgm's own reader
(overlapping centres, radius ranges...): packinfo(1) is the full check.
"""

from __future__ import annotations

import gzip
import io
import math
import os
import sys
import warnings
from typing import IO, Any, Dict, Iterator, List, Optional, Sequence, Tuple, Union

import numpy as np

__all__ = ["read_pack", "read_packs", "read_table", "Pack", "Table", "FormatError", "WALLS", "UNITS", "SHAPES"]
__version__ = "0.2.0"

#: What the readers take: a path, "-" for standard input, or a binary (or text) file object.
Source = Union[str, "os.PathLike[str]", IO[bytes], IO[str], None]

WALLS = ("xlo", "xhi", "ylo", "yhi", "zlo", "zhi")
VERSIONS = (1, 2)

# The unit of every column a pack can hold ('' dimensionless or a count).
UNITS: Dict[str, str] = {
    "id": "", "x": "m", "y": "m", "z": "m", "r": "m", "E": "Pa", "nu": "", "rho": "kg/m^3",
    "shape": "", "side": "m", "qw": "", "qx": "", "qy": "", "qz": "", "phase": "",
    "i": "", "j": "", "j_wall": "", "P0": "N", "Q0x": "N", "Q0y": "N", "Q0z": "N", "M0": "N m",
}

# The grains' kinds, the names of the shape column: lib/pack/shape.h's table (SHAPES), in its
# order.
SHAPES = ("sphere", "spheroplate")

_REQUIRED = ("id", "x", "y", "z", "r", "E", "nu", "rho")
_SHAPE = ("side", "qw", "qx", "qy", "qz")
_VALID_COLUMNS = (
    _REQUIRED,
    _REQUIRED + _SHAPE,
    _REQUIRED + ("shape",) + _SHAPE,
    _REQUIRED + ("phase",),
    _REQUIRED + _SHAPE + ("phase",),
    _REQUIRED + ("shape",) + _SHAPE + ("phase",),
)
_DTYPES = {"id": np.int64, "phase": np.int8, "shape": "U%d" % max(len(k) for k in SHAPES)}
_CONTACT_DTYPE = np.dtype([("i", np.int64), ("j", np.int64), ("j_wall", "U3"), ("P0", np.float64),
                           ("Q0x", np.float64), ("Q0y", np.float64), ("Q0z", np.float64),
                           ("M0", np.float64)])

class FormatError(ValueError):
    """A malformed pack or table: the message is "FILE:LINE: what is wrong"."""


def _open(source: Source) -> Tuple[IO[bytes], str, bool]:
    """(binary stream, display name, whether to close it) for a path, '-' or a file object.
    gzip is told by its magic bytes, as the tools tell it."""
    if source is None or source == "-":
        fp, name, own = sys.stdin.buffer, "<stdin>", False
    elif hasattr(source, "read"):
        fp = source.buffer if isinstance(source, io.TextIOBase) else source  # type: ignore[union-attr]
        name, own = getattr(source, "name", "<stream>"), False
    else:
        fp, name, own = open(source, "rb"), os.fsdecode(source), True  # type: ignore[arg-type]
    if not hasattr(fp, "peek"):
        fp = io.BufferedReader(fp)  # type: ignore[arg-type]
    if fp.peek(2)[:2] == b"\x1f\x8b":  # type: ignore[union-attr]
        fp = gzip.GzipFile(fileobj=fp, mode="rb")  # type: ignore[assignment]
    return fp, name, own  # type: ignore[return-value]


class _Lines:
    """Numbered text lines, each of which must end in '\\n' (one '\\r' before it dropped).
    Read as bytes, so that a block of lines can go to a C parser whole (take) and come back
    (unread) for the line-by-line reader to name the line that is wrong."""

    def __init__(self, source: Source) -> None:
        self.raw, self.name, self.own = _open(source)
        self.lineno = 0
        self.buf = b""  # bytes read ahead (take) or given back (unread), before the stream's
        self.pos = 0
        self.deferred: Optional[Exception] = None  # a read error met by take, raised after buf

    def error(self, msg: str, lineno: Optional[int] = None) -> FormatError:
        return FormatError("%s:%d: %s" % (self.name, self.lineno if lineno is None else lineno, msg))

    def _corrupt(self, e: Exception) -> FormatError:
        return self.error("corrupt or truncated input (%s)" % e, self.lineno + 1)

    def _readline(self) -> bytes:
        head = b""
        if self.pos < len(self.buf):
            k = self.buf.find(b"\n", self.pos)
            if k >= 0:
                line, self.pos = self.buf[self.pos:k + 1], k + 1
                return line
            head = self.buf[self.pos:]
        self.buf, self.pos = b"", 0
        if self.deferred is not None:
            if head:
                return head
            raise self._corrupt(self.deferred)
        try:
            return head + self.raw.readline()
        except (OSError, EOFError, gzip.BadGzipFile) as e:
            raise self._corrupt(e) from None

    def next(self) -> Optional[str]:
        """The next line without its end, or None at the end of input."""
        b = self._readline()
        if not b:
            return None
        self.lineno += 1
        if not b.endswith(b"\n"):
            raise self.error("truncated: the last line has no newline")
        s = b[:-1].decode("utf-8", "surrogateescape")
        if s.endswith("\r"):
            s = s[:-1]
        if "\0" in s:
            raise self.error("binary data (NUL byte) in a text file")
        return s

    def push(self, s: str) -> None:
        self.unread(s.encode("utf-8", "surrogateescape") + b"\n")
        self.lineno -= 1

    def take(self, n: int) -> bytes:
        """The next n lines, with their ends, as one bytes (fewer at the end of input or at a
        read error), not counted: the caller counts them (lineno += n) or gives them back
        (unread).  Read in large chunks, the n-th newline found by numpy."""
        chunks, have = [], 0
        if self.pos < len(self.buf):
            chunks.append(self.buf[self.pos:])
            have = chunks[0].count(b"\n")
        self.buf, self.pos = b"", 0
        while have < n and self.deferred is None:
            try:
                c = self.raw.read(1 << 22)
            except (OSError, EOFError, gzip.BadGzipFile) as e:
                self.deferred = e  # raised by the line-by-line reader after the lines before it
                break
            if not c:
                break
            chunks.append(c)
            have += c.count(b"\n")
        if have <= n:
            return b"".join(chunks)
        # the n-th newline is in the last chunk
        last = chunks.pop()
        before = have - last.count(b"\n")
        end = int(np.flatnonzero(np.frombuffer(last, np.uint8) == 10)[n - before - 1]) + 1
        self.unread(last[end:])
        chunks.append(last[:end])
        return b"".join(chunks)

    def unread(self, data: bytes) -> None:
        if data:
            self.buf, self.pos = data + self.buf[self.pos:], 0

    def close(self) -> None:
        if self.own:
            self.raw.close()


def _float(tok: str, what: str, lines: _Lines) -> float:
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


def _int(tok: str, what: str, lines: _Lines) -> int:
    t = tok[1:] if tok[:1] in ("+", "-") else tok
    if not (t.isascii() and t.isdigit()):
        raise lines.error("%s: '%s' is not an integer" % (what, tok))
    return int(tok)


class Pack:
    """One pack of a qusgm-pack stream (see the module's docstring for the attributes)."""

    version: int
    history: List[str]
    meta: Dict[str, str]
    units: Optional[str]
    box: np.ndarray
    refbox: Optional[np.ndarray]
    boundary: Tuple[str, str, str]
    walls: Dict[str, float]
    friction: float
    columns: Tuple[str, ...]
    grains: np.ndarray
    contacts: np.ndarray
    name: str
    line: int

    def __init__(self) -> None:
        self.version = 0
        self.history = []
        self.meta = {}
        self.units = None
        self.box = np.zeros(6)
        self.refbox = None
        self.boundary = ("walls", "walls", "walls")
        self.walls = {}
        self.friction = 0.0
        self.columns = _REQUIRED
        self.grains = np.zeros(0, dtype=[(c, _DTYPES.get(c, np.float64)) for c in _REQUIRED])
        self.contacts = np.zeros(0, dtype=_CONTACT_DTYPE)
        self.name = ""
        self.line = 0

    @property
    def n(self) -> int:
        """The number of grains."""
        return len(self.grains)

    @property
    def kinds(self) -> np.ndarray:
        """Each grain's kind (one of SHAPES): the shape column; without it, 'spheroplate'
        where side > 0 and 'sphere' elsewhere (pack-format.md, "The shape column")."""
        g = self.grains
        if "shape" in self.columns:
            return g["shape"].copy()
        if "side" in self.columns:
            return np.where(g["side"] > 0, SHAPES[1], SHAPES[0]).astype(_DTYPES["shape"])
        return np.full(len(g), SHAPES[0], dtype=_DTYPES["shape"])

    @property
    def periodic(self) -> Tuple[bool, bool, bool]:
        """Per axis x y z, whether it is periodic."""
        return (self.boundary[0] == "periodic", self.boundary[1] == "periodic", self.boundary[2] == "periodic")

    @property
    def volume(self) -> float:
        """The box's volume (m^3)."""
        b = self.box
        return float((b[3] - b[0]) * (b[4] - b[1]) * (b[5] - b[2]))

    @property
    def units_of(self) -> Dict[str, str]:
        """Column -> unit of the grain and contact columns ('' dimensionless)."""
        return {c: UNITS[c] for c in self.columns + _CONTACT_DTYPE.names}

    def to_dataframe(self, which: str = "grains") -> Any:
        """The grains (or with "contacts", the contact lines) as a pandas DataFrame, one
        column per field, the units in df.attrs["units"]: the way to pandas."""
        import pandas as pd

        if which not in ("grains", "contacts"):
            raise ValueError("to_dataframe: 'grains' or 'contacts', not %r" % (which,))
        a = self.grains if which == "grains" else self.contacts
        df = pd.DataFrame({f: a[f] for f in a.dtype.names})
        df.attrs["units"] = {f: UNITS[f] for f in a.dtype.names}
        return df

    def __repr__(self) -> str:
        return "<qusgm.Pack version %s: %d grains, %d contacts, from %s:%s>" % (
            self.version, len(self.grains), len(self.contacts), self.name, self.line)


_ONCE = ("units", "box", "refbox", "walls", "friction", "grains", "contacts", "boundary", "columns")
_REQUIRED_KEYS = ("units", "box", "walls", "friction", "grains", "contacts")


def _read_header(lines: _Lines, magic: str) -> Tuple[Pack, int, int]:
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


def _grains_slow(lines: _Lines, p: Pack, ng: int) -> np.ndarray:
    """The grain lines, one by one: the reference, and what names a wrong line."""
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
            elif c == "shape":
                v = tok[k]
                if v not in SHAPES:
                    raise lines.error("grain %s: shape '%s' is not a kind (%s)" % (tok[0], v, ", ".join(SHAPES)))
            elif c == "phase":
                v = _int(tok[k], "phase", lines)
                if v not in (0, 1):
                    raise lines.error("grain %s: phase '%s' is neither 0 (mineral) nor 1 (hydrate)"
                                      % (tok[0], tok[k]))
            else:
                v = _float(tok[k], c, lines)
            cols[k].append(v)
        if "shape" in p.columns:
            kind, side = cols[p.columns.index("shape")][-1], cols[p.columns.index("side")][-1]
            if (kind == "sphere") != (side == 0) or not side >= 0:
                raise lines.error("grain %s: a %s cannot have side %s (a sphere has side 0, a spheroplate side > 0)"
                                  % (tok[0], kind, tok[p.columns.index("side")]))
    dt = np.dtype([(c, _DTYPES.get(c, np.float64)) for c in p.columns])
    g = np.empty(ng, dtype=dt)
    for k, c in enumerate(p.columns):
        g[c] = cols[k]
    return g


def _contacts_slow(lines: _Lines, p: Pack, nc: int, g: np.ndarray) -> np.ndarray:
    """The contact lines, one by one."""
    ids = dict.fromkeys(g["id"].tolist())
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
    return c


def _spans(arr: np.ndarray, start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """The bytes of arr[start[k]:end[k]] for every k, concatenated."""
    lens = end - start
    if (lens <= 0).any():
        raise ValueError("an empty token")
    first = np.repeat(start - np.concatenate(([0], np.cumsum(lens)[:-1])), lens)
    return arr[first + np.arange(int(lens.sum()))]


def _kinds_to_numbers(data: bytes, arr: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> bytes:
    """The kind names (SHAPES) of the tokens arr[lo:hi] written over with their index in
    SHAPES, right-aligned in blanks (the same length), or ValueError at a token that is none."""
    out = np.array(arr)  # a copy to write on
    done = np.zeros(len(lo), dtype=bool)
    for k, name in enumerate(SHAPES):
        w = np.frombuffer(name.encode(), np.uint8)
        cand = (hi - lo == len(w)) & ~done
        for j in range(len(w)):
            cand &= arr[np.where(cand, lo + j, 0)] == w[j]
        at = lo[cand]
        for j in range(len(w) - 1):
            out[at + j] = 32
        out[at + len(w) - 1] = 48 + k
        done |= cand
    if not done.all():
        raise ValueError("a word that is not a kind's name")
    return out.tobytes()


def _parse_block(data: bytes, dtype: np.dtype, n: int, wall_col: int = -1,
                 kind_col: int = -1) -> Tuple[np.ndarray, np.ndarray]:
    """n lines of numbers, separated by single spaces, into a structured array, or ValueError.
    numpy's fromstring reads the numbers (its strtod rounds correctly, as Python's float()
    does); the shape is checked on the bytes first: no other blank than one space between
    tokens, as many tokens on every line as dtype has fields, and the integer fields' tokens
    made of digits and signs alone (fromstring reads '1.5' as a float where the line-by-line
    reader wants an integer).  In the column wall_col a token may be a wall's name instead,
    which is written over with a number before fromstring reads the lines; the second array
    returned is each line's wall index in WALLS there, -1 for a number.  In the column
    kind_col (an integer field) every token is a kind's name (SHAPES), read as its index."""
    ncol = len(dtype.names)
    if (b"\t" in data or b"\r" in data or b"\v" in data or b"\f" in data or b"  " in data
            or b" \n" in data or b"\n " in data or data[:1] == b" "):
        raise ValueError("not single spaces")
    arr = np.frombuffer(data, np.uint8)
    nl = np.flatnonzero(arr == 10)
    sp = np.flatnonzero(arr == 32)
    if len(nl) != n or len(sp) != n * (ncol - 1):
        raise ValueError("token count")
    if ncol > 1 and (np.diff(np.searchsorted(sp, nl), prepend=0) != ncol - 1).any():
        raise ValueError("tokens per line")
    starts = np.concatenate(([0], nl[:-1] + 1))
    walls = np.full(n, -1, dtype=np.int64)
    for k, f in enumerate(dtype.names):
        if dtype[f].kind != "i":
            continue
        lo = starts if k == 0 else sp[k - 1::ncol - 1] + 1
        hi = nl if k == ncol - 1 else sp[k::ncol - 1]
        if k == kind_col:
            data = _kinds_to_numbers(data, arr, lo, hi)
            continue
        if k == wall_col:
            # xlo xhi ylo yhi zlo zhi: x, y or z, then lo or hi; the index 2 axis + (hi)
            first = arr[lo]
            cand = (hi - lo == 3) & (first >= 120) & (first <= 122)
            at = lo[cand]
            s1, s2 = arr[at + 1], arr[at + 2]
            is_hi = (s1 == 104) & (s2 == 105)
            if not (is_hi | ((s1 == 108) & (s2 == 111))).all():
                raise ValueError("a word that is not a wall's name")
            walls[cand] = (first[cand] - 120) * 2 + is_hi
            lo, hi = lo[~cand], hi[~cand]
            if len(at):  # the names written over with 0 (the same length), one copy
                pieces, prev = [], 0
                for q in at.tolist():
                    pieces += (data[prev:q], b"  0")
                    prev = q + 3
                pieces.append(data[prev:])
                data = b"".join(pieces)
        if len(lo):
            b = _spans(arr, lo, hi)
            if not (((b >= 48) & (b <= 57)) | (b == 43) | (b == 45)).all():
                raise ValueError("an integer field that is not digits")
    v = np.fromstring(data, dtype=np.float64, sep=" ")  # warns (an error here) at a bad token
    if v.size != n * ncol:
        raise ValueError("numbers")
    v = v.reshape(n, ncol)
    a = np.empty(n, dtype=dtype)
    for k, f in enumerate(dtype.names):
        col = v[:, k]
        if dtype[f].kind == "i":
            if not (np.abs(col) <= 2.0 ** 53).all():
                raise ValueError("an integer beyond 2^53")
            if not (col == col.astype(dtype[f])).all():
                raise ValueError("an integer out of range")
        a[f] = col
    return a, walls


# Lines parsed per call of _parse_block: its buffers stay a few megabytes, reused, where a
# whole large pack's would be fresh pages each time (a third more time, in the kernel).
_CHUNK = 1 << 16


def _parse_lines(lines: _Lines, n: int, dtype: np.dtype, wall_col: int = -1,
                 kind_col: int = -1) -> Tuple[Optional[np.ndarray], np.ndarray, bytes]:
    """The next n lines parsed by numpy's C parser (_parse_block, _CHUNK lines at a time) into
    a structured array, or None where it cannot (a token that is not a number of the field's
    kind, a line of another length, fewer lines, a blank or a NUL byte...); the lines' walls
    (_parse_block); the raw lines, for lines.unread."""
    raws: List[bytes] = []
    parts: List[np.ndarray] = []
    wparts: List[np.ndarray] = []
    left = n
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # fromstring warns at a token it cannot read
        while left > 0:
            m = min(left, _CHUNK)
            block = lines.take(m)  # fewer lines than m: _parse_block counts them
            raws.append(block)
            if b"\0" in block or b"#" in block or b"\r" in block:
                return None, np.zeros(0, dtype=np.int64), b"".join(raws)
            try:
                a, w = _parse_block(block, dtype, m, wall_col, kind_col)
            except Exception:  # whatever the C parser refuses, the line-by-line reader names
                return None, np.zeros(0, dtype=np.int64), b"".join(raws)
            parts.append(a)
            wparts.append(w)
            left -= m
    if not parts:
        return np.zeros(0, dtype=dtype), np.zeros(0, dtype=np.int64), b""
    return np.concatenate(parts), np.concatenate(wparts), b"".join(raws)


def _grains_fast(lines: _Lines, p: Pack, ng: int) -> Optional[np.ndarray]:
    """The grain lines through a C parser, checked as _grains_slow checks them; None,
    the lines given back, where any check fails."""
    kind_col = p.columns.index("shape") if "shape" in p.columns else -1
    dt = np.dtype([(c, np.int8 if c == "shape" else _DTYPES.get(c, np.float64)) for c in p.columns])
    g, _, block = _parse_lines(lines, ng, dt, kind_col=kind_col)
    if g is not None and kind_col >= 0:  # the kinds' indices as their names
        ok = ((g["shape"] == 0) == (g["side"] == 0)).all() and (g["side"] >= 0).all()
        names = np.array(SHAPES, dtype=_DTYPES["shape"])[g["shape"]]
        g2 = np.empty(ng, dtype=[(c, _DTYPES.get(c, np.float64)) for c in p.columns])
        for c in p.columns:
            g2[c] = names if c == "shape" else g[c]
        g = g2 if ok else None
    if g is not None:
        floats = [c for c in p.columns if c not in _DTYPES]
        ok = all(np.isfinite(g[c]).all() for c in floats)
        ok = ok and (g["id"] >= 0).all() and np.unique(g["id"]).size == ng
        if "phase" in p.columns:
            ok = ok and ((g["phase"] == 0) | (g["phase"] == 1)).all()
        if ok:
            lines.lineno += ng
            return g
    lines.unread(block)
    return None


def _contacts_fast(lines: _Lines, p: Pack, nc: int, g: np.ndarray) -> Optional[np.ndarray]:
    """The contact lines through a C parser, checked as _contacts_slow checks them."""
    if nc == 0:
        return np.zeros(0, dtype=_CONTACT_DTYPE)
    dt = np.dtype([("i", np.int64), ("j", np.int64), ("P0", np.float64), ("Q0x", np.float64),
                   ("Q0y", np.float64), ("Q0z", np.float64), ("M0", np.float64)])
    a, walls, block = _parse_lines(lines, nc, dt, wall_col=1)
    if a is not None:
        ids = np.sort(g["id"])
        i, j = a["i"], a["j"]
        wall = walls >= 0
        w = np.where(wall, walls, 0)
        ok = all(np.isfinite(a[f]).all() for f in ("P0", "Q0x", "Q0y", "Q0z", "M0"))
        ok = ok and bool((a["P0"] >= 0).all())
        k = np.clip(np.searchsorted(ids, i), 0, len(ids) - 1)
        ok = ok and bool((ids[k] == i).all())
        jg = j[~wall]
        k = np.clip(np.searchsorted(ids, jg), 0, len(ids) - 1)
        ok = ok and bool((ids[k] == jg).all()) and bool((jg != i[~wall]).all())
        for axis, periodic in enumerate(p.periodic):
            if periodic:
                ok = ok and not (wall & (w // 2 == axis)).any()
        if ok:
            c = np.zeros(nc, dtype=_CONTACT_DTYPE)
            c["i"] = i
            c["j"] = np.where(wall, -1 - w, j)
            c["j_wall"] = np.where(wall, np.array(WALLS)[w], "")
            for f in ("P0", "Q0x", "Q0y", "Q0z", "M0"):
                c[f] = a[f]
            lines.lineno += nc
            return c
    lines.unread(block)
    return None


def _read_body(lines: _Lines, p: Pack, ng: int, nc: int, fast: bool = True) -> Pack:
    """The grain and contact lines: numpy's C parser (fast) where it can, line by line where
    it cannot or finds something wrong, so that the error names its line; the same arrays,
    byte for byte, either way (tests/tools/python.sh)."""
    g = _grains_fast(lines, p, ng) if fast else None
    if g is None:
        g = _grains_slow(lines, p, ng)
    c = _contacts_fast(lines, p, nc, g) if fast else None
    if c is None:
        c = _contacts_slow(lines, p, nc, g)
    p.grains, p.contacts = g, c
    return p


def read_packs(source: Source, fast: bool = True) -> Iterator[Pack]:
    """Every pack of a stream, in order (a generator): source is a path, '-' (stdin) or a
    binary file object, plain or gzip.  fast=False reads every line in Python (the same
    arrays, slower: the reference the fast path is tested against)."""
    lines = _Lines(source)
    try:
        s = lines.next()
        if s is None:
            raise lines.error("empty input", 1)
        while s is not None:
            p, ng, nc = _read_header(lines, s)
            yield _read_body(lines, p, ng, nc, fast)
            s = lines.next()
            if s is not None and not s.startswith("qusgm-pack"):
                raise lines.error("unexpected line after the last contact")
    finally:
        lines.close()


def read_pack(source: Source, fast: bool = True) -> Pack:
    """Exactly one pack (as the tools that transform one pack read): see read_packs."""
    lines = _Lines(source)
    try:
        s = lines.next()
        if s is None:
            raise lines.error("empty input", 1)
        p, ng, nc = _read_header(lines, s)
        _read_body(lines, p, ng, nc, fast)
        s = lines.next()
        if s is not None:
            raise lines.error("a second pack follows; use read_packs" if s.startswith("qusgm-pack")
                              else "unexpected line after the last contact")
        return p
    finally:
        lines.close()


class Table:
    """A qusgm table (see the module's docstring)."""

    names: List[str]
    units: Dict[str, str]
    meta: List[str]
    data: np.ndarray
    name: str

    def __init__(self, names: List[str], units: Dict[str, str], meta: List[str], data: np.ndarray,
                 name: str) -> None:
        self.names, self.units, self.meta, self.data, self.name = names, units, meta, data, name

    def __getitem__(self, name: str) -> np.ndarray:
        return self.data[name]

    def __len__(self) -> int:
        return len(self.data)

    def __contains__(self, name: object) -> bool:
        return name in self.units

    @property
    def text_columns(self) -> List[str]:
        """The columns of text (their dtype str), in order."""
        return [n for n in self.names if self.data.dtype[n].kind == "U"]

    def to_dataframe(self) -> Any:
        """The table as a pandas DataFrame (text columns as str, the others float64), the units
        in df.attrs["units"]: the way to pandas."""
        import pandas as pd

        df = pd.DataFrame({f: self.data[f] for f in self.names})
        df.attrs["units"] = dict(self.units)
        return df

    def __repr__(self) -> str:
        return "<qusgm.Table %s: %d rows, columns %s>" % (self.name, len(self.data), " ".join(self.names))


def _split_name(field: str) -> Tuple[str, str]:
    """'sig_zz[Pa]' -> ('sig_zz', 'Pa'); 'porosity' -> ('porosity', '')."""
    if field.endswith("]") and "[" in field:
        k = field.index("[")
        if k > 0:
            return field[:k], field[k + 1:-1]
    return field, ""


def _table_number(t: str) -> float:
    """A table's number as strtod reads it (nan allowed), or ValueError."""
    if "_" in t or t != t.strip():
        raise ValueError(t)
    return float.fromhex(t) if "x" in t or "X" in t else float(t)


def read_table(source: Source) -> Table:
    """A table (path, '-' or binary file object; plain or gzip).  '##' lines anywhere are
    collected in meta, repeats of the header (concatenated tables) skipped, a different
    header refused, as the tools' table reader does.  A column whose value in the first row
    is not a number (densify's stage) is a text column, read as str; in every other column
    each value must be a number ('nan' included)."""
    lines = _Lines(source)
    header, names, meta, rows = None, [], [], []
    text: List[bool] = []
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
            if not rows:
                for t in tok:
                    try:
                        _table_number(t)
                        text.append(False)
                    except ValueError:
                        text.append(True)
            row: List[Union[float, str]] = []
            for t, (n, _), is_text in zip(tok, names, text):
                if is_text:
                    row.append(t)
                    continue
                try:
                    row.append(_table_number(t))
                except ValueError:
                    raise lines.error("column %s: '%s' is not a number" % (n, t)) from None
            rows.append(tuple(row))
        if header is None:
            raise FormatError("%s: empty (no header line)" % lines.name)
    finally:
        lines.close()
    if not rows:
        text = [False] * len(names)
    width = [max([len(r[k]) for r in rows] + [1]) if is_text else 0 for k, is_text in enumerate(text)]  # type: ignore[arg-type]
    dt = [(n, "U%d" % w if is_text else np.float64) for (n, _), is_text, w in zip(names, text, width)]
    data = np.array(rows, dtype=dt)
    return Table([n for n, _ in names], {n: u for n, u in names}, meta, data, lines.name)
