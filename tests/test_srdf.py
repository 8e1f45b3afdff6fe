"""A robot's configuration checked against it (UL710-UL799): the SRDF, the controller YAML and
MoveIt's YAML files tied to the model, each mismatch reported at its own SRDF/YAML line with the
robot element's xacro line as related location. One clean package; each test plants one
mismatch in a copy of it."""
from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import pytest

from conftest import make_package

XACRO = """<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="segment" params="n parent">
    <link name="link${n}"/>
    <joint name="joint${n}" type="revolute">
      <parent link="${parent}"/><child link="link${n}"/>
      <axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="10" velocity="1"/>
    </joint>
  </xacro:macro>
  <link name="base_link"/>
  <xacro:segment n="1" parent="base_link"/>
  <xacro:segment n="2" parent="link1"/>
  <link name="finger_a"/><link name="finger_b"/>
  <joint name="finger_a_joint" type="prismatic"><parent link="link2"/><child link="finger_a"/>
    <axis xyz="0 1 0"/><limit lower="0" upper="0.04" effort="5" velocity="0.1"/></joint>
  <joint name="finger_b_joint" type="prismatic"><parent link="link2"/><child link="finger_b"/>
    <axis xyz="0 -1 0"/><limit lower="0" upper="0.04" effort="5" velocity="0.1"/>
    <mimic joint="finger_a_joint"/></joint>
  <ros2_control name="sys" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="position"/>
      <state_interface name="position"><param name="initial_value">0.0</param></state_interface></joint>
    <joint name="joint2"><command_interface name="position"/><state_interface name="position"/></joint>
    <joint name="finger_a_joint"><command_interface name="position"/>
      <state_interface name="position"/></joint>
  </ros2_control>
</robot>
"""
SRDF = """<robot name="arm">
  <virtual_joint name="world_joint" type="fixed" parent_frame="world" child_link="base_link"/>
  <group name="arm">
    <chain base_link="base_link" tip_link="link2"/>
  </group>
  <group name="hand">
    <joint name="finger_a_joint"/>
  </group>
  <group_state name="home" group="arm">
    <joint name="joint1" value="0"/>
    <joint name="joint2" value="1"/>
  </group_state>
  <end_effector name="gripper" parent_link="link2" group="hand" parent_group="arm"/>
  <passive_joint name="finger_b_joint"/>
  <disable_collisions link1="base_link" link2="link1" reason="Adjacent"/>
</robot>
"""
CONTROLLERS = """controller_manager:
  ros__parameters:
    arm_controller:
      type: joint_trajectory_controller/JointTrajectoryController
    hand_controller:
      type: position_controllers/GripperActionController

arm_controller:
  ros__parameters:
    joints: [joint1, joint2]
    command_interfaces: [position]
    state_interfaces: [position]

hand_controller:
  ros__parameters:
    joint: finger_a_joint
"""
LIMITS = """joint_limits:
  joint1:
    has_velocity_limits: true
    max_velocity: 1.0
    has_acceleration_limits: true
    max_acceleration: 2.0
  joint2:
    has_velocity_limits: true
    max_velocity: 0.5
    has_acceleration_limits: true
    max_acceleration: 2.0
  finger_a_joint:
    has_acceleration_limits: true
    max_acceleration: 1.0
"""
MOVEIT_CONTROLLERS = """moveit_simple_controller_manager:
  controller_names: [arm_controller, hand_controller]
  arm_controller:
    type: FollowJointTrajectory
    joints: [joint1, joint2]
  hand_controller:
    type: GripperCommand
    joints: [finger_a_joint]
"""
KINEMATICS = """arm:
  kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin
"""
INITIAL = """initial_positions:
  joint1: 0.0
  joint2: 0.5
"""
FILES = {"urdf/arm.urdf.xacro": XACRO, "config/arm.srdf": SRDF,
         "config/ros2_controllers.yaml": CONTROLLERS, "config/joint_limits.yaml": LIMITS,
         "config/kinematics.yaml": KINEMATICS, "config/initial_positions.yaml": INITIAL,
         "config/moveit_controllers.yaml": MOVEIT_CONTROLLERS}
CODES = ["UL710", "UL711", "UL712", "UL713", "UL714", "UL715", "UL750", "UL751", "UL752", "UL753",
         "UL754", "UL755", "UL760", "UL761", "UL762", "UL799"]


def line_of(text: str, needle: str) -> int:
    return next(i for i, t in enumerate(text.splitlines(), 1) if needle in t)


