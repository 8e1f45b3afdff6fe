"""The editor's rough edges (issue 36, item 5), each in this process on a workspace written
in tmp_path: the server object with its Workspace, its features called as the protocol
handlers call them (the workers lint in their sandbox, as for the editor)."""
from __future__ import annotations

import os
from pathlib import Path

import pytest

pytest.importorskip("pygls")
from lsprotocol import types  # noqa: E402

from conftest import make_package  # noqa: E402

X = 'xmlns:xacro="http://wiki.ros.org/xacro"'


def _server(root: Path, monkeypatch, tmp_path: Path):
    from urdf_lint.lsp.core import UrdfLintServer
    from urdf_lint.lsp.state import Workspace
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    ls = UrdfLintServer()
    ls.ws = Workspace(str(root), pool_size=1)
    return ls


def _linted(pkg: Path, f: Path, monkeypatch, tmp_path: Path):
    """The server of ``pkg`` with ``f`` open, every model linted (close its ``ws``)."""
    ls = _server(pkg, monkeypatch, tmp_path)
    _open(ls, f)
    ls.ws.lint()
    return ls


def _open(ls, path: Path, text: str | None = None) -> str:
    p = os.path.realpath(path)
    ls.ws.buffers[p] = (path.read_text() if text is None else text).encode()
    return p


def _at(path: Path, needle: str, delta: int = 0) -> types.Position:
    """The LSP position of the first ``needle`` in the file (plus ``delta`` characters)."""
    text = path.read_text()
    i = text.index(needle) + delta
    return types.Position(text.count("\n", 0, i), i - (text.rfind("\n", 0, i) + 1))


# -- (b) a pyproject.toml that does not parse ----------------------------------------------------
ROBOT = ('<?xml version="1.0"?>\n<robot name="r">\n  <link name="a"/>\n  <link name="b"/>\n'
         '  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
         '<axis xyz="0 0 2"/>\n    <limit lower="0" upper="1" effort="1" velocity="1"/>'
         '</joint>\n</robot>\n')
GOOD_TOML = '[project]\nname = "r"\n\n[tool.urdf-lint]\nfail-on = "error"\n'


def test_a_pyproject_that_does_not_parse_is_one_diagnostic_and_linting_resumes(
        tmp_path, monkeypatch):
    """A ``pyproject.toml`` with an unterminated string (line 5): the workspace still loads,
    the config file holds one diagnostic at the TOML error's line, the models are linted with
    the defaults; once the file is fixed and saved (the server reloads), the diagnostic is gone
    and linting goes on."""
    pkg = make_package(tmp_path, "r", {"urdf/r.urdf": ROBOT,
                                       "pyproject.toml": GOOD_TOML.replace('"error"', '"error')})
    ls = _server(pkg, monkeypatch, tmp_path)
    toml = os.path.realpath(pkg / "pyproject.toml")
    model = _open(ls, pkg / "urdf" / "r.urdf")
    try:
        ds = ls.diagnostics(toml)
        assert len(ds) == 1, ds
        (d,) = ds
        assert d.code == "config" and d.range.start.line == 4, d
        assert "invalid TOML" in d.message
        ls.ws.lint()
        assert "UL307" in [d.code for d in ls.diagnostics(model)]
        (pkg / "pyproject.toml").write_text(GOOD_TOML)
        ls.ws.load()   # what the server does on saving a config file
        ls.ws.start()
        ls.ws.lint()
        assert ls.diagnostics(toml) == []
        assert "UL307" in [d.code for d in ls.diagnostics(model)]
    finally:
        ls.ws.close()


# -- (c) findings grouped as check groups them -------------------------------------------------
MACROS = (f'<?xml version="1.0"?>\n<robot {X}>\n'
          '  <xacro:macro name="finger" params="n parent">\n'
          '    <link name="${n}"/>\n'
          '    <joint name="${n}_j" type="revolute"><parent link="${parent}"/>'
          '<child link="${n}"/><axis xyz="0 0 2"/>\n'
          '      <limit lower="0" upper="1" effort="1" velocity="1"/></joint>\n'
          '  </xacro:macro>\n</robot>\n')
