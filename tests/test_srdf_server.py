"""The language server on a robot's configuration files: a broken controller YAML shows its
findings in the YAML file (with the robot's element as related information), and go to
definition from a joint name in the YAML or the SRDF lands on the xacro line writing it."""
from __future__ import annotations

from pathlib import Path

import pytest

pytest.importorskip("pygls")
pytest_lsp = pytest.importorskip("pytest_lsp")
from lsprotocol import types  # noqa: E402
from pytest_lsp import LanguageClient  # noqa: E402

from support import lsp_client  # noqa: E402
from support.lsp_client import diagnostics_for  # noqa: E402

DEMO = Path(__file__).resolve().parents[1] / "descriptions" / "broken" / "broken_moveit_config"
aio = pytest.mark.asyncio(loop_scope="function")

pkg = lsp_client.copy_of(DEMO, "pkg")
LSP_WORKSPACE = "pkg"             # the fixture the client's server works on
client = lsp_client.client


def open_doc(client: LanguageClient, path: Path) -> str:
    return lsp_client.open_doc(client, path, language_id="yaml")


async def definition(client, uri, line, char):
    return await client.text_document_definition_async(types.DefinitionParams(
        text_document=types.TextDocumentIdentifier(uri=uri),
        position=types.Position(line, char)))


def where(locs):
    return [(loc.uri.rsplit("/", 1)[-1], loc.range.start.line) for loc in locs or ()]


@aio
async def test_controller_yaml_diagnostics_and_definition(client, pkg):
    yaml_path = pkg / "config" / "ros2_controllers.yaml"
    lines = yaml_path.read_text().splitlines()
    stale = next(i for i, t in enumerate(lines) if t.strip() == "- joint_3")
    uri = open_doc(client, yaml_path)
    ds = await diagnostics_for(client, uri, lambda ds: any(d.code == "UL710" for d in ds),
                               timeout=90.0)
    d = next(d for d in ds if d.code == "UL710")
    # at the YAML line naming the stale joint, the robot's joint3 as related information
    assert (d.range.start.line, d.range.start.character) == (stale, lines[stale].index("joint_3"))
    assert "joint_3" in d.message
    rel = [(r.location.uri.rsplit("/", 1)[-1], r.location.range.start.line, r.message)
           for r in d.related_information or ()]
    xacro = (pkg / "urdf" / "arm.urdf.xacro").read_text().splitlines()
    joint_line = next(i for i, t in enumerate(xacro) if 'joint name="joint${n}"' in t)
    assert ("arm.urdf.xacro", joint_line, "robot element here") in rel
    # definition from a joint name in the YAML lands on the xacro line that writes the joint
    ok = next(i for i, t in enumerate(lines) if t.strip() == "- joint2")
    got = await definition(client, uri, ok, lines[ok].index("joint2") + 2)
    assert where(got) == [("arm.urdf.xacro", joint_line)]
    # and from a link name in the SRDF to its <link>
    srdf = pkg / "config" / "broken_arm.srdf"
    s_lines = srdf.read_text().splitlines()
    s_uri = open_doc(client, srdf)
    at = next(i for i, t in enumerate(s_lines) if 'link1="base_link"' in t)
    got = await definition(client, s_uri, at, s_lines[at].index("base_link") + 1)
    base = next(i for i, t in enumerate(xacro) if '<link name="base_link"' in t)
    assert where(got) == [("arm.urdf.xacro", base)]
    # completion offers the robot's joint and link names in the YAML
    items = await client.text_document_completion_async(types.CompletionParams(
        text_document=types.TextDocumentIdentifier(uri=uri),
        position=types.Position(ok, lines[ok].index("joint2"))))
    items = items.items if hasattr(items, "items") else items
    labels = {i.label: i.detail for i in items or ()}
    assert labels.get("joint3") == "joint of arm.urdf" and labels.get("tool0") == "link of arm.urdf"
