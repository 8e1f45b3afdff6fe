"""The formatting engine of ``urdf-lint format``: a token-level rewriter of one XML source.

The source is split into tokens by a small tokenizer that knows XML's grammar (the XML
declaration, processing instructions, comments, CDATA, a DOCTYPE with its internal subset,
start, end and empty tags with quoted attribute values, text). expat (xacro's own parser) checks first that
the source is well-formed, so the tokens always nest. Only the whitespace *between* tokens and
inside tags is rewritten; every token's own text (attribute values with their quotes, text,
comments, CDATA, entity references, ``${...}`` and ``$(...)``) is copied byte for byte:

* one element per line, children indented by ``indent`` spaces; a comment or processing
  instruction that followed something on the same line stays there (one space before it);
  runs of blank lines between children become one, blank lines right after a start tag or
  before an end tag go, and so does one between a ``disable-next`` suppression comment and the
  element it governs;
* attributes are separated by one space (no space around ``=``); past ``line-length`` they are
  wrapped one per line, aligned under the first (a hanging indent of two levels when the tag
  name is too long for that); ``attribute-order = "canonical"`` puts
  ``name`` first, then the URDF/xacro schema order of the element, then the rest as written;
* only an element whose content is child elements and whitespace is re-laid out. Any other
  content (text, mixed content, CDATA, comments without elements, everything below
  ``xml:space="preserve"``) is kept exactly as written: whitespace inside a text-only element
  is significant (``<robotNamespace>``). An element with no content is self-closed
  (``<link name="a"/>``), and so is one holding only whitespace when it is a URDF or xacro
  element whose text nobody reads (``link``, ``joint``, ``xacro:if``, ...);
* the BOM, the XML declaration, the encoding and the line endings are kept; the file ends
  with one line ending.

:func:`check_same` is the guard every result passes before it is used: the document expat
reads from the result must be the one it reads from the source (elements, attributes,
comments, processing instructions, all text but the whitespace between child elements), and
every ``urdf-lint:`` suppression comment must cover the same elements
(:func:`urdf_lint.engine.suppress.coverage`). That the layout is a fixed point is shown by the tests
(every unit input and the whole corpus), not checked on each run.
:mod:`urdf_lint.run.format` adds the proof on the expanded robots.
"""
from __future__ import annotations

import codecs
import re
from dataclasses import dataclass
from typing import Any


# A node of read_document: ("el", name, [attribute, value, ...], children), ("text", s),
# ("comment", s), ("pi", target, data), ("decl", ...), ("doctype", ...).
Node = tuple[Any, ...]


@dataclass(frozen=True)
class Style:
    """How to lay a file out (``[tool.urdf-lint.format]``)."""
    indent: int = 2
    line_length: int = 100
    attribute_order: str = "keep"     # "keep" | "canonical"
    self_closing: str = "auto"        # "auto" (the file's majority) | "compact" | "spaced"


class FormatError(Exception):
    """The source cannot be formatted (not well-formed, an encoding it cannot round-trip)."""

    def __init__(self, message: str, line: int = 1, col: int = 1) -> None:
        super().__init__(message)
        self.message, self.line, self.col = message, line, col


# -- the URDF / xacro schema order (attribute-order = "canonical") ---------------------------
SCHEMA_ORDER: dict[str, tuple[str, ...]] = {
    "robot": ("name", "version"),
    "link": ("name", "type"),
    "joint": ("name", "type"),
    "origin": ("xyz", "rpy"),
    "parent": ("link",),
    "child": ("link",),
    "axis": ("xyz",),
    "calibration": ("rising", "falling", "reference_position"),
    "dynamics": ("damping", "friction"),
    "limit": ("lower", "upper", "effort", "velocity"),
    "mimic": ("joint", "multiplier", "offset"),
    "safety_controller": ("soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"),
    "mass": ("value",),
    "inertia": ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"),
    "box": ("size",),
    "cylinder": ("radius", "length"),
    "capsule": ("radius", "length"),
    "sphere": ("radius",),
    "mesh": ("filename", "scale"),
    "material": ("name",),
    "color": ("rgba",),
    "texture": ("filename",),
    "transmission": ("name", "type"),
    "actuator": ("name",),
    "gazebo": ("reference",),
    "plugin": ("name", "filename"),
    "ros2_control": ("name", "type"),
    "xacro:macro": ("name", "params"),
    "xacro:property": ("name", "value", "default", "lazy_eval", "scope"),
    "xacro:arg": ("name", "default"),
    "xacro:include": ("filename", "ns"),
    "xacro:if": ("value",),
    "xacro:unless": ("value",),
    "xacro:insert_block": ("name",),
    "xacro:element": ("xacro:name",),
    "xacro:attribute": ("name", "value"),
    "xacro:call": ("macro",),
}

