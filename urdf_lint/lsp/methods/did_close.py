"""``textDocument/didClose``: the file on disk is what counts again."""
from __future__ import annotations

from lsprotocol import types

from urdf_lint.lsp.core import UrdfLintServer
from urdf_lint.lsp.uris import uri_path


def handle(ls: UrdfLintServer, params: types.DidCloseTextDocumentParams) -> None:
    path = uri_path(params.text_document.uri)
    if ls.ws is not None and ls.ws.buffers.pop(path, None) is not None:
        ls.schedule(path, 0.0)
