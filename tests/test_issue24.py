"""Issue 24's false alarms, misses and bugs, each on a fixture that reproduces the pattern seen
on real description repositories."""
from __future__ import annotations

import json

from conftest import make_package, run_cli

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def check_json(pkg, *args):
    p = run_cli("check", ".", "--no-cache", "--isolated", "--format", "json", *args, cwd=pkg)
    return json.loads(p.stdout), p


def test_missing_dollar_after_a_word_character(tmp_path):
    """Item 13: `arm_{side}_link` / `caster_{side}_1_joint` in a macro with params="side" is
    UL212 (with its fix), and UL703 suggests no wrong name."""
    src = f"""<robot name="r" {X}>
  <link name="base"/>
  <xacro:macro name="caster" params="side">
    <link name="caster_${{side}}_1"/>
    <joint name="caster_${{side}}_1_joint" type="fixed">
      <parent link="base"/><child link="caster_${{side}}_1"/></joint>
    <link name="arm_{{side}}_link"/>
    <gazebo reference="caster_{{side}}_1_joint"><mu1>1</mu1></gazebo>
  </xacro:macro>
  <xacro:caster side="left"/>
  <xacro:caster side="right"/>
</robot>
"""
    pkg = make_package(tmp_path, "casters", {"urdf/r.urdf.xacro": src})
    doc, _ = check_json(pkg)
    ul212 = {f["line"]: f for f in doc["findings"] if f["code"] == "UL212"}
    assert set(ul212) == {7, 8}, doc["findings"]
    assert "'${side}'" in ul212[7]["message"] and ul212[7]["fix"]["applicability"] == "safe"
    (g,) = [f for f in doc["findings"] if f["code"] == "UL703"]
    assert "did you mean '${side}'" in g["message"] and "caster_left" not in g["message"]
    d = run_cli("check", ".", "--diff", "--no-cache", "--isolated", cwd=pkg).stdout
    assert '+    <link name="arm_${side}_link"/>' in d, d
    assert '+    <gazebo reference="caster_${side}_1_joint">' in d, d


def test_mimic_fix_is_safe_only_with_one_candidate(tmp_path):
    """Item 20: 'left_finger' is close to left_finger_joint (0.79) and to left_inner_joint
    (0.67): the right inner finger was made to mimic the left hand by a "safe" fix."""
    src = f"""<robot name="r" {X}>
  <link name="palm"/><link name="a"/><link name="b"/><link name="c"/><link name="d"/>
  <joint name="left_finger_joint" type="revolute"><parent link="palm"/><child link="a"/>
    <axis xyz="0 0 1"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>
  <joint name="left_inner_joint" type="revolute"><parent link="palm"/><child link="b"/>
    <axis xyz="0 0 1"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>
  <joint name="right_finger_joint" type="revolute"><parent link="palm"/><child link="c"/>
    <axis xyz="0 0 1"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>
  <joint name="right_inner_joint" type="revolute"><parent link="palm"/><child link="d"/>
    <axis xyz="0 0 1"/><limit lower="0" upper="1" effort="1" velocity="1"/>
    <mimic joint="left_finger"/></joint>
</robot>
"""
    pkg = make_package(tmp_path, "hand2", {"urdf/r.urdf.xacro": src})
    doc, _ = check_json(pkg, "--select", "UL308")
    (f,) = doc["findings"]
    assert "did you mean 'left_finger_joint'" in f["message"]
    assert "fix" not in f, f
    d = run_cli("check", ".", "--diff", "--no-cache", "--isolated", cwd=pkg)
    assert "left_finger_joint" not in d.stdout
