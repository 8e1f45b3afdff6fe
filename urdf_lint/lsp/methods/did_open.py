"""``textDocument/didOpen``: the buffer is what counts; linted at once, after the lint under
way (opening a file is no newer text of it: that lint is not stopped)."""
from __future__ import annotations

from lsprotocol import types

from urdf_lint.lsp.core import UrdfLintServer


def handle(ls: UrdfLintServer, params: types.DidOpenTextDocumentParams) -> None:
    ls.schedule(ls.set_buffer(params.text_document.uri), 0.0, newer=False)
