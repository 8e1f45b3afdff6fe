"""The language server's ``urdf-lint.preview`` command: it starts the preview of the file
(its server in the language server's process, its scenes the server's own reports) and returns
the URL with the element under the cursor as the highlight; an unsaved edit reaches the open
page; a click in the page shows the element's line in the editor (``window/showDocument``),
and a forged click is refused; and the VS Code client declares the command."""
from __future__ import annotations

import asyncio
import json
import sys
import time
import types as pytypes
import urllib.parse
import urllib.request

import pytest

from conftest import REPO
from support.preview_robot import get, make_robot

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
    # the highlight follows the cursor of a previewed file
    assert "onDidChangeTextEditorSelection" in src
    assert 'command: "urdf-lint.previewHighlight"' in src


@pytest.fixture
def robot(tmp_path):
    return make_robot(tmp_path)


@pytest_lsp.fixture(config=ClientServerConfig(
    server_command=[sys.executable, "-m", "urdf_lint", "server"]))
async def client(lsp_client: LanguageClient, robot):
    root = robot.parent.parent
    # (pytest-lsp's client answers window/showDocument and keeps each in .shown_documents)
    caps = types.ClientCapabilities(window=types.WindowClientCapabilities(
        show_document=types.ShowDocumentClientCapabilities(support=True)))
    result = await lsp_client.initialize_session(types.InitializeParams(
        capabilities=caps, root_uri=root.as_uri(),
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


async def _open_preview(client, robot, line=0, character=0):
    text = robot.read_text()
    client.text_document_did_open(types.DidOpenTextDocumentParams(types.TextDocumentItem(
        uri=robot.as_uri(), language_id="xml", version=1, text=text)))
    got = await client.workspace_execute_command_async(types.ExecuteCommandParams(
        command="urdf-lint.preview", arguments=[robot.as_uri(), line, character]))
    return text, got["url"].split("#")[0]


def _fetch(url: str, path: str):
    return json.loads(urllib.request.urlopen(url + path, timeout=30).read())


def _server_of(url: str):
    """(an object ``get`` takes, the token) of a preview URL."""
    u = urllib.parse.urlsplit(url)
    return pytypes.SimpleNamespace(port=u.port), u.path.strip("/")


@aio
async def test_an_unsaved_edit_reaches_the_open_preview(client, robot):
    text, url = await _open_preview(client, robot)
    first = _fetch(url, "state.json")
    assert "probe" not in first["variants"][0]["links"]
    # the editor adds a link and renames a joint, and does not save
    edited = text.replace('<link name="tool"/>', '<link name="tool"/>\n  <link name="probe"/>\n'
                          '  <joint name="probe_joint" type="fixed"><parent link="tool"/>'
                          '<child link="probe"/></joint>').replace('"tool_joint"', '"tip_joint"')
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=robot.as_uri(), version=2),
        content_changes=[types.TextDocumentContentChangeWholeDocument(text=edited)]))
    end = time.monotonic() + 90
    while True:
        # (the page's own long poll: it answers when the version changes)
        await asyncio.to_thread(_fetch, url, f"version?v={first['version']}")
        state = _fetch(url, "state.json")
        if "probe" in state["variants"][0]["links"] or time.monotonic() > end:
            break
    v = state["variants"][0]
    assert sorted(v["links"]) == ["base_link", "lower", "probe", "tool", "upper"]
    assert sorted(v["joints"]) == ["lower_joint", "probe_joint", "tip_joint", "upper_joint"]
    assert '<link name="probe"/>' in v["urdf"]
    # where the new link was written: the buffer's line (the file on disk has no such line)
    lines = edited.split("\n")
    assert v["links"]["probe"][1] == lines.index('  <link name="probe"/>') + 1
    assert robot.read_text() == text   # nothing was saved
    # mid-edit, the buffer does not expand (an unclosed tag): the page keeps the last robot
    # that did, and says so
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=robot.as_uri(), version=3),
        content_changes=[types.TextDocumentContentChangeWholeDocument(
            text=edited.replace("</robot>", ""))]))
    end = time.monotonic() + 90
    while True:
        await asyncio.to_thread(_fetch, url, f"version?v={state['version']}")
        state = _fetch(url, "state.json")
        v = state["variants"][0]
        if any("does not expand" in n for n in v["notes"]) or time.monotonic() > end:
            break
    assert any("the last version that expanded is shown" in n for n in v["notes"]), v
    assert "probe" in v["links"] and v["error"] == ""


def _click(url: str, body: dict, origin: str | None = "own", token: str | None = None,
           kind: str = "application/json"):
    server, own_token = _server_of(url)
    headers = {"Content-Type": kind}
    if origin == "own":
        origin = f"http://127.0.0.1:{server.port}"
    if origin is not None:
        headers["Origin"] = origin
    return get(server, f"/{token or own_token}/jump", headers, method="POST",
               body=json.dumps(body).encode())


