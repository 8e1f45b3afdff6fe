"""``textDocument/didSave``: a saved config re-reads the workspace and lints every model;
any other file is linted at once (after the lint under way, which read the same text)."""
from __future__ import annotations

import os

from lsprotocol import types

from urdf_lint.lsp.core import UrdfLintServer

CONFIG_NAMES = ("pyproject.toml", ".urdf-lint.toml", "urdf-lint.toml")


async def handle(ls: UrdfLintServer, params: types.DidSaveTextDocumentParams) -> None:
    path = ls.set_buffer(params.text_document.uri)
    ws = ls.ws
    if ws is not None and os.path.basename(path) in CONFIG_NAMES:
        old = ws.config_problem.file if ws.config_problem else None
        await ls.reload({path} | ({old} if old else set()))
        return
    ls.schedule(path, 0.0, newer=False)   # (the text of its last change: no newer text)
