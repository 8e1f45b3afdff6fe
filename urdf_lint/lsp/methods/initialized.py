"""``initialized``: the workspace folder's config, packages and models are read, the worker
pool forked, and the models are linted as documents open."""
from __future__ import annotations

import os

from lsprotocol import types

from urdf_lint.lsp.core import UrdfLintServer
from urdf_lint.lsp.state import Workspace


def handle(ls: UrdfLintServer, params: types.InitializedParams) -> None:
    root = ls.workspace.root_path or os.getcwd()
    ls.ws = Workspace(root)
    # fork the pool from the main thread, before the lint thread exists
    ls.ws.start()
    ls.publish(set())
    if ls.ws.config_problem is not None:
        ls.publish({ls.ws.config_problem.file})
