"""Issue 39 in the editor: a defect inside an ``xacro:if`` the default args do not take is a
diagnostic, labelled with the args that reach it as ``check`` labels it, once; it comes after
the models' own diagnostics (``Workspace.explore``, through check's ``run.explore.explore``)."""
from __future__ import annotations

import dataclasses

from lsp_workspace import BRANCHY as ROBOT, editor  # noqa: F401 (the fixture)

from urdf_lint.lsp.methods import diagnostics



def _diags(ed, name="robot.urdf.xacro"):
    return sorted((d.code, d.range.start.line, d.message)
                  for d in diagnostics.handle(ed.sv, ed.path(name)))


def test_a_defect_in_a_branch_the_defaults_leave_out_is_a_labelled_diagnostic(editor):
    ed = editor({"robot.urdf.xacro": ROBOT})
    ed.lint()
    defaults = _diags(ed)
    # the models' own lint: nothing of the branches yet (published first)
    assert not [d for d in defaults if d[0] in ("UL602", "UL103")], defaults
    files = ed.ws.explore()
    assert ed.path("robot.urdf.xacro") in files
    got = _diags(ed)
    assert [d for d in got if d[0] == "UL602"] == [
        ("UL602", 6, next(d[2] for d in got if d[0] == "UL602"))]
    (neg,) = [m for c, _, m in got if c == "UL602"]
    assert neg.endswith("(only with sim:=true)"), neg
    (grip,) = [(line, m) for c, line, m in got if c == "UL103"]
    assert grip[0] == 11 and grip[1].endswith("(only with gripper:=robotiq)"), grip
    # a finding the defaults have (base has no inertial) is not repeated per variant
    assert [d for d in got if d[0] == "UL601" and "'base'" in d[2]] == \
        [d for d in defaults if d[0] == "UL601" and "'base'" in d[2]]
    assert len(got) == len(set(got))
    # nothing new to lint: no publish again
    assert ed.ws.explore() == set()


def test_an_edit_inside_the_branch_is_linted_again_from_the_buffer(editor):
    ed = editor({"robot.urdf.xacro": ROBOT})
    ed.lint()
    ed.ws.explore()
    assert "UL602" in [c for c, _, _ in _diags(ed)]
    fixed = ROBOT.replace('<mass value="-1"/>', '<mass value="1"/>')
    ed.open("robot.urdf.xacro", fixed)
    jobs = ed.ws.affected(ed.path("robot.urdf.xacro"))
    ed.ws.forget(jobs)
    assert not ed.ws.variants   # a variant of older text is not shown
    ed.ws.lint(jobs)
    ed.ws.explore()
    assert "UL602" not in [c for c, _, _ in _diags(ed)]
    assert "UL103" in [c for c, _, _ in _diags(ed)]


def test_explore_false_in_the_config_keeps_the_editor_at_the_defaults(editor, tmp_path):
    ed = editor({"robot.urdf.xacro": ROBOT})
    ed.ws.cfg = dataclasses.replace(ed.ws.cfg, explore=False)
    ed.lint()
    assert ed.ws.explore() == set()
    assert "UL602" not in [c for c, _, _ in _diags(ed)]


def test_hover_on_the_condition_names_the_variant_that_takes_it(editor):
    from lsprotocol import types
    from urdf_lint.lsp.methods import hover
    ed = editor({"robot.urdf.xacro": ROBOT})
    ed.lint()
    ed.ws.explore()
    got = hover.handle(ed.sv, types.HoverParams(
        text_document=ed.doc("robot.urdf.xacro"),
        position=ed.at("robot.urdf.xacro", '<xacro:if value="$(arg sim)">', 3)))
    text = got.contents.value
    assert "body expanded in: `r [sim:=true]`" in text, text
    assert "left out in: `r`, `r [gripper:=robotiq]`" in text, text
