"""Completion where the editor is mid-edit (``textDocument/completion``, after the completers
of :mod:`urdf_lint.lsp.features`):

* a **block macro** (one taking a ``*block`` parameter or writing ``<xacro:insert_block>``)
  completes as an open/close pair with the cursor between them: its block is the content;
* **link and joint names inside an unclosed attribute** (``<parent link="`` with the rest of
  the file not closed yet): the buffer does not expand while it is typed, so the names come
  from the last model of each variant that expanded (:attr:`Workspace.last_good`), not only
  from the latest lint."""
from __future__ import annotations

import re

from lsprotocol import types

_BLOCK_USE = re.compile(r"<xacro:insert_block\b")


def refine(ls, path: str, at, completer, items: list) -> list:
    """The items ``completer`` gave at ``at``, completed as above."""
    from urdf_lint.lsp import features
    if completer is features._complete_macros:
        return [_block_pair(ls, path, it) for it in items]
    if completer is features._complete_references:
        return _with_last_good(ls, path, at, items)
    return items


def is_block_macro(ls, d) -> bool:
    from urdf_lint.lsp.index import macro_params
    if any(n.startswith("*") for n, _ in macro_params(d.attrs.get("params", ""))):
        return True
    text = ls.doc(d.file).text
    lines = text.split("\n")
    start = sum(len(ln) + 1 for ln in lines[:d.line - 1]) + d.col - 1
    end = text.find("</xacro:macro>", start)
    return bool(_BLOCK_USE.search(text, start, end if end >= 0 else len(text)))


def _block_pair(ls, path: str, item: types.CompletionItem) -> types.CompletionItem:
    from urdf_lint.lsp.features import INDEX
    snippet = item.insert_text or ""
    d = next(iter(INDEX.decls(ls, path, "macro", item.label)), None)
    if d is None or not snippet.endswith("/>") or not is_block_macro(ls, d):
        return item
    item.insert_text = f"{snippet[:-2]}>\n\t$0\n</xacro:{item.label}>"
    item.detail = (item.detail or "macro") + ", takes a block"
    return item


def _with_last_good(ls, path: str, at, items: list) -> list:
    """Add the names of the last model of each variant that expanded and read ``path``."""
    from urdf_lint.lsp.features import _model_files, view_of
    ws = ls.ws
    if ws is None:
        return items
    have = {it.label for it in items}
    want = "joint" if at.attr == "joint" else "link"
    for rep in list(ws.last_good.values()):
        v = view_of(rep)
        if v is None:
            continue
        if path not in _model_files(v):
            continue
        for (k, n) in v.named:
            if (k == want or at.attr == "reference") and n not in have:
                have.add(n)
                items.append(types.CompletionItem(label=n, kind=types.CompletionItemKind.Reference,
                                                  detail=f"{k} in {v.name} (last expanded)"))
    return items
