"""`urdf-lint server` end to end: a real LSP client (pytest-lsp) talks to the server over
stdio, on a copy of the corpus UR description, and checks positions and contents."""
from __future__ import annotations

import asyncio
import os
import shutil
import sys
from pathlib import Path

import pytest

pytest.importorskip("pygls")
pytest_lsp = pytest.importorskip("pytest_lsp")
from lsprotocol import types  # noqa: E402
from pytest_lsp import ClientServerConfig, LanguageClient  # noqa: E402

from conftest import CORPUS  # noqa: E402
from support import lsp_client  # noqa: E402
from support.lsp_client import diagnostics_for, open_doc  # noqa: E402

# (a worktree beside the checkout: URDF_LINT_CORPUS names the corpus)
UR = Path(os.environ.get("URDF_LINT_CORPUS") or CORPUS) / "ur_description"
pytestmark = pytest.mark.skipif(not (UR / "package.xml").is_file(),
                                reason="the corpus UR description is not present")
aio = pytest.mark.asyncio(loop_scope="function")

ur = lsp_client.copy_of(UR, "ur")
LSP_WORKSPACE = "ur"             # the fixture the client's server works on
client = lsp_client.client


def change(client: LanguageClient, uri: str, text: str, version: int) -> None:
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=version),
        content_changes=[types.TextDocumentContentChangeWholeDocument(text=text)]))


def pos(d):
    return (d.range.start.line, d.range.start.character)


@aio
async def test_diagnostics_in_an_included_macro_file_with_the_call_chain(client, ur):
    """ur_macro.xacro is a macro library: it shows the findings of the robots including it
    (the missing visual meshes of ur10), at its own lines, with each call site as related
    information."""
    macro = ur / "urdf" / "inc" / "ur_macro.xacro"
    uri = open_doc(client, macro)
    ds = await diagnostics_for(client, uri, lambda ds: any(d.code == "UL401" for d in ds))
    base = [d for d in ds if d.code == "UL401" and "ur10/visual/base.dae" in d.message]
    assert len(base) == 1
    d = base[0]
    assert pos(d) == (83, 10)                     # line 84, col 11: the <mesh> in the macro
    assert d.range.end == types.Position(83, 15)  # "<mesh"
    assert d.severity == types.DiagnosticSeverity.Error and d.source == "urdf-lint"
    # one diagnostic per finding, as check counts it: the missing base.dae of every variant
    # that reads it (ur10, ur10e, ...) at this macro line is one finding
    assert "(in ur10, ur10e, ur16e, ur20 ...)" in d.message, d.message
    rel = [(r.location.uri.rsplit("/", 1)[-1], r.location.range.start.line,
            r.location.range.start.character) for r in d.related_information]
    # every instance's call sites (issue 36: instances in the related information too)
    assert rel[:2] == [("ur10.xacro", 20, 2), ("ur10_macro.xacro", 34, 4)], rel
    assert ("ur10e.xacro", 20, 2) in rel and len(rel) == len(set(rel)), rel


@aio
async def test_diagnostics_follow_the_unsaved_buffer_and_reach_every_robot(client, ur):
    """An unsaved edit of the shared macro (a joint axis of length 2) is linted from the
    buffer, not the file, and lands for all nine robots at the edited line; undoing it in the
    buffer clears it. The file on disk is never written."""
    macro = ur / "urdf" / "inc" / "ur_macro.xacro"
    disk = macro.read_text()
    uri = open_doc(client, macro)
    await diagnostics_for(client, uri, lambda ds: any(d.code == "UL401" for d in ds))
    lines = disk.split("\n")
    assert lines[236].strip() == '<axis xyz="0 0 1" />'
    lines[236] = lines[236].replace('"0 0 1"', '"0 0 2"')
    change(client, uri, "\n".join(lines), 2)
    # (the edited file's first model's diagnostics come first, then all nine: docs/editors.md)
    ds = await diagnostics_for(client, uri, lambda ds: any(
        d.code == "UL307" and "(in " in d.message for d in ds))
    (d,) = [d for d in ds if d.code == "UL307"]
    assert pos(d) == (236, 6)
    for robot in ("ur3", "ur3e", "ur5", "ur5e", "ur10", "ur10e", "ur16e", "ur20", "ur30"):
        assert robot in d.message.split("(in ")[-1] or d.message.endswith("...)")
    assert macro.read_text() == disk
    change(client, uri, disk, 3)
    await diagnostics_for(client, uri, lambda ds: not any(d.code == "UL307" for d in ds))


@aio
async def test_a_config_mistake_is_one_diagnostic_at_its_line(client, ur, tmp_path):
    """A bad key in [tool.urdf-lint] of pyproject.toml: one diagnostic on that line."""
    pp = ur / "pyproject.toml"
    pp.write_text('[project]\nname = "x"\n\n[tool.urdf-lint]\nselect = ["UL4"]\nfail_onn = 1\n')
    uri = open_doc(client, pp)
    client.text_document_did_save(types.DidSaveTextDocumentParams(
        text_document=types.TextDocumentIdentifier(uri=uri)))
    ds = await diagnostics_for(client, uri, lambda ds: len(ds) > 0)
    assert len(ds) == 1
    assert pos(ds[0]) == (5, 0) and ds[0].range.end.character == len("fail_onn = 1")
    assert "unknown key 'fail_onn'" in ds[0].message


