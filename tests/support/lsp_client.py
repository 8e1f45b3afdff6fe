"""A real language-server client for the end-to-end tests (pytest-lsp over stdio): the
``client`` fixture starts ``urdf-lint server`` on the workspace of the fixture the test
module's ``LSP_WORKSPACE`` names (``copy_of`` makes one: a copy of a directory), and the
helpers open a document and wait for its diagnostics."""
from __future__ import annotations

import asyncio
import shutil
import sys
from pathlib import Path

import pytest
import pytest_lsp
from lsprotocol import types
from pytest_lsp import ClientServerConfig, LanguageClient


def copy_of(src: Path, name: str):
    """The fixture ``name``: a copy of the directory ``src`` in the test's tmp_path."""
    @pytest.fixture(name=name)
    def copy(tmp_path) -> Path:
        dst = tmp_path / src.name
        shutil.copytree(src, dst)
        return dst
    return copy


@pytest_lsp.fixture(config=ClientServerConfig(
    server_command=[sys.executable, "-m", "urdf_lint", "server"]))
async def client(lsp_client: LanguageClient, request):
    """The server on the workspace of the fixture the test module's ``LSP_WORKSPACE`` names
    (a folder of that name in the session)."""
    name = request.module.LSP_WORKSPACE
    root = request.getfixturevalue(name)
    await lsp_client.initialize_session(types.InitializeParams(
        capabilities=types.ClientCapabilities(), root_uri=root.as_uri(),
        workspace_folders=[types.WorkspaceFolder(uri=root.as_uri(), name=name)]))
    yield
    await lsp_client.shutdown_session()


def open_doc(client: LanguageClient, path: Path, text: str | None = None,
             language_id: str = "xml") -> str:
    """Opens ``path`` (with ``text``, else its content) in the server; its URI."""
    uri = path.as_uri()
    client.text_document_did_open(types.DidOpenTextDocumentParams(types.TextDocumentItem(
        uri=uri, language_id=language_id, version=1,
        text=path.read_text() if text is None else text)))
    return uri


async def diagnostics_for(client: LanguageClient, uri: str, want=lambda ds: True,
                          timeout: float = 60.0) -> list:
    """The diagnostics of ``uri`` once ``want`` holds for them."""
    async def wait():
        while True:
            got = client.diagnostics.get(uri)
            if got is not None and want(got):
                return got
            await client.wait_for_notification(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
    return await asyncio.wait_for(wait(), timeout)
