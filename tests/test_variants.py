"""Issue 32, one xacro and many variants: a generated URDF is checked against the variant
(the xacro args) that made it, ``generate`` never rewrites a file with args it cannot tie to
it, and ``diff`` reads the whole repository model of each revision (configured models it
does not touch, variants it does not reach, locations relative to the repository)."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import make_package, run_cli

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
# a robot whose colour picks its mesh folder (robot.blue.urdf is `xacro ... color:=blue`)
COLOURED = f"""<?xml version="1.0"?>
<robot name="r" {X}>
  <xacro:arg name="color" default="white"/>
  <link name="base">
    <visual><geometry><mesh filename="meshes/robot_$(arg color)/base.stl"/></geometry></visual>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
</robot>
"""
NOTE = '<!-- xacro args (urdf-lint generate): {"color": "blue"} -->'
BANNER_END = "<!-- " + "=" * 83 + " -->\n"


def _after_banner(text: str, line: str) -> str:
    """``text`` with ``line`` after xacro's four-line banner."""
    at = text.index(BANNER_END, text.index("EDITING")) + len(BANNER_END)
    return text[:at] + line + text[at:]


def _expand(pkg: Path, out: str, *args: str) -> None:
    p = run_cli("expand", "urdf/robot.urdf.xacro", *args, "-o", out, cwd=pkg)
    assert p.returncode == 0, p.stderr


def _ul011(pkg: Path, *args: str) -> dict:
    p = run_cli("check", ".", "--no-cache", "--format", "json", "--select", "UL011", *args,
                cwd=pkg)
    return {f["file"]: f["message"] for f in json.loads(p.stdout)["findings"]}


def _restyle(pkg: Path) -> None:
    """A change of the xacro every variant sees."""
    xacro = pkg / "urdf/robot.urdf.xacro"
    xacro.write_text(xacro.read_text().replace('size="0.1 0.1 0.1"', 'size="0.2 0.2 0.2"'))


def test_a_variant_whose_header_records_its_args_is_checked_and_regenerated_with_them(tmp_path):
    """robot.blue.urdf, made with color:=blue, its args recorded after xacro's banner: current
    (it was UL011 against the white robot); once stale, UL011 names its args and generate
    rewrites it as the blue robot, keeping the record."""
    pkg = make_package(tmp_path, "p", {"urdf/robot.urdf.xacro": COLOURED})
    _expand(pkg, "urdf/robot.blue.urdf", "color:=blue")
    blue = pkg / "urdf/robot.blue.urdf"
    blue.write_text(_after_banner(blue.read_text(), NOTE + "\n"))
    assert _ul011(pkg) == {}
    _restyle(pkg)
    found = _ul011(pkg)
    assert list(found) == ["urdf/robot.blue.urdf"], found
    assert "expands to today with args color:=blue; regenerate it with 'urdf-lint generate'" \
        in found["urdf/robot.blue.urdf"], found
    p = run_cli("generate", cwd=pkg)
    assert p.returncode == 1 and "regenerated urdf/robot.blue.urdf from urdf/robot.urdf.xacro " \
                                 "with args color:=blue" in p.stdout, (p.stdout, p.stderr)
    text = blue.read_text()
    assert "robot_blue" in text and "robot_white" not in text and NOTE in text, text
    assert _ul011(pkg) == {}
    assert run_cli("generate", cwd=pkg).returncode == 0


def test_a_variant_xacro_wrote_is_never_rewritten_as_another(tmp_path):
    """robot.blue.urdf as xacro writes it (a banner, no args) and no [[models]] entry: UL011
    says it is stale or made with unknown args (naming the closest variant and the first
    difference), and generate refuses (exit 1, the file byte for byte as it was), --check
    too. Listed with its output and args, it is current, and generate rewrites it as blue."""
    pkg = make_package(tmp_path, "p", {"urdf/robot.urdf.xacro": COLOURED})
    _expand(pkg, "urdf/robot.blue.urdf", "color:=blue")
    blue = pkg / "urdf/robot.blue.urdf"
    before = blue.read_bytes()
    found = _ul011(pkg)
    assert list(found) == ["urdf/robot.blue.urdf"], found
    msg = found["urdf/robot.blue.urdf"]
    assert msg.startswith("generated file is stale, or made with args urdf-lint does not know: "
                          "it is not what urdf/robot.urdf.xacro expands to today with the "
                          "default args (<link 'base'> > <visual> > <geometry> > <mesh> filename: "
                          "'meshes/robot_blue/base.stl' in the file, "
                          "'meshes/robot_white/base.stl' from the xacro); "
                          "add a [[tool.urdf-lint.models]] "
                          "entry with its output and args"), msg
    for extra in ((), ("--check",)):
        p = run_cli("generate", *extra, cwd=pkg)
        assert p.returncode == 1, (p.stdout, p.stderr)
        assert "urdf/robot.blue.urdf:10: not rewritten: it is stale, or made with args " \
               "urdf-lint does not know" in p.stderr, p.stderr
        assert "1 refused" in p.stdout and "regenerated" not in p.stdout, p.stdout
        assert blue.read_bytes() == before
    (pkg / "urdf-lint.toml").write_text('[[models]]\npath = "urdf/robot.urdf.xacro"\n'
                                        'args = [{color = "blue"}]\n'
                                        'output = "urdf/robot.blue.urdf"\n')
    assert _ul011(pkg) == {}
    _restyle(pkg)
    assert run_cli("generate", cwd=pkg).returncode == 1
    assert "robot_blue" in blue.read_text() and "robot_white" not in blue.read_text()