# elements whose text no consumer reads: holding only whitespace, they are self-closed
STRUCTURAL = frozenset({
    "robot", "link", "joint", "visual", "collision", "inertial", "origin", "geometry", "box",
    "cylinder", "capsule", "sphere", "mesh", "material", "color", "texture", "parent", "child",
    "axis", "calibration", "dynamics", "limit", "mimic", "safety_controller", "mass", "inertia",
    "xacro:macro", "xacro:if", "xacro:unless", "xacro:include", "xacro:arg",
    "xacro:insert_block",
})


# -- tokens -----------------------------------------------------------------------------------
_QUOTED = r"(?:\"[^\"]*\"|'[^']*')"
_TOKEN = re.compile(
    r"(?P<text>[^<]+)"
    r"|(?P<comment><!--.*?-->)"
    r"|(?P<cdata><!\[CDATA\[.*?\]\]>)"
    r"|(?P<pi><\?.*?\?>)"
    r"|</(?P<end>[^\s>]+)\s*>"
    r"|<(?P<start>[^\s/>!?]+)(?P<attrs>(?:\s+[^\s=/>]+\s*=\s*" + _QUOTED + r")*)\s*(?P<empty>/?)>"
    r"|(?P<doctype><!)", re.S)
_ATTR = re.compile(r"([^\s=/>]+)\s*=\s*(" + _QUOTED + r")")


class _Leaf:
    """A token kept as written: text, comment, pi, cdata, doctype."""
    __slots__ = ("kind", "raw", "blank")

    def __init__(self, kind: str, raw: str) -> None:
        self.kind, self.raw = kind, raw
        self.blank = kind == "text" and not raw.strip()


class _El:
    __slots__ = ("name", "attrs", "children", "inner", "spaced")

    def __init__(self, name: str, attrs: list[tuple[str, str]]) -> None:
        self.name, self.attrs = name, attrs
        self.children: list[_El | _Leaf] = []
        self.inner: tuple[int, int] | None = None    # source span of the content; None: <x/>
        self.spaced = False                          # written <x />


def _doctype_end(src: str, i: int) -> int:
    """The end of ``<!DOCTYPE ...>`` starting at ``i``: quotes and an internal subset
    (``[...]``, with its own comments and quoted strings) may hold ``>``."""
    depth, n = 0, len(src)
    while i < n:
        c = src[i]
        if c in "\"'":
            i = src.index(c, i + 1)
        elif src.startswith("<!--", i):
            i = src.index("-->", i) + 2
        elif c == "[":
            depth += 1
        elif c == "]":
            depth -= 1
        elif c == ">" and depth == 0:
            return i + 1
        i += 1
    raise ValueError("unterminated DOCTYPE")


def _tokenize(src: str) -> list[_El | _Leaf]:
    """The document's top-level nodes (elements hold their children)."""
    top: list[_El | _Leaf] = []
    stack: list[_El] = []
    into = top
    i, n = 0, len(src)
    match = _TOKEN.match
    while i < n:
        m = match(src, i)
        if m is None:
            raise ValueError(f"unreadable markup at offset {i}")
        kind = m.lastgroup
        if kind == "attrs" or kind == "empty":
            el = _El(m.group("start"), _ATTR.findall(m.group("attrs")))
            into.append(el)
            i = m.end()
            if m.group("empty"):
                el.spaced = src[m.start("empty") - 1].isspace()
            else:
                el.inner = (i, i)
                stack.append(el)
                into = el.children
            continue
        if kind == "end":
            if not stack or stack[-1].name != m.group("end"):
                raise ValueError(f"unexpected end tag at offset {i}")
            el = stack.pop()
            el.inner = (el.inner[0], i)    # type: ignore[index]
            into = stack[-1].children if stack else top
        elif kind == "doctype":
            j = _doctype_end(src, i)
            into.append(_Leaf("doctype", src[i:j]))
            i = j
            continue
        else:
            into.append(_Leaf(kind, m.group()))   # type: ignore[arg-type]
        i = m.end()
    if stack:
        raise ValueError("unclosed element")
    return top