X = {"joint2": line_of(XACRO, 'joint name="joint${n}"'), "link1": line_of(XACRO, 'link name="link${n}"'),
     "limit": line_of(XACRO, "<limit lower=\"-2\""), "robot": line_of(XACRO, "<robot "),
     "rc_joint1": line_of(XACRO, '<joint name="joint1">'),
     "finger_a": line_of(XACRO, 'joint name="finger_a_joint"'),
     "finger_b": line_of(XACRO, 'mimic joint')}

# (file, text, its replacement) -> [(code, file, the line holding `at`, related xacro line)]
PLANTED = {
    "group joint renamed": ("config/arm.srdf", '<joint name="finger_a_joint"/>',
                            '<joint name="finger_a_jnt"/>',
                            [("UL751", "config/arm.srdf", "finger_a_jnt", X["finger_a"])]),
    "stale collision pair": ("config/arm.srdf", 'link2="link1"', 'link2="link_1"',
                             [("UL752", "config/arm.srdf", "link_1", X["link1"])]),
    "tip above base": ("config/arm.srdf", 'base_link="base_link" tip_link="link2"',
                       'base_link="link2" tip_link="base_link"',
                       [("UL753", "config/arm.srdf", 'tip_link="base_link"',
                         line_of(XACRO, '<link name="base_link"'))]),
    "group state outside limits": ("config/arm.srdf", 'name="joint2" value="1"', 'name="joint2" value="2.5"',
                                   [("UL754", "config/arm.srdf", 'value="2.5"', X["limit"])]),
    "unknown link": ("config/arm.srdf", 'parent_link="link2"', 'parent_link="tool0"',
                     [("UL750", "config/arm.srdf", "tool0", X["robot"])]),
    "unknown group": ("config/arm.srdf", 'group="arm">', 'group="manipulator">',
                      [("UL755", "config/arm.srdf", "manipulator", X["robot"])]),
    "kinematics group": ("config/kinematics.yaml", "arm:", "arms:",
                         [("UL755", "config/kinematics.yaml", "arms:", X["robot"])]),
    "controller joint unknown": ("config/ros2_controllers.yaml", "[joint1, joint2]", "[joint1, joint_2]",
                                 [("UL710", "config/ros2_controllers.yaml", "joint_2", X["joint2"])]),
    "controller joint not in ros2_control": (
        "urdf/arm.urdf.xacro", '<joint name="joint2"><command_interface name="position"/>'
        '<state_interface name="position"/></joint>', "",
        [("UL711", "config/ros2_controllers.yaml", "[joint1, joint2]", X["joint2"])]),
    "missing command interface": (
        "urdf/arm.urdf.xacro", '<joint name="joint1"><command_interface name="position"/>',
        '<joint name="joint1"><command_interface name="velocity"/>',
        [("UL711", "config/ros2_controllers.yaml", "[joint1, joint2]", X["rc_joint1"])]),
    "commanded mimic joint": ("config/ros2_controllers.yaml", "joint: finger_a_joint",
                              "joint: finger_b_joint",
                              [("UL712", "config/ros2_controllers.yaml", "finger_b_joint", X["finger_b"]),
                               ("UL711", "config/ros2_controllers.yaml", "finger_b_joint",
                                line_of(XACRO, 'joint name="finger_b_joint"'))]),
    "max_velocity above the URDF's": ("config/joint_limits.yaml", "max_velocity: 0.5", "max_velocity: 1.5",
                                      [("UL761", "config/joint_limits.yaml", "max_velocity: 1.5",
                                        X["limit"])]),
    "initial position outside limits": ("config/initial_positions.yaml", "joint2: 0.5", "joint2: 2.5",
                                        [("UL713", "config/initial_positions.yaml", "joint2: 2.5",
                                          X["limit"])]),
    "initial_value outside limits": ("urdf/arm.urdf.xacro", "<param name=\"initial_value\">0.0<",
                                     "<param name=\"initial_value\">3.0<",
                                     [("UL713", "urdf/arm.urdf.xacro", "initial_value\">3.0", None)]),
    "joint_limits names no joint": ("config/joint_limits.yaml", "  finger_a_joint:", "  finger_a_jnt:",
                                    [("UL760", "config/joint_limits.yaml", "finger_a_jnt:", X["finger_a"]),
                                     ("UL762", "config/joint_limits.yaml", "joint_limits:", X["finger_a"])]),
    "missing acceleration limit": ("config/joint_limits.yaml",
                                   "max_velocity: 0.5\n    has_acceleration_limits: true",
                                   "max_velocity: 0.5\n    has_acceleration_limits: false",
                                   [("UL762", "config/joint_limits.yaml", "  joint2:", X["joint2"])]),
    "launch substitution": ("config/ros2_controllers.yaml", "[joint1, joint2]",
                            "[joint1, $(var prefix)joint2]",
                            [("UL714", "config/ros2_controllers.yaml", "$(var prefix)", None)]),
    "group no controller drives": ("config/moveit_controllers.yaml", "joints: [joint1, joint2]",
                                   "joints: [joint1]",
                                   [("UL715", "config/arm.srdf", '<group name="arm">', X["joint2"])]),
    "moveit controller joint unknown": ("config/moveit_controllers.yaml", "joints: [joint1, joint2]",
                                        "joints: [joint1, joint2, joint3]",
                                        [("UL710", "config/moveit_controllers.yaml", "joint3", X["joint2"])]),
    "unreadable YAML": ("config/ros2_controllers.yaml", "joint: finger_a_joint", "joint: [finger_a_joint",
                        [("UL799", "config/ros2_controllers.yaml", None, None)]),
}


