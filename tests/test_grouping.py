"""Issue 24: a finding is identified by its source location and rule (the elements, models and
values behind it listed under it), a root cause is one finding with its consequences folded
under it, and a value read from YAML carries the YAML line as a second location."""
from __future__ import annotations

import json

import pytest

from conftest import make_package, run_main

LIMITS_YAML = "# limits\nfinger:\n  lower: 1.5\n  upper: -1.5\n"

INERTIA = 'ixy="0" ixz="0" iyz="0"'
HAND = """<?xml version="1.0"?>
<robot name="hand" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="lim" value="${load_yaml('joint_limits.yaml')}"/>
  <link name="base"/>
  <joint name="base_joint" type="fixed"><parent link="base"/><child link="palm"/></joint>
  <link name="palm">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" {I}/></inertial></link>
  <xacro:macro name="finger" params="n">
    <link name="finger_${n}">
      <inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" {I}/></inertial>
      <visual><geometry><mesh filename="package://ghost_meshes/finger.stl"/></geometry></visual>
    </link>
    <joint name="finger_${n}_joint" type="revolute"><parent link="palm"/><child link="finger_${n}"/>
      <axis xyz="0 1 0"/>
      <limit lower="${lim['finger']['lower']}" upper="${lim['finger']['upper']}"
             effort="1" velocity="1"/></joint>
  </xacro:macro>
  <xacro:finger n="1"/>
  <xacro:finger n="2"/>
  <xacro:finger n="3"/>
  <xacro:finger n="4"/>
  <xacro:finger n="5"/>
  <link name="cover"><visual><geometry>
    <mesh filename="package://ghost_meshes/cover.stl"/></geometry></visual></link>
  <joint name="cover_joint" type="fixed"><parent link="palm"/><child link="cover"/></joint>
</robot>
""".replace("{I}", INERTIA)
LIMIT_LINE = 15          # the <limit> line inside the macro
FINGER_MESH_LINE = 11
COVER_MESH_LINE = 24


@pytest.fixture(scope="module")
def hand(tmp_path_factory):
    return make_package(tmp_path_factory.mktemp("grouping"), "hand",
                        {"urdf/hand.urdf.xacro": HAND, "urdf/joint_limits.yaml": LIMITS_YAML})


def check(pkg, *args):
    return run_main("check", ".", "--no-cache", "--isolated", *args, cwd=pkg)


def test_one_finding_per_source_line_with_its_elements_listed(hand):
    doc = json.loads(check(hand, "--format", "json").stdout)
    limits = [f for f in doc["findings"] if f["code"] == "UL302"]
    assert len(limits) == 1, limits
    (f,) = limits
    assert (f["file"], f["line"]) == ("urdf/hand.urdf.xacro", LIMIT_LINE)
    assert f["count"] == 5
    assert [i["target"] for i in f["instances"]] == [["joint", f"finger_{n}_joint"]
                                                      for n in range(1, 6)]
    assert doc["summary"]["errors"] == sum(1 for x in doc["findings"] if x["severity"] == "error")
    text = check(hand).stdout
    assert ("in 5 joints: finger_1_joint, finger_2_joint, finger_3_joint, ... (+2)"
            in text), text
    assert text.count(f"urdf/hand.urdf.xacro:{LIMIT_LINE}:") == 1


def test_github_and_sarif_count_source_locations(hand):
    gh = check(hand, "--format", "github").stdout
    assert gh.count(f"line={LIMIT_LINE},") == 1, gh
    sarif = json.loads(check(hand, "--format", "sarif").stdout)
    results = sarif["runs"][0]["results"]
    (res,) = [r for r in results if r["ruleId"] == "UL302"]
    assert res["properties"]["count"] == 5
    assert len(res["properties"]["instances"]) == 5