# -- layout -----------------------------------------------------------------------------------
_DISABLE_NEXT = re.compile(r"<!--\s*urdf[-_]lint\s*:\s*disable-next\b")   # (suppress.py)


def _newlines(ws: str) -> int:
    return ws.count("\n") + ws.count("\r") - ws.count("\r\n")


class _Layout:
    def __init__(self, src: str, style: Style, nl: str, spaced: bool = False) -> None:
        self.src, self.style, self.nl = src, style, nl
        self.out: list[str] = []
        self.empty_close = " />" if spaced else "/>"

    def kind(self, el: _El) -> str:
        """"empty" (self-closed), "elements" (re-laid out) or "verbatim" (kept as written)."""
        if el.inner is None or el.inner[0] == el.inner[1]:
            return "empty"
        if any(v[1:-1] == "preserve" for k, v in el.attrs if k == "xml:space"):
            return "verbatim"
        kids = el.children
        leaves = [c for c in kids if c.__class__ is _Leaf]
        if len(leaves) < len(kids):
            return "elements" if all(c.blank or c.kind in ("comment", "pi")
                                     for c in leaves) else "verbatim"
        if el.name in STRUCTURAL and all(c.blank for c in leaves):
            return "empty"
        return "verbatim"

    def ordered(self, el: _El) -> list[tuple[str, str]]:
        attrs = el.attrs
        if self.style.attribute_order != "canonical" or len(attrs) < 2:
            return attrs
        schema = ("name",) + SCHEMA_ORDER.get(el.name, ())

        def key(item: tuple[str, str]) -> tuple[int, int]:
            return (0, schema.index(item[0])) if item[0] in schema else (1, 0)
        return sorted(attrs, key=key)    # stable: the rest keep their order

    def element(self, el: _El, depth: int) -> None:
        out, style = self.out, self.style
        indent = " " * (style.indent * depth)
        kind = self.kind(el)
        attrs = [f"{k}={v}" for k, v in self.ordered(el)]
        close = self.empty_close if kind == "empty" else ">"
        one = "<" + el.name + "".join(" " + a for a in attrs) + close
        first_line = one.split("\n", 1)[0].split("\r", 1)[0]
        if len(attrs) > 1 and len(indent) + len(first_line) > style.line_length:
            col = len(indent) + len(el.name) + 2
            if col <= style.line_length // 2:    # aligned under the first attribute
                pad = self.nl + " " * col
                one = "<" + el.name + " " + pad.join(attrs) + close
            else:                                # a long name: a hanging indent
                pad = self.nl + indent + " " * (2 * style.indent)
                one = "<" + el.name + pad + pad.join(attrs) + close
        out.append(one)
        if kind == "empty":
            return
        assert el.inner is not None
        if kind == "verbatim":
            out.append(self.src[el.inner[0]:el.inner[1]])
        else:
            self.children(el.children, depth + 1)
            out.append(self.nl + indent)
        out.append(f"</{el.name}>")

    def children(self, nodes: list[_El | _Leaf], depth: int, top: bool = False) -> None:
        out, nl = self.out, self.nl
        indent = " " * (self.style.indent * depth)
        ws, first, lined = "", True, False   # lined: a child has a line of its own
        attached = False    # after a disable-next comment: no blank line before its element
        for node in nodes:
            if isinstance(node, _Leaf) and node.kind == "text":
                ws += node.raw
                continue
            lines = _newlines(ws)
            if isinstance(node, _Leaf) and node.kind in ("comment", "pi") and not lines \
                    and not (top and first):
                out.append(" " + node.raw)          # it followed something on that line
            else:
                if not (top and first):
                    blank = lines > 1 and lined and not attached
                    out.append(nl + (nl if blank else "") + indent)
                if isinstance(node, _El):
                    self.element(node, depth)
                else:
                    out.append(node.raw)
                lined = True
            attached = isinstance(node, _Leaf) and node.kind == "comment" and \
                _DISABLE_NEXT.match(node.raw) is not None
            ws, first = "", False


