"""Source locations: where in the xacro sources an expanded element came from."""
from __future__ import annotations

import os
from typing import NamedTuple


class Loc(NamedTuple):
    file: str
    line: int
    col: int

    def format(self, base: str | None = None) -> str:
        return f"{display_path(self.file, base)}:{self.line}:{self.col}"


class Origin(NamedTuple):
    """The source of one expanded element.

    ``chain`` holds the macro call sites that led to it, outermost first (each a ``Loc``).
    """
    file: str
    line: int
    col: int
    chain: tuple = ()

    @property
    def loc(self) -> Loc:
        return Loc(self.file, self.line, self.col)

    def format(self, base: str | None = None) -> str:
        return f"{display_path(self.file, base)}:{self.line}:{self.col}"

    def format_chain(self, base: str | None = None) -> str:
        """``called from arm.xacro:22 < robot.urdf.xacro:17`` (innermost call first)."""
        if not self.chain:
            return ""
        return "called from " + " < ".join(
            f"{display_path(c[0], base)}:{c[1]}" for c in reversed(self.chain))


_displayed: dict = {}


def display_path(path: str, base: str | None = None) -> str:
    """A path relative to ``base`` (default: the working directory) when it lies below it.
    Remembered per (path, base): a report names the same few files thousands of times."""
    if not path:
        return "<unknown>"
    base = base or os.getcwd()
    key = (path, base)
    shown = _displayed.get(key)
    if shown is None:
        try:
            rel = os.path.relpath(path, base)
        except ValueError:
            rel = ".."
        shown = path if rel.startswith("..") else rel
        if len(_displayed) > 50000:
            _displayed.clear()
        _displayed[key] = shown
    return shown