def lint(pkg: Path, monkeypatch, paths=(".",), config=None):
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import RunRequest, run_check
    monkeypatch.chdir(pkg)
    cfg = load_config(config)
    cfg.select = list(CODES)
    res = run_check(RunRequest(list(paths), cfg, build_resolver(list(paths), cfg), in_process=True))
    assert not res.internal, res.internal
    return res.findings


def rel(f, pkg):
    return os.path.relpath(f.file, pkg)


def test_the_clean_package_has_no_finding(tmp_path, monkeypatch):
    """Every file is tied to the model by the package convention, and all agree with it."""
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver, discover_models
    pkg = make_package(tmp_path, "arm_config", FILES)
    assert lint(pkg, monkeypatch) == []
    cfg = load_config(None)
    (job,) = discover_models(["."], cfg, build_resolver(["."], cfg)).jobs
    assert sorted((k, os.path.relpath(p, pkg), how) for k, p, how in job.configs) == [
        ("controllers", "config/ros2_controllers.yaml", "package"),
        ("initial-positions", "config/initial_positions.yaml", "package"),
        ("joint-limits", "config/joint_limits.yaml", "package"),
        ("kinematics", "config/kinematics.yaml", "package"),
        ("moveit-controllers", "config/moveit_controllers.yaml", "package"),
        ("srdf", "config/arm.srdf", "package")]


@pytest.mark.parametrize("case", sorted(PLANTED))
def test_each_planted_mismatch_at_its_line_with_the_xacro_line(tmp_path, monkeypatch, case):
    file, old, new, want = PLANTED[case]
    files = dict(FILES)
    assert old in files[file], case
    files[file] = files[file].replace(old, new, 1)
    pkg = make_package(tmp_path, "arm_config", files)
    got = sorted((f.code, rel(f, pkg), f.line,
                  f.related[1] if f.related else None,
                  os.path.relpath(f.related[0], pkg) if f.related else None)
                 for f in lint(pkg, monkeypatch))
    expected = sorted((code, where, line_of(files[where], at) if at else got[0][2], xline,
                       "urdf/arm.urdf.xacro" if xline else None)
                      for code, where, at, xline in want)
    assert got == expected


def test_every_output_format_shows_the_related_xacro_line(tmp_path, monkeypatch, capsys):
    from urdf_lint.cli.main import main
    files = dict(FILES)
    files["config/ros2_controllers.yaml"] = CONTROLLERS.replace("[joint1, joint2]", "[joint1, joint_2]")
    pkg = make_package(tmp_path, "arm_config", files)
    monkeypatch.chdir(pkg)
    at = f"urdf/arm.urdf.xacro:{X['joint2']}"
    for fmt, check in (("text", lambda o: f"robot element at {at}" in o),
                       ("concise", lambda o: f"robot element at {at}" in o),
                       ("github", lambda o: f"robot element at {at}" in o),
                       ("junit", lambda o: f"robot element at {at}" in o)):
        assert main(["check", ".", "--no-cache", "--select", "UL710", "--output-format", fmt]) == 1
        out = capsys.readouterr().out
        assert "config/ros2_controllers.yaml" in out and check(out), (fmt, out)
    main(["check", ".", "--no-cache", "--select", "UL710", "--output-format", "json"])
    (f,) = json.loads(capsys.readouterr().out)["findings"]
    assert (f["file"], f["line"], f["related"]) == (
        "config/ros2_controllers.yaml", 10, ["urdf/arm.urdf.xacro", X["joint2"], 5])
    main(["check", ".", "--no-cache", "--select", "UL710", "--output-format", "sarif"])
    res = json.loads(capsys.readouterr().out)["runs"][0]["results"][0]
    assert res["locations"][0]["physicalLocation"]["artifactLocation"]["uri"].endswith(
        "config/ros2_controllers.yaml")
    rl = [r for r in res["relatedLocations"] if r["message"]["text"] == "robot element here"]
    assert rl and rl[0]["physicalLocation"]["region"]["startLine"] == X["joint2"]