def _newline_of(src: str) -> str:
    i = src.find("\n")
    if i < 0:
        return "\r" if "\r" in src else "\n"
    return "\r\n" if i > 0 and src[i - 1] == "\r" else "\n"


def format_text(src: str, style: Style = Style()) -> str:
    """``src`` (decoded, no BOM) laid out; raises ValueError when the tokenizer cannot read it
    (callers check well-formedness with expat first: :func:`format_source`)."""
    nl = _newline_of(src)
    nodes = _tokenize(src)
    lay = _Layout(src, style, nl, _spaced(nodes, style.self_closing))
    lay.children(nodes, 0, top=True)
    return "".join(lay.out) + nl


def _spaced(nodes: list[Any], how: str) -> bool:
    """Are empty elements closed with `` />``? ``auto``: when most of the file's self-closed
    tags are written so (a tie, or none: ``/>``), so formatting a repository that writes
    ``<a />`` does not rewrite every such line."""
    if how != "auto":
        return how == "spaced"
    counts = [0, 0]    # [compact, spaced]
    todo = list(nodes)
    while todo:
        n = todo.pop()
        if n.__class__ is _El:
            if n.inner is None:
                counts[n.spaced] += 1
            todo.extend(n.children)
    return counts[1] > counts[0]


# -- bytes: BOM, encoding, well-formedness ------------------------------------------------------
_BOM = codecs.BOM_UTF8
_DECL_ENCODING = re.compile(rb"""^<\?xml[^>]*?\sencoding\s*=\s*["']([A-Za-z0-9._-]+)["']""")


def _encoding(data: bytes) -> tuple[str, bytes]:
    """(the codec of the file, its BOM)."""
    if data.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE, codecs.BOM_UTF32_LE,
                        codecs.BOM_UTF32_BE)):
        raise FormatError("UTF-16/UTF-32 files are not formatted")
    bom = _BOM if data.startswith(_BOM) else b""
    m = _DECL_ENCODING.match(data[len(bom):len(bom) + 256])
    name = m.group(1).decode("ascii") if m else "utf-8"
    try:
        codec = codecs.lookup(name).name
    except LookupError:
        raise FormatError(f"unknown encoding {name!r} in the XML declaration") from None
    if codec.startswith(("utf-16", "utf-32")):
        raise FormatError("UTF-16/UTF-32 files are not formatted")
    return codec, bom


def read_document(data: bytes) -> list[Node]:
    """The document as xacro's parser (expat, without namespace processing) reads it: a
    list of nodes, elements nested (``("el", name, [attribute, value, ...], children)``);
    raises a located :class:`FormatError` when it is not well-formed."""
    import xml.parsers.expat as expat
    p = expat.ParserCreate()
    p.ordered_attributes = True
    p.buffer_text = True
    top: list[Node] = []
    stack: list[list[Node]] = [top]

    def start(name: str, attrs: list[str]) -> None:
        kids: list[Node] = []
        stack[-1].append(("el", name, attrs, kids))
        stack.append(kids)
    p.XmlDeclHandler = lambda v, e, s: top.append(("decl", v, e, s))
    p.StartDoctypeDeclHandler = lambda *a: top.append(("doctype",) + a)
    p.StartElementHandler = start
    p.EndElementHandler = lambda name: stack.pop()
    p.CharacterDataHandler = lambda d: stack[-1].append(("text", d))
    p.CommentHandler = lambda d: stack[-1].append(("comment", d))
    p.ProcessingInstructionHandler = lambda t, d: stack[-1].append(("pi", t, d))
    try:
        p.Parse(data, True)
    except expat.ExpatError as e:
        raise FormatError(f"not well-formed XML: {expat.ErrorString(e.code)}", e.lineno,
                          e.offset + 1) from None
    return top


def _decode(data: bytes) -> tuple[str, str, bytes]:
    """(the text of the file, its codec, its BOM)."""
    codec, bom = _encoding(data)
    try:
        return data[len(bom):].decode(codec), codec, bom
    except UnicodeDecodeError as e:
        raise FormatError(f"cannot decode as {codec}: {e.reason}") from None