@aio
async def test_quick_fix_and_suppressions_as_code_actions(client, ur):
    """The UL307 fix is a workspace edit of the buffer's "0 0 2" to "0 0 1"; the suppression
    actions insert the comment above the element and at the top of the file."""
    macro = ur / "urdf" / "inc" / "ur_macro.xacro"
    lines = macro.read_text().split("\n")
    lines[236] = lines[236].replace('"0 0 1"', '"0 0 2"')
    uri = open_doc(client, macro, "\n".join(lines))
    ds = await diagnostics_for(client, uri, lambda ds: any(d.code == "UL307" for d in ds))
    (d,) = [d for d in ds if d.code == "UL307"]
    acts = await client.text_document_code_action_async(types.CodeActionParams(
        text_document=types.TextDocumentIdentifier(uri=uri), range=d.range,
        context=types.CodeActionContext(diagnostics=[d])))
    by = {a.title: a for a in acts}
    fix = next(a for t, a in by.items() if t.startswith("UL307:"))
    assert fix.kind == types.CodeActionKind.QuickFix and fix.is_preferred
    (edit,) = fix.edit.changes[uri]
    assert edit.new_text in ("0 0 1", '"0 0 1"', "0.0 0.0 1.0")
    assert edit.range.start.line == 236
    assert lines[236][edit.range.start.character:edit.range.end.character] in ("0 0 2", '"0 0 2"')
    nxt = by["Disable UL307 for the next element"].edit.changes[uri][0]
    assert nxt.range.start == types.Position(236, 0)
    assert nxt.new_text == "      <!-- urdf-lint: disable-next UL307 -->\n"
    whole = by["Disable UL307 for this file"].edit.changes[uri][0]
    assert whole.range.start == types.Position(1, 0)
    assert whole.new_text == "<!-- urdf-lint: disable-file UL307 -->\n"
    allsafe = await client.text_document_code_action_async(types.CodeActionParams(
        text_document=types.TextDocumentIdentifier(uri=uri), range=d.range,
        context=types.CodeActionContext(diagnostics=[], only=[types.CodeActionKind.SourceFixAll])))
    (a,) = allsafe
    assert a.title == "urdf-lint: fix all safe"
    assert [e.range.start.line for e in a.edit.changes[uri]] == [236]
    # the suppression, typed into the buffer, silences the finding
    lines.insert(236, "      <!-- urdf-lint: disable-next UL307 -->")
    change(client, uri, "\n".join(lines), 2)
    await diagnostics_for(client, uri, lambda ds: not any(d.code == "UL307" for d in ds))


async def linted(client, ur) -> str:
    """Open the shared macro file and wait until every robot including it is linted."""
    uri = open_doc(client, ur / "urdf" / "inc" / "ur_macro.xacro")
    await diagnostics_for(client, uri, lambda ds: any(d.code == "UL401" for d in ds))
    return uri


def where(locs):
    return [(loc.uri.rsplit("/", 1)[-1], loc.range.start.line, loc.range.start.character)
            for loc in locs]


async def definition(client, uri, line, char):
    return await client.text_document_definition_async(types.DefinitionParams(
        text_document=types.TextDocumentIdentifier(uri=uri),
        position=types.Position(line, char)))


@aio
async def test_go_to_definition(client, ur):
    """A macro call to its xacro:macro; ${prefix} to the parameter of the macro it is in;
    $(find pkg)/... to the file; $(arg x) to its xacro:arg; a parent link written as
    ${prefix}base_link to the <link> that defines it, through the expanded robots' maps."""
    macro_uri = await linted(client, ur)
    ur5e = ur / "urdf" / "ur5e.xacro"
    uri = open_doc(client, ur5e)
    lines = ur5e.read_text().split("\n")
    call = lines[20].index("ur5e_robot")
    assert where(await definition(client, uri, 20, call + 2)) == [("ur5e_macro.xacro", 22, 2)]
    inc = lines[19].index("inc/ur5e_macro")
    got = await definition(client, uri, 19, inc + 3)
    assert got[0].uri == (ur / "urdf" / "inc" / "ur5e_macro.xacro").as_uri()
    # in the shared macro: <parent link="${prefix}base_link" /> (line 224)
    macro_lines = (ur / "urdf" / "inc" / "ur_macro.xacro").read_text().split("\n")
    assert macro_lines[223].strip() == '<parent link="${prefix}base_link" />'
    col = macro_lines[223].index("base_link")
    assert where(await definition(client, macro_uri, 223, col + 1)) == \
        [("ur_macro.xacro", 78, 4)]                           # <link name="${prefix}base_link">
    col = macro_lines[223].index("prefix")
    assert where(await definition(client, macro_uri, 223, col + 1)) == \
        [("ur_macro.xacro", 56, 2)]                           # <xacro:macro name="ur_robot" ...
    ur_x = ur / "urdf" / "ur.xacro"
    ur_lines = ur_x.read_text().split("\n")
    uri = open_doc(client, ur_x)
    col = ur_lines[24].index("joint_limit_params")
    assert where(await definition(client, uri, 24, col + 2)) == [("ur.xacro", 7, 3)]


