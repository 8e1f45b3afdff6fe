"""``textDocument/references`` (urdf_lint/lsp/methods/references.py), in process."""
from __future__ import annotations

from lsp_workspace import ARM, BOT, SHORT, editor  # noqa: F401 (the fixture)
from lsprotocol import types

from urdf_lint.lsp.methods import references


def _refs(ed, name, needle, offset, declaration=True):
    got = references.handle(ed.sv, types.ReferenceParams(
        text_document=ed.doc(name), position=ed.at(name, needle, offset),
        context=types.ReferenceContext(include_declaration=declaration))) or []
    return sorted((loc.uri.rsplit("/", 1)[-1], loc.range.start.line) for loc in got)


def test_the_calls_of_a_macro_in_every_file_and_its_declaration(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT, "short.urdf.xacro": SHORT})
    ed.open("bot.urdf.xacro")
    ed.open("short.urdf.xacro")
    assert _refs(ed, "arm.xacro", 'name="arm"', 7) == [
        ("arm.xacro", 3), ("bot.urdf.xacro", 5), ("short.urdf.xacro", 4)]
    assert _refs(ed, "arm.xacro", 'name="arm"', 7, declaration=False) == [
        ("bot.urdf.xacro", 5), ("short.urdf.xacro", 4)]


def test_a_link_is_found_wherever_a_model_names_it(editor):
    """``base`` is written in the robot and named as a parent in the macro library."""
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    ed.lint()
    assert _refs(ed, "bot.urdf.xacro", '<link name="base', 13) == [
        ("arm.xacro", 6), ("bot.urdf.xacro", 4)]