def _layout(src: str, codec: str, bom: bytes, style: Style) -> bytes:
    try:
        return bom + format_text(src, style).encode(codec)
    except ValueError as e:   # (well-formed XML the tokenizer cannot read: a bug)
        raise FormatError(f"internal: the tokenizer could not read the file ({e})") from None


class Refused(Exception):
    """The layout was made but is not safe to use: :attr:`reason` says why."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


def format_source(data: bytes, style: Style = Style(), path: str = "",
                  docs: dict[bytes, list[Node]] | None = None) -> bytes:
    """The formatted file, ``data`` itself when it is formatted already. Raises
    :class:`FormatError` (not well-formed, an encoding it cannot keep) or :class:`Refused`
    (the guard of :func:`check_same` failed). ``docs``, when given, receives the
    :func:`read_document` of the source and of a new layout, by their bytes."""
    src, codec, bom = _decode(data)
    old_doc = read_document(data)
    new = _layout(src, codec, bom, style)
    if new != data:
        new_doc: list[Node] = []
        reason = check_same(data, new, style, path, old_doc, new_doc)
        if reason is not None:
            raise Refused(reason)
        if docs is not None:
            docs[data], docs[new] = old_doc, new_doc
    return new


# -- the guard ----------------------------------------------------------------------------------
def normal_nodes(nodes: list[Node], ordered_attrs: bool, comments: bool = True) -> list[Node]:
    """The nodes of :func:`read_document` as a reader of the robot sees them: adjacent text
    joined, whitespace between child elements (layout) dropped, whitespace-only text of a
    :data:`STRUCTURAL` element dropped, attributes sorted unless their order is kept, comments
    dropped unless ``comments``."""
    return _kids(nodes, ordered_attrs, comments)[0]


def _kids(nodes: list[Node], ordered: bool, comments: bool) -> tuple[list[Node], bool, bool]:
    """(the normal nodes, whether one is an element, whether all text is whitespace)."""
    res: list[Node] = []
    has_el, blank = False, True
    for node in nodes:
        kind = node[0]
        if kind == "el":
            _, name, attrs, kids = node
            kids, el_kids, blank_kids = _kids(kids, ordered, comments)
            if blank_kids and (el_kids or name in STRUCTURAL and len(kids) == sum(
                    1 for k in kids if k[0] == "text")):
                kids = [k for k in kids if k[0] != "text"]   # layout whitespace
            pairs = list(zip(attrs[::2], attrs[1::2], strict=True))
            res.append(("el", name, pairs if ordered else sorted(pairs), kids))
            has_el = True
        elif kind == "text":
            if res and res[-1][0] == "text":
                res[-1] = ("text", res[-1][1] + node[1])
            else:
                res.append(node)
        elif comments or kind != "comment":
            res.append(node)
    for node in res:
        if node[0] == "text" and node[1].strip():
            blank = False
            break
    return res, has_el, blank


def check_same(old: bytes, new: bytes, style: Style, path: str = "",
               old_doc: list[Node] | None = None, new_doc: list[Node] | None = None) -> str | None:
    """None when ``new`` is a safe layout of ``old``; else why not (a formatter bug, or a
    suppression comment whose reach would change). ``new_doc``, when given (empty), receives
    the :func:`read_document` of ``new``."""
    try:
        a = old_doc if old_doc is not None else read_document(old)
        b = read_document(new)
    except FormatError as e:
        return f"internal: the result is not well-formed ({e.message})"
    if new_doc is not None:
        new_doc.extend(b)
    ordered = style.attribute_order != "canonical"
    a = [n for n in a if n[0] != "text"]   # (only whitespace outside the root element)
    b = [n for n in b if n[0] != "text"]
    if normal_nodes(a, ordered) != normal_nodes(b, ordered):
        return "internal: the result would read differently (please report)"
    if b"urdf-lint" in old or b"urdf_lint" in old:
        from urdf_lint.engine.suppress import coverage
        before, after = coverage(old, path), coverage(new, path)
        for (line, what, x), (_, _, y) in zip(before, after, strict=True):
            if x != y:
                return (f"the suppression comment at line {line} ({what}) would cover other "
                        "elements once the lines move")
    return None
