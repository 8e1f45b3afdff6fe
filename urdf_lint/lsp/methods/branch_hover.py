"""Hover on an ``<xacro:if>``/``<xacro:unless>``: which linted models (and the variants
explored for them) expand its body, which evaluate it and leave it out (the workers record
every condition's outcome: ``ModelReport.branches``; docs/coverage.md)."""
from __future__ import annotations

import os
from typing import Any

from lsprotocol import types

CONDITIONS = ("xacro:if", "xacro:unless")


def outcomes(models: list[Any], path: str, line: int) -> tuple[list[str], list[str]]:
    """(the models whose expansion kept the body of the condition at ``path:line``, those that
    evaluated it and left it out), by name and args."""
    kept: list[str] = []
    left: list[str] = []
    real = os.path.realpath(path)
    for r in models:
        got = {bool(b[3]) for b in r.branches
               if b[1] == line and os.path.realpath(b[0]) == real}
        name = _name(r)
        if True in got:
            kept.append(name)
        elif got:
            left.append(name)
    return sorted(set(kept)), sorted(set(left))


def _name(r: Any) -> str:
    base: str = r.name or os.path.basename(r.entry)
    if r.args:
        base += " [" + " ".join(f"{k}:={v}" for k, v in sorted(r.args.items())) + "]"
    return base


def branch_hover(ls: Any, path: str, tag: str | None, tag_line: int | None
                 ) -> types.Hover | None:
    """The hover of a condition's start tag, or None (not a condition, or no model reads it)."""
    if tag not in CONDITIONS or not tag_line or ls.ws is None:
        return None
    # the models and their explored variants (Workspace.explore)
    kept, left = outcomes(list(ls.ws.models()) + list(ls.ws.variants.values()), path, tag_line)
    if not kept and not left:
        return None
    rows = [f"**{tag}**"]
    rows.append("body expanded in: " + (", ".join(f"`{k}`" for k in kept) or "no linted model"))
    if left:
        rows.append("left out in: " + ", ".join(f"`{k}`" for k in left))
    if not kept:
        rows.append("`urdf-lint check --coverage` says whether an arg value takes it")
    return types.Hover(contents=types.MarkupContent(kind=types.MarkupKind.Markdown,
                                                    value="\n\n".join(rows)))
