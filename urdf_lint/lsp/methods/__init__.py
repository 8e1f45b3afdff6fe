"""The language server's methods, one module per LSP method: each a plain function
``handle(ws, params)`` returning the LSP result (registered in :mod:`urdf_lint.lsp.server`)."""
from __future__ import annotations

from pygls.exceptions import JsonRpcException


class Refused(JsonRpcException):
    """The request is refused, :attr:`message` saying why: the response is LSP's
    ``RequestFailed`` error with it, which the editor shows (a rename of a name built by an
    expression, a layout that is not proved)."""
    CODE = -32803

    def __init__(self, reason: str):
        super().__init__(reason)
        self.reason = reason
