"""``urdf-lint mcp`` end to end (issue 27): the MCP SDK's own client starts the server over
stdio, lists the tools and calls each on a git copy of descriptions/, asserting the contents;
a path outside the server's root is refused."""
from __future__ import annotations

import json
import shutil
import subprocess
import sys

import pytest

from conftest import DESCRIPTIONS


def _git(cwd, *args):
    subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True)


@pytest.fixture
def repo(tmp_path):
    root = tmp_path / "repo"
    shutil.copytree(DESCRIPTIONS / "r2d2_description", root / "r2d2_description")
    _git(root, "init", "-q")
    _git(root, "-c", "user.email=t@t", "-c", "user.name=t", "add", "-A")
    _git(root, "-c", "user.email=t@t", "-c", "user.name=t", "commit", "-qm", "base")
    return root


def _is_error(result) -> bool:
    return bool(getattr(result, "is_error", None) or getattr(result, "isError", None))


def _payload(result) -> dict:
    assert not _is_error(result), result.content
    sc = getattr(result, "structuredContent", None) or getattr(result, "structured_content", None)
    if sc:
        return sc.get("result", sc) if set(sc) == {"result"} else sc
    return json.loads(result.content[0].text)


def test_mcp_server_over_stdio_lists_and_runs_every_tool(repo, tmp_path):
    pytest.importorskip("mcp")
    import anyio
    from mcp import ClientSession, StdioServerParameters
    from mcp.client.stdio import stdio_client
    macros = repo / "r2d2_description" / "urdf" / "r2d2_macros.xacro"
    entry = "r2d2_description/urdf/r2d2.urdf.xacro"
    seen: dict = {}

    async def session():
        params = StdioServerParameters(command=sys.executable,
                                       args=["-m", "urdf_lint", "mcp", "--root", str(repo)],
                                       cwd=str(repo))
        async with stdio_client(params) as (read, write):
            async with ClientSession(read, write) as s:
                await s.initialize()
                seen["tools"] = sorted(t.name for t in (await s.list_tools()).tools)
                seen["rule"] = _payload(await s.call_tool("explain_rule", {"code": "UL302"}))
                seen["expand"] = _payload(await s.call_tool("expand", {"file": entry}))
                # a change check, fix and diff can see: a limit whose lower > upper
                text = macros.read_text()
                macros.write_text(text.replace('type="continuous"', 'type="revolute"', 1)
                                  .replace('<limit effort="100" velocity="10"/>',
                                           '<limit lower="1" upper="0" effort="100" '
                                           'velocity="10"/>', 1))
                # and one whose severity depends on the consumer: two transmissions of
                # one name driving one actuator name, as a macro called twice writes them
                # (UL704: a warning for ROS, an error for Drake)
                robot = repo / entry
                robot.write_text(robot.read_text().replace("</robot>", "".join(
                    f'<transmission name="t"><type>transmission_interface/SimpleTransmission'
                    f'</type><joint name="{j}"><hardwareInterface>EffortJointInterface'
                    f'</hardwareInterface></joint><actuator name="m"/></transmission>\n'
                    for j in ("head_swivel", "gripper_extension")) + "</robot>"))
                seen["check"] = _payload(await s.call_tool("check", {"paths": ["."]}))
                seen["drake"] = _payload(await s.call_tool(
                    "check", {"paths": ["."], "select": "UL704", "targets": ["drake"]}))
                seen["bad-target"] = await s.call_tool("check", {"targets": ["--fix"]})
                seen["fix"] = _payload(await s.call_tool("fix", {"paths": ["."]}))
                seen["diff"] = _payload(await s.call_tool("diff", {"base": "HEAD"}))
                seen["render"] = _payload(await s.call_tool("render", {"paths": [entry]}))
                seen["outside"] = await s.call_tool("check", {"paths": [str(tmp_path)]})
    anyio.run(session)
    assert seen["tools"] == ["check", "diff", "expand", "explain_rule", "fix", "render"]
    check = seen["check"]
    assert check["exit_code"] == 1 and isinstance(check["result"], dict), check
    assert [m["entry"] for m in check["result"]["models"]] == [entry]
    ul302 = [f for f in check["result"]["findings"] if f["code"] == "UL302"]
    # one finding at the macro line, the four wheel joints it makes as its instances (issue 24)
    assert len(ul302) == 1 and ul302[0]["count"] == 4, ul302
    assert {(f["file"], f["line"]) for f in ul302} == {
        ("r2d2_description/urdf/r2d2_macros.xacro", 47)}
    assert all(f.get("fix") for f in ul302), ul302
    # the consumer targets: the same transmission, a warning for ROS, an error for Drake
    ros = [f for f in check["result"]["findings"] if f["code"] == "UL704"]
    assert [(f["severity"], f.get("severity_from")) for f in ros] == [("warning", None)], ros
    drake = seen["drake"]
    assert drake["exit_code"] == 1, drake
    assert {f["code"] for f in drake["result"]["findings"]} == {"UL704"}    # select
    assert [(f["file"], f["severity"], f["severity_from"]) for f in drake["result"]["findings"]] \
        == [(entry, "error", ["drake"])], drake["result"]["findings"]
    assert _is_error(seen["bad-target"]) and "cannot start with '-'" in str(
        seen["bad-target"].content)
    assert seen["rule"]["exit_code"] == 0 and "UL302 limit-order" in seen["rule"]["stdout"]
    exp = seen["expand"]
    assert exp["exit_code"] == 0 and '<robot name="r2d2">' in exp["stdout"]
    assert "xacro:" not in exp["stdout"].split("-->")[-1]
    fix = seen["fix"]
    assert "r2d2_macros.xacro" in fix["stdout"] and 'lower="0" upper="1"' in fix["stdout"], fix
    assert 'lower="1" upper="0"' in macros.read_text()        # a dry run: nothing written
    diff = seen["diff"]
    assert isinstance(diff["result"], dict), diff
    assert "UL302" in json.dumps(diff["result"]) and "revolute" in json.dumps(diff["result"])
    pngs = seen["render"]["pngs"]
    assert pngs and all(p.startswith(str(repo)) and p.endswith(".png") for p in pngs), seen["render"]
    assert open(pngs[0], "rb").read(8) == b"\x89PNG\r\n\x1a\n"
    assert _is_error(seen["outside"]) and "outside the server's root" in str(seen["outside"].content)


def test_without_the_extra_it_says_how_to_install_it(monkeypatch, capsys, tmp_path):
    monkeypatch.setitem(sys.modules, "mcp", None)     # as if urdf-lint[mcp] were not installed
    for name in [m for m in sys.modules if m.startswith("mcp.")]:
        monkeypatch.setitem(sys.modules, name, None)
    from urdf_lint.cli.main import main
    assert main(["mcp", "--root", str(tmp_path)]) == 2
    assert "pip install 'urdf-lint[mcp]'" in capsys.readouterr().err


def test_paths_outside_the_root_are_refused_before_anything_runs(tmp_path):
    from urdf_lint.cli.mcp import OutsideRoot, Tools
    root = tmp_path / "root"
    (root / "sub").mkdir(parents=True)
    (root / "link").symlink_to(tmp_path)              # a symlink out of the root
    tools = Tools(str(root))
    assert tools.paths(["sub", "."]) == ["sub", "."]
    for bad in ["..", str(tmp_path), "link", "sub/../../x"]:
        with pytest.raises(OutsideRoot):
            tools.paths([bad])
    with pytest.raises(OutsideRoot):
        tools.expand("../r.xacro")
    with pytest.raises(ValueError):
        tools.diff("--output=/tmp/x")