HAND = (f'<?xml version="1.0"?>\n<robot name="hand" {X}>\n'
        '  <xacro:include filename="fingers.xacro"/>\n  <link name="palm"/>\n'
        '  <xacro:finger n="f1" parent="palm"/>\n'
        '  <xacro:finger n="f2" parent="palm"/>\n'
        '  <xacro:finger n="f3" parent="palm"/>\n</robot>\n')


def test_a_macro_line_wrong_in_three_calls_is_one_diagnostic_naming_them(tmp_path, monkeypatch):
    """The axis written once in a macro called three times: one diagnostic at that line (as
    ``check`` counts it), its three joints in the message, each call site as related
    information."""
    pkg = make_package(tmp_path, "hand", {"urdf/fingers.xacro": MACROS,
                                          "urdf/hand.urdf.xacro": HAND})
    ls = _server(pkg, monkeypatch, tmp_path)
    try:
        lib = _open(ls, pkg / "urdf" / "fingers.xacro")
        ls.ws.lint()
        ds = [d for d in ls.diagnostics(lib) if d.code == "UL307"]
        assert len(ds) == 1, ds
        (d,) = ds
        assert d.range.start.line == 4
        assert "in 3 joints: f1_j, f2_j, f3_j" in d.message, d.message
        calls = sorted(r.location.range.start.line for r in d.related_information or ())
        assert calls == [4, 5, 6], d.related_information
        assert all(r.location.uri == (pkg / "urdf" / "hand.urdf.xacro").resolve().as_uri()
                   for r in d.related_information)
    finally:
        ls.ws.close()


# -- (g) formatting through the language server ------------------------------------------------
def _apply(text: str, edits) -> str:
    """``text`` with LSP text edits applied (ASCII text: characters are UTF-16 units)."""
    lines = text.split("\n")

    def off(p):
        return sum(len(ln) + 1 for ln in lines[:p.line]) + p.character
    for e in sorted(edits, key=lambda e: off(e.range.start), reverse=True):
        text = text[:off(e.range.start)] + e.new_text + text[off(e.range.end):]
    return text


UGLY = (f'<?xml version="1.0"?>\n<robot name="r" {X}>\n<xacro:property name="w" value="0.1" />\n'
        '<link name="base"><visual><geometry><box size="${w} ${w} ${w}" /></geometry></visual>'
        '</link>\n<link name="tip" />\n<joint name="j" type="fixed"><parent link="base"/>'
        '<child link="tip" /></joint>\n</robot>\n')
NS_MACRO = (f'<robot {X}>\n<xacro:macro name="ns"><gazebo><plugin name="p" filename="x.so">'
            '<robotNamespace><xacro:if value="1">/arm</xacro:if></robotNamespace>'
            '</plugin></gazebo></xacro:macro>\n</robot>\n')


def _fmt_params(path: Path, rng=None):
    doc = types.TextDocumentIdentifier(uri=path.resolve().as_uri())
    opts = types.FormattingOptions(tab_size=8, insert_spaces=False)
    if rng is None:
        return types.DocumentFormattingParams(text_document=doc, options=opts)
    return types.DocumentRangeFormattingParams(text_document=doc, range=rng, options=opts)