@aio
async def test_references_of_a_macro_and_a_link(client, ur):
    """Every call of ur_robot (one per robot's macro file, and ur.xacro's), and every element naming
    base_link_inertia (its definition, the joint's child, the next joint's parent)."""
    macro_uri = await linted(client, ur)
    lines = (ur / "urdf" / "inc" / "ur_macro.xacro").read_text().split("\n")
    refs = await client.text_document_references_async(types.ReferenceParams(
        text_document=types.TextDocumentIdentifier(uri=macro_uri),
        position=types.Position(56, lines[56].index("ur_robot") + 1),
        context=types.ReferenceContext(include_declaration=False)))
    files = sorted(r[0] for r in where(refs))
    assert files == sorted([f"{m}_macro.xacro" for m in (
        "ur3", "ur3e", "ur5", "ur5e", "ur10", "ur10e", "ur16e", "ur20", "ur30")] + ["ur.xacro"])
    refs = await client.text_document_references_async(types.ReferenceParams(
        text_document=types.TextDocumentIdentifier(uri=macro_uri),
        position=types.Position(79, lines[79].index("base_link_inertia") + 2),
        context=types.ReferenceContext(include_declaration=True)))
    assert sorted(where(refs)) == [("ur_macro.xacro", 79, 4), ("ur_macro.xacro", 224, 6),
                                   ("ur_macro.xacro", 233, 6)]


@aio
async def test_hover_shows_values_per_model_macro_parameters_and_rule_summaries(client, ur):
    macro_uri = await linted(client, ur)
    lines = (ur / "urdf" / "inc" / "ur_macro.xacro").read_text().split("\n")
    assert '<origin xyz="0 0 ${shoulder_offset}"' in lines[121]
    h = await client.text_document_hover_async(types.HoverParams(
        text_document=types.TextDocumentIdentifier(uri=macro_uri),
        position=types.Position(121, lines[121].index("shoulder_offset") + 3)))
    text = h.contents.value
    assert "`0 0 0.138` in ur5e (config/ur5e/physical_parameters.yaml:12)" in text
    assert "`0 0 0.220941` in ur10 (config/ur10/physical_parameters.yaml:12)" in text
    # a joint: its type, parent, child, limits and world pose at the zero configuration
    assert lines[232].strip().startswith('<joint name="${prefix}shoulder_pan_joint"')
    h = await client.text_document_hover_async(types.HoverParams(
        text_document=types.TextDocumentIdentifier(uri=macro_uri),
        position=types.Position(232, lines[232].index("shoulder_pan") + 2)))
    row = next(r for r in h.contents.value.split("\n") if r.startswith("- **ur5e**"))
    assert row.startswith("- **ur5e**: `shoulder_pan_joint` revolute; parent `base_link_inertia`, "
                          "child `shoulder_link`; limits lower -6.283185307179586, upper "
                          "6.283185307179586, effort 150.0, velocity 3.141592653589793")
    assert row.endswith("world pose at zero: xyz 0.0 0.0 0.1625, rpy 0.0 0.0 3.1416")
    ur5e = ur / "urdf" / "ur5e.xacro"
    uri = open_doc(client, ur5e)
    h = await client.text_document_hover_async(types.HoverParams(
        text_document=types.TextDocumentIdentifier(uri=uri),
        position=types.Position(20, 10)))
    assert h.contents.value.startswith("**macro ur5e_robot** (ur5e_macro.xacro:23)")
    assert "- `prefix` (required)" in h.contents.value
    assert "- `safety_pos_margin` = `0.15`" in h.contents.value
    text = ur5e.read_text().replace("<robot ", "<!-- urdf-lint: disable-next UL307 -->\n<robot ", 1)
    change(client, uri, text, 2)
    h = await client.text_document_hover_async(types.HoverParams(
        text_document=types.TextDocumentIdentifier(uri=uri),
        position=types.Position(1, text.split("\n")[1].index("UL307") + 2)))
    assert h.contents.value.startswith("**UL307 joint-axis** (error)")


