"""The diagnostics the server publishes (urdf_lint/lsp/methods/diagnostics.py), in process:
one per finding as ``check`` groups them, from the unsaved buffers."""
from __future__ import annotations

from lsp_workspace import ARM, BOT, SHORT, editor  # noqa: F401 (the fixture)
from lsprotocol import types

from urdf_lint.lsp.methods import diagnostics

INERTIAL = ('<link name="${prefix}arm"><inertial><mass value="1"/>'
            '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>')


def _diags(ed, name):
    return [(d.code, d.range.start.line, d.message) for d in
            diagnostics.handle(ed.sv, ed.path(name))]


def test_a_finding_in_a_macro_is_one_diagnostic_there_naming_every_model(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT, "short.urdf.xacro": SHORT})
    ed.lint()
    ((code, line, message),) = [d for d in _diags(ed, "arm.xacro") if d[0] == "UL601"]
    assert (code, line) == ("UL601", 4)
    assert message.endswith("(in bot.urdf, short.urdf)"), message
    assert [d for d in _diags(ed, "bot.urdf.xacro") if d[0] == "UL601"] == []
    (d,) = [d for d in diagnostics.handle(ed.sv, ed.path("arm.xacro")) if d.code == "UL601"]
    assert d.severity == types.DiagnosticSeverity.Warning and d.source == "urdf-lint"


def test_the_unsaved_buffer_is_what_is_linted(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    ed.lint()
    assert "UL601" in [c for c, _, _ in _diags(ed, "arm.xacro")]
    ed.open("arm.xacro", ARM.replace('<link name="${prefix}arm"/>', INERTIAL))
    ed.lint()
    assert "UL601" not in [c for c, _, _ in _diags(ed, "arm.xacro")]


def test_a_suppression_comment_in_the_buffer_hides_the_finding(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    ed.open("arm.xacro", ARM.replace('    <link name="${prefix}arm"/>',
                                     '    <!-- urdf-lint: disable UL601 -->\n'
                                     '    <link name="${prefix}arm"/>'))
    ed.lint()
    assert "UL601" not in [c for c, _, _ in _diags(ed, "arm.xacro")]


def test_a_config_mistake_is_an_error_at_its_line(editor, tmp_path):
    (tmp_path / "pkg").mkdir()
    (tmp_path / "pkg" / "pyproject.toml").write_text(
        '[tool.urdf-lint]\nselect = ["UL601"]\nno-such-key = 1\n')
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    got = diagnostics.handle(ed.sv, str((tmp_path / "pkg" / "pyproject.toml").resolve()))
    assert [(d.code, d.range.start.line, d.severity) for d in got] == \
        [("config", 2, types.DiagnosticSeverity.Error)]
    assert "no-such-key" in got[0].message