def test_formatting_lays_out_the_unsaved_buffer_as_format_does(tmp_path, monkeypatch):
    """``textDocument/formatting`` on an unsaved buffer (the file on disk is another text):
    its edits make the buffer what ``urdf-lint format`` makes of it, in the repository's
    style (indent 4 from the config, not the editor's tab size) and the file's own `` />``;
    a buffer laid out already gets no edit."""
    from urdf_lint.formatting.layout import Style, format_source
    from urdf_lint.lsp.methods import formatting
    pkg = make_package(tmp_path, "r", {"urdf/r.urdf.xacro": "<robot/>\n",
                                       "urdf-lint.toml": "[format]\nindent = 4\n"})
    f = pkg / "urdf" / "r.urdf.xacro"
    ls = _server(pkg, monkeypatch, tmp_path)
    try:
        _open(ls, f, UGLY)
        got = _apply(UGLY, formatting.handle(ls.services, _fmt_params(f)))
        assert got == format_source(UGLY.encode(), Style(indent=4)).decode()
        assert '\n    <link name="tip" />\n' in got and '<parent link="base" />' in got, got
        assert f.read_text() == "<robot/>\n"   # nothing written
        _open(ls, f, got)
        assert formatting.handle(ls.services, _fmt_params(f)) == []
    finally:
        ls.ws.close()


def test_range_formatting_changes_only_the_lines_asked_for(tmp_path, monkeypatch):
    from urdf_lint.lsp.methods import range_formatting
    pkg = make_package(tmp_path, "r", {"urdf/r.urdf.xacro": UGLY})
    f = pkg / "urdf" / "r.urdf.xacro"
    ls = _server(pkg, monkeypatch, tmp_path)
    try:
        _open(ls, f)
        rng = types.Range(types.Position(3, 0), types.Position(3, 5))   # the base link's line
        edits = range_formatting.handle(ls.services, _fmt_params(f, rng))
        got = _apply(UGLY, edits)
        old, new = UGLY.split("\n"), got.split("\n")
        assert new[:3] == old[:3] and new[-4:] == old[-4:], got   # the rest as it was
        assert new[3:8] == ['  <link name="base">', '    <visual>', '      <geometry>',
                            '        <box size="${w} ${w} ${w}" />', '      </geometry>'], got
    finally:
        ls.ws.close()


def test_formatting_that_would_change_the_robot_is_refused_with_the_proof(tmp_path, monkeypatch):
    """The text of ``<robotNamespace>`` comes from an ``xacro:if`` in it: laying it out would
    change the expanded robot. Format's proof expands the model that reads it (in the
    server's workers, with the buffers) and the request is refused, saying why."""
    from urdf_lint.lsp.methods import Refused, formatting
    main = UGLY.replace("</robot>", '<xacro:include filename="ns.xacro"/><xacro:ns/>\n</robot>')
    pkg = make_package(tmp_path, "r", {"urdf/r.urdf.xacro": main, "urdf/ns.xacro": "<robot/>"})
    ns = pkg / "urdf" / "ns.xacro"
    ls = _server(pkg, monkeypatch, tmp_path)
    try:
        _open(ls, ns, NS_MACRO)   # unsaved: only the buffer holds the macro
        with pytest.raises(Refused) as e:
            formatting.handle(ls.services, _fmt_params(ns))
        assert "would change the robot" in e.value.reason and "robotNamespace" in e.value.reason
        assert e.value.to_response_error().code == -32803   # LSP's RequestFailed
    finally:
        ls.ws.close()


# -- (d) hover on xacro's own names -------------------------------------------------------------
ARM = (f'<?xml version="1.0"?>\n<robot name="arm" {X}>\n'
       '  <xacro:arg name="side" default="left"/>\n'
       '  <xacro:property name="bar_len" value="0.5"/>\n'
       '  <xacro:include filename="fingers.xacro"/>\n'
       '  <link name="$(arg side)_palm"/>\n'
       '  <link name="bar"><visual><geometry><box size="${bar_len} 1 1"/></geometry></visual>'
       '</link>\n'
       '  <joint name="fix" type="fixed"><parent link="$(arg side)_palm"/><child link="bar"/>'
       '</joint>\n'
       '  <link name="rod"><visual><geometry><cylinder radius="0.1" length="${bar_len}"/>'
       '</geometry></visual></link>\n'
       '  <joint name="fix2" type="fixed"><parent link="bar"/><child link="rod"/></joint>\n'
       '  <xacro:property name="prefix" value="$(arg side)_"/>\n'
       '  <xacro:finger n="${prefix}f1" parent="$(arg side)_palm"/>\n'
       '  <xacro:finger n="${prefix}f2" parent="$(arg side)_palm"/>\n'
       '</robot>\n')