@aio
async def test_a_click_in_the_page_shows_its_line_in_the_editor(client, robot):
    text, url = await _open_preview(client, robot)
    state = _fetch(url, "state.json")
    assert state["editor"] is True
    lines = text.split("\n")
    base = lines.index('  <link name="base_link">')
    status, body = await asyncio.to_thread(
        _click, url, {"version": state["scene_version"], "variant": 0,
                       "element": "link:base_link"})
    assert status == 200, body
    shown = client.shown_documents[-1]
    assert shown.uri == robot.as_uri() and not shown.external
    assert shown.selection.start.line == base and shown.selection.start.character == 2
    # a link a macro writes: the macro's <link> line, as the findings' source map says
    macro = next(n for n, s in enumerate(lines) if '<link name="${name}">' in s)
    assert (await asyncio.to_thread(_click, url, {"variant": 0, "element": "link:upper"}))[0] \
        == 200
    assert client.shown_documents[-1].selection.start.line == macro
    # a finding's marker: that finding's line
    v = state["variants"][0]
    i = next(n for n, f in enumerate(v["findings"]) if f["target"] == ["link", "tool"])
    assert (await asyncio.to_thread(
        _click, url, {"version": state["scene_version"], "variant": 0, "finding": i}))[0] == 200
    assert client.shown_documents[-1].selection.start.line == v["findings"][i]["line"] - 1


@aio
async def test_a_forged_click_is_refused_and_shows_nothing(client, robot):
    _, url = await _open_preview(client, robot)
    server, _ = _server_of(url)
    ok = {"variant": 0, "element": "link:base_link"}
    refused = [
        (_click, (url, ok), {"origin": None}, 403),                     # no Origin
        (_click, (url, ok), {"origin": "http://evil.example"}, 403),
        (_click, (url, ok), {"origin": f"http://localhost:{server.port + 1}"}, 403),
        (_click, (url, ok), {"token": "x" * 32}, 404),
        (_click, (url, ok), {"kind": "text/plain"}, 415),              # a form's simple POST
        (_click, (url, {"variant": 0, "element": "link:nope"}), {}, 400),
        (_click, (url, {"variant": 0, "file": "/etc/passwd", "line": 1}), {}, 400),
        (_click, (url, {"variant": 7, "element": "link:base_link"}), {}, 400),
        (_click, (url, {"version": -5, "variant": 0, "finding": 0}), {}, 409),
    ]
    for f, args, kw, code in refused:
        status, body = await asyncio.to_thread(f, *args, **kw)
        assert status == code, (kw, args[1], status, body)
    # a wrong Host (DNS rebinding)
    status, _ = await asyncio.to_thread(
        get, server, f"/{_server_of(url)[1]}/jump", {"Content-Type": "application/json",
                                                      "Origin": "http://evil.example"},
        "POST", "evil.example", b"{}")
    assert status == 403
    await asyncio.sleep(0.5)
    assert client.shown_documents == []


@aio
async def test_the_highlight_follows_the_cursor(client, robot):
    text, url = await _open_preview(client, robot)
    first = _fetch(url, "state.json")
    assert first["highlight"] == ""
    lines = text.split("\n")
    mimic = next(n for n, s in enumerate(lines) if "<mimic" in s)

    async def cursor(line, character):
        return await client.workspace_execute_command_async(types.ExecuteCommandParams(
            command="urdf-lint.previewHighlight", arguments=[robot.as_uri(), line, character]))
    got = await cursor(mimic, 6)
    assert got == {"highlight": "joint:tool_joint"}
    state = _fetch(url, "state.json")
    assert state["highlight"] == "joint:tool_joint" and state["version"] > first["version"]
    assert state["scene_version"] == first["scene_version"]   # the page restyles, no reload
    assert (await cursor(lines.index('  <link name="base_link">') + 1, 8)) == \
        {"highlight": "link:base_link"}
    assert _fetch(url, "state.json")["highlight"] == "link:base_link"
    # a file no preview shows: nothing happens, nothing starts
    other = robot.parent / "other.urdf"
    other.write_text('<robot name="o"><link name="a"/></robot>\n')
    got = await client.workspace_execute_command_async(types.ExecuteCommandParams(
        command="urdf-lint.previewHighlight", arguments=[other.as_uri(), 0, 20]))
    assert got == {"highlight": ""}


