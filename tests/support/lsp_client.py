"""A real language-server client for the end-to-end tests (pytest-lsp over stdio): the
``client`` fixture starts ``urdf-lint server`` on the workspace the test module's ``lsp_root``
fixture gives (a directory, named ``lsp_root_name`` in the session), and the helpers open a
document and wait for its diagnostics. A test module imports ``client`` and defines
``lsp_root`` (and ``lsp_root_name``)."""
from __future__ import annotations

import asyncio
import sys
from pathlib import Path

import pytest
import pytest_lsp
from lsprotocol import types
from pytest_lsp import ClientServerConfig, LanguageClient


@pytest.fixture
def lsp_root_name() -> str:
    return "ws"


@pytest_lsp.fixture(config=ClientServerConfig(
    server_command=[sys.executable, "-m", "urdf_lint", "server"]))
async def client(lsp_client: LanguageClient, lsp_root: Path, lsp_root_name: str):
    await lsp_client.initialize_session(types.InitializeParams(
        capabilities=types.ClientCapabilities(), root_uri=lsp_root.as_uri(),
        workspace_folders=[types.WorkspaceFolder(uri=lsp_root.as_uri(), name=lsp_root_name)]))
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