ARGS_TOML = ('[[models]]\npath = "urdf/arm.urdf.xacro"\n'
             'args = [{}, { side = "right" }]\n')


def _hover_text(ls, f: Path, needle: str, delta: int = 0) -> str:
    from urdf_lint.lsp.methods import hover
    h = hover.hover(ls.services, os.path.realpath(f), _at(f, needle, delta))
    assert h is not None, needle
    return h.contents.value


def test_hover_on_args_properties_and_expressions_in_macro_calls(tmp_path, monkeypatch):
    """Two variants of one model (the config sets ``side = "right"`` for one): hover on
    ``$(arg side)`` and on its declaration shows both values and where each was set; on a
    property declaration, its value as written and its value in the models; on
    ``${prefix}`` in a macro call, what ``prefix`` is and the call's value in each model."""
    pkg = make_package(tmp_path, "arm", {"urdf/arm.urdf.xacro": ARM,
                                         "urdf/fingers.xacro": MACROS,
                                         "urdf-lint.toml": ARGS_TOML})
    arm = pkg / "urdf" / "arm.urdf.xacro"
    ls = _linted(pkg, arm, monkeypatch, tmp_path)
    try:
        for needle, delta in (("$(arg side)_palm", 7), ('<xacro:arg name="side"', 3)):
            text = _hover_text(ls, arm, needle, delta)
            assert "**arg** `side`" in text, text
            assert "- `left` in arm.urdf (default, urdf/arm.urdf.xacro:3)" in text, text
            assert "- `right` in arm.urdf [side:=right] (set in urdf-lint.toml:3)" in text, text
        text = _hover_text(ls, arm, '<xacro:property name="bar_len"', 20)
        assert "- urdf/arm.urdf.xacro:4: `0.5`" in text, text
        assert "value `0.5` in arm.urdf, arm.urdf [side:=right]" in text, text
        text = _hover_text(ls, arm, 'n="${prefix}f2"', 6)
        assert "`prefix`: property = `$(arg side)_` (urdf/arm.urdf.xacro:11)" in text, text
        assert "`n` = `left_f2` in arm.urdf; `right_f2` in arm.urdf [side:=right]" in text, text
    finally:
        ls.ws.close()


# -- (e) completion mid-edit ----------------------------------------------------------------------
BLOCKS = (f'<?xml version="1.0"?>\n<robot {X}>\n'
          '  <xacro:macro name="wrap" params="name *origin">\n'
          '    <link name="${name}"/>\n'
          '    <joint name="${name}_j" type="fixed"><xacro:insert_block name="origin"/>'
          '<parent link="base"/><child link="${name}"/></joint>\n'
          '  </xacro:macro>\n</robot>\n')
BODY = (f'<?xml version="1.0"?>\n<robot name="b" {X}>\n'
        '  <xacro:include filename="fingers.xacro"/>\n'
        '  <xacro:include filename="blocks.xacro"/>\n'
        '  <link name="base"/>\n'
        '  <xacro:finger n="f1" parent="base"/>\n'
        '</robot>\n')


def test_a_block_macro_completes_as_an_open_close_pair(tmp_path, monkeypatch):
    from urdf_lint.lsp.methods import completion
    pkg = make_package(tmp_path, "b", {"urdf/b.urdf.xacro": BODY, "urdf/fingers.xacro": MACROS,
                                       "urdf/blocks.xacro": BLOCKS})
    f = pkg / "urdf" / "b.urdf.xacro"
    ls = _server(pkg, monkeypatch, tmp_path)
    try:
        typed = BODY.replace("</robot>", "  <xacro:\n</robot>")
        path = _open(ls, f, typed)
        line = typed.count("\n", 0, typed.index("<xacro:\n"))
        items = {i.label: i for i in completion.completion(ls.services, path,
                                                           types.Position(line, 9))}
        assert items["wrap"].insert_text == 'wrap name="${1}">\n\t$0\n</xacro:wrap>', \
            items["wrap"].insert_text
        assert items["finger"].insert_text == 'finger n="${1}" parent="${2}"/>'
    finally:
        ls.ws.close()


