"""Patterns of real repositories nobody here wrote that gave false errors (issue 33's precision
on fresh repositories), each reproduced on a fixture written here:

- ros2_control_demos: ``$(find pkg)/ros2_control/x.xacro`` where the package's CMakeLists.txt
  installs ``description/ros2_control`` into ``share/pkg``: the file is in the source tree
  under another folder (16 false UL003 on that repository);
- jackal: an extras file (``custom_example.urdf``) with no name, no link of its own and xacro
  macro calls, included through an environment variable: not a model (18 false errors);
- kortex: an include built from an arg left empty at its default (``${dof}dof``) says which
  arg."""
from __future__ import annotations

import json

from conftest import make_package, run_main

CMAKE = """cmake_minimum_required(VERSION 3.16)
project(demo_example LANGUAGES CXX)
install(
  DIRECTORY description/ros2_control description/urdf  # the robot
  DESTINATION share/${PROJECT_NAME}
)
install(DIRECTORY description/meshes/ DESTINATION share/${PROJECT_NAME}/meshes)
install(FILES bringup/config/limits.yaml DESTINATION share/demo_example/config)
ament_package()
"""
BOT = """<?xml version="1.0"?>
<robot name="rrbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find demo_example)/ros2_control/rrbot.ros2_control.xacro"/>
  <xacro:property name="lim" value="${xacro.load_yaml('$(find demo_example)/config/limits.yaml')}"/>
  <link name="base">
    <visual><geometry><mesh filename="package://demo_example/meshes/base.stl"/></geometry></visual>
  </link>
  <link name="arm"/>
  <joint name="j" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="${lim['lower']}" upper="${lim['upper']}" effort="1" velocity="1"/>
  </joint>
  <xacro:rrbot_control name="rrbot"/>
</robot>
"""
CONTROL = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="rrbot_control" params="name">
    <ros2_control name="${name}" type="system">
      <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
      <joint name="j"><command_interface name="position"/><state_interface name="position"/></joint>
    </ros2_control>
  </xacro:macro>
</robot>
"""
STL = (b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
       b"endloop\nendfacet\nendsolid t\n")


def _lint(pkg, *args):
    p = run_main("check", ".", "--no-cache", "--output-format", "json", *args, cwd=pkg)
    assert p.returncode in (0, 1), p.stderr
    return json.loads(p.stdout)["findings"]


def _errors(findings):
    return [(f["code"], f["file"], f["message"]) for f in findings if f["severity"] == "error"]


def test_a_path_the_build_installs_from_another_folder_is_found(tmp_path):
    pkg = make_package(tmp_path, "demo_example", {
        "CMakeLists.txt": CMAKE, "description/urdf/rrbot.urdf.xacro": BOT,
        "description/ros2_control/rrbot.ros2_control.xacro": CONTROL,
        "description/meshes/base.stl": STL,
        "bringup/config/limits.yaml": "lower: -1.0\nupper: 1.0\n"})
    assert _errors(_lint(pkg)) == []
    # the source is read where it is: a broken limit names the source YAML's line
    (pkg / "bringup/config/limits.yaml").write_text("lower: 1.0\nupper: -1.0\n")
    (f,) = [f for f in _lint(pkg) if f["code"] == "UL302"]
    assert f["value_from"][:2] == ["bringup/config/limits.yaml", 1], f
    # without the install rule, the include is missing (the rule is what finds it)
    (pkg / "CMakeLists.txt").write_text(CMAKE.replace("description/ros2_control ", ""))
    codes = {c for c, _, _ in _errors(_lint(pkg))}
    assert "UL003" in codes, codes


def test_install_rules_of_a_cmakelists():
    from urdf_lint.discovery.installs import install_rules, source_of
    rules = install_rules(CMAKE, "demo_example")
    assert rules == [("description/ros2_control", "ros2_control"), ("description/urdf", "urdf"),
                     ("description/meshes", "meshes"),
                     ("bringup/config/limits.yaml", "config/limits.yaml")]
    assert source_of("ros2_control/a.xacro", rules) == ["description/ros2_control/a.xacro"]
    assert source_of("meshes/x/b.stl", rules) == ["description/meshes/x/b.stl"]
    assert source_of("config/limits.yaml", rules) == ["bringup/config/limits.yaml"]
    assert source_of("launch/x.py", rules) == []
    # another package's share, a variable, an absolute path or a climb: not mapped
    assert install_rules("install(DIRECTORY urdf DESTINATION share/other)\n"
                         "install(DIRECTORY ${X}/urdf /abs ../up DESTINATION share/p)", "p") == []


EXTRAS = """<robot>
  <!-- included from robot.urdf.xacro when ROBOT_URDF_EXTRAS names this file -->
  <xacro:camera_mount prefix="front"/>
  <joint name="front_camera_joint" type="fixed">
    <parent link="front_mount"/><child link="front_camera"/>
  </joint>
</robot>
"""
ROBOT = """<?xml version="1.0"?>
<robot name="rover" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base"/>
  <xacro:include filename="$(optenv ROBOT_URDF_EXTRAS empty.urdf)"/>
</robot>
"""


def test_an_extras_file_of_xacro_calls_is_no_model(tmp_path, monkeypatch):
    monkeypatch.delenv("ROBOT_URDF_EXTRAS", raising=False)
    pkg = make_package(tmp_path, "rover_description", {
        "urdf/robot.urdf.xacro": ROBOT, "urdf/empty.urdf": "<robot/>\n",
        "urdf/custom_example.urdf": EXTRAS})
    assert _errors(_lint(pkg)) == []
    # a nameless robot with links of its own is still a (broken) model
    (pkg / "urdf/custom_example.urdf").write_text(EXTRAS.replace(
        "<robot>", '<robot>\n  <link name="front_mount"/>'))
    assert "UL201" in {c for c, _, _ in _errors(_lint(pkg))}


KORTEX = """<?xml version="1.0"?>
<robot name="gen3" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="arm" default="gen3"/>
  <xacro:arg name="dof" default=""/>
  <xacro:include filename="$(find arm_description)/arms/$(arg arm)/$(arg dof)dof/urdf/macro.xacro"/>
  <link name="base"/>
</robot>
"""


def test_an_include_built_from_an_empty_arg_names_it(tmp_path):
    pkg = make_package(tmp_path, "arm_description", {
        "robots/gen3.xacro": KORTEX, "arms/gen3/7dof/urdf/macro.xacro": "<robot/>\n"})
    (f,) = [f for f in _lint(pkg) if f["code"] == "UL003"]
    assert "args left empty: dof;" in f["message"], f["message"]


HAND = """<?xml version="1.0"?>
<robot name="hand">
  <link name="palm">
    <visual><geometry><mesh filename="meshes/palm.STL"/></geometry></visual>
  </link>
</robot>
"""


def test_a_relative_mesh_found_a_folder_up_says_where(tmp_path):
    """unitree's hand URDFs write ``meshes/x.STL`` in a folder below the package's meshes: the
    error stays (relative to the URDF there is no file) and says where the file is and which
    key decides."""
    pkg = make_package(tmp_path, "g1_description", {
        "hands/hand.urdf": HAND, "meshes/palm.STL": STL})
    (f,) = [f for f in _lint(pkg) if f["code"] == "UL401"]
    assert "a file of that name is at meshes/palm.STL" in f["message"], f["message"]
    assert "set mesh-base" in f["message"] and f["severity"] == "error"