@aio
async def test_completion_of_macros_parameters_and_rule_codes(client, ur):
    await linted(client, ur)
    ur5e = ur / "urdf" / "ur5e.xacro"
    lines = ur5e.read_text().split("\n")
    lines.insert(21, "  <xacro:")
    uri = open_doc(client, ur5e, "\n".join(lines))
    got = await client.text_document_completion_async(types.CompletionParams(
        text_document=types.TextDocumentIdentifier(uri=uri), position=types.Position(21, 9)))
    by = {i.label: i for i in got.items}
    assert by["ur5e_robot"].insert_text == 'ur5e_robot prefix="${1}"/>'
    assert "ur_robot" in by and "ur10_robot" in by
    # parameter names inside the call, those not written yet
    lines[21] = '  <xacro:ur5e_robot prefix="a_" '
    change(client, uri, "\n".join(lines), 2)
    got = await client.text_document_completion_async(types.CompletionParams(
        text_document=types.TextDocumentIdentifier(uri=uri), position=types.Position(21, 31)))
    by = {i.label: i for i in got.items}
    assert "prefix" not in by and by["safety_limits"].detail == "default false"
    assert by["joint_limits_parameters_file"].insert_text == 'joint_limits_parameters_file="${1}"'
    # mesh files below a package
    lines[21] = '  <mesh filename="package://ur_description/meshes/ur5e/vi'
    change(client, uri, "\n".join(lines), 3)
    got = await client.text_document_completion_async(types.CompletionParams(
        text_document=types.TextDocumentIdentifier(uri=uri),
        position=types.Position(21, len(lines[21]))))
    assert sorted(i.label for i in got.items) == ["collision/", "visual/"]
    lines[21] = "  <!-- urdf-lint: disable-next UL3"
    change(client, uri, "\n".join(lines), 4)
    got = await client.text_document_completion_async(types.CompletionParams(
        text_document=types.TextDocumentIdentifier(uri=uri), position=types.Position(21, 34)))
    by = {i.label: i for i in got.items}
    assert by["UL307"].detail == "joint-axis"


@aio
async def test_document_symbols(client, ur):
    macro_uri = await linted(client, ur)
    syms = await client.text_document_document_symbol_async(types.DocumentSymbolParams(
        text_document=types.TextDocumentIdentifier(uri=macro_uri)))
    by = {(s.detail, s.name): (s.range.start.line, s.range.start.character) for s in syms}
    assert by[("macro", "ur_robot")] == (56, 2)
    assert by[("link", "${prefix}base_link")] == (78, 4)
    assert by[("joint", "${prefix}shoulder_pan_joint")] == (232, 4)


@aio
async def test_formatting_and_rename_over_the_protocol(client, ur):
    """The server advertises and answers formatting and rename over the protocol:
    formatting a one-line URDF buffer returns format's layout (run in the lint thread, the
    proof from the file itself); a rename where nothing is renameable (a comment) is LSP's
    RequestFailed error with the reason; a macro renames in its library and every robot."""
    from pygls.exceptions import JsonRpcException
    tiny = ur / "urdf" / "tiny.urdf"
    tiny.write_text('<robot name="t"><link name="a" /><link name="b" /></robot>\n')
    uri = open_doc(client, tiny)
    doc = types.TextDocumentIdentifier(uri=uri)
    edits = await client.text_document_formatting_async(types.DocumentFormattingParams(
        text_document=doc, options=types.FormattingOptions(tab_size=4, insert_spaces=True)))
    assert [e.new_text for e in edits] == ['<robot name="t">\n  <link name="a" />\n'
                                           '  <link name="b" />\n</robot>\n'], edits
    macro = ur / "urdf" / "inc" / "ur_macro.xacro"
    muri = open_doc(client, macro)
    await diagnostics_for(client, muri, lambda ds: any(d.code == "UL401" for d in ds))
    lines = macro.read_text().split("\n")
    comment = next(i for i, ln in enumerate(lines) if ln.strip().startswith("<!--"))
    with pytest.raises(JsonRpcException) as e:
        await client.text_document_prepare_rename_async(types.PrepareRenameParams(
            text_document=types.TextDocumentIdentifier(uri=muri),
            position=types.Position(comment, lines[comment].index("<!--") + 5)))
    assert e.value.code == -32803 and "nothing to rename" in e.value.message
    decl = next(i for i, ln in enumerate(lines) if '<xacro:macro name="ur_robot"' in ln)
    got = await client.text_document_rename_async(types.RenameParams(
        text_document=types.TextDocumentIdentifier(uri=muri), new_name="ur_arm",
        position=types.Position(decl, lines[decl].index("ur_robot") + 2)))
    files = {u.rsplit("/", 1)[-1] for u in got.changes}
    assert {"ur_macro.xacro", "ur.xacro", "ur10_macro.xacro", "ur5e_macro.xacro"} <= files, files


REPO = Path(__file__).resolve().parents[1]