def test_unknown_package_is_one_root_cause_with_its_references(hand):
    doc = json.loads(check(hand, "--format", "json").stdout)
    assert not [f for f in doc["findings"] if f["code"] == "UL401"]
    (f,) = [f for f in doc["findings"] if f["code"] == "UL004"]
    assert "unknown package 'ghost_meshes'" in f["message"]
    assert f["count"] == 2          # the fingers' macro line and the cover's line
    assert {(i["line"], i["detail"]) for i in f["instances"]} == {
        (FINGER_MESH_LINE, "mesh 'package://ghost_meshes/finger.stl'"),
        (COVER_MESH_LINE, "mesh 'package://ghost_meshes/cover.stl'")}
    sarif = json.loads(check(hand, "--format", "sarif").stdout)
    (res,) = [r for r in sarif["runs"][0]["results"] if r["ruleId"] == "UL004"]
    assert any(r["physicalLocation"]["region"]["startLine"] == COVER_MESH_LINE
               for r in res["relatedLocations"])
    assert "in 2 places:" in check(hand).stdout


def test_value_from_yaml_is_a_second_location(hand):
    text = check(hand).stdout
    block = text.split(f"urdf/hand.urdf.xacro:{LIMIT_LINE}:")[1].split("\nurdf/")[0]
    assert "value from urdf/joint_limits.yaml:3" in block, text
    doc = json.loads(check(hand, "--format", "json").stdout)
    (f,) = [f for f in doc["findings"] if f["code"] == "UL302"]
    assert f["value_from"][:2] == ["urdf/joint_limits.yaml", 3]
    sarif = json.loads(check(hand, "--format", "sarif").stdout)
    (res,) = [r for r in sarif["runs"][0]["results"] if r["ruleId"] == "UL302"]
    assert any(r["message"]["text"] == "value from here"
               and r["physicalLocation"]["artifactLocation"]["uri"] == "urdf/joint_limits.yaml"
               and r["physicalLocation"]["region"]["startLine"] == 3
               for r in res["relatedLocations"])
    # the fix of all five goes to the YAML scalars, once
    d = check(hand, "--diff").stdout
    assert "-  lower: 1.5\n-  upper: -1.5\n+  lower: -1.5\n+  upper: 1.5" in d, d


def test_refused_fix_reason_is_in_text(tmp_path):
    src = HAND.replace("${lim['finger']['lower']}", "${lim['finger']['lower'] * 1}")
    pkg = make_package(tmp_path, "refused", {"urdf/hand.urdf.xacro": src,
                                            "urdf/joint_limits.yaml": LIMITS_YAML})
    text = check(pkg).stdout
    assert (f"not fixable automatically: the value comes from the expression at "
            f"urdf/hand.urdf.xacro:{LIMIT_LINE}") in text, text


