"""textDocument/definition and completion in a robot's configuration files (an SRDF, a
controller or MoveIt YAML): from a joint or link name there to the line of the xacro that
writes that element, and the names of those joints and links as completions, in every linted
model the file configures (the models that read it: ``ModelReport.deps``). Asked first by
:mod:`.definition` and :mod:`.completion`; None hands the request on to them."""
from __future__ import annotations

import os
import re

from lsprotocol import types

from urdf_lint.lsp.services import ModelView, Services

CONFIG_SUFFIXES = (".srdf", ".srdf.xacro", ".yaml", ".yml")
NAME = re.compile(r"[A-Za-z0-9_\-/.]+")


def word_at(line: str, col: int) -> str:
    """The name under the cursor (letters, digits, ``_ - / .``), quotes and YAML punctuation
    around it dropped."""
    for m in NAME.finditer(line):
        if m.start() <= col <= m.end():
            return m.group(0).strip(".")
    return ""


def definition(sv: Services, path: str, pos: types.Position) -> list[types.Location] | None:
    """Where the joint or link named under the cursor is written, or None when ``path`` is no
    configuration file (the xacro navigation answers then)."""
    if not path.endswith(CONFIG_SUFFIXES) or sv.ws is None:
        return None
    word = word_at(sv.doc(path).line(pos.line), pos.character)
    if not word:
        return None
    out: dict[tuple[str, int, int], types.Location] = {}
    for v in configured(sv, path):
        for kind in ("joint", "link"):
            el = v.named.get((kind, word))
            o = v.origin.get(el) if el is not None else None
            if o is not None:
                out[(o.file, o.line, o.col)] = sv.loc(o.file, o.line, o.col)
    return list(out.values()) if out else None


def configured(sv: Services, path: str) -> list[ModelView]:
    """The model views of the linted models ``path`` configures: each model's latest report,
    else (while its lint of newer text is under way: the server forgets the older report) the
    last one that expanded (:attr:`Workspace.last_good`)."""
    ws = sv.ws
    if ws is None:
        return []
    real = os.path.realpath(path)
    reports = {r.label: r for r in list(ws.last_good.values())}
    reports.update((r.label, r) for r in ws.models())
    out = []
    for r in reports.values():
        if real in {os.path.realpath(d) for d in r.deps}:
            v = sv.view_of(r)
            if v is not None:
                out.append(v)
    return out


def completion(sv: Services, path: str,
               pos: types.Position) -> list[types.CompletionItem] | None:
    """The joint and link names of the robots the file configures (None when ``path`` is no
    configuration file, or configures no linted robot: the xacro completion answers then)."""
    if not path.endswith(CONFIG_SUFFIXES) or sv.ws is None:
        return None
    items: dict[str, types.CompletionItem] = {}
    for v in configured(sv, path):
        for (kind, name) in v.named:
            items.setdefault(name, types.CompletionItem(
                label=name, detail=f"{kind} of {v.name}",
                kind=types.CompletionItemKind.Field if kind == "joint"
                else types.CompletionItemKind.Module))
    return list(items.values()) if items else None
