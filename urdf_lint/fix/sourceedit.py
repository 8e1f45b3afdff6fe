"""Byte-exact editing of xacro / URDF sources: find a start tag from its (line, col) origin,
tokenise its attributes in the raw bytes, and apply byte-range edits.

Nothing outside an edited range moves: line endings (CRLF), tabs, non-ASCII text, comments,
attribute order and quoting are kept as they are. Values are read with XML attribute-value
normalisation (entities, character references, whitespace) and written back escaped for the
quote character that surrounds them.
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Iterable, Iterator

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.core.edits import Edit


_NAME = re.compile(rb"[^\s/>=]+")
_WS = re.compile(rb"\s*")
_ENTITY = re.compile(r"&(#x[0-9a-fA-F]+|#[0-9]+|amp|lt|gt|quot|apos);")
_NAMED = {"amp": "&", "lt": "<", "gt": ">", "quot": '"', "apos": "'"}


@dataclass(frozen=True)
class Attr:
    """One attribute of a start tag, as byte offsets into the file."""
    name: str
    name_start: int
    value_start: int     # first byte of the value (after the opening quote)
    value_end: int       # the closing quote
    quote: str
    raw: str             # the value as written (entities not decoded)

    @property
    def value(self) -> str:
        return unescape(self.raw)


@dataclass(frozen=True)
class StartTag:
    """A start tag in the raw bytes of a file."""
    start: int           # the '<'
    end: int             # one past the '>'
    name: str
    name_end: int
    attrs: tuple[Attr, ...]
    self_closing: bool

    def attr(self, name: str) -> Attr | None:
        for a in self.attrs:
            if a.name == name:
                return a
        return None


def unescape(raw: str) -> str:
    """An attribute value as an XML parser reads it (entities, char refs, normalised spaces)."""
    raw = re.sub(r"[\t\r\n]", " ", raw.replace("\r\n", "\n"))

    def sub(m: "re.Match[str]") -> str:
        g = m.group(1)
        if g.startswith("#x"):
            return chr(int(g[2:], 16))
        if g.startswith("#"):
            return chr(int(g[1:]))
        return _NAMED[g]
    return _ENTITY.sub(sub, raw)


def escape(value: str, quote: str) -> str:
    out = value.replace("&", "&amp;").replace("<", "&lt;")
    return out.replace('"', "&quot;") if quote == '"' else out.replace("'", "&apos;")


_LINE_STARTS: list[Any] = [None, []]   # (the bytes, the offset of each of its lines)


def line_offset(data: bytes, line: int) -> int | None:
    """Byte offset of the start of 1-based ``line`` (None past the end). The line table of
    the last ``data`` asked about is kept: asking for every line of a file is linear, not
    quadratic (one unused suppression comment per line of a large file)."""
    if _LINE_STARTS[0] is not data:
        _LINE_STARTS[:] = [data, [0] + [m.end() for m in re.finditer(b"\n", data)]]
    starts = _LINE_STARTS[1]
    return starts[line - 1] if 1 <= line <= len(starts) else (0 if line < 1 else None)


def offset_of(data: bytes, line: int, col: int) -> int | None:
    """Byte offset of the '<' of the start tag at (line, col) (col: 1-based characters, as
    expat reports them, or bytes: both are tried)."""
    start = line_offset(data, line)
    if start is None:
        return None
    end = data.find(b"\n", start)
    text = data[start:end if end >= 0 else len(data)]
    try:
        chars = text.decode("utf-8")
        by_char = start + len(chars[:col - 1].encode("utf-8"))
    except UnicodeDecodeError:
        by_char = None
    for off in (by_char, start + col - 1):
        if off is not None and data[off:off + 1] == b"<":
            return off
    return None


def _skip_ws(data: bytes, pos: int) -> int:
    """The first offset at or after ``pos`` that is not whitespace."""
    m = _WS.match(data, pos)
    return m.end() if m else pos


def parse_start_tag(data: bytes, off: int) -> StartTag | None:
    """Tokenise the start tag whose '<' is at ``off`` (None if it is not one)."""
    if data[off:off + 1] != b"<":
        return None
    m = _NAME.match(data, off + 1)
    if not m:
        return None
    name = m.group().decode("utf-8")
    name_end = m.end()
    pos = name_end
    attrs: list[Attr] = []
    while True:
        pos = _skip_ws(data, pos)
        if data.startswith(b"/>", pos):
            return StartTag(off, pos + 2, name, name_end, tuple(attrs), True)
        if data.startswith(b">", pos):
            return StartTag(off, pos + 1, name, name_end, tuple(attrs), False)
        m = _NAME.match(data, pos)
        if not m:
            return None
        aname, astart = m.group().decode("utf-8"), m.start()
        pos = _skip_ws(data, m.end())
        if data[pos:pos + 1] != b"=":
            return None
        pos = _skip_ws(data, pos + 1)
        q = data[pos:pos + 1]
        if q not in (b'"', b"'"):
            return None
        close = data.find(q, pos + 1)
        if close < 0:
            return None
        raw = data[pos + 1:close].decode("utf-8")
        attrs.append(Attr(aname, astart, pos + 1, close, q.decode(), raw))
        pos = close + 1


def start_tag_at(data: bytes, line: int, col: int) -> StartTag | None:
    off = offset_of(data, line, col)
    return parse_start_tag(data, off) if off is not None else None


def iter_start_tags(data: bytes, local_name: str) -> "Iterator[StartTag]":
    """Every start tag whose local name (after any prefix) is ``local_name``, outside comments
    and CDATA."""
    pat = re.compile(rb"<!--.*?-->|<!\[CDATA\[.*?\]\]>|<([^\s/>!?]+)", re.S)
    for m in pat.finditer(data):
        tag = m.group(1)
        if tag and tag.decode("utf-8", "replace").rpartition(":")[2] == local_name:
            st = parse_start_tag(data, m.start())
            if st is not None:
                yield st


def end_tag_of(data: bytes, tag: StartTag) -> int | None:
    """Offset of the '<' of the end tag that closes ``tag`` (not self-closing), skipping
    comments, CDATA, processing instructions and nested elements of the same name."""
    pat = re.compile(rb"<!--.*?-->|<!\[CDATA\[.*?\]\]>|<\?.*?\?>|</([^\s>]+)\s*>|<([^\s/>!?]+)",
                     re.S)
    name = tag.name.encode("utf-8")
    depth = 0
    pos = tag.end
    while True:
        m = pat.search(data, pos)
        if m is None:
            return None
        if m.group(1) is not None:
            if m.group(1) == name:
                if depth == 0:
                    return m.start()
                depth -= 1
            pos = m.end()
        elif m.group(2) is not None:
            inner = parse_start_tag(data, m.start())
            if inner is None:
                return None
            if inner.name == tag.name and not inner.self_closing:
                depth += 1
            pos = inner.end
        else:
            pos = m.end()


def line_col(data: bytes, off: int) -> tuple[int, int]:
    line = data.count(b"\n", 0, off) + 1
    start = data.rfind(b"\n", 0, off) + 1
    return line, len(data[start:off].decode("utf-8", "replace")) + 1


def apply_edits(data: bytes, edits: Iterable["Edit"]) -> bytes:
    """``data`` with non-overlapping edits applied (raises ValueError on an overlap)."""
    out: list[bytes] = []
    pos = 0
    for e in sorted(edits, key=lambda e: (e.start, e.end)):
        if e.start < pos:
            raise ValueError(f"overlapping edits at byte {e.start}")
        out.append(data[pos:e.start])
        out.append(e.text.encode("utf-8"))
        pos = e.end
    out.append(data[pos:])
    return b"".join(out)


