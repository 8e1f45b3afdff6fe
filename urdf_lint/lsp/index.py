"""What the xacro sources declare, read from the text the editor has: macros (parameters,
defaults, doc comments), properties, args, includes, links and joints, each at its line and
column. Navigation, hover, completion and symbols are answered from here and from the
expanded models' source maps."""
from __future__ import annotations

import re
from dataclasses import dataclass, field

XACRO_NS = ("http://wiki.ros.org/xacro", "http://www.ros.org/wiki/xacro")


@dataclass
class Decl:
    """A declaration found in a source file: a macro, property, arg, include, link or joint, where it is."""
    kind: str            # macro | property | arg | include | link | joint
    name: str
    file: str
    line: int            # 1-based
    col: int             # 1-based character column of the '<'
    attrs: dict[str, str] = field(default_factory=dict)
    doc: str = ""        # the comment just above (macros)
    depth: int = 0       # nesting: 0 = a child of the root
    in_macro: str = ""   # the macro it is written in


@dataclass
class FileIndex:
    """The declarations and references of one source file (for definition, references, completion)."""
    file: str
    decls: list[Decl] = field(default_factory=list)


def index_text(path: str, data: bytes) -> FileIndex:
    """The declarations of one file (expat: the start tag's own line and column; a file with
    a syntax error gives what precedes the error)."""
    import xml.parsers.expat
    out = FileIndex(path)
    p = xml.parsers.expat.ParserCreate()
    stack: list[tuple[str, str]] = []   # (tag, macro name or "")
    last_comment: list[str | None] = [None]

    def start(tag: str, attrs: dict[str, str]) -> None:
        macro = next((m for _, m in reversed(stack) if m), "")
        local = tag.split(":", 1)[-1]
        xacro = tag.startswith("xacro:")
        depth = sum(1 for t, _ in stack[1:] if t not in ("xacro:if", "xacro:unless"))
        kind = None
        if xacro and local in ("macro", "property", "arg", "include"):
            kind = local
        elif not xacro and local in ("link", "joint") and stack and (
                depth == 0 or stack[-1][0] in ("xacro:macro", "xacro:if", "xacro:unless")):
            kind = local
        if kind:
            d = Decl(kind, attrs.get("filename" if kind == "include" else "name", ""), path,
                     p.CurrentLineNumber, p.CurrentColumnNumber + 1, dict(attrs),
                     depth=depth, in_macro=macro)
            if kind == "macro" and last_comment[0] is not None:
                d.doc = _dedent(last_comment[0])
            out.decls.append(d)
        last_comment[0] = None
        stack.append((tag, attrs.get("name", "") if kind == "macro" else ""))

    def end(tag: str) -> None:
        stack.pop()
        last_comment[0] = None

    def comment(text: str) -> None:
        last_comment[0] = text
    p.StartElementHandler = start
    p.EndElementHandler = end
    p.CommentHandler = comment
    try:
        p.Parse(data, True)
    except xml.parsers.expat.ExpatError:
        pass
    return out


def _dedent(s: str) -> str:
    lines = [ln.rstrip() for ln in s.strip("\n").split("\n")]
    pad = min((len(ln) - len(ln.lstrip()) for ln in lines if ln.strip()), default=0)
    return "\n".join(ln[pad:] for ln in lines).strip()


def macro_params(params: str) -> list[tuple[str, str | None]]:
    """(name, default or None) of a macro's ``params`` (``*block``, ``**block``, ``x:=1``,
    ``x:=^``, ``x:=^|2``, ``x=1``)."""
    out = []
    for tok in re.findall(r"""\S+?(?:=(?:'[^']*'|"[^"]*"|\S*))?(?=\s|$)""", params or ""):
        m = re.match(r"(\*{0,2}[\w-]+)(?::?=(.*))?$", tok)
        if m:
            out.append((m.group(1), m.group(2)))
    return out
