"""``textDocument/rangeFormatting``: the layout of :mod:`.formatting` for the changed lines
that touch the range only, guarded and proved as that partial layout."""
from __future__ import annotations

from lsprotocol import types

from urdf_lint.lsp.methods.formatting import edits
from urdf_lint.lsp.services import Services
from urdf_lint.lsp.uris import uri_path


def handle(sv: Services, params: types.DocumentRangeFormattingParams
           ) -> list[types.TextEdit] | None:
    """Run in the lint thread, as :func:`.formatting.handle`."""
    return edits(sv.ws, uri_path(params.text_document.uri), params.range)