def test_a_changed_yaml_alone_lints_the_robot_it_configures(tmp_path, monkeypatch, capsys):
    """`check FILE` (what the pre-commit hook does with the commit's files): a YAML or SRDF
    file that is no model lints the models it configures, and its findings are shown."""
    from urdf_lint.cli.main import main
    files = dict(FILES)
    files["config/arm.srdf"] = SRDF.replace('link2="link1"', 'link2="link_1"')
    pkg = make_package(tmp_path, "arm_config", files)
    monkeypatch.chdir(pkg)
    rc = main(["check", "--no-cache", "--select", ",".join(CODES), "--output-format", "concise",
               "config/arm.srdf"])
    out = capsys.readouterr().out
    assert rc == 0 and f"config/arm.srdf:{line_of(files['config/arm.srdf'], 'link_1')}:3: UL752" in out, out


def test_setup_assistant_and_explicit_keys_tie_configs_elsewhere(tmp_path, monkeypatch):
    """A MoveIt package's .setup_assistant names the description's URDF (another package):
    its SRDF and config files are checked against that model; a [[models]] entry's srdf,
    controllers and joint-limits keys tie files anywhere in the repository."""
    desc = make_package(tmp_path, "arm_description", {"urdf/arm.urdf.xacro": XACRO})
    moveit = make_package(tmp_path, "arm_moveit_config", {
        ".setup_assistant": "moveit_setup_assistant_config:\n  URDF:\n    package: arm_description\n"
                            "    relative_path: urdf/arm.urdf.xacro\n  SRDF:\n"
                            "    relative_path: config/semantic.srdf\n",
        "config/semantic.srdf": SRDF.replace('link2="link1"', 'link2="link_1"'),
        "config/joint_limits.yaml": LIMITS.replace("max_velocity: 0.5", "max_velocity: 1.5")})
    got = sorted((f.code, rel(f, tmp_path)) for f in lint(tmp_path, monkeypatch))
    assert got == [("UL752", "arm_moveit_config/config/semantic.srdf"),
                   ("UL761", "arm_moveit_config/config/joint_limits.yaml")]
    shutil.rmtree(moveit)
    other = tmp_path / "elsewhere"
    other.mkdir()
    (other / "my.srdf").write_text(SRDF.replace('name="arm"', 'name="not_the_name"', 1)
                                   .replace('link2="link1"', 'link2="link_1"'))
    (other / "ctl.yaml").write_text(CONTROLLERS.replace("[joint1, joint2]", "[joint1, joint_2]"))
    (tmp_path / "urdf-lint.toml").write_text(
        '[[models]]\npath = "arm_description/urdf/arm.urdf.xacro"\nsrdf = "elsewhere/my.srdf"\n'
        'controllers = ["elsewhere/ctl.yaml"]\n')
    got = sorted((f.code, rel(f, tmp_path)) for f in lint(
        tmp_path, monkeypatch, config=tmp_path / "urdf-lint.toml"))
    assert got == [("UL710", "elsewhere/ctl.yaml"), ("UL752", "elsewhere/my.srdf")]
    assert desc.is_dir()


def test_an_srdf_of_another_robot_and_another_robots_controllers_are_left_alone(tmp_path, monkeypatch):
    """By the package convention, an SRDF is checked only against the robot it names, and a
    controller YAML beside several models only against those it names a joint of."""
    files = dict(FILES)
    files["config/other.srdf"] = SRDF.replace('name="arm"', 'name="other"', 1).replace(
        "link1", "elsewhere_link")
    files["urdf/gripper.urdf"] = '<robot name="gripper"><link name="g"/></robot>\n'
    files["config/gripper_controllers.yaml"] = CONTROLLERS.replace("joint1", "g_joint").replace(
        "joint2", "g_joint2").replace("finger_a_joint", "g_finger")
    files["config/arm.srdf"] = SRDF.replace('link2="link1"', 'link2="link_1"')
    pkg = make_package(tmp_path, "arm_config", files)
    got = [(f.code, rel(f, pkg), f.models) for f in lint(pkg, monkeypatch)]
    assert got == [("UL752", "config/arm.srdf", ("urdf/arm.urdf.xacro",))]


