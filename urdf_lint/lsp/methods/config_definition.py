"""textDocument/definition and completion in a robot's configuration files (an SRDF, a
controller or MoveIt YAML): from a joint or link name there to the line of the xacro that
writes that element, and the names of those joints and links as completions, in every linted
model the file configures (the models that read it: ``ModelReport.deps``)."""
from __future__ import annotations

import os
import re

from lsprotocol import types

CONFIG_SUFFIXES = (".srdf", ".srdf.xacro", ".yaml", ".yml")
NAME = re.compile(r"[A-Za-z0-9_\-/.]+")


def word_at(line: str, col: int) -> str:
    """The name under the cursor (letters, digits, ``_ - / .``), quotes and YAML punctuation
    around it dropped."""
    for m in NAME.finditer(line):
        if m.start() <= col <= m.end():
            return m.group(0).strip(".")
    return ""


def definition(ls, path: str, pos: types.Position) -> list[types.Location] | None:
    """Where the joint or link named under the cursor is written, or None when ``path`` is no
    configuration file (the xacro navigation answers then)."""
    if not path.endswith(CONFIG_SUFFIXES) or ls.ws is None:
        return None
    word = word_at(ls.doc(path).line(pos.line), pos.character)
    if not word:
        return None
    from urdf_lint.lsp.features import _loc
    out: dict = {}
    for v in _configured(ls, path):
        for kind in ("joint", "link"):
            el = v.named.get((kind, word))
            o = v.origin.get(el) if el is not None else None
            if o is not None:
                out[(o.file, o.line, o.col)] = _loc(ls, o.file, o.line, o.col)
    return list(out.values()) if out else None


def _configured(ls, path: str) -> list:
    """The model views of the linted models ``path`` configures."""
    from urdf_lint.lsp.features import views
    real = os.path.realpath(path)
    configured = {r.label for r in ls.ws.models()
                  if real in {os.path.realpath(d) for d in r.deps}}
    return [v for v in views(ls) if v.label in configured]


def completion(ls, path: str, pos: types.Position) -> list[types.CompletionItem] | None:
    """The joint and link names of the robots the file configures (None when ``path`` is no
    configuration file, or configures no linted robot: the xacro completion answers then)."""
    if not path.endswith(CONFIG_SUFFIXES) or ls.ws is None:
        return None
    items: dict = {}
    for v in _configured(ls, path):
        for (kind, name) in v.named:
            items.setdefault(name, types.CompletionItem(
                label=name, detail=f"{kind} of {v.name}",
                kind=types.CompletionItemKind.Field if kind == "joint"
                else types.CompletionItemKind.Module))
    return list(items.values()) if items else None
