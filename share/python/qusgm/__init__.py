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
report it.  A pack is held to every rule of qusgm's own reader (lib/pack/packio.c), and refused
with its words: the same inputs as packinfo(1) refuses, the same message after its "packinfo: "
(tests/tools/readers.sh runs both over tests/corpus/packs and the fuzz corpus).  Memory grows
with the input read, never with a count a header declares.
"""

from __future__ import annotations

import io
import math
import os
import re
import sys
import warnings
import zlib
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
    "glued": "", "i": "", "j": "", "j_wall": "", "P0": "N", "Q0x": "N", "Q0y": "N", "Q0z": "N", "M0": "N m",
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
_DTYPES = {"id": np.int64, "phase": np.int8, "shape": "U%d" % max(len(k) for k in SHAPES), "glued": "U3"}
_CONTACT_DTYPE = np.dtype([("i", np.int64), ("j", np.int64), ("j_wall", "U3"), ("P0", np.float64),
                           ("Q0x", np.float64), ("Q0y", np.float64), ("Q0z", np.float64),
                           ("M0", np.float64)])

class FormatError(ValueError):
    """A malformed pack or table: the message is "FILE:LINE: what is wrong"."""


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


# ---- the bytes: plain or gzip, as lib/base/lines.c reads them ----

_MiB = 1 << 20
_READ = 1 << 16  # the C reader's chunk: what it sniffs for a foreign format

# What the first bytes of the text say when they are not text (lib/base/lines.c,
# foreign_start): the C reader's words.
_FOREIGN = (
    (b"\xfd7zXZ\0", "xz-compressed: decompress it first (xz -d FILE; qusgm reads plain text and gzip)"),
    (b"BZh", "bzip2-compressed: decompress it first (bzip2 -d FILE; qusgm reads plain text and gzip)"),
    (b"\x28\xb5\x2f\xfd", "zstd-compressed: decompress it first (zstd -d FILE; qusgm reads plain text and gzip)"),
    (b"\x04\x22\x4d\x18", "lz4-compressed: decompress it first (lz4 -d FILE; qusgm reads plain text and gzip)"),
    (b"\x1f\x9d", "compressed by compress (.Z): decompress it first (gzip -d FILE; qusgm reads plain text and gzip)"),
    (b"PK\x03\x04", "a zip archive: extract the file first (unzip)"),
    (b"\xef\xbb\xbf", "a UTF-8 byte-order mark (bytes EF BB BF) starts the file: save it without one "
                      "(sed -i '1s/^\\xEF\\xBB\\xBF//' FILE)"),
    (b"\xff\xfe", "UTF-16 text (byte-order mark FF FE): convert it (iconv -f UTF-16 -t UTF-8 FILE)"),
    (b"\xfe\xff", "UTF-16 text (byte-order mark FE FF): convert it (iconv -f UTF-16 -t UTF-8 FILE)"),
)


def _foreign(b: bytes) -> Optional[str]:
    # zlib's own format (RFC 1950: CM 8, the header a multiple of 31), which is no text
    if (len(b) >= 2 and (b[0] & 0x0F) == 8 and (b[0] >> 4) <= 7 and ((b[0] << 8) | b[1]) % 31 == 0
            and not b[1] & 0x20 and (b"\0" in b[:64] or b[1] < 0x20 or b[1] >= 0x7F)):
        return ("zlib-compressed data (no gzip header): only gzip is read; decompress it first (pigz -dz FILE, or "
                "python3 -c 'import sys, zlib; sys.stdout.buffer.write(zlib.decompress(sys.stdin.buffer.read()))' <FILE)")
    for magic, what in _FOREIGN:
        if b.startswith(magic):
            # bzip2: "BZh", a block size 1-9, then the block magic (pi's digits)
            if magic == b"BZh" and (len(b) < 10 or not 0x31 <= b[3] <= 0x39 or b[4:10] != b"\x31\x41\x59\x26\x53\x59"):
                continue
            return what
    return None


class _StreamError(Exception):
    """A read error or a corrupt gzip stream, met after the bytes before it were handed out:
    what, and why (the C reader's "what (why)")."""

    def __init__(self, what: str, why: Optional[str]) -> None:
        super().__init__(what)
        self.what, self.why = what, why

    def text(self) -> str:
        return self.what + (" (%s)" % self.why if self.why else "")


class _Source:
    """The text of an input: plain, or gzip (told by its first two bytes) inflated member
    after member, anything after a member that is not one refused, as lib/base/lines.c does.
    read(n) gives at most about n bytes, b"" at the end; an error is raised (_StreamError)
    only once every byte decoded before it has been given.  Memory: what one read asks."""

    def __init__(self, fp: IO[bytes]) -> None:
        self.fp = fp
        self.raw = b""
        self.raw_eof = False
        self.gzip: Optional[bool] = None
        self.z: Any = None
        self.member_end = False
        self.pending: Optional[_StreamError] = None
        self.eof = False

    def _raw(self, n: int) -> bytes:
        """Up to n more raw bytes (b"" at the end)."""
        if self.raw_eof:
            return b""
        try:
            b = self.fp.read(n)
        except OSError as e:
            raise _StreamError("read error", e.strerror or str(e)) from None
        if not b:
            self.raw_eof = True
        return b or b""

    def read(self, n: int = _READ) -> bytes:
        if self.pending is not None:
            raise self.pending
        if self.eof:
            return b""
        if self.gzip is None:
            while len(self.raw) < 2:
                b = self._raw(_READ)
                if not b:
                    break
                self.raw += b
            self.gzip = self.raw[:2] == b"\x1f\x8b"
            if self.gzip:
                self.z = zlib.decompressobj(16 + zlib.MAX_WBITS)
        if not self.gzip:
            out = self.raw[:n]
            self.raw = self.raw[n:]
            while len(out) < n:
                b = self._raw(n - len(out))
                if not b:
                    break
                out += b
            if not out:
                self.eof = True
            return out
        out = self._inflate(n)
        if not out:
            if self.pending is not None:
                raise self.pending
            self.eof = True
        return out

    def _stop(self, parts: List[bytes], what: str, why: Optional[str]) -> bytes:
        self.pending = _StreamError(what, why)
        return b"".join(parts)

    def _inflate(self, n: int) -> bytes:
        parts: List[bytes] = []
        have = 0
        while have < n:
            if self.member_end:  # the next member's magic, or the end of the input
                while len(self.raw) < 2:
                    b = self._raw(_READ)
                    if not b:
                        break
                    self.raw += b
                if not self.raw:
                    self.eof = True
                    break
                if self.raw[0] == 0:  # zero padding (a tape block), as gzip -d accepts
                    while True:
                        if self.raw.count(0) != len(self.raw):
                            return self._stop(parts, "trailing data after the end of the gzip stream",
                                              "zero bytes, then others: neither padding nor a gzip member")
                        self.raw = self._raw(_READ)
                        if not self.raw:
                            self.eof = True
                            return b"".join(parts)
                        if self.raw[0] != 0:
                            return self._stop(parts, "trailing data after the end of the gzip stream",
                                              "zero bytes, then others: neither padding nor a gzip member")
                if self.raw[:2] != b"\x1f\x8b":
                    return self._stop(parts, "trailing data after the end of the gzip stream",
                                      "not a gzip member; gzip -t calls it trailing garbage: a file appended to a .gz one?")
                self.z = zlib.decompressobj(16 + zlib.MAX_WBITS)
                self.member_end = False
            if not self.raw:
                self.raw = self._raw(_READ)
                if not self.raw:
                    return self._stop(parts, "corrupt or truncated input", "unexpected end of compressed data")
            data, self.raw = self.raw, b""
            before = self.z.copy()
            try:
                o = self.z.decompress(data, n - have)
            except zlib.error:
                # inflate again a byte at a time, from before this call, to hand out every
                # byte decoded before the error (as zlib's inflate does)
                self.z = before
                for k in range(len(data)):
                    try:
                        o = self.z.decompress(data[k:k + 1])
                    except zlib.error as e:
                        m = str(e)
                        return self._stop(parts, "corrupt or truncated input",
                                          m.split(": ", 1)[1] if ": " in m else "corrupt data")
                    parts.append(o)
                    if self.z.eof:
                        self.raw = self.z.unused_data + data[k + 1:]
                        self.member_end = True
                        break
                continue
            parts.append(o)
            have += len(o)
            if self.z.eof:
                self.raw = self.z.unused_data
                self.member_end = True
            else:
                self.raw = self.z.unconsumed_tail
        return b"".join(parts)


def _open(source: Source) -> Tuple[IO[bytes], str, bool]:
    """(binary stream, display name, whether to close it) for a path, '-' or a file object."""
    if source is None or source == "-":
        return sys.stdin.buffer, "<stdin>", False
    if hasattr(source, "read"):
        fp = source.buffer if isinstance(source, io.TextIOBase) else source  # type: ignore[union-attr]
        return fp, getattr(source, "name", "<stream>"), False  # type: ignore[return-value]
    return open(source, "rb"), os.fsdecode(source), True  # type: ignore[arg-type]


class _Lines:
    """Numbered text lines of an input, as lib/base/lines.c and lib/pack/packio.c cut them:
    one '\\r' before the '\\n' dropped; a foreign format (another compression, a byte-order
    mark, UTF-16), a NUL byte, old Mac line endings refused with the C reader's words.  Read
    as bytes, so that a block of lines can go to a C parser whole (take) and come back
    (unread) for the line-by-line reader to name the line that is wrong."""

    def __init__(self, source: Source) -> None:
        fp, self.name, self.own = _open(source)
        self.fp = fp
        self.src = _Source(fp)
        self.lineno = 0
        self.buf = b""  # bytes read ahead (take) or given back (unread), before the source's
        self.pos = 0
        self.scan = 0  # where to look on for a newline in buf (none before it)
        self.sniffed = False
        self.deferred: Optional[_StreamError] = None  # met by take, raised after buf's lines
        self.newline = True  # the last line read ended in '\n'

    def error(self, msg: str, lineno: Optional[int] = None) -> FormatError:
        line = self.lineno if lineno is None else lineno
        return FormatError("%s:%d: %s" % (self.name, line if line > 0 else 1, msg))

    def _more(self, n: int = _READ) -> bytes:
        """The source's next bytes (b"" at the end); an error after them as deferred."""
        if self.deferred is not None:
            return b""
        try:
            b = self.src.read(n)
        except _StreamError as e:
            self.deferred = e
            return b""
        if not self.sniffed and b:
            # at least the bytes a foreign format is told by (the C reader sniffs a chunk)
            while len(b) < 16 and self.deferred is None:
                try:
                    c = self.src.read(n)
                except _StreamError as e:
                    self.deferred = e
                    c = b""
                if not c:
                    break
                b += c
            self.sniffed = True
            if self.src.gzip and b[:2] == b"\x1f\x8b":
                raise self.error("a gzip inside a gzip (compressed twice): decompress it once "
                                 "(gzip -d FILE), and the inner gzip is read", 1)
            why = _foreign(b)
            if why:
                raise self.error(("inside the gzip stream, " if self.src.gzip else "") + why, 1)
        return b

    def _readline(self) -> Tuple[bytes, bool]:
        """The next line's bytes without the '\\n', and whether it had one; (b"", False) at
        the end."""
        while True:
            k = self.buf.find(b"\n", max(self.pos, self.scan))
            if k >= 0:
                line = self.buf[self.pos:k]
                self.pos = self.scan = k + 1
                return line, True
            self.scan = len(self.buf)
            more = self._more()
            if not more:
                if self.deferred is not None:  # an error reported at the line being read
                    raise self.error(self.deferred.text(), self.lineno + 1)
                line = self.buf[self.pos:]
                self.buf, self.pos, self.scan = b"", 0, 0
                return line, False
            if self.pos:
                self.buf, self.scan, self.pos = self.buf[self.pos:], self.scan - self.pos, 0
            self.buf += more

    def next(self, table: bool = False) -> Optional[str]:
        """The next line without its end, or None at the end of input; the pack reader's
        checks (a newline at its end, no '\\r' inside), or with table, the table reader's."""
        b, nl = self._readline()
        if not b and not nl:
            return None
        if b.endswith(b"\r"):
            b = b[:-1]
        self.lineno += 1
        self.newline = nl
        if b"\0" in b:
            raise self.error("binary data (NUL byte) in a text file")
        if self.lineno == 1 and not nl and b"\r" in b:
            raise self.error("CR line endings (old Mac): convert them (tr '\\r' '\\n' < FILE)")
        if not nl:
            raise self.error("the last line has no newline (truncated?)" if table
                             else "truncated: the last line has no newline")
        if b"\r" in b and not table:
            raise self.error("a carriage return (\\r) inside a line (only one, just before the newline, is allowed)")
        return b.decode("utf-8", "surrogateescape")

    def push(self, s: str) -> None:
        self.unread(s.encode("utf-8", "surrogateescape") + b"\n")
        self.lineno -= 1

    def take(self, n: int) -> bytes:
        """The next n lines, with their ends, as one bytes (fewer at the end of input or at a
        read error), not counted: the caller counts them (lineno += n) or gives them back
        (unread).  Read in chunks of a few megabytes, the n-th newline found by numpy."""
        chunks, have = [], 0
        if self.pos < len(self.buf):
            chunks.append(self.buf[self.pos:])
            have = chunks[0].count(b"\n")
        self.buf, self.pos, self.scan = b"", 0, 0
        while have < n:
            c = self._more(4 * _MiB)
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
            self.buf, self.pos, self.scan = data + self.buf[self.pos:], 0, 0

    def close(self) -> None:
        if self.own:
            self.fp.close()


# ---- numbers and fields, as the C reader's strtod, strtol and split ----

_CSPACE = "[ \t\n\v\f\r]*"  # what strtod and strtol skip before a number (the C locale's isspace)
_DEC = re.compile(_CSPACE + r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?\Z")
_HEX = re.compile(_CSPACE + r"[+-]?0[xX](?:[0-9a-fA-F]+\.?[0-9a-fA-F]*|\.[0-9a-fA-F]+)(?:[pP][+-]?[0-9]+)?\Z")
_LONG = re.compile(_CSPACE + r"[+-]?[0-9]+\Z")
_LONG_MIN, _LONG_MAX = -(1 << 63), (1 << 63) - 1


def _num(tok: str) -> Optional[float]:
    """A finite double as num_parse (strtod, the whole token, ASCII, C locale) reads it, or
    None: no Unicode digits or blanks, no '_', no inf or nan, no overflow."""
    try:
        if _DEC.match(tok):
            v = float(tok)
        elif _HEX.match(tok):
            v = float.fromhex(tok.strip(" \t\n\v\f\r"))
        else:
            return None
    except (ValueError, OverflowError):
        return None
    return v if math.isfinite(v) else None


def _long(tok: str) -> Optional[int]:
    """An integer as num_parse_long (strtol base 10, the whole token, a 64-bit long) reads
    it, or None."""
    if not _LONG.match(tok):
        return None
    v = int(tok.strip(" \t\n\v\f\r"))
    return v if _LONG_MIN <= v <= _LONG_MAX else None


def _split(s: str) -> List[str]:
    """The fields of a line, separated by spaces and tabs (no other blank)."""
    return [t for t in s.replace("\t", " ").split(" ") if t]


def _g(v: float) -> str:
    """C's %g."""
    return "%g" % v


# ---- the pack's rules (lib/pack/packio.h) ----

_MU_MAX = 10.0
_E_MIN, _E_MAX, _WALL_E_MAX = 1e3, 1e13, 1e15
_QUAT_TOL = 1e-6
_BOX_MAX = 1e3  # lib/pack/pack.h: PACK_BOX_MAX
_SQRT2 = math.sqrt(2.0)  # M_SQRT2
_MAX_COUNT = 1000000000
_MAGIC = "qusgm-pack"
_EXPECT = "'%s %d' or '%s %d'" % (_MAGIC, VERSIONS[0], _MAGIC, VERSIONS[-1])

# The grain columns, in the order writers put them, and their groups (lib/pack/packio.c).
_COLUMNS = (("id", 0), ("x", 0), ("y", 0), ("z", 0), ("r", 0), ("E", 0), ("nu", 0), ("rho", 0),
            ("shape", 1), ("side", 2), ("qw", 2), ("qx", 2), ("qy", 2), ("qz", 2), ("phase", 3),
            ("glued", 4))
_GROUP = dict(_COLUMNS)
_GROUPS = ("required", "kind", "shape", "phase", "glued")


def _group_names(g: int) -> List[str]:
    return [c for c, k in _COLUMNS if k == g]


class _Header:
    """What the header declares, as it is read."""

    def __init__(self, lines: _Lines, p: Pack) -> None:
        self.lines, self.p = lines, p
        self.version = 0
        self.ngr = self.nco = 0
        self.seen: set = set()
        self.colnames = " ".join(_REQUIRED)

    def error(self, msg: str) -> FormatError:
        return self.lines.error(msg)


def _numbers(h: _Header, tok: List[str], what: str) -> List[float]:
    v = []
    for t in tok:
        x = _num(t)
        if x is None:
            raise h.error("%s: '%s' is not a finite number" % (what, t))
        v.append(x)
    return v


def _kw_units(h: _Header, tok: List[str]) -> None:
    if len(tok) != 2 or tok[1] != "SI":
        raise h.error("units: only 'units SI' is defined")
    h.p.units = "SI"


def _kw_box(h: _Header, tok: List[str]) -> None:
    if len(tok) != 7:
        raise h.error("%s: expected 6 numbers (xlo ylo zlo xhi yhi zhi), found %d" % (tok[0], len(tok) - 1))
    v = _numbers(h, tok[1:], tok[0])
    for a in range(3):
        if not v[a + 3] > v[a]:
            raise h.error("%s: upper bound %s not above lower bound %s on axis %s"
                          % (tok[0], _g(v[a + 3]), _g(v[a]), "xyz"[a]))
    for a in range(6):
        if not abs(v[a]) <= _BOX_MAX:
            raise h.error("%s: bound %s m is outside [-%s, %s] m (a pack of grains, in metres)"
                          % (tok[0], _g(v[a]), _g(_BOX_MAX), _g(_BOX_MAX)))
    setattr(h.p, tok[0], np.array(v))


def _kw_walls(h: _Header, tok: List[str]) -> None:
    if len(tok) != 4:
        raise h.error("walls: expected 3 numbers (E nu mu), found %d" % (len(tok) - 1))
    E, nu, mu = _numbers(h, tok[1:], "walls")
    if not E > 0:
        raise h.error("walls: Young's modulus %s is not positive" % _g(E))
    if not _E_MIN <= E <= _WALL_E_MAX:
        raise h.error("walls: Young's modulus %s Pa is outside [%s, %s] Pa" % (_g(E), _g(_E_MIN), _g(_WALL_E_MAX)))
    if not -1 < nu < 0.5:
        raise h.error("walls: Poisson ratio %s is outside (-1, 0.5)" % _g(nu))
    if not mu >= 0:
        raise h.error("walls: friction coefficient %s is negative" % _g(mu))
    if not mu <= _MU_MAX:
        raise h.error("walls: friction coefficient %s is outside [0, %s] (the range of the tools' --mu)"
                      % (_g(mu), _g(_MU_MAX)))
    h.p.walls = {"E": E, "nu": nu, "mu": mu}


def _kw_friction(h: _Header, tok: List[str]) -> None:
    if len(tok) != 2:
        raise h.error("friction: expected 1 number (mu), found %d" % (len(tok) - 1))
    mu = _numbers(h, tok[1:], "friction")[0]
    if not mu >= 0:
        raise h.error("friction: coefficient %s is negative" % _g(mu))
    if not mu <= _MU_MAX:
        raise h.error("friction: coefficient %s is outside [0, %s] (the range of the tools' --mu)" % (_g(mu), _g(_MU_MAX)))
    h.p.friction = mu


def _kw_count(h: _Header, tok: List[str]) -> None:
    grains = tok[0] == "grains"
    if len(tok) != 2:
        raise h.error("%s: expected 1 count, found %d" % (tok[0], len(tok) - 1))
    v = _long(tok[1])
    if v is None or v < (1 if grains else 0) or v > _MAX_COUNT:
        raise h.error("%s: '%s' is not a valid count" % (tok[0], tok[1]))
    if grains:
        h.ngr = v
    else:
        h.nco = v


def _kw_columns(h: _Header, tok: List[str]) -> None:
    n = len(tok)
    if n < 2:
        raise h.error("columns: expected the names of the grain columns (%s ...)" % h.colnames)
    named: set = set()
    have = [0] * len(_GROUPS)
    for t in tok[1:]:
        if t not in _GROUP:
            raise h.error("columns: unknown column '%s'" % t)
        if t in named:
            raise h.error("columns: column '%s' named twice" % t)
        named.add(t)
        have[_GROUP[t]] += 1
    for c in _REQUIRED:
        if c not in named:
            raise h.error("columns: the required column '%s' is missing" % c)
    k = 1
    for c in _REQUIRED:
        if tok[k] != c:
            raise h.error("columns: column %d must be '%s' (the required columns come first, in the order %s)"
                          % (k, c, h.colnames))
        k += 1
    for g in range(1, len(_GROUPS)):
        names = _group_names(g)
        if have[g] and have[g] < len(names):
            missing = [c for c in names if c not in named][0]
            raise h.error("columns: only some of the %s columns (%s): they come all %d or none; '%s' is missing"
                          % (_GROUPS[g], " ".join(names), len(names), missing))
    last = 0
    while k < n:
        g = _GROUP[tok[k]]
        if g < last:
            raise h.error("columns: column %d '%s': the %s columns come before the %s columns"
                          % (k, tok[k], _GROUPS[g], _GROUPS[last]))
        names = _group_names(g)
        for c in names:
            if k >= n or tok[k] != c:
                raise h.error("columns: column %d must be '%s' (the %s columns come together, in the order %s)"
                              % (k, c, _GROUPS[g], " ".join(names)))
            k += 1
        last = g
    h.colnames = " ".join(tok[1:])
    if have[1] and not have[2]:
        raise h.error("columns: 'shape' (the grains' kinds) needs the shape columns (side qw qx qy qz)")
    h.p.columns = tuple(tok[1:])


def _kw_boundary(h: _Header, tok: List[str]) -> None:
    if len(tok) != 4:
        raise h.error("boundary: expected 3 words (x y z, each 'walls' or 'periodic'), found %d" % (len(tok) - 1))
    for a in range(3):
        if tok[1 + a] not in ("walls", "periodic"):
            raise h.error("boundary: '%s' for axis %s is neither 'walls' nor 'periodic'" % (tok[1 + a], "xyz"[a]))
    h.p.boundary = (tok[1], tok[2], tok[3])


# name: (since version, required, parser), in the C reader's order
_KEYWORDS = (("units", 1, True, _kw_units), ("box", 1, True, _kw_box), ("refbox", 1, False, _kw_box),
             ("walls", 1, True, _kw_walls), ("friction", 1, True, _kw_friction),
             ("grains", 1, True, _kw_count), ("contacts", 1, True, _kw_count),
             ("columns", 2, True, _kw_columns), ("boundary", 2, True, _kw_boundary))


def _starts_word(s: str, w: str) -> bool:
    return s.startswith(w) and s[len(w):len(w) + 1] in (" ", "\t")


def _header_meta(h: _Header, s: str) -> None:
    rest = s[5:].lstrip(" \t")
    k = min([i for i in (rest.find(" "), rest.find("\t")) if i >= 0], default=-1)
    if not rest or k < 0:
        raise h.error("meta: expected a key and a value")
    key, val = rest[:k], rest[k + 1:].lstrip(" \t")
    if not val:
        raise h.error("meta: expected a key and a value")
    if key in h.p.meta:
        raise h.error("meta: duplicate key '%s'" % key)
    h.p.meta[key] = val


def _read_header(lines: _Lines, magic: str) -> Tuple[Pack, int, int]:
    p = Pack()
    p.name, p.line = lines.name, lines.lineno
    h = _Header(lines, p)
    tok = _split(magic)
    if not tok or tok[0] != _MAGIC:
        raise lines.error("not a qusgm pack (first line must be %s)" % _EXPECT)
    v = _long(tok[1]) if len(tok) == 2 else None
    if v is None:
        raise lines.error("%s: missing or malformed version" % _MAGIC)
    if v > VERSIONS[-1]:
        raise lines.error("pack format version %d is newer than this qusgm reads (%d); upgrade qusgm" % (v, VERSIONS[-1]))
    if v < VERSIONS[0]:
        raise lines.error("unknown pack format version %d" % v)
    p.version = h.version = v
    while True:
        s = lines.next()
        if s is None:
            raise lines.error("unexpected end of input in the header (no 'end' line)", lines.lineno + 1)
        if s.startswith("#"):
            continue
        if _starts_word(s, "history"):
            p.history.append(s[8:])
            continue
        if _starts_word(s, "meta"):
            _header_meta(h, s)
            continue
        tok = _split(s)
        if not tok:
            raise lines.error("empty line in the header")
        if tok[0] == "end":
            if len(tok) != 1:
                raise lines.error("end: unexpected text after 'end'")
            break
        for name, since, _, parse in _KEYWORDS:
            if tok[0] == name:
                break
        else:
            raise lines.error("unknown header keyword '%s'" % tok[0])
        if h.version < since:
            raise lines.error("%s: not in version %d of the format (a pack with a %s line starts '%s %d')"
                              % (name, h.version, name, _MAGIC, since))
        if name in h.seen:
            raise lines.error("duplicate '%s' line (the header must contain exactly one)" % name)
        h.seen.add(name)
        parse(h, tok)
    for name, since, required, _ in _KEYWORDS:
        if required and h.version >= since and name not in h.seen:
            raise lines.error("missing '%s' line in the header" % name)
    return p, h.ngr, h.nco


def _grain_why(p: Pack, gid: int, v: Dict[str, Any]) -> Optional[str]:
    """lib/pack/packio.c's check_grain_values: what is wrong with one grain, or None."""
    box = p.box
    if gid < 0:
        return "grain id %d is negative" % gid
    if not v["r"] > 0:
        return "grain %d: radius %s is not positive" % (gid, _g(v["r"]))
    if not v["E"] > 0:
        return "grain %d: Young's modulus %s is not positive" % (gid, _g(v["E"]))
    if not _E_MIN <= v["E"] <= _E_MAX:
        return "grain %d: Young's modulus %s Pa is outside [%s, %s] Pa" % (gid, _g(v["E"]), _g(_E_MIN), _g(_E_MAX))
    if not -1 < v["nu"] < 0.5:
        return "grain %d: Poisson ratio %s is outside (-1, 0.5)" % (gid, _g(v["nu"]))
    if not v["rho"] > 0:
        return "grain %d: density %s is not positive" % (gid, _g(v["rho"]))
    shapes = "side" in v
    if shapes and not v["side"] >= 0:
        return "grain %d: side %s is negative" % (gid, _g(v["side"]))
    if shapes and "shape" in v and (v["side"] == 0) != (v["shape"] == "sphere"):
        return ("grain %d: a %s cannot have side %s (a sphere has side 0, a spheroplate side > 0)"
                % (gid, v["shape"], _g(v["side"])))
    g = v.get("glued", "-")
    if g != "-" and p.periodic[WALLS.index(g) // 2]:
        return "grain %d: glued to %s, but that axis is periodic" % (gid, g)
    if shapes:
        q = (v["qw"], v["qx"], v["qy"], v["qz"])
        norm = math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
        if not abs(norm - 1) <= _QUAT_TOL:
            return ("grain %d: (qw, qx, qy, qz) = (%.9g, %.9g, %.9g, %.9g) is not a unit quaternion "
                    "(norm %.9g, off 1 by more than %s)" % (gid, q[0], q[1], q[2], q[3], norm, _g(_QUAT_TOL)))
    for a, c in enumerate("xyz"):
        if v[c] < box[a] or v[c] > box[a + 3]:
            return ("grain %d: centre %s = %s is outside the box [%s, %s]"
                    % (gid, c, _g(v[c]), _g(box[a]), _g(box[a + 3])))
    for a, c in enumerate("xyz"):
        if v["r"] > box[a + 3] - box[a]:
            return ("grain %d: radius %s m is larger than the box along %s (%s m): the radius must be at most the box length"
                    % (gid, _g(v["r"]), c, _g(box[a + 3] - box[a])))
    if shapes and (v["shape"] != "sphere" if "shape" in v else v["side"] > 0):
        rb = v["r"] + v["side"] / _SQRT2  # shape_bounding_radius
        for a, c in enumerate("xyz"):
            if not rb <= box[a + 3] - box[a]:
                return ("grain %d: bounding radius %s m (side %s m) is larger than the box along %s (%s m): it must be at most the box length"
                        % (gid, _g(rb), _g(v["side"]), c, _g(box[a + 3] - box[a])))
    return None


def _grain_volume(p: Pack, g: np.ndarray) -> float:
    """lib/pack/pack.c's pack_grain_volume, in its order: the spheres as r^3 summed times
    4 pi/3 at the end, each plate's 2 r L^2 + 2 pi r^2 L + 4/3 pi r^3 summed apart."""
    v = vp = 0.0
    rs = g["r"].tolist()
    sides = g["side"].tolist() if "side" in p.columns else [0.0] * len(rs)
    kinds = g["shape"].tolist() if "shape" in p.columns else None
    for k, r in enumerate(rs):
        L = sides[k]
        if (kinds[k] != "sphere") if kinds is not None else L > 0:
            vp += 2 * r * L * L + 2 * math.pi * r * r * L + 4.0 / 3.0 * math.pi * r * r * r
        else:
            v += r * r * r
    return v * 4.0 / 3.0 * 3.14159265358979323846 + vp


def _volume_why(p: Pack, g: np.ndarray) -> Optional[str]:
    """The grains' volume against the box's (read_grains), or None."""
    b = p.box
    vb = (b[3] - b[0]) * (b[4] - b[1]) * (b[5] - b[2])
    vg = _grain_volume(p, g)
    if not vg <= vb:
        return "the grains' volume %s m^3 exceeds the box's %s m^3 (a grain far too large?)" % (_g(vg), _g(vb))
    return None


def _grain_dtype(columns: Sequence[str]) -> np.dtype:
    return np.dtype([(c, _DTYPES.get(c, np.float64)) for c in columns])


def _grains_slow(lines: _Lines, p: Pack, ng: int) -> np.ndarray:
    """The grain lines, one by one, as lib/pack/packio.c reads them: the reference, and
    what names a wrong line.  Room grows with the lines read, never from the count."""
    ncol = len(p.columns)
    colnames = " ".join(p.columns)
    rows: List[Tuple[Any, ...]] = []
    first = lines.lineno + 1
    for n in range(ng):
        s = lines.next()
        if s is None:
            raise lines.error("unexpected end of input: %d grains declared, %d found" % (ng, n), lines.lineno + 1)
        tok = _split(s)
        if len(tok) != ncol:
            raise lines.error("grain line: expected %d columns (%s), found %d%s" % (
                ncol, colnames, len(tok),
                "; more columns need 'qusgm-pack 2' and a columns line" if p.version < 2 and len(tok) > ncol else ""))
        gid = _long(tok[0])
        if gid is None:
            raise lines.error("grain id '%s' is not an integer" % tok[0])
        v: Dict[str, Any] = {"id": gid}
        for k in range(1, ncol):
            c, t = p.columns[k], tok[k]
            if c == "shape":
                if t not in SHAPES:
                    raise lines.error("grain %d: shape '%s' is not a kind (%s)" % (gid, t, ", ".join(SHAPES)))
                v[c] = t
            elif c == "phase":
                ph = _long(t)
                if ph is None or ph < 0 or ph > 1:
                    raise lines.error("grain %d: phase '%s' is neither 0 (mineral) nor 1 (hydrate)" % (gid, t))
                v[c] = ph
            elif c == "glued":
                if t != "-" and t not in WALLS:
                    raise lines.error("grain %d: glued '%s' is neither '-' (free) nor a wall (xlo ... zhi)" % (gid, t))
                v[c] = t
            else:
                x = _num(t)
                if x is None:
                    raise lines.error("grain: '%s' is not a finite number" % t)
                v[c] = x
        why = _grain_why(p, gid, v)
        if why:
            raise lines.error(why)
        rows.append(tuple(v[c] for c in p.columns))
    g = np.array(rows, dtype=_grain_dtype(p.columns)) if rows else np.zeros(0, dtype=_grain_dtype(p.columns))
    why = _volume_why(p, g)
    if why:
        raise lines.error(why, first)
    seen: Dict[int, int] = {}
    for n, r in enumerate(rows):
        if r[0] in seen:
            raise lines.error("duplicate grain id %d" % r[0], first + n)
        seen[r[0]] = n
    centres: Dict[Tuple[float, float, float], int] = {}
    for n, r in enumerate(rows):
        c = (r[1], r[2], r[3])
        if c in centres:
            raise lines.error("grains %d and %d have the same centre" % (rows[centres[c]][0], r[0]), first + n)
        centres[c] = n
    return g


def _hertz(p: Pack) -> bool:
    """Whether contact forces are held to Hertz's bound: not for the plate engine's law."""
    return p.meta.get("contact-law") != "linear"


def _contacts_slow(lines: _Lines, p: Pack, nc: int, g: np.ndarray) -> np.ndarray:
    """The contact lines, one by one, as lib/pack/packio.c reads them."""
    index = {gid: k for k, gid in enumerate(g["id"].tolist())}
    r, E, nu = g["r"], g["E"], g["nu"]
    hertz = _hertz(p)
    rows: List[Tuple[Any, ...]] = []
    keys: List[Tuple[int, int]] = []
    first = lines.lineno + 1

    def end(t: str, allow_wall: bool) -> int:
        if allow_wall and t in WALLS:
            w = WALLS.index(t)
            if p.periodic[w // 2]:
                raise lines.error("contact: wall '%s' on axis %s, which is periodic (no walls)" % (t, "xyz"[w // 2]))
            return -1 - w
        gid = _long(t)
        if gid is None:
            raise lines.error("contact: '%s' is neither a grain id nor a wall (xlo xhi ylo yhi zlo zhi)" % t)
        if gid not in index:
            raise lines.error("contact names grain %d, which is not in the pack" % gid)
        return index[gid]

    for n in range(nc):
        s = lines.next()
        if s is None:
            raise lines.error("unexpected end of input: %d contacts declared, %d found" % (nc, n), lines.lineno + 1)
        tok = _split(s)
        if len(tok) != 7:
            raise lines.error("contact line: expected 7 columns (i j P0 Q0x Q0y Q0z M0), found %d" % len(tok))
        i = end(tok[0], False)
        j = end(tok[1], True)
        if i == j:
            raise lines.error("contact of grain %s with itself" % tok[0])
        v = []
        for t in tok[2:]:
            x = _num(t)
            if x is None:
                raise lines.error("contact: '%s' is not a finite number" % t)
            v.append(x)
        if v[0] < 0:
            raise lines.error("contact: normal force P0 = %s is negative" % _g(v[0]))
        if hertz:
            wall = j < 0
            Ej = p.walls["E"] if wall else float(E[j])
            nuj = p.walls["nu"] if wall else float(nu[j])
            ri = float(r[i])
            Rs = ri if wall else ri * float(r[j]) / (ri + float(r[j]))
            Es = 1 / ((1 - float(nu[i]) * float(nu[i])) / float(E[i]) + (1 - nuj * nuj) / Ej)
            Pmax = 4.0 / 3.0 * Es * Rs * Rs
            q = float(np.hypot(np.hypot(v[1], v[2]), v[3]))
            if v[0] > Pmax:
                raise lines.error("contact: normal force P0 = %s N is outside [0, %s] N, the Hertz force at an overlap "
                                  "as large as the contact's radius R* = %s m" % (_g(v[0]), _g(Pmax), _g(Rs)))
            if q > _MU_MAX * Pmax:
                raise lines.error("contact: tangential force |Q0| = %s N is outside [0, %s] N (%s times the Hertz "
                                  "force at an overlap of R*)" % (_g(q), _g(_MU_MAX * Pmax), _g(_MU_MAX)))
            if abs(v[4]) > _MU_MAX * Pmax * Rs:
                raise lines.error("contact: couple |M0| = %s N m is outside [0, %s] N m (%s times the Hertz force at "
                                  "an overlap of R*, times R*)" % (_g(abs(v[4])), _g(_MU_MAX * Pmax * Rs), _g(_MU_MAX)))
        rows.append((int(g["id"][i]), j, tok[1] if j < 0 else "", *v))
        keys.append((min(i, j), max(i, j)) if j >= 0 else (i, j))
    seen: set = set()
    for n, k in enumerate(keys):
        if k in seen:
            raise lines.error("contact pair listed twice", first + n)
        seen.add(k)
    c = np.zeros(len(rows), dtype=_CONTACT_DTYPE)
    if rows:
        ids = g["id"]
        c["i"] = [row[0] for row in rows]
        c["j"] = [int(ids[row[1]]) if row[1] >= 0 else row[1] for row in rows]
        c["j_wall"] = [row[2] for row in rows]
        for k, f in enumerate(("P0", "Q0x", "Q0y", "Q0z", "M0")):
            c[f] = [row[3 + k] for row in rows]
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
            if b"\0" in block or b"#" in block or b"\r" in block or not block.isascii():
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
    """The grain lines through a C parser, checked as _grains_slow checks them (every rule
    of check_grain_values, the ids, the centres), vectorised; None, the lines given back,
    where any check fails (the line-by-line reader then names the line)."""
    if "glued" in p.columns:
        return None  # a word column the C parser does not take: line by line
    kind_col = p.columns.index("shape") if "shape" in p.columns else -1
    dt = np.dtype([(c, np.int8 if c == "shape" else _DTYPES.get(c, np.float64)) for c in p.columns])
    g, _, block = _parse_lines(lines, ng, dt, kind_col=kind_col)
    if g is not None and kind_col >= 0:  # the kinds' indices as their names
        ok = ((g["shape"] == 0) == (g["side"] == 0)).all()
        names = np.array(SHAPES, dtype=_DTYPES["shape"])[g["shape"]]
        g2 = np.empty(ng, dtype=_grain_dtype(p.columns))
        for c in p.columns:
            g2[c] = names if c == "shape" else g[c]
        g = g2 if ok else None
    if g is not None and _grains_ok(p, g):
        lines.lineno += ng
        return g
    lines.unread(block)
    return None


def _grains_ok(p: Pack, g: np.ndarray) -> bool:
    """Every grain passes the C reader's checks (_grain_why, the ids, the centres)."""
    floats = [c for c in p.columns if c not in _DTYPES]
    if not all(np.isfinite(g[c]).all() for c in floats):
        return False
    r, E, nu, b = g["r"], g["E"], g["nu"], p.box
    ok = (g["id"] >= 0) & (r > 0) & (E >= _E_MIN) & (E <= _E_MAX) & (nu > -1) & (nu < 0.5) & (g["rho"] > 0)
    for a, c in enumerate("xyz"):
        ok &= (g[c] >= b[a]) & (g[c] <= b[a + 3]) & (r <= b[a + 3] - b[a])
    if "side" in p.columns:
        q = g["qw"] * g["qw"] + g["qx"] * g["qx"] + g["qy"] * g["qy"] + g["qz"] * g["qz"]
        ok &= (g["side"] >= 0) & (np.abs(np.sqrt(q) - 1) <= _QUAT_TOL)
    if "phase" in p.columns:
        ok &= (g["phase"] == 0) | (g["phase"] == 1)
    if "side" in p.columns:  # a plate by its bounding radius
        plate = (g["shape"] != "sphere") if "shape" in p.columns else (g["side"] > 0)
        rb = r + g["side"] / _SQRT2
        for a in range(3):
            ok &= ~plate | (rb <= b[a + 3] - b[a])
    if not ok.all() or _volume_why(p, g) is not None or np.unique(g["id"]).size != len(g):
        return False
    # no two centres alike (-0 is 0, as C's == has it)
    x, y, z = g["x"] + 0.0, g["y"] + 0.0, g["z"] + 0.0
    o = np.lexsort((z, y, x))
    x, y, z = x[o], y[o], z[o]
    return not ((x[1:] == x[:-1]) & (y[1:] == y[:-1]) & (z[1:] == z[:-1])).any()


def _contacts_fast(lines: _Lines, p: Pack, nc: int, g: np.ndarray) -> Optional[np.ndarray]:
    """The contact lines through a C parser, checked as _contacts_slow checks them."""
    if nc == 0:
        return np.zeros(0, dtype=_CONTACT_DTYPE)
    dt = np.dtype([("i", np.int64), ("j", np.int64), ("P0", np.float64), ("Q0x", np.float64),
                   ("Q0y", np.float64), ("Q0z", np.float64), ("M0", np.float64)])
    a, walls, block = _parse_lines(lines, nc, dt, wall_col=1)
    if a is not None:
        c = _contacts_ok(p, a, walls, g)
        if c is not None:
            lines.lineno += nc
            return c
    lines.unread(block)
    return None


def _contacts_ok(p: Pack, a: np.ndarray, walls: np.ndarray, g: np.ndarray) -> Optional[np.ndarray]:
    """The contacts, where every one passes the C reader's checks; else None."""
    nc = len(a)
    order = np.argsort(g["id"], kind="stable")
    ids = g["id"][order]
    i, j = a["i"], a["j"]
    wall = walls >= 0
    w = np.where(wall, walls, 0)
    if not all(np.isfinite(a[f]).all() for f in ("P0", "Q0x", "Q0y", "Q0z", "M0")) or not (a["P0"] >= 0).all():
        return None
    k = np.clip(np.searchsorted(ids, i), 0, len(ids) - 1)
    if not (ids[k] == i).all():
        return None
    ii = order[k]  # the grains' indices
    jk = np.clip(np.searchsorted(ids, j), 0, len(ids) - 1)
    if not ((ids[jk] == j) | wall).all():
        return None
    jj = np.where(wall, -1 - w, order[jk])
    if (jj == ii).any():
        return None
    for axis, periodic in enumerate(p.periodic):
        if periodic and (wall & (w // 2 == axis)).any():
            return None
    if _hertz(p):
        r, E, nu = g["r"], g["E"], g["nu"]
        jg = np.where(wall, 0, jj)
        Ej = np.where(wall, p.walls["E"], E[jg])
        nuj = np.where(wall, p.walls["nu"], nu[jg])
        ri, rj = r[ii], r[jg]
        Rs = np.where(wall, ri, ri * rj / (ri + rj))
        Es = 1 / ((1 - nu[ii] * nu[ii]) / E[ii] + (1 - nuj * nuj) / Ej)
        Pmax = 4.0 / 3.0 * Es * Rs * Rs
        q = np.hypot(np.hypot(a["Q0x"], a["Q0y"]), a["Q0z"])
        if not ((a["P0"] <= Pmax) & (q <= _MU_MAX * Pmax) & (np.abs(a["M0"]) <= _MU_MAX * Pmax * Rs)).all():
            return None
    lo, hi = np.where(wall, ii, np.minimum(ii, jj)), np.where(wall, jj, np.maximum(ii, jj))
    if np.unique(np.stack((lo, hi), axis=1), axis=0).shape[0] != nc:
        return None
    c = np.zeros(nc, dtype=_CONTACT_DTYPE)
    c["i"] = i
    c["j"] = np.where(wall, -1 - w, j)
    c["j_wall"] = np.where(wall, np.array(WALLS)[w], "")
    for f in ("P0", "Q0x", "Q0y", "Q0z", "M0"):
        c[f] = a[f]
    return c


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


def _next_pack(lines: _Lines, fast: bool) -> Optional[Pack]:
    """The next pack of the stream, None at its end (lib/pack/packio.c, pack_read_next)."""
    s = lines.next()
    if s is None:
        if lines.lineno == 0:
            raise lines.error("empty input (expected %s)" % _EXPECT, 1)
        return None
    p, ng, nc = _read_header(lines, s)
    _read_body(lines, p, ng, nc, fast)
    s = lines.next()
    if s is not None:
        if not s.startswith(_MAGIC):
            raise lines.error("unexpected line after the last contact (counts in the header are %d grains, %d contacts)"
                              % (ng, nc))
        lines.push(s)
    return p


def read_packs(source: Source, fast: bool = True) -> Iterator[Pack]:
    """Every pack of a stream, in order (a generator), as packinfo(1) reads a stream: source
    is a path, '-' (stdin) or a binary file object, plain or gzip.  fast=False reads every
    line in Python (the same arrays, slower: the reference the fast path is tested
    against)."""
    lines = _Lines(source)
    try:
        while True:
            p = _next_pack(lines, fast)
            if p is None:
                return
            yield p
    finally:
        lines.close()


def read_pack(source: Source, fast: bool = True) -> Pack:
    """Exactly one pack, as the tools that transform one pack read it (pack_read_path): a
    second pack after it is read and refused ("a second pack follows; this tool reads one
    pack"; read_packs reads a stream)."""
    lines = _Lines(source)
    try:
        p = _next_pack(lines, fast)
        assert p is not None
        line = lines.lineno + 1
        if _next_pack(lines, fast) is not None:
            raise lines.error("a second pack follows; this tool reads one pack", line)
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
        return [n for n in self.names if self.data.dtype[n].kind == "O"]

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


_SPECIAL = re.compile(_CSPACE + r"([+-]?)(?:(inf(?:inity)?)|nan(?:\([0-9A-Za-z_]*\))?)\Z", re.I)


def _table_number(t: str) -> float:
    """A table's number as the tables' reader's strtod reads it (the whole field, ASCII, C
    locale; nan and inf allowed), or ValueError."""
    if _DEC.match(t):
        return float(t)
    if _HEX.match(t):
        try:
            return float.fromhex(t.strip(" \t\n\v\f\r"))
        except OverflowError:
            return -math.inf if t.lstrip(" \t\n\v\f\r").startswith("-") else math.inf
    m = _SPECIAL.match(t)
    if m:
        return (-1.0 if m.group(1) == "-" else 1.0) * (math.inf if m.group(2) else math.nan)
    raise ValueError(t)


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
            s = lines.next(table=True)
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
    # a text column holds Python str objects: its memory is its text, where a numpy str
    # field is as wide as its longest cell in every row (one cell of 20000 characters in a
    # table of 30000 rows took 2.3 GB)
    dt = [(n, object if is_text else np.float64) for (n, _), is_text in zip(names, text)]
    data = np.empty(len(rows), dtype=dt)
    for k, ((n, _), is_text) in enumerate(zip(names, text)):
        data[n] = [r[k] for r in rows]
    return Table([n for n, _ in names], {n: u for n, u in names}, meta, data, lines.name)
