"""``workspace/didChangeWatchedFiles``: files changed outside the editor (a checkout, a
generator). A new or deleted model or config re-reads the workspace; a changed file re-lints
what it reaches."""
from __future__ import annotations

import os

from lsprotocol import types

from urdf_lint.lsp.core import UrdfLintServer
from urdf_lint.lsp.methods.did_save import CONFIG_NAMES
from urdf_lint.lsp.uris import uri_path


async def handle(ls: UrdfLintServer, params: types.DidChangeWatchedFilesParams) -> None:
    ws = ls.ws
    if ws is None:
        return
    paths = [(uri_path(c.uri), c.type) for c in params.changes]
    if any(t != types.FileChangeType.Changed and p.endswith((".xacro", ".urdf")) or
           os.path.basename(p) in CONFIG_NAMES for p, t in paths):
        await ls.reload()
        return
    for p, _ in paths:
        if p not in ws.buffers:
            ls.schedule(p, 0.0)