def test_link_names_complete_inside_an_unclosed_attribute(tmp_path, monkeypatch):
    """The user types ``<parent link="`` in a new joint: the buffer is not well-formed (the
    attribute and the tag are open), the model fails to expand on that lint, and the link
    names of the model as it last expanded are offered."""
    from urdf_lint.lsp.methods import completion
    pkg = make_package(tmp_path, "b", {"urdf/b.urdf.xacro": BODY, "urdf/fingers.xacro": MACROS,
                                       "urdf/blocks.xacro": BLOCKS})
    f = pkg / "urdf" / "b.urdf.xacro"
    ls = _server(pkg, monkeypatch, tmp_path)
    try:
        path = _open(ls, f)
        ls.ws.lint()
        typed = BODY.replace("</robot>", '  <joint name="k" type="fixed"><parent link="\n'
                             '</robot>')
        _open(ls, f, typed)
        ls.ws.lint(ls.ws.affected(path))   # what the server does after the keystroke
        assert not ls.ws.models()          # it does not expand now
        line = typed.count("\n", 0, typed.index('<parent link="'))
        char = len(typed.split("\n")[line])
        labels = {i.label for i in completion.completion(ls.services, path,
                                                         types.Position(line, char))}
        assert {"base", "f1"} <= labels, labels
    finally:
        ls.ws.close()


# -- (f) rename ---------------------------------------------------------------------------------
def _renamed(ls, f: Path, needle: str, delta: int, new: str) -> dict:
    """{file name: text} of every file the rename edits, the edits applied."""
    from urdf_lint.lsp.methods import rename
    uri = f.resolve().as_uri()
    pos = _at(f, needle, delta)
    prep = rename.prepare(ls.services, types.PrepareRenameParams(
        text_document=types.TextDocumentIdentifier(uri=uri), position=pos))
    assert prep.placeholder
    got = rename.handle(ls.services, types.RenameParams(
        text_document=types.TextDocumentIdentifier(uri=uri), position=pos, new_name=new))
    out = {}
    for u, edits in got.changes.items():
        p = Path(u[len("file://"):])
        out[p.name] = _apply(p.read_text(), edits)
    return out


def test_rename_a_macro_a_property_an_arg_and_a_link_across_files(tmp_path, monkeypatch):
    pkg = make_package(tmp_path, "arm", {"urdf/arm.urdf.xacro": ARM.replace(
        "$(arg side)_palm", "palm").replace("$(arg side)_", "$(arg side)"),
        "urdf/fingers.xacro": MACROS})
    arm = pkg / "urdf" / "arm.urdf.xacro"
    ls = _linted(pkg, arm, monkeypatch, tmp_path)
    try:
        # a macro, from a call: its declaration in the library, both calls
        got = _renamed(ls, arm, "<xacro:finger", 9, "digit")
        assert set(got) == {"arm.urdf.xacro", "fingers.xacro"}
        assert got["arm.urdf.xacro"].count("<xacro:digit ") == 2
        assert "<xacro:finger" not in got["arm.urdf.xacro"]
        assert '<xacro:macro name="digit" params="n parent">' in got["fingers.xacro"]
        # a property, from a use: its declaration and both uses
        got = _renamed(ls, arm, "${bar_len}", 3, "bar_length")
        assert got["arm.urdf.xacro"].count("bar_length") == 3
        assert "bar_len}" not in got["arm.urdf.xacro"]
        # an arg, from its declaration: every $(arg side)
        got = _renamed(ls, arm, '<xacro:arg name="side"', 18, "hand")
        assert got["arm.urdf.xacro"].count("$(arg hand)") == 1
        assert "$(arg side)" not in got["arm.urdf.xacro"]
        assert '<xacro:arg name="hand" default="left"/>' in got["arm.urdf.xacro"]
        # a link: its <link>, the joint's parent, and the calls giving parent="palm" to the
        # macro's <parent link="${parent}"> (edited where the value is written)
        got = _renamed(ls, arm, '<link name="palm"', 13, "hand_base")
        assert list(got) == ["arm.urdf.xacro"]
        text = got["arm.urdf.xacro"]
        assert "palm" not in text and text.count("hand_base") == 4, text
    finally:
        ls.ws.close()


