"""`urdf-lint server` end to end on issue 39: a defect inside an ``xacro:if`` the default
args leave out is published as a diagnostic labelled with the args that reach it (as
``check`` labels it), once, after the defaults' diagnostics (docs/coverage.md)."""
from __future__ import annotations

from pathlib import Path

import pytest

pytest.importorskip("pygls")
pytest_lsp = pytest.importorskip("pytest_lsp")
from lsprotocol import types  # noqa: E402

from support import lsp_client  # noqa: E402
from support.lsp_client import diagnostics_for, open_doc  # noqa: E402
from support.lsp_workspace import BRANCHY as ROBOT  # noqa: E402

aio = pytest.mark.asyncio(loop_scope="function")
LSP_WORKSPACE = "pkg"
client = lsp_client.client


@pytest.fixture
def pkg(tmp_path, monkeypatch) -> Path:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    root = tmp_path / "pkg"
    (root / "urdf").mkdir(parents=True)
    (root / "package.xml").write_text("<package><name>pkg</name></package>\n")
    (root / "urdf" / "robot.urdf.xacro").write_text(ROBOT)
    return root


@aio
async def test_a_defect_in_an_unexplored_branch_is_published_labelled_once(client, pkg):
    uri = open_doc(client, pkg / "urdf" / "robot.urdf.xacro")
    ds = await diagnostics_for(client, uri, lambda ds: any(d.code == "UL602" for d in ds),
                               timeout=90.0)
    (neg,) = [d for d in ds if d.code == "UL602"]
    assert (neg.range.start.line, neg.message.endswith("(only with sim:=true)")) == (6, True)
    grip = [d for d in ds if d.code == "UL103"]
    assert [d.range.start.line for d in grip] == [11], grip
    assert grip[0].message.endswith("(only with gripper:=robotiq)")
    assert len({(d.code, d.range.start.line, d.message) for d in ds}) == len(ds)
    # an edit inside the branch (unsaved): linted again, the defect gone, the other kept
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=2),
        content_changes=[types.TextDocumentContentChangeWholeDocument(
            text=ROBOT.replace('<mass value="-1"/>', '<mass value="1"/>'))]))
    ds = await diagnostics_for(client, uri, lambda ds: not any(d.code == "UL602" for d in ds)
                               and any(d.code == "UL103" for d in ds), timeout=90.0)
    assert [d.range.start.line for d in ds if d.code == "UL103"] == [11]