@pytest.mark.skipif(not shutil.which("nvim"), reason="nvim is not installed (apt: neovim)")
def test_neovim_receives_the_diagnostics(ur, tmp_path):
    """Neovim's own LSP client (headless, editors/neovim/urdf_lint.lua) starts the server on
    the shared macro file with a planted defect (a joint axis of length 2 at line 237) and
    holds the finding at that line and column, from urdf-lint."""
    import json
    import subprocess
    macro = ur / "urdf" / "inc" / "ur_macro.xacro"
    lines = macro.read_text().split("\n")
    lines[236] = lines[236].replace('"0 0 1"', '"0 0 2"')
    macro.write_text("\n".join(lines))
    out = tmp_path / "diagnostics.json"
    env = dict(os.environ, URDF_LINT_NVIM_OUT=str(out), URDF_LINT_NVIM_WANT="UL307",
               URDF_LINT_PY=sys.executable,
               URDF_LINT_NVIM_PLUGIN=str(REPO / "editors" / "neovim" / "urdf_lint.lua"))
    subprocess.run(["nvim", "--headless", "-u", "NONE", "-i", "NONE", "-n", str(macro),
                    "-c", f"luafile {REPO / 'tests' / 'support' / 'nvim_lsp_probe.lua'}"],
                   cwd=ur, env=env, timeout=120, stdin=subprocess.DEVNULL,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    got = json.loads(out.read_text())
    (axis,) = [d for d in got if d["code"] == "UL307"]
    assert (axis["lnum"], axis["col"]) == (236, 6)
    assert axis["source"] == "urdf-lint" and axis["severity"] == 2   # vim.diagnostic WARN
    assert "axis" in axis["message"]
    assert any(d["code"] == "UL401" and d["lnum"] == 83 and d["col"] == 10 for d in got)


@pytest.mark.skipif(not shutil.which("nvim"), reason="nvim is not installed (apt: neovim)")
def test_neovim_runs_one_server_per_workspace_with_yaml_and_each_diagnostic_once(ur, tmp_path):
    """The documented Neovim set-up (docs/editors.md: the plugin in init.lua) with three files
    of one workspace open, two xacro files (one named ``*.urdf.xacro``) and a YAML file the
    models load: exactly one server process, every buffer attached to it (the YAML file
    too), and each diagnostic once in Neovim (the old set-up started one server per file,
    two for a ``*.urdf.xacro``, none for YAML, and showed each diagnostic once per server)."""
    import json
    import subprocess
    macro = ur / "urdf" / "inc" / "ur_macro.xacro"
    lines = macro.read_text().split("\n")
    lines[236] = lines[236].replace('"0 0 1"', '"0 0 2"')
    macro.write_text("\n".join(lines))
    model = ur / "urdf" / "ur10.urdf.xacro"
    (ur / "urdf" / "ur10.xacro").rename(model)
    yaml = ur / "config" / "ur10" / "joint_limits.yaml"
    init = tmp_path / "init.lua"
    init.write_text(f'vim.g.urdf_lint_cmd = {{ "{sys.executable}", "-m", "urdf_lint", "server" }}\n'
                    f'dofile("{REPO / "editors" / "neovim" / "urdf_lint.lua"}")\n')
    out = tmp_path / "nvim.json"
    env = dict(os.environ, URDF_LINT_NVIM_OUT=str(out), URDF_LINT_NVIM_WANT="UL307")
    subprocess.run(["nvim", "--headless", "-u", str(init), "-i", "NONE", "-n", "-p",
                    str(macro), str(model), str(yaml),
                    "-c", f"luafile {REPO / 'tests' / 'support' / 'nvim_workspace_probe.lua'}"],
                   cwd=ur, env=env, timeout=150, stdin=subprocess.DEVNULL,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    got = json.loads(out.read_text())
    assert len(got["servers"]) == 1, got["servers"]
    assert got["clients"] == 1, got
    bufs = {os.path.realpath(b["name"]): b for b in got["buffers"]}
    for f in (macro, model, yaml):
        assert len(bufs[os.path.realpath(f)]["clients"]) == 1, (f, bufs)
    diags = [(name, d["lnum"], d["col"], d["code"], d["message"])
             for name, b in bufs.items() for d in b["diagnostics"]]
    assert diags and len(diags) == len(set(diags)), sorted(diags)
    assert any(d[3] == "UL307" and d[1] == 236 for d in diags), diags


@pytest.mark.skipif(not shutil.which("npm"), reason="npm is not installed")
def test_the_vscode_client_builds(tmp_path):
    """editors/vscode compiles with its locked dependencies (vscode-languageclient) into an
    extension that starts `urdf-lint server`."""
    import json
    import subprocess
    src = REPO / "editors" / "vscode"
    dst = tmp_path / "vscode"
    shutil.copytree(src, dst, ignore=shutil.ignore_patterns("node_modules", "out"))
    r = subprocess.run(["npm", "ci", "--no-audit", "--no-fund"], cwd=dst, capture_output=True,
                       text=True, timeout=300)
    if r.returncode and any(s in r.stderr for s in ("ENOTFOUND", "EAI_AGAIN", "ECONNREFUSED",
                                                     "ETIMEDOUT")):
        pytest.skip("the npm registry is not reachable")
    assert r.returncode == 0, r.stderr[-2000:]
    r = subprocess.run(["npm", "run", "compile"], cwd=dst, capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
    js = (dst / "out" / "extension.js").read_text()
    assert 'require("vscode-languageclient/node")' in js
    assert '"urdf-lint", "server"' in js
    manifest = json.loads((dst / "package.json").read_text())
    assert manifest["main"] == "./out/extension.js"


@aio
async def test_an_unsaved_yaml_file_reaches_the_models_that_load_it(client, ur):
    """ur10's visual meshes are named in config/ur10/visual_parameters.yaml (read with
    xacro.load_yaml in the sandboxed workers): pointing its base at a mesh that exists, in
    the unsaved buffer only, clears that finding in the macro file."""
    macro_uri = await linted(client, ur)
    yml = ur / "config" / "ur10" / "visual_parameters.yaml"
    text = yml.read_text()
    assert "package://ur_description/meshes/ur10/visual/base.dae" in text
    uri = open_doc(client, yml, text)
    edited = text.replace("meshes/ur10/visual/base.dae", "meshes/ur5e/visual/base.dae")
    change(client, uri, edited, 2)
    ds = await diagnostics_for(client, macro_uri, lambda ds: not any(
        "ur10/visual/base.dae" in d.message for d in ds))
    assert any("ur10/visual/shoulder.dae" in d.message for d in ds)   # the rest stays
    assert yml.read_text() == text


def test_a_buffer_outside_the_roots_is_never_read(tmp_path):
    """An include outside the package roots stays refused (UL902) even when the editor holds
    a buffer for that path: the overlay replaces a file's bytes only where the file itself
    could be read."""
    pytest.importorskip("pygls")
    from urdf_lint.lsp.state import Workspace
    pkg = tmp_path / "ws" / "bot"
    pkg.mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>bot</name></package>")
    outside = tmp_path / "outside.xacro"
    outside.write_text('<robot xmlns:xacro="http://wiki.ros.org/xacro"/>')
    model = pkg / "bot.xacro"
    model.write_text(f'<robot name="b" xmlns:xacro="http://wiki.ros.org/xacro">\n'
                     f'  <xacro:include filename="{outside}"/>\n  <link name="a"/>\n</robot>\n')
    ws = Workspace(str(pkg), pool_size=1)
    try:
        ws.buffers[str(outside)] = b'<robot xmlns:xacro="http://wiki.ros.org/xacro">' \
            b'<link name="from_the_buffer"/></robot>'
        ws.buffers[str(model)] = model.read_bytes()
        ws.lint()
        (f,) = [f for f in ws.findings if f.code == "UL902"]
        assert (f.file, f.line, f.col) == (str(model), 2, 3)
        rep = next(iter(r for r in ws.reports.values() if r.entry == str(model)))
        assert str(outside) not in rep.deps
    finally:
        ws.close()


@aio
async def test_a_file_changed_outside_the_editor_relints_what_it_reaches(client, ur):
    """A watched-file notification for a YAML file rewritten on disk (a checkout) re-lints
    the models that load it; the open macro file's diagnostics follow."""
    macro_uri = await linted(client, ur)
    yml = ur / "config" / "ur10" / "visual_parameters.yaml"
    yml.write_text(yml.read_text().replace("meshes/ur10/visual/base.dae",
                                           "meshes/ur5e/visual/base.dae"))
    client.workspace_did_change_watched_files(types.DidChangeWatchedFilesParams(changes=[
        types.FileEvent(uri=yml.as_uri(), type=types.FileChangeType.Changed)]))
    ds = await diagnostics_for(client, macro_uri, lambda ds: not any(
        "ur10/visual/base.dae" in d.message for d in ds))
    assert any("ur10/visual/shoulder.dae" in d.message for d in ds)


@pytest.fixture
def hanging(tmp_path) -> Path:
    """A package whose one model never finishes (a sum over 10**13 numbers), with the time
    limit lowered in its own config (a repository may lower it, never raise it)."""
    pkg = tmp_path / "hang"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>hang</name></package>")
    (pkg / "pyproject.toml").write_text("[tool.urdf-lint]\ntimeout = 2\n")
    (pkg / "urdf" / "slow.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://wiki.ros.org/xacro">\n'
        '  <link name="${python.sum(python.range(10**13))}"/>\n</robot>\n')
    (pkg / "urdf" / "ok.urdf.xacro").write_text(
        '<robot name="ok" xmlns:xacro="http://wiki.ros.org/xacro">\n'
        '  <xacro:property name="w" value="0.5"/>\n'
        '  <link name="a"/>\n  <link name="b"/>\n'
        '  <joint name="j" type="fixed"><parent link="a"/><child link="b"/>'
        '<origin xyz="${w} 0 0"/></joint>\n</robot>\n')
    return pkg


@pytest_lsp.fixture(config=ClientServerConfig(
    server_command=[sys.executable, "-m", "urdf_lint", "server"]))
async def hang_client(lsp_client: LanguageClient, hanging):
    await lsp_client.initialize_session(types.InitializeParams(
        capabilities=types.ClientCapabilities(), root_uri=hanging.as_uri()))
    yield
    await lsp_client.shutdown_session()


@aio
async def test_a_model_that_hangs_costs_its_worker_not_the_editor(hang_client, hanging):
    """The hanging model gets UL904 from the time limit of its worker (killed, replaced);
    while it runs, the editor's requests are answered, and the next lint works."""
    import time
    client = hang_client
    slow = open_doc(client, hanging / "urdf" / "slow.urdf.xacro")
    ok = hanging / "urdf" / "ok.urdf.xacro"
    ok_uri = open_doc(client, ok)
    await asyncio.sleep(0.3)   # the slow model's lint is under way
    t0 = time.perf_counter()
    syms = await client.text_document_document_symbol_async(types.DocumentSymbolParams(
        text_document=types.TextDocumentIdentifier(uri=ok_uri)))
    assert time.perf_counter() - t0 < 1.5
    assert [(s.detail, s.name) for s in syms] == [("property", "w"), ("link", "a"),
                                                 ("link", "b"), ("joint", "j")]
    ds = await diagnostics_for(client, slow, lambda ds: any(d.code == "UL904" for d in ds))
    (d,) = [d for d in ds if d.code == "UL904"]
    # (the limit of check's pool, which the server's now is: CPU time, and 4x in wall time)
    assert "within the time limit (2 s of CPU time" in d.message and pos(d) == (0, 0)
    # a worker took the hanging job's place: a change to the good model is linted
    text = ok.read_text().replace('<origin xyz="${w} 0 0"/>', '<axis xyz="0 0 0"/>') \
        .replace('type="fixed"', 'type="continuous"')
    change(client, ok_uri, text, 2)
    await diagnostics_for(client, ok_uri, lambda ds: any(d.code == "UL307" for d in ds))


YAML_BOT = """<robot name="yamlbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="lim"
    value="${xacro.load_yaml('$(find ur_description)/config/yamlbot.yaml')}"/>
  <link name="base"/>
  <link name="arm"/>
  <joint name="j" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="${lim['lower']}" upper="${lim['upper']}" effort="1" velocity="1"/>
  </joint>
</robot>
"""


@aio
async def test_a_yaml_file_shows_the_findings_whose_values_it_holds(client, ur):
    """A value read with xacro.load_yaml that breaks a joint: the YAML file, opened, shows the
    finding at the line that holds the value, related to the xacro element that uses it;
    fixing the value in the unsaved buffer clears it in both files."""
    yml = ur / "config" / "yamlbot.yaml"
    yml.write_text("# limits of the yamlbot\nlower: 1.5\nupper: -1.5\n")
    bot = ur / "urdf" / "yamlbot.urdf.xacro"
    bot.write_text(YAML_BOT)
    bot_uri = open_doc(client, bot)
    await diagnostics_for(client, bot_uri, lambda ds: any(d.code == "UL302" for d in ds))
    uri = open_doc(client, yml)
    ds = await diagnostics_for(client, uri, lambda ds: any(d.code == "UL302" for d in ds))
    (d,) = [d for d in ds if d.code == "UL302"]
    assert pos(d) == (1, 7), pos(d)                      # `1.5` on "lower: 1.5" (line 2)
    assert "lower 1.5 > upper -1.5" in d.message and "yamlbot.urdf.xacro:8" in d.message
    (rel,) = d.related_information
    assert rel.location.uri == bot_uri and rel.location.range.start.line == 7
    change(client, uri, "# limits of the yamlbot\nlower: -1.5\nupper: 1.5\n", 2)
    await diagnostics_for(client, uri, lambda ds: not any(d.code == "UL302" for d in ds))
    await diagnostics_for(client, bot_uri, lambda ds: not any(d.code == "UL302" for d in ds))


UR_STYLE_BOT = """<robot name="urstyle" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="cfg"
    value="${xacro.load_yaml('$(find ur_description)/config/urstyle.yaml')}"/>
  <link name="base"/>
  <xacro:macro name="rev" params="name">
    <xacro:property name="lim" value="${cfg['joint_limits'][name]}"/>
    <link name="${name}_link"/>
    <joint name="${name}" type="revolute">
      <parent link="base"/><child link="${name}_link"/><axis xyz="0 0 1"/>
      <limit lower="${lim.lower}" upper="${lim['upper']}" effort="1" velocity="1"/>
    </joint>
  </xacro:macro>
  <xacro:rev name="shoulder"/>
</robot>
"""


@aio
async def test_a_yaml_file_shows_a_value_read_through_a_sub_dict_and_a_macro(client, ur):
    """As UR's descriptions read their limits (a property holding one joint's sub-dict inside
    a macro): the YAML file, opened, shows the finding at the line of the value."""
    yml = ur / "config" / "urstyle.yaml"
    yml.write_text("joint_limits:\n  shoulder:\n    lower: 1.5\n    upper: -1.5\n")
    bot = ur / "urdf" / "urstyle.urdf.xacro"
    bot.write_text(UR_STYLE_BOT)
    bot_uri = open_doc(client, bot)
    await diagnostics_for(client, bot_uri, lambda ds: any(d.code == "UL302" for d in ds))
    uri = open_doc(client, yml)
    ds = await diagnostics_for(client, uri, lambda ds: any(d.code == "UL302" for d in ds))
    (d,) = [d for d in ds if d.code == "UL302"]
    assert pos(d) == (2, 11), pos(d)                     # `1.5` on "    lower: 1.5" (line 3)


@aio
async def test_run_scope_findings_reach_the_editor(client, ur):
    """A rule over all the models of the run (UL106: two robots with one name) is reported in
    the editor as `check` reports it, at the robot element of each file."""
    for name in ("twin_a", "twin_b"):
        (ur / "urdf" / f"{name}.urdf").write_text(
            '<?xml version="1.0"?>\n<robot name="twin">\n  <link name="base"/>\n</robot>\n')
    uri = open_doc(client, ur / "urdf" / "twin_a.urdf")
    ds = await diagnostics_for(client, uri, lambda ds: any(d.code == "UL106" for d in ds))
    (d,) = [d for d in ds if d.code == "UL106"]
    assert pos(d) == (1, 0) and "twin_b.urdf" in d.message, (pos(d), d.message)


@aio
async def test_hover_on_a_condition_says_which_models_expand_its_body(client, ur):
    """Issue 39: every UR variant passes safety_limits="false": the hover on the condition
    lists them as leaving its body out (and points at --coverage)."""
    macro_uri = await linted(client, ur)
    lines = (ur / "urdf" / "inc" / "ur_macro.xacro").read_text().split("\n")
    assert lines[239].strip() == '<xacro:if value="${safety_limits}">'
    h = await client.text_document_hover_async(types.HoverParams(
        text_document=types.TextDocumentIdentifier(uri=macro_uri),
        position=types.Position(239, lines[239].index("xacro:if") + 3)))
    text = h.contents.value
    assert text.startswith("**xacro:if**"), text
    assert "body expanded in: no linted model" in text
    left = text.split("left out in: ")[1].split("\n")[0]
    assert "`ur5e_robot`" in left and "`ur10_robot`" in left, text
    assert "--coverage" in text


# -- latest wins: typing ----------------------------------------------------------------------
def test_typing_publishes_no_older_version_after_a_newer_change(tmp_path, monkeypatch):
    """Ten changes of a macro three robots use, 250 ms apart (each model takes a while to
    lint, so every change lands while the previous text is being linted): the server, in
    process with its real worker pool, never publishes diagnostics of an older version of the
    document after it received a newer one, each publication's findings are of the version it
    carries, lints under way were stopped (their workers killed), and the last version's
    diagnostics arrive: first those of one model, then those of all three."""
    import ur_like
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    pkg = ur_like.write(tmp_path, variants=3, marker="v0", work=3 * 10**7)
    asyncio.run(_type_ten_changes(pkg))


async def _type_ten_changes(pkg):
    import re

    from pygls.workspace import Workspace as Documents

    from urdf_lint.lsp.core import UrdfLintServer
    from urdf_lint.lsp.methods import did_change, did_open, initialized
    import ur_like
    ls = UrdfLintServer()
    ls.protocol._workspace = Documents(pkg.as_uri(), types.TextDocumentSyncKind.Full)
    macro = pkg / "urdf" / "inc" / "arm_macro.xacro"
    uri = macro.resolve().as_uri()
    received = [0]    # the newest version of the macro the server was sent
    published = []    # (version received by then, version published, markers in the messages)
    models = []       # per publication: the models the marker link's finding names

    def record(params: types.PublishDiagnosticsParams):
        if params.uri == uri:
            marks = {m for d in params.diagnostics for m in re.findall(r"'(v\d+)'", d.message)}
            published.append((received[0], params.version, marks))
            models.append(next((re.findall(r"\(in ([^)]*)\)$", d.message) for d in
                                params.diagnostics if "'v" in d.message), None))
    ls.text_document_publish_diagnostics = record
    initialized.handle(ls, types.InitializedParams())
    try:
        text = macro.read_text()
        ls.workspace.put_text_document(types.TextDocumentItem(
            uri=uri, language_id="xml", version=0, text=text))
        did_open.handle(ls, types.DidOpenTextDocumentParams(types.TextDocumentItem(
            uri=uri, language_id="xml", version=0, text=text)))
        await asyncio.sleep(0.25)
        for k in range(1, 11):
            text = ur_like.arm_macro(f"v{k}", 3 * 10**7)
            doc = types.VersionedTextDocumentIdentifier(uri=uri, version=k)
            change = types.TextDocumentContentChangeWholeDocument(text=text)
            ls.workspace.update_text_document(doc, change)
            received[0] = k
            did_change.handle(ls, types.DidChangeTextDocumentParams(doc, [change]))
            await asyncio.sleep(0.25)
        for _ in range(1200):   # the last version's, however loaded the machine
            if published and published[-1][1] == 10 and ls.task is not None and \
                    ls.task.done() and ls.timer is None:
                break
            await asyncio.sleep(0.1)
        stale = [p for p in published if p[1] != p[0]]
        assert stale == [], stale
        assert all(marks <= {f"v{v}"} for _, v, marks in published), published
        assert published[-1] == (10, 10, {"v10"}), published
        # partial results first: the edited file's model alone, then every variant
        last = [m for p, m in zip(published, models, strict=True) if p[1] == 10]
        assert last[0] == [] and last[-1] == ["ur3.urdf, ur3e.urdf, ur5.urdf"], last
        assert ls.ws.pool.stopped > 0   # lints of older text were stopped, not just ignored
    finally:
        ls.ws.close()
        ls.executor.shutdown(wait=True)
