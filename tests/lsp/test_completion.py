"""``textDocument/completion`` (urdf_lint/lsp/methods/completion.py), in process."""
from __future__ import annotations

from lsp_workspace import ARM, BOT, editor  # noqa: F401 (the fixture)
from lsprotocol import types

from urdf_lint.lsp.methods import completion


def _items(ed, name, text, needle, offset):
    ed.open(name, text)
    got = completion.handle(ed.sv, types.CompletionParams(
        text_document=ed.doc(name), position=ed.at(name, needle, offset)))
    return {i.label: i for i in got.items}


def test_after_xacro_colon_the_macros_with_their_required_parameters(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    text = BOT.replace("</robot>", "  <xacro:\n</robot>")
    items = _items(ed, "bot.urdf.xacro", text, "<xacro:\n", 7)
    assert list(items) == ["arm"]
    assert items["arm"].insert_text == 'arm prefix="${1}" upper="${2}"/>'


def test_in_an_expression_the_macro_parameters_then_the_properties(editor):
    ed = editor({"arm.xacro": ARM.replace('value="1"/>', 'value="${}"/>', 1)
                 .replace('effort="1"', 'effort="${}"'), "bot.urdf.xacro": BOT})
    text = ed.sv.doc(ed.path("arm.xacro")).text
    items = _items(ed, "arm.xacro", text, 'effort="${', 10)
    assert [k for k in items if items[k].detail == "parameter of arm"] == \
        ["prefix", "lower", "upper"]
    assert "reach" in items   # the robot's property, reachable from the workspace


def test_in_a_suppression_comment_the_rule_codes(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    text = BOT.replace("<link name=\"base\"/>", "<!-- urdf-lint: disable U -->")
    items = _items(ed, "bot.urdf.xacro", text, "disable U", 9)
    assert "UL601" in items and all(k.startswith("UL") for k in items)


def test_a_parent_link_completes_the_links_of_the_models_using_the_file(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    ed.lint()
    items = _items(ed, "arm.xacro", ARM, 'parent link="', 13)
    assert set(items) == {"base", "l_arm"}
