"""``urdf-lint server``: the language server's entry point. It only registers the methods,
one module each in :mod:`urdf_lint.lsp.methods` (``handle(services, params)``; the document
lifecycle is handed the server); the lint, its scheduling and the diagnostics are
:mod:`.core`, the shared state :mod:`.services` and :mod:`.state`."""
from __future__ import annotations

import asyncio
from typing import Any, Callable

from lsprotocol import types

from urdf_lint.lsp.core import UrdfLintServer
from urdf_lint.lsp.methods import (code_action, completion, definition, did_change,
                                   did_change_watched_files, did_close, did_open, did_save,
                                   document_symbol, formatting, hover, initialized, preview,
                                   range_formatting, references, rename, shutdown,
                                   workspace_symbol)

server = UrdfLintServer()


def request(method: str, handle: Callable[[Any, Any], Any], options: Any = None) -> None:
    """Register a request answered from the shared services: ``handle(services, params)``."""
    server.feature(method, options)(lambda ls, params: handle(ls.services, params))


def in_lint_thread(method: str, handle: Callable[[Any, Any], Any]) -> None:
    """Register a request answered in the lint thread: ``handle(services, params)`` may use
    the warm pool of workers (one run at a time, after the lint under way)."""
    async def run(ls: UrdfLintServer, params: Any) -> Any:
        if ls.ws is None:
            return None
        return await asyncio.get_running_loop().run_in_executor(ls.executor, handle,
                                                                ls.services, params)
    server.feature(method)(run)


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
request(types.TEXT_DOCUMENT_RENAME, rename.handle, rename.OPTIONS)
request(types.TEXT_DOCUMENT_PREPARE_RENAME, rename.prepare)
in_lint_thread(types.TEXT_DOCUMENT_FORMATTING, formatting.handle)
in_lint_thread(types.TEXT_DOCUMENT_RANGE_FORMATTING, range_formatting.handle)
server.command(preview.COMMAND)(preview.command)   # (async: it waits for the scenes)
server.command(preview.HIGHLIGHT_COMMAND)(lambda ls, *a: preview.highlight(ls.services, list(a)))


def main() -> int:
    server.start_io()
    if server.ws is not None:
        server.ws.close()
    return 0
