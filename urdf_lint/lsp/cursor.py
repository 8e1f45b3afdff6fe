"""What is under the cursor (:class:`At`): the enclosing start tag, the attribute, the word,
an expression; and the macro whose body holds it."""
from __future__ import annotations

import re
from typing import Protocol

from lsprotocol import types

from urdf_lint.lsp.index import Decl
from urdf_lint.lsp.services import Services
from urdf_lint.lsp.text import Doc


class At:
    """What is under the cursor: the enclosing start tag, the attribute and the word."""

    def __init__(self, doc: Doc, pos: types.Position):
        self.doc = doc
        self.line = doc.line(pos.line)
        self.i = doc.char_index(pos)
        text, off = doc.text, char_offset(doc, pos.line, self.i)
        self.off = off
        lt = text.rfind("<", 0, off)
        gt = text.rfind(">", 0, off)
        self.tag: str | None = None
        self.tag_line: int | None = None
        self.tag_col: int | None = None
        self.attr: str | None = None
        self.value: str | None = None
        self.value_pos = 0
        self.in_tag = lt > gt and lt >= 0 and text[lt + 1:lt + 2] not in ("/", "!", "?")
        if self.in_tag:
            m = re.match(r"<([\w:.-]+)", text[lt:])
            self.tag = m.group(1) if m else None
            self.tag_line = text.count("\n", 0, lt) + 1
            self.tag_col = lt - (text.rfind("\n", 0, lt) + 1) + 1
            head = text[lt:off]
            am = re.search(r"""([\w:.-]+)\s*=\s*(["'])([^"']*)$""", head)
            if am:
                self.attr = am.group(1)
                rest = text[off:]
                tail = rest[:rest.find(am.group(2))] if am.group(2) in rest else ""
                self.value = am.group(3) + tail
                self.value_pos = len(am.group(3))
        self.comment = text.rfind("<!--", 0, off) > text.rfind("-->", 0, off)
        s, i = self.line, self.i
        a = i
        while a > 0 and re.match(r"[\w.-]", s[a - 1]):
            a -= 1
        b = i
        while b < len(s) and re.match(r"[\w.-]", s[b]):
            b += 1
        self.word, self.word_start, self.word_end = s[a:b], a, b
        self.before = s[:i]

    def expr(self) -> str | None:
        """The ``${...}`` the cursor is in (its text), if any."""
        s, i = self.line, self.i
        a = s.rfind("${", 0, i)
        if a < 0 or "}" in s[a:i]:
            return None
        b = s.find("}", i)
        return s[a + 2:b if b >= 0 else len(s)]

    def arg(self) -> bool:
        return bool(re.search(r"\$\(arg\s+[\w-]*$", self.line[:self.word_start]
                              + self.word[:self.i - self.word_start]))

    def on_macro_call(self, pos: types.Position) -> str | None:
        """The macro name when the cursor is on a ``<xacro:NAME`` start tag's line (not in
        one of its attributes)."""
        if self.tag and self.tag.startswith("xacro:") and self.attr is None and \
                self.tag_line == pos.line + 1:
            return self.tag.split(":", 1)[1]
        return None


def char_offset(doc: Doc, line0: int, i: int) -> int:
    return sum(len(ln) + 1 for ln in doc.lines[:line0]) + i


def enclosing_macro(sv: Services, path: str, at: At) -> Decl | None:
    """The macro whose body holds the cursor (the last macro start above it whose end is not
    above it: a macro's body is the text up to its end tag)."""
    text = at.doc.text
    best = None
    for d in sv.index.of(path).decls:
        if d.kind != "macro":
            continue
        start = char_offset(at.doc, d.line - 1, d.col - 1)
        end = text.find("</xacro:macro>", start)
        if start <= at.off and (end < 0 or at.off <= end):
            best = d
    return best


class PositionParams(Protocol):
    """The params of a request about a place in a document (hover, definition, ...)."""
    @property
    def text_document(self) -> types.TextDocumentIdentifier: ...

    @property
    def position(self) -> types.Position: ...


def params_of(params: PositionParams) -> tuple[str, types.Position]:
    """(real path, position) of a request about a place in a document."""
    from urdf_lint.lsp.uris import uri_path
    return uri_path(params.text_document.uri), params.position