GRIPPED = f"""<?xml version="1.0"?>
<robot name="r" {X}>
  <xacro:arg name="gripper" default="false"/>
  <link name="base"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <xacro:if value="$(arg gripper)">
    <link name="gripper"/>
    <joint name="g" type="fixed"><parent link="base"/><child link="gripper"/></joint>
  </xacro:if>
</robot>
"""


def test_headed_outputs_of_other_link_counts_are_checked(tmp_path):
    """robot.urdf and robot_gripper.urdf (one link more), both from xacro with a banner and the
    two variants configured: each is compared with the variant it matches, and when the xacro
    changes both are stale (robot_gripper.urdf was never checked: another link count)."""
    pkg = make_package(tmp_path, "p", {"urdf/robot.urdf.xacro": GRIPPED})
    (pkg / "urdf-lint.toml").write_text('[[models]]\npath = "urdf/robot.urdf.xacro"\n'
                                        'args = [{}, {gripper = "true"}]\n')
    _expand(pkg, "urdf/robot.urdf")
    _expand(pkg, "urdf/robot_gripper.urdf", "gripper:=true")
    assert _ul011(pkg) == {}
    xacro = pkg / "urdf/robot.urdf.xacro"
    xacro.write_text(xacro.read_text().replace('size="0.1 0.1 0.1"', 'size="0.2 0.2 0.2"'))
    found = _ul011(pkg)
    assert sorted(found) == ["urdf/robot.urdf", "urdf/robot_gripper.urdf"], found
    assert "closest: args gripper:=true, <link 'base'> > <collision> > <geometry> > <box> " \
        "size: '0.1 0.1 0.1' in the file, '0.2 0.2 0.2' from the xacro" \
        in found["urdf/robot_gripper.urdf"], found


def test_regenerated_banner_is_xacros_own_for_a_xacro_in_another_folder(tmp_path):
    """urdf/robot.urdf made by xacro itself from urdf/ (`xacro ../xacro/robot.xacro`): the
    file generate writes is byte for byte what xacro writes there, plus the args record
    after the banner (the banner line was padded for another name)."""
    xacro_bin = Path(sys.executable).parent / "xacro"
    if not xacro_bin.exists():
        pytest.skip("the xacro command is not installed")
    src = f"""<?xml version="1.0"?>
<robot name="r" {X}>
  <xacro:property name="h" value="0.2"/>
  <link name="a"/>
  <link name="b"/>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/><origin xyz="0 0 ${{h}}"/></joint>
</robot>
"""
    pkg = make_package(tmp_path, "p", {"xacro/robot.xacro": src})
    (pkg / "urdf").mkdir()

    def xacro(out):
        subprocess.run([str(xacro_bin), "../xacro/robot.xacro", "-o", out], cwd=pkg / "urdf",
                       check=True, capture_output=True)
    xacro("robot.urdf")
    (pkg / "xacro/robot.xacro").write_text(src.replace('value="0.2"', 'value="0.3"'))
    p = run_cli("generate", cwd=pkg)
    assert p.returncode == 1 and "regenerated urdf/robot.urdf" in p.stdout, (p.stdout, p.stderr)
    xacro(str(tmp_path / "want.urdf"))
    want = (tmp_path / "want.urdf").read_text()
    assert "0.3" in want
    note = "<!-- xacro args (urdf-lint generate): {} -->\n"
    assert (pkg / "urdf/robot.urdf").read_text() == _after_banner(want, note)


# -- diff -----------------------------------------------------------------------------------------
def git(repo: Path, *args: str) -> str:
    return subprocess.run(["git", "-c", "user.name=t", "-c", "user.email=t@t", *args], cwd=repo,
                          check=True, capture_output=True, text=True).stdout


def _commit(repo: Path, msg: str) -> None:
    git(repo, "add", "-A")
    git(repo, "commit", "-qm", msg)


def _diff_json(repo: Path, *revs: str):
    p = run_cli("diff", *revs, "--format", "json", "--no-cache", cwd=repo)
    assert p.returncode in (0, 1), (p.returncode, p.stdout, p.stderr)
    return json.loads(p.stdout), p


ROBOT = f"""<?xml version="1.0"?>
<robot name="{{name}}" {X}>
  <link name="base"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="tip"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="j" type="fixed"><parent link="base"/><child link="tip"/><origin xyz="0 0 0.5"/></joint>
</robot>
"""


