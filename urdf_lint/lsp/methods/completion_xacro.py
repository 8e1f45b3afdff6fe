"""Completion where the editor is mid-edit (``textDocument/completion``: applied by
:mod:`urdf_lint.lsp.methods.completion` to the items of the completer that answered):

* a **block macro** (one taking a ``*block`` parameter or writing ``<xacro:insert_block>``)
  completes as an open/close pair with the cursor between them: its block is the content
  (:func:`block_pairs`, after the macro names);
* **link and joint names inside an unclosed attribute** (``<parent link="`` with the rest of
  the file not closed yet): the buffer does not expand while it is typed, so the names come
  from the last model of each variant that expanded (:attr:`Workspace.last_good`), not only
  from the latest lint (:func:`with_last_good`, after the link and joint names)."""
from __future__ import annotations

import re

from lsprotocol import types

from urdf_lint.lsp.cursor import At
from urdf_lint.lsp.index import Decl, macro_params
from urdf_lint.lsp.services import Services

_BLOCK_USE = re.compile(r"<xacro:insert_block\b")


def block_pairs(sv: Services, path: str, items: list[types.CompletionItem]
                ) -> list[types.CompletionItem]:
    """The macro names ``items``, a block macro's as an open/close pair."""
    return [_block_pair(sv, path, it) for it in items]


def is_block_macro(sv: Services, d: Decl) -> bool:
    if any(n.startswith("*") for n, _ in macro_params(d.attrs.get("params", ""))):
        return True
    text = sv.doc(d.file).text
    lines = text.split("\n")
    start = sum(len(ln) + 1 for ln in lines[:d.line - 1]) + d.col - 1
    end = text.find("</xacro:macro>", start)
    return bool(_BLOCK_USE.search(text, start, end if end >= 0 else len(text)))


def _block_pair(sv: Services, path: str, item: types.CompletionItem) -> types.CompletionItem:
    snippet = item.insert_text or ""
    d = next(iter(sv.index.decls(path, "macro", item.label)), None)
    if d is None or not snippet.endswith("/>") or not is_block_macro(sv, d):
        return item
    item.insert_text = f"{snippet[:-2]}>\n\t$0\n</xacro:{item.label}>"
    item.detail = (item.detail or "macro") + ", takes a block"
    return item


def with_last_good(sv: Services, path: str, at: At, items: list[types.CompletionItem]
                   ) -> list[types.CompletionItem]:
    """Add the names of the last model of each variant that expanded and read ``path``."""
    ws = sv.ws
    if ws is None:
        return items
    have = {it.label for it in items}
    want = "joint" if at.attr == "joint" else "link"
    for rep in list(ws.last_good.values()):
        v = sv.view_of(rep)
        if v is None or path not in v.files:
            continue
        for (k, n) in v.named:
            if (k == want or at.attr == "reference") and n not in have:
                have.add(n)
                items.append(types.CompletionItem(label=n, kind=types.CompletionItemKind.Reference,
                                                  detail=f"{k} in {v.name} (last expanded)"))
    return items
