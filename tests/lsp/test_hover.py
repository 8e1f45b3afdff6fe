"""``textDocument/hover`` (urdf_lint/lsp/methods/hover.py), in process."""
from __future__ import annotations

from lsp_workspace import ARM, BOT, SHORT, editor  # noqa: F401 (the fixture)
from lsprotocol import types

from urdf_lint.lsp.methods import hover


def _hover(ed, name, needle, offset=0):
    got = hover.handle(ed.sv, types.HoverParams(text_document=ed.doc(name),
                                                position=ed.at(name, needle, offset)))
    return got.contents.value if got is not None else None


def test_a_macro_call_shows_its_parameters_defaults_and_doc_comment(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    assert _hover(ed, "bot.urdf.xacro", "<xacro:arm", 3) == (
        "**macro arm** (arm.xacro:4)\n\n- `prefix` (required)\n- `lower` = `0.5`\n"
        "- `upper` (required)\n\nAn arm link on a revolute elbow.")


def test_an_expression_shows_its_value_in_each_model(editor):
    """The same ``${upper}`` of the macro is 1.5 in one robot and 0.2 in the other."""
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT, "short.urdf.xacro": SHORT})
    ed.lint()
    assert _hover(ed, "arm.xacro", 'upper="${upper}', 10) == \
        "`upper` = `1.5` in bot.urdf; `0.2` in short.urdf"


def test_a_buffer_edit_shows_the_new_value_after_the_lint(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    ed.open("bot.urdf.xacro", BOT.replace('value="1.5"', 'value="2.5"'))
    ed.lint()
    assert _hover(ed, "arm.xacro", 'upper="${upper}', 10) == "`upper` = `2.5` in bot.urdf"


def test_a_link_shows_its_frame_in_each_model(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    ed.lint()
    assert _hover(ed, "bot.urdf.xacro", '<link name="base', 13) == (
        "**link**\n\n- **bot.urdf**: `base`; world pose at zero: xyz 0.0 0.0 0.0, "
        "rpy 0.0 0.0 0.0")


def test_a_rule_code_in_a_suppression_comment_shows_the_rule(editor):
    text = BOT.replace("<link name=\"base\"/>",
                       "<!-- urdf-lint: disable UL601 -->\n  <link name=\"base\"/>")
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": text})
    got = _hover(ed, "bot.urdf.xacro", "UL601", 2)
    assert got is not None and got.startswith("**UL601 ")


def test_plain_text_has_no_hover(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    assert _hover(ed, "bot.urdf.xacro", "<?xml", 2) is None
