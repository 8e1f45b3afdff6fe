"""Positions: urdf-lint's (1-based line, 1-based character column; byte offsets of edits)
to LSP's (0-based line, UTF-16 code units) and back."""
from __future__ import annotations

import re

from lsprotocol import types


def _utf16_len(s: str) -> int:
    return len(s.encode("utf-16-le")) // 2


class Doc:
    """The text of one file as the editor has it (buffer) or as it is on disk."""

    def __init__(self, data: bytes):
        self.data = data
        self.text = data.decode("utf-8", "replace")
        self.lines = self.text.split("\n")

    def line(self, n0: int) -> str:
        return self.lines[n0] if 0 <= n0 < len(self.lines) else ""

    # (line, col) as urdf-lint gives them: 1-based, col in characters
    def position(self, line: int, col: int) -> types.Position:
        n0 = max(0, line - 1)
        return types.Position(n0, _utf16_len(self.line(n0)[:max(0, col - 1)]))

    def char_index(self, pos: types.Position) -> int:
        """The character index in ``pos``'s line of an LSP position."""
        s = self.line(pos.line)
        units = 0
        for i, ch in enumerate(s):
            if units >= pos.character:
                return i
            units += 2 if ord(ch) > 0xFFFF else 1
        return len(s)

    def offset_position(self, offset: int) -> types.Position:
        """An LSP position from a byte offset into ``data``."""
        before = self.data[:offset].decode("utf-8", "replace")
        n0 = before.count("\n")
        return types.Position(n0, _utf16_len(before[before.rfind("\n") + 1:]))

    def element_range(self, line: int, col: int) -> types.Range:
        """The start tag's name (``<link``) at (line, col), or one character there."""
        start = self.position(line, col)
        s = self.line(line - 1)[max(0, col - 1):]
        m = re.match(r"<[\w:.-]+", s)
        n = len(m.group(0)) if m else 1
        return types.Range(start, types.Position(start.line, start.character + _utf16_len(s[:n])))

    def offset(self, pos: types.Position) -> int:
        """The byte offset of an LSP position."""
        head = "\n".join(self.lines[:pos.line])
        if pos.line > 0:
            head += "\n"
        return len(head.encode("utf-8")) + \
            len(self.line(pos.line)[:self.char_index(pos)].encode("utf-8"))
