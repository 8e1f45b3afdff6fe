"""``textDocument/rangeFormatting``: the layout of :mod:`.formatting` for the changed lines
that touch the range only, guarded and proved as that partial layout."""
from __future__ import annotations

from lsprotocol import types

from urdf_lint.lsp.core import uri_path
from urdf_lint.lsp.methods.formatting import edits

METHOD = types.TEXT_DOCUMENT_RANGE_FORMATTING


def handle(ws, params: types.DocumentRangeFormattingParams) -> list[types.TextEdit] | None:
    return edits(ws, uri_path(params.text_document.uri), params.range)
