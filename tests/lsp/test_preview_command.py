"""``workspace/executeCommand`` ``urdf-lint.preview`` (urdf_lint/lsp/methods/preview.py), in
process: a file outside the workspace's roots is refused before any preview starts (the
preview itself runs as a process: tests/test_lsp_preview.py)."""
from __future__ import annotations

import pytest
from lsp_workspace import BOT, editor  # noqa: F401 (the fixture)

from urdf_lint.lsp.methods import Refused, preview


def test_a_file_outside_the_roots_is_not_previewed(editor, tmp_path_factory):  # noqa: F811
    ed = editor({"bot.urdf.xacro": BOT})
    outside = tmp_path_factory.mktemp("elsewhere") / "other.urdf"
    outside.write_text('<robot name="o"><link name="a"/></robot>\n')
    with pytest.raises(Refused, match="outside the workspace"):
        preview.handle(ed.sv, [outside.as_uri(), 0, 0])
    assert not preview._running
