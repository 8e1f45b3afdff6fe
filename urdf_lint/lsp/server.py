"""``urdf-lint server``: the language server's entry point. It only registers the methods,
one module each in :mod:`urdf_lint.lsp.methods` (``handle(services, params)``; the document
lifecycle is handed the server); the lint, its scheduling and the diagnostics are
:mod:`.core`, the shared state :mod:`.services` and :mod:`.state`."""
from __future__ import annotations

from typing import Any, Callable

from lsprotocol import types

from urdf_lint.lsp.core import UrdfLintServer
from urdf_lint.lsp.methods import (code_action, completion, definition, did_change,
                                   did_change_watched_files, did_close, did_open, did_save,
                                   document_symbol, hover, initialized, references, shutdown,
                                   workspace_symbol)

server = UrdfLintServer()


def request(method: str, handle: Callable[[Any, Any], Any], options: Any = None) -> None:
    """Register a request answered from the shared services: ``handle(services, params)``."""
    server.feature(method, options)(lambda ls, params: handle(ls.services, params))


# the document lifecycle: handed the server (it schedules the lint and publishes)
server.feature(types.INITIALIZED)(initialized.handle)
server.feature(types.TEXT_DOCUMENT_DID_OPEN)(did_open.handle)
server.feature(types.TEXT_DOCUMENT_DID_CHANGE)(did_change.handle)
server.feature(types.TEXT_DOCUMENT_DID_SAVE)(did_save.handle)
server.feature(types.TEXT_DOCUMENT_DID_CLOSE)(did_close.handle)
server.feature(types.WORKSPACE_DID_CHANGE_WATCHED_FILES)(did_change_watched_files.handle)
server.feature(types.SHUTDOWN)(shutdown.handle)
# requests
request(types.TEXT_DOCUMENT_DEFINITION, definition.handle)
request(types.TEXT_DOCUMENT_REFERENCES, references.handle)
request(types.TEXT_DOCUMENT_HOVER, hover.handle)
request(types.TEXT_DOCUMENT_COMPLETION, completion.handle, completion.OPTIONS)
request(types.TEXT_DOCUMENT_DOCUMENT_SYMBOL, document_symbol.handle)
request(types.WORKSPACE_SYMBOL, workspace_symbol.handle)
request(types.TEXT_DOCUMENT_CODE_ACTION, code_action.handle, code_action.OPTIONS)


def main() -> int:
    server.start_io()
    if server.ws is not None:
        server.ws.close()
    return 0
