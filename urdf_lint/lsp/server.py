"""``urdf-lint server``: the language server's entry point and its document lifecycle
(open, change, save, close); the lint and diagnostics are :mod:`.core`, the code actions
:mod:`.actions`, navigation, hover, completion and symbols :mod:`.features`."""
from __future__ import annotations

import asyncio
import os

from lsprotocol import types

from urdf_lint.lsp import actions, features
from urdf_lint.lsp.core import DEBOUNCE_S, UrdfLintServer, uri_path
from urdf_lint.lsp.methods import config_definition
from urdf_lint.lsp.state import Workspace

server = UrdfLintServer()


@server.feature(types.INITIALIZED)
def _initialized(ls: UrdfLintServer, params: types.InitializedParams) -> None:
    root = ls.workspace.root_path or os.getcwd()
    ls.ws = Workspace(root)
    # fork the pool from the main thread, before the lint thread exists
    ls.ws.start()
    ls.publish(set())
    if ls.ws.config_problem is not None:
        ls.publish({ls.ws.config_problem.file})


@server.feature(types.TEXT_DOCUMENT_DID_OPEN)
def _did_open(ls: UrdfLintServer, params: types.DidOpenTextDocumentParams) -> None:
    path = ls.set_buffer(params.text_document.uri)
    ls.schedule(path, 0.0)


@server.feature(types.TEXT_DOCUMENT_DID_CHANGE)
def _did_change(ls: UrdfLintServer, params: types.DidChangeTextDocumentParams) -> None:
    path = ls.set_buffer(params.text_document.uri)
    ls.schedule(path, DEBOUNCE_S)


@server.feature(types.TEXT_DOCUMENT_DID_SAVE)
async def _did_save(ls: UrdfLintServer, params: types.DidSaveTextDocumentParams) -> None:
    path = ls.set_buffer(params.text_document.uri)
    ws = ls.ws
    if ws is not None and os.path.basename(path) in CONFIG_NAMES:
        old = ws.config_problem.file if ws.config_problem else None
        loop = asyncio.get_running_loop()
        await loop.run_in_executor(ls.executor, ws.load)
        ws.start()
        files = await loop.run_in_executor(ls.executor, ws.lint, None)
        ls.publish(files | {path} | ({old} if old else set()))
        return
    ls.schedule(path, 0.0)


@server.feature(types.TEXT_DOCUMENT_DID_CLOSE)
def _did_close(ls: UrdfLintServer, params: types.DidCloseTextDocumentParams) -> None:
    path = uri_path(params.text_document.uri)
    if ls.ws is not None and ls.ws.buffers.pop(path, None) is not None:
        ls.schedule(path, 0.0)   # the file on disk is what counts again


@server.feature(types.WORKSPACE_DID_CHANGE_WATCHED_FILES)
async def _watched(ls: UrdfLintServer, params: types.DidChangeWatchedFilesParams) -> None:
    """Files changed outside the editor (a checkout, a generator): a new or deleted model or
    config re-reads the workspace; a changed file re-lints what it reaches."""
    ws = ls.ws
    if ws is None:
        return
    paths = [(uri_path(c.uri), c.type) for c in params.changes]
    if any(t != types.FileChangeType.Changed and p.endswith((".xacro", ".urdf")) or
           os.path.basename(p) in CONFIG_NAMES for p, t in paths):
        loop = asyncio.get_running_loop()
        await loop.run_in_executor(ls.executor, ws.load)
        ws.start()
        files = await loop.run_in_executor(ls.executor, ws.lint, None)
        ls.publish(files | set(ws.buffers), ls.versions())
        return
    for p, _ in paths:
        if p not in ws.buffers:
            ls.schedule(p, 0.0)


@server.feature(types.SHUTDOWN)
async def _shutdown(ls: UrdfLintServer, params) -> None:
    if ls.ws is not None:
        ls.ws.stop_soon()   # the lint under way ends with the jobs it has started
        await asyncio.get_running_loop().run_in_executor(ls.executor, ls.ws.close)


CONFIG_NAMES = ("pyproject.toml", ".urdf-lint.toml", "urdf-lint.toml")

actions.register(server)
features.register(server)
features.DEFINITION_FIRST.append(config_definition.definition)
features.COMPLETION_FIRST.append(config_definition.completion)


def main() -> int:
    server.start_io()
    if server.ws is not None:
        server.ws.close()
    return 0