def _ros_configs():
    from conftest import SHARED
    return SHARED / "ros-configs" / "moveit_resources"


@pytest.mark.skipif(not (_ros_configs() / "panda_moveit_config").is_dir(),
                    reason="../shared/ros-configs is not present")
def test_real_moveit_packages_are_clean_and_a_rename_reaches_every_line(tmp_path, monkeypatch):
    """moveit_resources' real configuration packages: no error, two warnings (an upstream
    defect: the dual-arm SRDF's end effectors name groups it never defines). A joint and a link
    renamed in panda's xacro: every SRDF, YAML and ros2_control line naming them is reported."""
    import re
    src = tmp_path / "ws"
    shutil.copytree(_ros_configs(), src / "moveit_resources")
    codes = CODES + ["UL702"]

    def findings():
        monkeypatch.chdir(src)
        from urdf_lint.config.schema import load_config
        from urdf_lint.discovery.discover import build_resolver
        from urdf_lint.run.pipeline import RunRequest, run_check
        cfg = load_config(None)
        cfg.select = codes
        res = run_check(RunRequest(["."], cfg, build_resolver(["."], cfg), in_process=True))
        return res.findings
    clean = findings()
    assert sorted((f.code, f.severity, os.path.basename(f.file), f.line) for f in clean) == [
        ("UL755", "warning", "panda.srdf", 42), ("UL755", "warning", "panda.srdf", 43)]
    xacro = src / "moveit_resources" / "panda_description" / "urdf" / "panda.urdf.xacro"
    xacro.write_text(xacro.read_text().replace('"panda_joint3"', '"panda_joint_3"')
                     .replace('"panda_link4"', '"panda_link4_renamed"'))
    config = src / "moveit_resources" / "panda_moveit_config" / "config"
    naming = {(str(f), i) for f in config.iterdir() if f.name != "initial_positions.yaml"
              for i, t in enumerate(f.read_text().splitlines(), 1)
              if re.search(r"\bpanda_(joint3|link4)\b", t) and "initial_positions[" not in t}
    got = findings()
    reported = {(os.path.realpath(f.file), f.line) for f in got if f not in clean}
    assert len(naming) == 32
    assert {(os.path.realpath(f), i) for f, i in naming} <= reported


@pytest.mark.skipif(shutil.which("git") is None, reason="needs git")
def test_the_hook_on_a_commit_changing_only_an_srdf(tmp_path):
    """pre-commit passes only the changed SRDF: the hook lints the robot it configures and
    shows the SRDF's finding at its line."""
    import subprocess
    from conftest import run_cli
    pkg = make_package(tmp_path, "arm_config", FILES)
    for cmd in (["init", "-q"], ["add", "-A"],
                ["-c", "user.email=t@t", "-c", "user.name=t", "commit", "-qm", "init"]):
        subprocess.run(["git", *cmd], cwd=pkg, check=True)
    srdf = pkg / "config" / "arm.srdf"
    srdf.write_text(SRDF.replace('link2="link1"', 'link2="link_1"'))
    p = run_cli("hook", "--select", ",".join(CODES), "--", "config/arm.srdf", cwd=pkg)
    line = line_of(srdf.read_text(), "link_1")
    assert f"config/arm.srdf:{line}:3: UL752" in p.stdout, p.stdout + p.stderr
    assert f"robot element at urdf/arm.urdf.xacro:{X['link1']}" in p.stdout


def test_unsafe_fix_renames_a_link_renamed_in_the_xacro(tmp_path, monkeypatch, capsys):
    """A link renamed in the xacro: `--fix --unsafe-fixes` renames its stale uses in the SRDF
    (the one close name the SRDF does not name yet), verified by re-linting; without
    --unsafe-fixes nothing is written."""
    from urdf_lint.cli.main import main
    files = dict(FILES)
    files["urdf/arm.urdf.xacro"] = XACRO.replace('"base_link"', '"base_link0"')
    pkg = make_package(tmp_path, "arm_config", files)
    monkeypatch.chdir(pkg)
    srdf = pkg / "config" / "arm.srdf"
    sel = ["--no-cache", "--select", ",".join(CODES)]
    assert main(["check", ".", *sel, "--fix"]) == 1
    assert srdf.read_text() == SRDF
    main(["check", ".", *sel, "--fix", "--unsafe-fixes"])
    capsys.readouterr()
    assert srdf.read_text() == SRDF.replace('"base_link"', '"base_link0"')
    assert main(["check", ".", *sel]) == 0, capsys.readouterr().out
