"""``textDocument/documentSymbol`` and ``workspace/symbol``
(urdf_lint/lsp/methods/document_symbol.py, workspace_symbol.py), in process."""
from __future__ import annotations

from lsp_workspace import ARM, BOT, editor  # noqa: F401 (the fixture)
from lsprotocol import types

from urdf_lint.lsp.methods import document_symbol, workspace_symbol


def test_the_declarations_of_a_document_from_its_unsaved_text(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    ed.open("bot.urdf.xacro", BOT.replace('<link name="base"/>',
                                          '<link name="base"/>\n  <link name="tool"/>'))
    got = document_symbol.handle(ed.sv, types.DocumentSymbolParams(
        text_document=ed.doc("bot.urdf.xacro")))
    assert [(s.detail, s.name, s.range.start.line) for s in got] == [
        ("property", "reach", 3), ("link", "base", 4), ("link", "tool", 5)]


def test_workspace_symbols_match_the_query_in_every_file(editor):
    ed = editor({"arm.xacro": ARM, "bot.urdf.xacro": BOT})
    ed.open("bot.urdf.xacro")
    got = workspace_symbol.handle(ed.sv, types.WorkspaceSymbolParams(query="AR"))
    assert sorted((s.name, s.kind, s.location.uri.rsplit("/", 1)[-1]) for s in got) == [
        ("${prefix}arm", types.SymbolKind.Struct, "arm.xacro"),
        ("arm", types.SymbolKind.Function, "arm.xacro")]
