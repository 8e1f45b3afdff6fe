"""The language server's own process reads and offers to write exactly what ``check`` does
(issue 31): every read through the boundary with the run's roots, code-action edits only for
files ``check --fix`` would write, and an open file outside the roots says it is not linted.

(a) and (c) run in this process on a workspace built from strings (no worker is started);
(b) lints in the server's sandboxed workers; (d) runs ``urdf-lint server`` under strace,
driven by a real LSP client."""
from __future__ import annotations

import asyncio
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("pygls")
from lsprotocol import types  # noqa: E402

from conftest import make_package, run_main  # noqa: E402

X = 'xmlns:xacro="http://wiki.ros.org/xacro"'
SECRET = "SECRET_TOKEN_31"
SECRET_LIB = (f'<robot {X}>\n  <!-- {SECRET} doc -->\n'
              f'  <xacro:macro name="secret_macro" params="{SECRET}_param">\n'
              '    <link name="x"/>\n  </xacro:macro>\n'
              f'  <xacro:property name="secret_prop" value="{SECRET}"/>\n</robot>\n')


def _secret_dir(secret: Path) -> Path:
    """A folder outside the workspace (an installed package, a home folder) with xacro, YAML
    and a mesh whose text must never reach the editor."""
    (secret / "pkg").mkdir(parents=True)
    (secret / "lib.xacro").write_text(SECRET_LIB)
    (secret / "abs.xacro").write_text(SECRET_LIB.replace("secret_macro", "abs_macro"))
    (secret / "pkg" / "package.xml").write_text("<package><name>vendor</name></package>")
    (secret / "pkg" / "other.xacro").write_text(SECRET_LIB.replace("secret_macro",
                                                                   "vendor_macro"))
    (secret / "pkg" / "m.stl").write_text(f"solid {SECRET}\nendsolid\n")
    (secret / "values.yaml").write_text(f"token: {SECRET}\n")
    return secret


def _symlinked_workspace(ws: Path, secret: Path) -> tuple[Path, Path]:
    """(package, its model) below ``ws``: the model includes a file that is a symlink to
    ``secret``, a file below a symlinked folder, an absolute path there and ``$(find
    vendor)`` of a package whose folder is a symlink there, and loads a symlinked YAML file
    and a mesh below the symlinked folder; a symlinked entry leads there too."""
    _secret_dir(secret)
    pkg = ws / "bot"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>bot</name></package>")
    (pkg / "urdf" / "lib.xacro").symlink_to(secret / "lib.xacro")
    (pkg / "urdf" / "vendor").symlink_to(secret / "pkg", target_is_directory=True)
    (pkg / "urdf" / "values.yaml").symlink_to(secret / "values.yaml")
    (pkg / "urdf" / "entry.urdf").symlink_to(secret / "lib.xacro")
    (pkg / "linked_pkg").symlink_to(secret / "pkg", target_is_directory=True)   # "vendor"
    model = pkg / "urdf" / "bot.xacro"
    model.write_text(
        f'<robot name="b" {X}>\n'
        '  <xacro:include filename="lib.xacro"/>\n'
        '  <xacro:include filename="vendor/other.xacro"/>\n'
        f'  <xacro:include filename="{secret / "abs.xacro"}"/>\n'
        '  <link name="a"/>\n'
        '  <xacro:secret_macro p="1"/>\n'
        '  <link name="${secret_prop}"/>\n'
        """  <xacro:property name="y" value="${xacro.load_yaml('values.yaml')}"/>\n"""
        '  <link name="m"><visual><geometry>'
        '<mesh filename="package://bot/urdf/vendor/m.stl"/></geometry></visual></link>\n'
        '  <xacro:include filename="$(find vendor)/other.xacro"/>\n'
        '</robot>\n')
    return pkg, model


def _server(root: Path, monkeypatch, tmp_path: Path):
    from urdf_lint.lsp.core import UrdfLintServer
    from urdf_lint.lsp.state import Workspace
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    ls = UrdfLintServer()
    ls.ws = Workspace(str(root), pool_size=1)
    return ls


class _Opens:
    """The paths this process opens below a folder (an audit hook: ``open`` is raised by
    ``open``, ``os.open`` and ``io.open``), while ``on``."""

    def __init__(self, below: Path):
        self.below = str(below.resolve())
        self.seen: list = []
        self.on = False
        sys.addaudithook(self._hook)

    def _hook(self, event, args):
        if self.on and event == "open" and isinstance(args[0], (str, bytes, os.PathLike)):
            p = os.path.realpath(os.fsdecode(args[0]))
            if p.startswith(self.below):
                self.seen.append(p)


