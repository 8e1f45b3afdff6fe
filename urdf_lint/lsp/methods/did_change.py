"""``textDocument/didChange``: latest wins. The lint under way (of older text) stops, and
what the change reaches is linted after the pause in typing, the edited file's model first
(:meth:`UrdfLintServer.schedule`)."""
from __future__ import annotations

from lsprotocol import types

from urdf_lint.lsp.core import DEBOUNCE_S, UrdfLintServer


def handle(ls: UrdfLintServer, params: types.DidChangeTextDocumentParams) -> None:
    ls.schedule(ls.set_buffer(params.text_document.uri), DEBOUNCE_S)
