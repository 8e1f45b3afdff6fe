"""Exact xacro source locations (file:line:col + macro chain) for expanded elements."""
from __future__ import annotations

import os

import pytest

from conftest import make_package, run_main

ROBOT = """<?xml version="1.0"?>
<robot name="loc" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="arm.xacro"/>
  <xacro:include filename="$(find loc_pkg)/urdf/parts.xacro"/>
  <xacro:include filename="package://loc_pkg/urdf/extra.xacro"/>
  <link name="base"/>
  <xacro:arm prefix="left" parent="base">
    <origin xyz="0 1 0"/>
  </xacro:arm>
  <xacro:part name="p1"/>
  <xacro:extra/>
</robot>
"""
ARM = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm" params="prefix parent *origin">
    <link name="${prefix}_link"/>
    <xacro:revolute name="${prefix}_joint" parent="${parent}" child="${prefix}_link">
      <xacro:insert_block name="origin"/>
    </xacro:revolute>
  </xacro:macro>
  <xacro:macro name="revolute" params="name parent child *origin">
    <joint name="${name}" type="revolute">
      <xacro:insert_block name="origin"/>
      <parent link="${parent}"/>
      <child link="${child}"/>
      <limit lower="1" upper="-1" effort="1" velocity="1"/>
    </joint>
  </xacro:macro>
</robot>
"""
PARTS = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part" params="name">
    <link name="${name}"/>
    <joint name="${name}_joint" type="fixed"><parent link="base"/><child link="${name}"/></joint>
  </xacro:macro>
</robot>
"""
EXTRA = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="extra">
      <link name="x"/>
      <joint name="x_joint" type="fixed"><parent link="base"/><child link="x"/></joint>
  </xacro:macro>
  <link name="top_level_in_include"/>
</robot>
"""


@pytest.fixture()
def model(tmp_path):
    from urdf_lint.expansion import expand_file
    from urdf_lint.engine.model import model_from_xml
    from urdf_lint.discovery.packages import PackageResolver
    pkg = make_package(tmp_path, "loc_pkg", {"urdf/robot.urdf.xacro": ROBOT, "urdf/arm.xacro": ARM,
                                             "urdf/parts.xacro": PARTS, "urdf/extra.xacro": EXTRA})
    res = PackageResolver.build([tmp_path], extra_roots=[tmp_path])
    e = expand_file(str(pkg / "urdf/robot.urdf.xacro"), {}, res)
    assert e.error is None, e.error
    m = model_from_xml(e.entry, {}, e.xml, e.origins, e.deps, res)
    m.pkg = pkg
    return m


def where(model, el):
    o = model.origin(el)
    return (os.path.basename(o.file), o.line, o.col,
            tuple((os.path.basename(c[0]), c[1], c[2]) for c in o.chain))


def test_nested_macro_chain(model):
    j = model.joints["left_joint"]
    assert where(model, j) == ("arm.xacro", 10, 5, (("robot.urdf.xacro", 7, 3), ("arm.xacro", 5, 5)))
    assert model.origin(j).format_chain(str(model.pkg / "urdf")) == \
        "called from arm.xacro:5 < robot.urdf.xacro:7"
    assert where(model, j.find("limit")) == ("arm.xacro", 14, 7,
                                             (("robot.urdf.xacro", 7, 3), ("arm.xacro", 5, 5)))
    assert where(model, model.links["left_link"]) == ("arm.xacro", 4, 5, (("robot.urdf.xacro", 7, 3),))


def test_insert_block_keeps_the_callers_line(model):
    origin = model.joints["left_joint"].find("origin")
    assert origin.get("xyz") == "0 1 0"
    assert where(model, origin) == ("robot.urdf.xacro", 8, 5, ())


def test_find_and_package_includes(model):
    assert where(model, model.links["p1"]) == ("parts.xacro", 3, 5, (("robot.urdf.xacro", 10, 3),))
    assert where(model, model.joints["p1_joint"]) == ("parts.xacro", 4, 5, (("robot.urdf.xacro", 10, 3),))
    assert where(model, model.links["x"]) == ("extra.xacro", 3, 7, (("robot.urdf.xacro", 11, 3),))
    assert where(model, model.links["top_level_in_include"]) == ("extra.xacro", 6, 3, ())
    assert where(model, model.links["base"]) == ("robot.urdf.xacro", 6, 3, ())
    deps = [os.path.basename(d) for d in model.deps]
    assert deps == ["robot.urdf.xacro", "arm.xacro", "parts.xacro", "extra.xacro"]


def test_cli_reports_macro_line_and_chain(model):
    p = run_main("check", model.pkg, "--select", "UL302", "--no-cache", cwd=model.pkg)
    assert p.returncode == 1
    lines = p.stdout.splitlines()
    assert lines[0] == ("urdf/arm.xacro:14:7: UL302 joint 'left_joint': lower 1 > upper -1 "
                        "(swap them?) [limit-order]")
    assert lines[1].strip() == "called from urdf/arm.xacro:5 < urdf/robot.urdf.xacro:7"


def test_plain_urdf_lines_and_columns(tmp_path):
    from urdf_lint.engine.model import parse_urdf_bytes
    data = b'<robot name="r">\n  <link name="a"/>\n    <joint name="j" type="fixed"/>\n</robot>\n'
    root, origins, err = parse_urdf_bytes("/x.urdf", data)
    assert err is None
    assert origins[root.find("link")][1:3] == (2, 3)
    assert origins[root.find("joint")][1:3] == (3, 5)