def test_hover_definition_and_the_index_never_show_a_file_outside_the_roots(
        tmp_path, monkeypatch):
    """Includes leading out of the roots (a symlinked file, a symlinked folder, an absolute
    path): the document index, hover, definition, completion and symbols show nothing of
    them, and the server process opens no file there."""
    from urdf_lint.lsp.methods import (Refused, completion, definition, document_symbol,
                                       hover, references, rename, workspace_symbol)
    secret = tmp_path / "secret"
    pkg, model = _symlinked_workspace(tmp_path / "ws", secret)
    opens = _Opens(secret)
    ls = _server(pkg, monkeypatch, tmp_path)
    try:
        text = model.read_text()
        ls.ws.buffers[str(model.resolve())] = text.encode()
        path = str(model.resolve())
        opens.on = True
        got, renames = [], []
        for line, char in ((5, 12), (1, 30), (2, 30), (3, 30), (6, 18), (9, 30)):
            p = types.Position(line, char)
            sv = ls.services
            got.append(hover.hover(sv, path, p))
            got.append(definition.definition(sv, path, p))
            got.append(references.references(sv, path, p, True))
            try:   # a rename edits and says nothing of a file outside the roots either
                renames.append(rename.handle(sv, types.RenameParams(
                    text_document=types.TextDocumentIdentifier(uri=model.as_uri()),
                    position=p, new_name="renamed")))
            except Refused as e:
                renames.append(e.reason)   # (naming the workspace's own text at most)
        for line, char in ((5, 9), (6, 17)):   # <xacro:|  and ${|
            got.append(completion.completion(sv, path, types.Position(line, char)))
        got.append(workspace_symbol.workspace_symbols(sv, ""))
        got.append(document_symbol.document_symbols(sv, path))
        for link in ("lib.xacro", "vendor/other.xacro"):   # the editor asks for the symlink
            got.append(document_symbol.document_symbols(
                sv, os.path.realpath(pkg / "urdf" / link)))
        got.append(sv.index.all_files())
        got.append([ls.doc(str(secret / n)).text for n in ("lib.xacro", "values.yaml")])
        opens.on = False
        shown = repr(got)
        assert SECRET not in shown and "secret_macro" not in shown, shown
        assert "vendor_macro" not in shown and "abs_macro" not in shown, shown
        assert str(secret) not in shown, shown
        assert SECRET not in repr(renames) and str(secret) not in repr(renames), renames
        assert "declaration of the macro 'secret_macro' is not in the files" in renames[0]
        assert opens.seen == []
        # the workspace's own declarations are still indexed and shown
        assert [s.name for s in document_symbol.document_symbols(sv, path)] == ["a", "${secret_prop}",
                                                                      "y", "m"]
    finally:
        opens.on = False
        ls.ws.close()


def test_a_document_outside_the_roots_gets_one_not_linted_diagnostic(tmp_path, monkeypatch):
    """A file opened in the editor outside the workspace's roots (directly, or through a
    symlink in the workspace) is not linted, and says so: one information diagnostic, instead
    of looking clean; a file of the workspace gets none of it."""
    secret = tmp_path / "secret"
    pkg, model = _symlinked_workspace(tmp_path / "ws", secret)
    ls = _server(pkg, monkeypatch, tmp_path)
    try:
        for outside in (secret / "lib.xacro", pkg / "urdf" / "lib.xacro"):
            path = os.path.realpath(outside)
            ls.ws.buffers[path] = outside.read_bytes()
            ds = ls.diagnostics(path)
            assert len(ds) == 1, ds
            (d,) = ds
            assert d.severity == types.DiagnosticSeverity.Information
            assert d.message.startswith("not linted: ") and "outside the roots" in d.message
            assert d.source == "urdf-lint"
            ls.ws.buffers.pop(path)
            assert ls.diagnostics(path) == []   # closed: nothing left behind
        inside = str(model.resolve())
        ls.ws.buffers[inside] = model.read_bytes()
        assert not any(d.message.startswith("not linted") for d in ls.diagnostics(inside))
    finally:
        ls.ws.close()


# -- (b) code actions offer only what check --fix would write ----------------------------------
HEAD = f'<?xml version="1.0"?>\n<robot name="r" {X}>\n'
PROPS = (HEAD + '  <xacro:property name="lo" value="1.5"/>\n'
         '  <xacro:property name="hi" value="-0.5"/>\n</robot>\n')
