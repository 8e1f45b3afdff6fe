"""``textDocument/definition`` (urdf_lint/lsp/methods/definition.py), in process."""
from __future__ import annotations

from lsp_workspace import ARM, BOT, editor  # noqa: F401 (the fixture)
from lsprotocol import types

from urdf_lint.lsp.methods import definition


def _where(ed, name, needle, offset=0):
    got = definition.handle(ed.sv, types.DefinitionParams(
        text_document=ed.doc(name), position=ed.at(name, needle, offset))) or []
    return [(loc.uri.rsplit("/", 1)[-1], loc.range.start.line, loc.range.start.character)
            for loc in got]


def test_a_macro_call_goes_to_the_macro_in_the_included_file(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    assert _where(ed, "bot.urdf.xacro", "<xacro:arm", 8) == [("arm.xacro", 3, 2)]


def test_a_name_in_an_expression_goes_to_the_property(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    assert _where(ed, "bot.urdf.xacro", "${reach}", 3) == [("bot.urdf.xacro", 3, 2)]


def test_a_macro_parameter_goes_to_its_macro(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    assert _where(ed, "arm.xacro", "${lower}", 3) == [("arm.xacro", 3, 2)]


def test_an_include_goes_to_the_file(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    assert _where(ed, "bot.urdf.xacro", 'filename="arm', 11) == [("arm.xacro", 0, 0)]


def test_a_parent_link_in_a_macro_goes_to_the_link_in_the_robot(editor):
    """``<parent link="base"/>`` written in the macro library names the robot's own link:
    found through the expanded model's source map."""
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    assert _where(ed, "arm.xacro", 'parent link="base', 15) == []   # nothing linted yet
    ed.lint()
    assert _where(ed, "arm.xacro", 'parent link="base', 15) == [("bot.urdf.xacro", 4, 2)]