def test_diff_shows_the_yaml_line_that_changed(tmp_path):
    import subprocess

    def git(*a):
        subprocess.run(["git", *a], cwd=pkg, check=True, capture_output=True)
    good = LIMITS_YAML.replace("lower: 1.5", "lower: -1.5").replace("upper: -1.5", "upper: 1.5")
    pkg = make_package(tmp_path, "hand", {"urdf/hand.urdf.xacro": HAND,
                                          "urdf/joint_limits.yaml": good})
    git("init", "-q")
    git("add", "-A")
    git("-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "base")
    (pkg / "urdf/joint_limits.yaml").write_text(good.replace("upper: 1.5", "upper: 1.2"))
    doc = json.loads(run_main("diff", "HEAD", "--format", "json", "--no-cache", cwd=pkg).stdout)
    changes = [c for m in doc["models"] for c in m["changes"] if c["field"] == "limit.upper"]
    assert len(changes) == 5, doc
    assert all(c["value_from"][:2] == ["urdf/joint_limits.yaml", 4] for c in changes), changes
    assert all(c["head"]["line"] == LIMIT_LINE for c in changes)
    text = run_main("diff", "HEAD", "--no-cache", cwd=pkg).stdout
    assert "value from urdf/joint_limits.yaml:4" in text, text


def test_two_problems_of_one_rule_on_one_element_stay_two(tmp_path):
    """Grouping merges the same problem on many elements, not two problems a rule finds on
    one element (effort=0 is a warning, velocity=0 an error: UL304 at one <limit>)."""
    src = HAND.replace('effort="1" velocity="1"', 'effort="0" velocity="0"')
    pkg = make_package(tmp_path, "zeros", {"urdf/hand.urdf.xacro": src,
                                          "urdf/joint_limits.yaml": LIMITS_YAML})
    doc = json.loads(check(pkg, "--format", "json").stdout)
    limits = [f for f in doc["findings"] if f["code"] == "UL304"]
    # (both warnings since velocity=0 loads everywhere, issue 25; still two findings)
    assert len(limits) == 2, limits
    assert sorted("effort=0" in f["message"] for f in limits) == [False, True], limits
    assert sorted("velocity=0" in f["message"] for f in limits) == [False, True], limits
    assert sorted(f["severity"] for f in limits) == ["warning", "warning"], limits
    assert all(f["count"] == 5 for f in limits)


ARM = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm" params="prefix parent">
    <link name="${prefix}link"/>
    <joint name="${prefix}joint" type="revolute">
      <parent link="${parent}"/>
      <child link="${prefix}link"/>
      <axis xyz="0 0 1"/>
      <limit lower="1" upper="-1" effort="1" velocity="1"/>
    </joint>
  </xacro:macro>
</robot>
"""
ONE_ARM = """<?xml version="1.0"?>
<robot name="one" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="arm.xacro"/>
  <link name="base"/>
  <xacro:arm prefix="h_" parent="base"/>
</robot>
"""
TWO_ARMS = ONE_ARM.replace('name="one"', 'name="two"').replace(
    '<xacro:arm prefix="h_" parent="base"/>',
    '<xacro:arm prefix="l_" parent="base"/>\n  <xacro:arm prefix="r_" parent="base"/>')


def test_every_command_counts_one_tree_alike(tmp_path):
    """One swapped limit in a macro that two models call three times, and a missing inertial
    beside it: two findings (one error, one warning) of six instances. check, the hook's
    summary, --write-baseline and --fix count the same findings, the instances in parentheses
    (they said 2, '3 error(s), 3 warning(s)', 6 and 'Fixed 3 (3 remaining)')."""
    import subprocess
    (tmp_path / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="3"><name>arms</name><version>0.0.1</version>'
        '<description>x</description><maintainer email="a@b.c">a</maintainer>'
        "<license>MIT</license></package>\n")
    (tmp_path / "arm.xacro").write_text(ARM)
    (tmp_path / "one.urdf.xacro").write_text(ONE_ARM)
    (tmp_path / "two.urdf.xacro").write_text(TWO_ARMS)
    for cmd in (["init", "-q"], ["add", "-A"]):
        subprocess.run(["git", *cmd], cwd=tmp_path, check=True)
    check = run_main("check", ".", "--no-cache", cwd=tmp_path)
    assert check.stdout.splitlines()[-1] == \
        "Found 2 problem(s) (1 error, 1 warning, 0 info) in 2 model(s).", check.stdout
    hook = run_main("hook", "--no-cache", "--", "arm.xacro", cwd=tmp_path)
    assert ("2 model(s) affected by 1 file(s): 1 error(s), 1 warning(s), 0 info "
            "(2 in the committed files)") in hook.stdout + hook.stderr, hook.stdout + hook.stderr
    base = run_main("check", ".", "--no-cache", "--write-baseline", "bl.json", cwd=tmp_path)
    assert "wrote 2 finding(s) (6 instances) in 1 file(s)" in base.stdout + base.stderr
    fix = run_main("check", ".", "--no-cache", "--fix", cwd=tmp_path)
    assert "Fixed 1 finding (3 instances) in 1 file (1 remaining)." in fix.stdout + fix.stderr, \
        fix.stdout + fix.stderr