ROBOT = (HEAD + '  <xacro:include filename="$(find common)/urdf/props.xacro"/>\n'
         '  <link name="a"/><link name="b"/><link name="c"/>\n'
         '  <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/>'
         '<axis xyz="0 0 1"/>\n'
         '    <limit lower="${lo}" upper="${hi}" effort="1" velocity="1"/>\n  </joint>\n'
         '  <joint name="wrist" type="revolute"><parent link="b"/><child link="c"/>'
         '<axis xyz="0 0 1"/>\n'
         '    <limit lower="2" upper="1" effort="1" velocity="1"/>\n  </joint>\n</robot>\n')


def _installed(tmp_path: Path) -> tuple[Path, Path]:
    """(an ament prefix holding the installed package ``common``, the robot's package that
    includes its properties): ``common`` is readable (a root), never writable."""
    prefix = tmp_path / "install"
    index = prefix / "share" / "ament_index" / "resource_index" / "packages"
    index.mkdir(parents=True)
    (index / "common").write_text("")
    make_package(prefix / "share", "common", {"urdf/props.xacro": PROPS})
    robot = make_package(tmp_path / "ws", "robot", {"urdf/robot.urdf.xacro": ROBOT})
    return prefix, robot


def test_code_actions_offer_no_edit_of_a_file_check_fix_refuses(tmp_path, monkeypatch):
    """The joint limits of one joint come from the properties of an installed package:
    ``check --fix`` refuses that fix (the file is outside the linted paths) and the editor
    offers it neither as a quick fix nor in "fix all safe"; the other joint's fix, in the
    workspace, is offered by both."""
    from urdf_lint.lsp.methods import code_action
    prefix, robot = _installed(tmp_path)
    props = prefix / "share" / "common" / "urdf" / "props.xacro"
    model = robot / "urdf" / "robot.urdf.xacro"
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(prefix))
    ls = _server(robot, monkeypatch, tmp_path)
    try:
        ls.ws.lint()
        path = str(model.resolve())
        ul302 = [f for f in ls.ws.findings_in(path) if f.code == "UL302"]
        assert sorted(f.line for f in ul302) == [6, 9], ul302   # both joints, in the robot
        params = types.CodeActionParams(
            text_document=types.TextDocumentIdentifier(uri=model.as_uri()),
            range=types.Range(types.Position(0, 0), types.Position(99, 0)),
            context=types.CodeActionContext(diagnostics=[]))
        got = code_action.handle(ls.services, params)
        edited = {uri for a in got if a.edit for uri in a.edit.changes}
        assert edited == {model.as_uri()}, edited
        fixes = [a for a in got if a.title.startswith("UL302:")]
        assert len(fixes) == 1   # the wrist's, in the workspace
        (fix_all,) = [a for a in got if a.kind == code_action.FIX_ALL]
        assert list(fix_all.edit.changes) == [model.as_uri()]
    finally:
        ls.ws.close()
    env = {"AMENT_PREFIX_PATH": str(prefix), "XDG_CACHE_HOME": str(tmp_path / "c")}
    p = run_main("check", ".", "--format", "json", "--no-cache", "--isolated", cwd=robot,
                 env=env)
    refused = {f["line"]: f["fix"].get("refused") for f in json.loads(p.stdout)["findings"]
               if f["code"] == "UL302"}
    assert refused == {6: f"not fixable automatically: {props} is outside the linted paths",
                       9: None}, refused
    p = run_main("check", ".", "--fix", "--no-cache", "--isolated", cwd=robot, env=env)
    assert "Fixed 1 finding in 1 file" in p.stderr, p.stderr
    assert props.read_text() == PROPS