def test_diff_with_a_configured_model_the_change_does_not_touch(tmp_path):
    """Two configured models, a change to one: the base's config is valid there (it was exit 2,
    "model 'urdf/b.urdf.xacro' does not exist" in the partial copy); b is not reported."""
    repo = tmp_path / "repo"
    pkg = make_package(repo, "p", {"urdf/a.urdf.xacro": ROBOT.format(name="a"),
                                   "urdf/b.urdf.xacro": ROBOT.format(name="b")})
    (repo / "urdf-lint.toml").write_text('[[models]]\npath = "p/urdf/a.urdf.xacro"\n'
                                         '[[models]]\npath = "p/urdf/b.urdf.xacro"\n')
    git(repo, "init", "-q")
    _commit(repo, "base")
    a = pkg / "urdf/a.urdf.xacro"
    a.write_text(a.read_text().replace('xyz="0 0 0.5"', 'xyz="0 0 0.6"'))
    doc, _ = _diff_json(repo, "HEAD")
    assert [(m["model"], m["status"]) for m in doc["models"]] == \
        [("p/urdf/a.urdf.xacro", "changed")], doc


VARIANT = f"""<?xml version="1.0"?>
<robot name="ur" {X}>
  <xacro:arg name="ur_type" default="ur5"/>
  <xacro:property name="p" value="${{xacro.load_yaml('$(find p)/config/' + '$(arg ur_type)' + '.yaml')}}"/>
  <link name="base"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="tip"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="j" type="fixed"><parent link="base"/><child link="tip"/>
    <origin xyz="0 0 ${{p['reach']}}"/></joint>
</robot>
"""


def test_diff_of_one_xacro_configured_for_two_variants(tmp_path):
    """ur.urdf.xacro listed for ur5 and ur10 (each reads its own YAML): a change to neither's
    inputs reports no model; a change to ur5.yaml reports the ur5 variant changed and not the
    ur10 one "removed" with a false "fixed UL003 YAML file not found"."""
    repo = tmp_path / "repo"
    pkg = make_package(repo, "p", {"urdf/ur.urdf.xacro": VARIANT,
                                   "config/ur5.yaml": "reach: 0.5\n",
                                   "config/ur10.yaml": "reach: 1.0\n",
                                   "README.md": "robots\n"})
    (repo / "urdf-lint.toml").write_text('[[models]]\npath = "p/urdf/ur.urdf.xacro"\n'
                                         'args = [{ur_type = "ur5"}, {ur_type = "ur10"}]\n')
    git(repo, "init", "-q")
    _commit(repo, "base")
    (pkg / "README.md").write_text("robots, two\n")
    doc, p = _diff_json(repo, "HEAD")
    assert doc["models"] == [] and p.returncode == 0, doc
    (pkg / "config/ur5.yaml").write_text("reach: 0.6\n")
    doc, _ = _diff_json(repo, "HEAD")
    got = [(m["model"], m["status"], m["findings_fixed"]) for m in doc["models"]]
    assert got == [("p/urdf/ur.urdf.xacro [ur_type:=ur5]", "changed", [])], doc


def test_diff_of_two_revisions_names_files_in_the_repository(tmp_path):
    """`diff BASE HEAD`: every location is relative to the repository, in text and JSON (they
    named the temporary copy, .../urdf-lint-diff-XXXX/head/robots/common/arm.xacro:4)."""
    repo = tmp_path / "repo"
    arm = f"""<?xml version="1.0"?>
<robot {X}>
  <xacro:macro name="arm">
    <joint name="j" type="fixed"><parent link="base"/><child link="tip"/><origin xyz="0 0 0.5"/></joint>
  </xacro:macro>
</robot>
"""
    top = f"""<?xml version="1.0"?>
<robot name="r" {X}>
  <xacro:include filename="../common/arm.xacro"/>
  <link name="base"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="tip"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <xacro:arm/>
</robot>
"""
    pkg = make_package(repo, "robots", {"common/arm.xacro": arm, "urdf/r.urdf.xacro": top})
    git(repo, "init", "-q")
    _commit(repo, "base")
    base = git(repo, "rev-parse", "HEAD").strip()
    (pkg / "common/arm.xacro").write_text(arm.replace('xyz="0 0 0.5"', 'xyz="0 0 0.7"'))
    _commit(repo, "head")
    doc, p = _diff_json(repo, base, "HEAD")
    (model,) = doc["models"]
    locs = [c[side]["file"] for c in model["changes"] for side in ("head", "base") if c[side]]
    assert locs and set(locs) == {"robots/common/arm.xacro"}, model
    assert "urdf-lint-diff" not in p.stdout
    for fmt in ("text", "markdown"):
        p = run_cli("diff", base, "HEAD", "--no-cache", "--format", fmt, cwd=repo)
        assert p.returncode in (0, 1) and "robots/common/arm.xacro:4" in p.stdout, p.stdout
        assert "urdf-lint-diff" not in p.stdout + p.stderr and os.sep + "tmp" not in p.stdout