@aio
async def test_an_unsaved_edit_reaches_the_open_page_in_chromium(client, robot, tmp_path):
    """The page itself (Debian's Chromium, as tests/test_preview_browser.py drives it) shows
    the link a didChange added, without a save. Playwright's sync API lives in one thread of
    its own (the client's loop runs here)."""
    import concurrent.futures
    import os
    chromium = "/usr/bin/chromium"
    if not os.access(chromium, os.X_OK):
        pytest.skip("no /usr/bin/chromium")
    sync_api = pytest.importorskip("playwright.sync_api")
    text, url = await _open_preview(client, robot)
    one = concurrent.futures.ThreadPoolExecutor(max_workers=1)
    loop = asyncio.get_running_loop()
    held = {}

    def until(expr, timeout):
        # (page.evaluate goes through DevTools: wait_for_function's eval is what the CSP forbids)
        end = time.monotonic() + timeout
        while not held["page"].evaluate(expr):
            assert time.monotonic() < end, (expr, held["errors"])
            time.sleep(0.1)

    def open_page():
        held["pw"] = sync_api.sync_playwright().start()
        b = held["browser"] = held["pw"].chromium.launch(
            executable_path=chromium, args=["--headless", "--no-sandbox", "--disable-gpu"])
        page = held["page"] = b.new_page(viewport={"width": 1000, "height": 700})
        held["errors"] = []
        page.on("pageerror", lambda e: held["errors"].append(str(e)))
        page.goto(url)
        until("!!(window.preview && window.preview.ready)", 60)
        return page.evaluate("Object.keys(preview.robot.links).sort()")

    def wait_for_probe():
        page = held["page"]
        until("preview.ready && !!preview.robot && !!preview.robot.links.probe", 90)
        page.screenshot(path=str(tmp_path / "after-edit.png"))
        return (page.evaluate("Object.keys(preview.robot.links).sort()"),
                page.evaluate("preview.robot.joints.probe_joint.parent.name"))

    def close():
        held["browser"].close()
        held["pw"].stop()
    try:
        assert await loop.run_in_executor(one, open_page) == ["base_link", "lower", "tool",
                                                               "upper"]
        edited = text.replace('<link name="tool"/>', '<link name="tool"/>\n  <link name="probe">'
                              '<visual><geometry><sphere radius="0.08"/></geometry></visual>'
                              '</link>\n  <joint name="probe_joint" type="fixed"><parent '
                              'link="tool"/><child link="probe"/><origin xyz="0 0 0.1"/>'
                              '</joint>')
        client.text_document_did_change(types.DidChangeTextDocumentParams(
            text_document=types.VersionedTextDocumentIdentifier(uri=robot.as_uri(), version=2),
            content_changes=[types.TextDocumentContentChangeWholeDocument(text=edited)]))
        links, parent = await loop.run_in_executor(one, wait_for_probe)
        assert links == ["base_link", "lower", "probe", "tool", "upper"]
        assert parent == "tool" and held["errors"] == []
        if os.environ.get("URDF_LINT_PREVIEW_SHOT"):
            import shutil
            shutil.copy(tmp_path / "after-edit.png", os.environ["URDF_LINT_PREVIEW_SHOT"])
    finally:
        await loop.run_in_executor(one, close)
        one.shutdown()
    assert robot.read_text() == text   # nothing was saved


def test_in_neovim_a_click_moves_the_cursor_and_the_cursor_the_highlight(robot, tmp_path):
    """Neovim's own LSP client (headless, editors/neovim/urdf_lint.lua: :UrdfLintPreview, its
    window/showDocument handler, its CursorHold hook): a click on base_link in the page puts
    Neovim's cursor on that link's line; the cursor moved to tool_joint's <mimic> line moves
    the page's highlight."""
    import os
    import shutil
    import subprocess
    if not shutil.which("nvim"):
        pytest.skip("nvim is not installed (apt: neovim)")
    out = tmp_path / "nvim.json"
    env = dict(os.environ, URDF_LINT_NVIM_OUT=str(out), URDF_LINT_PY=sys.executable,
               URDF_LINT_NVIM_PLUGIN=str(REPO / "editors" / "neovim" / "urdf_lint.lua"))
    lines = robot.read_text().split("\n")
    base = lines.index('  <link name="base_link">')
    mimic = next(n for n, s in enumerate(lines) if "<mimic" in s)
    nvim = subprocess.Popen(
        ["nvim", "--headless", "-u", "NONE", "-i", "NONE", "-n", str(robot),
         "-c", f"luafile {REPO / 'tests' / 'support' / 'nvim_preview_probe.lua'}"],
        cwd=robot.parent, env=env, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL)

    def seen(pred, timeout=90):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            try:
                s = json.loads(out.read_text())
            except (OSError, ValueError):
                s = None
            if s and pred(s):
                return s
            assert nvim.poll() is None, "nvim ended"
            time.sleep(0.1)
        raise AssertionError(f"timed out; last: {out.read_text() if out.exists() else None}")
    try:
        url = seen(lambda s: s["url"])["url"].split("#")[0]
        assert seen(lambda s: True)["cursor"] == [1, 0]
        status, body = _click(url, {"variant": 0, "element": "link:base_link"})
        assert status == 200, body
        s = seen(lambda s: s["cursor"] != [1, 0])
        assert s["cursor"] == [base + 1, 2] and s["file"] == str(robot)
        (tmp_path / "nvim.json.move").write_text(str(mimic + 1))
        seen(lambda s: s["moved"])
        end = time.monotonic() + 30
        while _fetch(url, "state.json")["highlight"] != "joint:tool_joint":
            assert time.monotonic() < end, _fetch(url, "state.json")["highlight"]
            time.sleep(0.1)
    finally:
        (tmp_path / "nvim.json.quit").write_text("")
        try:
            nvim.wait(20)
        except subprocess.TimeoutExpired:
            nvim.kill()
            nvim.wait()