# -- (d) the real server under strace ----------------------------------------------------------
@pytest.mark.skipif(not shutil.which("strace"), reason="strace is not installed (apt: strace)")
@pytest.mark.parametrize("sandbox", ["1", "0"], ids=["sandbox-on", "sandbox-off"])
def test_the_server_process_opens_nothing_outside_the_repository(tmp_path, sandbox):
    """``urdf-lint server`` (and every process it starts: workers, git), driven by a real
    LSP client over a repository full of symlinks that lead to a secret folder: opening,
    editing, hovering, going to definitions, completing, listing symbols and asking for code
    actions, and opening a file of the secret folder, opens no path outside the repository,
    the cache, the (empty) home folder, the Python runtime and the system folders (a call
    that failed, like a worker's open that Landlock refused, opened nothing). With the OS
    sandbox off, the server's own process (its threads) still opens nothing there."""
    from strace_lsp import TracedServer, opened, opened_outside, trace_works
    if not trace_works(tmp_path):
        pytest.skip("strace cannot trace here (ptrace not permitted)")
    repo, secret = tmp_path / "repo", tmp_path / "secret"
    repo.mkdir()
    subprocess.run(["git", "init", "-q"], cwd=repo, check=True)
    pkg, model = _symlinked_workspace(repo, secret)
    text = model.read_text()
    home, cache = tmp_path / "home", tmp_path / "cache"
    home.mkdir()
    traces = tmp_path / "strace"

    async def drive():
        env = {"HOME": str(home), "XDG_CONFIG_HOME": str(home / ".config"),
               "XDG_CACHE_HOME": str(cache), "URDF_LINT_SANDBOX": sandbox}
        async with TracedServer(traces, cwd=repo, env=env) as c:
            await c.initialize(repo)
            uri = c.open(model)
            await c.diagnostics(uri)
            c.change(uri, text.replace('name="a"', 'name="a2"'), 2)
            await c.diagnostics(uri, version=2)
            for line, char in ((5, 12), (1, 30), (2, 30), (3, 30), (6, 18), (9, 30)):
                await c.request("hover", uri, line, char)
                await c.request("definition", uri, line, char)
            await c.request("completion", uri, 5, 9)
            await c.request("code_action", uri, 0, 0)
            await c.request("document_symbol", (pkg / "urdf" / "lib.xacro").as_uri())
            await c.workspace_symbols("")
            out_uri = c.open(secret / "lib.xacro")   # (the editor read it, not the server)
            try:
                outside = await c.diagnostics(out_uri, timeout=10)
            except TimeoutError:
                outside = []
            return c.shown, outside
    shown, outside = asyncio.run(asyncio.wait_for(drive(), 180))
    # with the OS sandbox off (macOS, an old kernel) the server's own process still opens
    # nothing outside; its workers are then confined by check's own code alone (not here)
    bad = opened_outside(traces, [repo, cache, home], server_only=sandbox == "0")
    assert bad == [], "\n".join(bad)
    # (and the trace was read: the server opened the repository's files)
    assert any(path.startswith(str(repo.resolve())) for path, _ in opened(traces)), \
        sorted(opened(traces))[:20]
    assert SECRET not in shown
    assert [d.message.split(":")[0] for d in outside] == ["not linted"]


def test_a_macro_line_is_one_diagnostic_as_check_counts_it(tmp_path, monkeypatch):
    """A swapped limit in a macro that two models call three times: check reports one finding
    (three instances); the editor shows one diagnostic at the macro line listing the joints,
    not one per joint."""
    from test_grouping import ARM, ONE_ARM, TWO_ARMS
    pkg = make_package(tmp_path / "ws", "arms", {"urdf/arm.xacro": ARM,
                                                 "urdf/one.urdf.xacro": ONE_ARM,
                                                 "urdf/two.urdf.xacro": TWO_ARMS})
    ls = _server(pkg, monkeypatch, tmp_path)
    try:
        ls.ws.lint()
        diags = [d for d in ls.diagnostics(str((pkg / "urdf" / "arm.xacro").resolve()))
                 if d.code == "UL302"]
    finally:
        ls.ws.close()
    assert len(diags) == 1, [d.message for d in diags]
    assert "in 3 joints: h_joint, l_joint, r_joint" in diags[0].message, diags[0].message
    p = run_main("check", ".", "--no-cache", cwd=pkg)
    assert "in 3 joints: h_joint, l_joint, r_joint" in p.stdout, p.stdout


def test_the_editor_hides_the_baselines_findings_as_check_does(tmp_path, monkeypatch):
    """A repository adopting urdf-lint with a baseline: its known findings are not shown in the
    editor either (the run's one end, run.finish.scope), new ones are."""
    from test_grouping import ARM, ONE_ARM
    pkg = make_package(tmp_path / "ws", "arms", {"urdf/arm.xacro": ARM,
                                                 "urdf/one.urdf.xacro": ONE_ARM})
    p = run_main("check", ".", "--no-cache", "--write-baseline", "baseline.json", cwd=pkg)
    assert p.returncode == 0, p.stderr
    (pkg / "urdf-lint.toml").write_text('baseline = "baseline.json"\n')
    assert run_main("check", ".", "--no-cache", cwd=pkg).returncode == 0
    arm = str((pkg / "urdf" / "arm.xacro").resolve())
    ls = _server(pkg, monkeypatch, tmp_path)
    try:
        ls.ws.lint()
        assert [d.code for d in ls.diagnostics(arm)] == []
        (pkg / "urdf" / "arm.xacro").write_text(ARM.replace('effort="1"', 'effort="-1"'))
        ls.ws.lint()
        assert "UL304" in [d.code for d in ls.diagnostics(arm)]
    finally:
        ls.ws.close()
