"""``textDocument/documentSymbol``: the macros, properties, args, links and joints a file
declares (from its text: :mod:`urdf_lint.lsp.index`)."""
from __future__ import annotations

from lsprotocol import types

from urdf_lint.lsp.services import Services
from urdf_lint.lsp.uris import uri_path

SYMBOL_KIND = {"macro": types.SymbolKind.Function, "property": types.SymbolKind.Constant,
               "arg": types.SymbolKind.Variable, "link": types.SymbolKind.Struct,
               "joint": types.SymbolKind.Interface}


def handle(sv: Services, params: types.DocumentSymbolParams) -> list[types.DocumentSymbol]:
    return document_symbols(sv, uri_path(params.text_document.uri))


def document_symbols(sv: Services, path: str) -> list[types.DocumentSymbol]:
    doc = sv.doc(path)
    out = []
    for d in sv.index.of(path).decls:
        if d.kind == "include":
            continue
        rng = doc.element_range(d.line, d.col)
        out.append(types.DocumentSymbol(name=d.name or "?", kind=SYMBOL_KIND[d.kind], range=rng,
                                        selection_range=rng, detail=d.kind))
    return out
