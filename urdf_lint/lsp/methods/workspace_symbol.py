"""``workspace/symbol``: the declarations of every xacro file of the workspace whose name
holds the query."""
from __future__ import annotations

from lsprotocol import types

from urdf_lint.lsp.methods.document_symbol import SYMBOL_KIND
from urdf_lint.lsp.services import Services


def handle(sv: Services, params: types.WorkspaceSymbolParams) -> list[types.WorkspaceSymbol]:
    return workspace_symbols(sv, params.query)


def workspace_symbols(sv: Services, query: str) -> list[types.WorkspaceSymbol]:
    out = []
    q = query.lower()
    for f in sv.index.all_files():
        for d in sv.index.of(f).decls:
            if d.kind != "include" and q in d.name.lower():
                out.append(types.WorkspaceSymbol(name=d.name, kind=SYMBOL_KIND[d.kind],
                                                 location=sv.loc(d.file, d.line, d.col)))
    return out
