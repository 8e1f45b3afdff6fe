"""The language server's ``urdf-lint.preview`` command: it starts the preview of the file
(its own ``urdf-lint preview`` process) and returns the URL with the element under the cursor
as the highlight; and the VS Code client declares the command."""
from __future__ import annotations

import json
import sys
import urllib.request

import pytest

from conftest import REPO
from support.preview_robot import make_robot

pytest.importorskip("pygls")
pytest_lsp = pytest.importorskip("pytest_lsp")
from lsprotocol import types  # noqa: E402
from pytest_lsp import ClientServerConfig, LanguageClient  # noqa: E402

aio = pytest.mark.asyncio(loop_scope="function")


def test_the_element_under_the_cursor():
    from urdf_lint.lsp.methods.preview import element_at
    text = (REPO / "tests" / "support" / "preview_robot.py").read_text()
    robot = text[text.index('<?xml'):text.index('</robot>') + 8]
    lines = robot.split("\n")
    at = {n: lines[n] for n in range(len(lines))}
    base = next(n for n, s in at.items() if '<link name="base_link">' in s)
    tool_joint = next(n for n, s in at.items() if '<joint name="tool_joint"' in s)
    macro_link = next(n for n, s in at.items() if '<link name="${name}">' in s)
    assert element_at(robot, base, 4) == "link:base_link"
    assert element_at(robot, base + 1, 10) == "link:base_link"     # inside the link
    assert element_at(robot, tool_joint + 1, 30) == "joint:tool_joint"
    assert element_at(robot, tool_joint + 3, 8) == "joint:tool_joint"   # the <mimic> line
    assert element_at(robot, macro_link, 6) == ""                 # a name built by ${...}
    assert element_at(robot, base + 3, 2) == ""                   # after </link>, between


def test_the_vscode_client_declares_the_command():
    manifest = json.loads((REPO / "editors" / "vscode" / "package.json").read_text())
    commands = {c["command"]: c for c in manifest["contributes"]["commands"]}
    # (the client's own command: vscode-languageclient registers the server's
    # `urdf-lint.preview` itself, so the one the user runs needs another id)
    assert "urdf-lint.showPreview" in commands
    assert "onCommand:urdf-lint.showPreview" in manifest["activationEvents"]
    src = (REPO / "editors" / "vscode" / "src" / "extension.ts").read_text()
    assert 'registerCommand("urdf-lint.showPreview"' in src
    assert 'command: "urdf-lint.preview"' in src     # sent to the server (executeCommand)
    assert "openExternal" in src


@pytest.fixture
def robot(tmp_path):
    return make_robot(tmp_path)


@pytest_lsp.fixture(config=ClientServerConfig(
    server_command=[sys.executable, "-m", "urdf_lint", "server"]))
async def client(lsp_client: LanguageClient, robot):
    root = robot.parent.parent
    result = await lsp_client.initialize_session(types.InitializeParams(
        capabilities=types.ClientCapabilities(), root_uri=root.as_uri(),
        workspace_folders=[types.WorkspaceFolder(uri=root.as_uri(), name="arm")]))
    lsp_client.initialized_with = result
    yield
    await lsp_client.shutdown_session()


@aio
async def test_the_command_opens_the_preview_with_the_element_highlighted(client, robot):
    caps = client.initialized_with.capabilities.execute_command_provider
    assert caps is not None and "urdf-lint.preview" in caps.commands
    text = robot.read_text()
    line = text.split("\n").index('  <link name="base_link">')
    client.text_document_did_open(types.DidOpenTextDocumentParams(types.TextDocumentItem(
        uri=robot.as_uri(), language_id="xml", version=1, text=text)))
    got = await client.workspace_execute_command_async(types.ExecuteCommandParams(
        command="urdf-lint.preview", arguments=[robot.as_uri(), line + 1, 6]))
    assert got["highlight"] == "link:base_link"
    url = got["url"]
    assert url.startswith("http://127.0.0.1:") and url.endswith("#highlight=link%3Abase_link")
    state = json.loads(urllib.request.urlopen(url.split("#")[0] + "state.json",
                                              timeout=30).read())
    assert sorted(state["variants"][0]["links"]) == ["base_link", "lower", "tool", "upper"]
    # the same file again: the same preview, another highlight
    again = await client.workspace_execute_command_async(types.ExecuteCommandParams(
        command="urdf-lint.preview", arguments=[robot.as_uri(), 0, 0]))
    assert again["url"] == url.split("#")[0] and again["highlight"] == ""
