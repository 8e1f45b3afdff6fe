"""One module per LSP method, each a ``handle(services, params)`` returning the method's
result (ruff's ``server/api/requests``, jedi-language-server's features): thin handlers over
:class:`urdf_lint.lsp.services.Services`. The document lifecycle (``did_open``,
``did_change``, ...) is handed the server itself (it schedules lints and publishes). Adding a
method: a new module here and one line in :mod:`urdf_lint.lsp.server`."""
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