def test_rename_is_refused_where_a_name_is_built_by_an_expression(tmp_path, monkeypatch):
    """The palm link is written ``$(arg side)_palm``: refused at once. The finger link
    ``left_f1``, named literally by a new joint, is written ``${n}`` in the macro and given as
    ``n="${prefix}f1"`` at the call: refused, saying where the expression is."""
    from urdf_lint.lsp.methods import Refused, rename
    extra = ('  <link name="tip"/><joint name="tip_j" type="fixed"><parent link="left_f1"/>'
             '<child link="tip"/></joint>\n</robot>')
    pkg = make_package(tmp_path, "arm", {"urdf/arm.urdf.xacro": ARM.replace("</robot>", extra),
                                         "urdf/fingers.xacro": MACROS})
    arm = pkg / "urdf" / "arm.urdf.xacro"
    ls = _linted(pkg, arm, monkeypatch, tmp_path)
    try:
        doc = types.TextDocumentIdentifier(uri=arm.resolve().as_uri())
        with pytest.raises(Refused) as e:
            rename.prepare(ls.services, types.PrepareRenameParams(
                text_document=doc, position=_at(arm, '<link name="$(arg side)_palm"', 25)))
        assert "built by an expression" in e.value.reason, e.value.reason
        with pytest.raises(Refused) as e:
            rename.handle(ls.services, types.RenameParams(
                text_document=doc, new_name="x", position=_at(arm, 'link="left_f1"', 8)))
        assert e.value.reason == ("not renamed: the name 'left_f1' is built by an expression "
                                  'at urdf/arm.urdf.xacro:12 (n="${prefix}f1")'), e.value.reason
        assert e.value.to_response_error().code == -32803
    finally:
        ls.ws.close()


INSTALLED = (f'<?xml version="1.0"?>\n<robot {X}>\n'
             '  <xacro:property name="shared_len" value="0.5"/>\n</robot>\n')
USER = (f'<?xml version="1.0"?>\n<robot name="u" {X}>\n'
        '  <xacro:include filename="$(find common)/urdf/props.xacro"/>\n'
        '  <link name="a"><visual><geometry><box size="${shared_len} 1 1"/></geometry></visual>'
        '</link>\n</robot>\n')


def test_rename_edits_nothing_outside_the_workspace_folder(tmp_path, monkeypatch):
    """A property declared in an installed package (readable, never writable: check --fix's
    rule): the rename is refused, naming that file, instead of a partial edit."""
    from urdf_lint.lsp.methods import Refused, rename
    prefix = tmp_path / "install"
    index = prefix / "share" / "ament_index" / "resource_index" / "packages"
    index.mkdir(parents=True)
    (index / "common").write_text("")
    make_package(prefix / "share", "common", {"urdf/props.xacro": INSTALLED})
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(prefix))
    pkg = make_package(tmp_path / "ws", "u", {"urdf/u.urdf.xacro": USER})
    f = pkg / "urdf" / "u.urdf.xacro"
    ls = _linted(pkg, f, monkeypatch, tmp_path)
    try:
        with pytest.raises(Refused) as e:
            rename.handle(ls.services, types.RenameParams(
                text_document=types.TextDocumentIdentifier(uri=f.resolve().as_uri()),
                new_name="len2", position=_at(f, "${shared_len}", 3)))
        assert "outside the workspace folder" in e.value.reason
        assert str((prefix / "share" / "common" / "urdf" / "props.xacro").resolve()) in \
            e.value.reason
    finally:
        ls.ws.close()
