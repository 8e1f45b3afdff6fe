"""Output that does not depend on where the repository is (issue 22): every path in every
message and format is relative (to the working directory, with ``..`` inside the repository or
workspace), and a baseline written in one checkout matches in a copy elsewhere after edits."""
from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest

from conftest import DESCRIPTIONS, make_package, run_cli

pytestmark = pytest.mark.skipif(shutil.which("git") is None, reason="needs git")

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
ARM = f"""<robot {X}>
  <xacro:macro name="arm" params="">
    <link name="a"/><link name="b"/>
    <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
      <limit lower="1" upper="0" effort="1" velocity="1"/></joint>
  </xacro:macro>
</robot>
"""
ROBOT = f"""<robot name="r" {X}>
  <xacro:include filename="$(find arm_parts)/urdf/arm.xacro"/>
  <xacro:arm/>
  <link name="base"><visual><geometry><mesh filename="package://robot/meshes/gone.stl"/></geometry></visual></link>
  <joint name="fix" type="fixed"><parent link="base"/><child link="a"/></joint>
</robot>
"""


def git(*args, cwd):
    subprocess.run(["git", "-c", "user.email=t@t", "-c", "user.name=t", *args], cwd=cwd,
                   check=True, capture_output=True)


def workspace(top: Path) -> Path:
    """A colcon workspace: ``src/robot`` (a git repository holding the demo's broken robots
    and a robot that uses a sibling package) and ``src/arm_parts`` beside it."""
    src = top / "ws" / "src"
    make_package(src, "arm_parts", {"urdf/arm.xacro": ARM})
    repo = make_package(src, "robot", {"urdf/robot.urdf.xacro": ROBOT})
    shutil.copytree(DESCRIPTIONS / "broken", repo / "broken")
    git("init", "-q", cwd=repo)
    git("add", "-A", cwd=repo)
    git("commit", "-qm", "init", cwd=repo)
    return repo


@pytest.fixture(scope="module")
def ws_repo(tmp_path_factory):
    return workspace(tmp_path_factory.mktemp("portable"))


def absolute_paths_of(top: Path, text: str) -> list:
    return [ln for ln in text.splitlines()
            if str(top) in ln or str(top.resolve()) in ln]


def test_every_format_is_free_of_the_checkout_path(ws_repo):
    from urdf_lint.report.registry import formats
    top = ws_repo.parents[2]
    names = list(formats())
    assert len(names) >= 6
    for fmt in names:
        p = run_cli("check", ".", "--no-cache", "--format", fmt, cwd=ws_repo)
        assert p.returncode == 1, (fmt, p.stderr)
        assert p.stdout.strip(), fmt
        assert absolute_paths_of(top, p.stdout + p.stderr) == [], fmt
    # the sibling package's file and the missing mesh are shown relative
    text = run_cli("check", ".", "--no-cache", cwd=ws_repo).stdout
    assert "../arm_parts/urdf/arm.xacro:5:7: UL302" in text, text
    assert "(looked for meshes/gone.stl)" in text
    assert "(looked for broken/broken_robots/meshes/no_such_part.stl)" in text


def test_diff_formats_are_free_of_the_checkout_path(ws_repo, tmp_path):
    from urdf_lint.report.diff import names
    repo = tmp_path / "copy"
    shutil.copytree(ws_repo.parents[1], repo, symlinks=True)
    repo = repo / "src" / "robot"
    (repo / "urdf/robot.urdf.xacro").write_text(
        ROBOT.replace("gone.stl", "gone_too.stl")   # a change, and a removal (base side)
        .replace('  <joint name="fix" type="fixed"><parent link="base"/><child link="a"/></joint>\n',
                 ""))
    for fmt in names():
        p = run_cli("diff", "HEAD", "--format", fmt, "--no-cache", cwd=repo)
        assert p.returncode in (0, 1), (fmt, p.stderr)
        assert "robot.urdf.xacro" in p.stdout, (fmt, p.stdout)
        assert absolute_paths_of(tmp_path, p.stdout + p.stderr) == [], fmt


def test_baseline_survives_a_move_a_reindent_and_edits_above(tmp_path):
    first = workspace(tmp_path / "a")
    p = run_cli("check", ".", "--no-cache", "--write-baseline", "known.json", cwd=first)
    assert p.returncode == 0, p.stderr
    doc = json.loads((first / "known.json").read_text())
    assert doc["version"] == 2 and doc["findings"]
    assert str(tmp_path) not in (first / "known.json").read_text()
    e = next(e for e in doc["findings"] if e["code"] == "UL302" and "arm.xacro" in e["file"])
    assert e["file"] == "../arm_parts/urdf/arm.xacro"
    assert e["element"] == "robot/xacro:macro[arm]/joint[elbow]/limit"
    # another developer's checkout, elsewhere, with lines added above the findings and reindented
    shutil.copytree(tmp_path / "a" / "ws", tmp_path / "b" / "elsewhere" / "ws", symlinks=True)
    moved = tmp_path / "b" / "elsewhere" / "ws" / "src" / "robot"
    arm = moved.parent / "arm_parts" / "urdf" / "arm.xacro"
    arm.write_text(arm.read_text().replace("<robot ", "<!-- the arm -->\n\n<robot ")
                   .replace("\n    <joint", "\n        <joint"))
    for f in (moved / "broken" / "broken_robots" / "urdf").glob("*.xacro"):
        f.write_text(f.read_text().replace("\n", "\n\n", 1))
    p = run_cli("check", ".", "--no-cache", "--baseline", "known.json", "--format", "json",
                cwd=moved)
    assert json.loads(p.stdout)["findings"] == [], p.stdout
    assert p.returncode == 0, p.stderr
    # a new finding at another element is still reported
    arm.write_text(arm.read_text().replace('effort="1"', 'effort="-1"'))
    p = run_cli("check", ".", "--no-cache", "--baseline", "known.json", "--format", "json",
                cwd=moved)
    assert {f["code"] for f in json.loads(p.stdout)["findings"]} == {"UL304"}, p.stdout


def test_old_baseline_still_loads_with_a_note(tmp_path):
    repo = workspace(tmp_path)
    p = run_cli("check", ".", "--no-cache", "--format", "json", "--fail-on", "never", cwd=repo)
    # a version 1 file held one entry per instance (urdf-lint before findings were grouped)
    old = [{"code": i["code"], "file": i["file"], "message": i["message"]}
           for f in json.loads(p.stdout)["findings"] for i in f.get("instances") or [f]]
    (repo / "old.json").write_text(json.dumps({"version": 1, "findings": old}))
    p = run_cli("check", ".", "--no-cache", "--baseline", "old.json", cwd=repo)
    assert p.returncode == 0, p.stdout
    assert "old (version 1) baseline" in p.stderr and "--write-baseline old.json" in p.stderr
