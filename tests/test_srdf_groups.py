"""The rest of a robot's configuration checked against it: a Gazebo-simulated `<ros2_control>`
sensor against the robot's Gazebo sensors (UL716), MoveIt controllers against the SRDF groups
they serve (UL717), the SRDF's virtual joint (UL756), `disable_collisions` pairs MoveIt never
uses (UL757), and the virtual joint as a group joint (UL751 leaves it alone). Each mismatch is
planted once in a copy of tests/test_srdf.py's clean package and found at its own line, with
the robot element (or the SRDF group) as related location."""
from __future__ import annotations

import os
from pathlib import Path

from conftest import make_package
from test_srdf import FILES, MOVEIT_CONTROLLERS, SRDF, XACRO, line_of

CODES = ["UL716", "UL717", "UL751", "UL756", "UL757"]
COLLISION = '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
# the clean package with collision geometry on every link (else its Adjacent pair is UL757's)
SOLID = (XACRO.replace('<link name="link${n}"/>', f'<link name="link${{n}}">{COLLISION}</link>')
         .replace('<link name="base_link"/>', f'<link name="base_link">{COLLISION}</link>'))


def lint(pkg: Path, monkeypatch, codes=CODES):
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import RunRequest, run_check
    monkeypatch.chdir(pkg)
    cfg = load_config(None)
    cfg.select = list(codes)
    res = run_check(RunRequest(["."], cfg, build_resolver(["."], cfg), in_process=True))
    assert not res.internal, res.internal
    return res.findings


def found(tmp_path, monkeypatch, **changed):
    """(code, severity, file, line, related file, related line) of every finding of the clean
    package with ``changed`` files (keyword: the file's key with / and . as _)."""
    files = {**FILES, "urdf/arm.urdf.xacro": SOLID}
    for key, text in changed.items():
        files[next(k for k in files if k.replace("/", "_").replace(".", "_") == key)] = text
    pkg = make_package(tmp_path, "arm_config", files)
    return sorted((f.code, f.severity, os.path.relpath(f.file, pkg), f.line,
                   os.path.relpath(f.related[0], pkg) if f.related else None,
                   f.related[1] if f.related else None) for f in lint(pkg, monkeypatch))


def test_the_clean_package_with_collision_geometry_has_no_finding(tmp_path, monkeypatch):
    assert found(tmp_path, monkeypatch) == []


# -- UL716: a Gazebo-simulated <ros2_control> sensor ------------------------------------------
def _simulated(sensor: str, plugin="gz_ros2_control/GazeboSimSystem") -> str:
    return SOLID.replace("mock_components/GenericSystem", plugin).replace(
        "  </ros2_control>",
        f'    <sensor name="{sensor}"><state_interface name="force.x"/></sensor>\n  </ros2_control>\n'
        '  <gazebo reference="link2">\n'
        '    <sensor name="tcp_fts" type="force_torque"><update_rate>100</update_rate></sensor>\n'
        "  </gazebo>")


def test_a_simulated_sensor_names_no_gazebo_sensor(tmp_path, monkeypatch):
    xacro = _simulated("tcp_fts_sensor")
    at = line_of(xacro, '<sensor name="tcp_fts_sensor">')
    assert found(tmp_path, monkeypatch, urdf_arm_urdf_xacro=xacro) == [
        ("UL716", "warning", "urdf/arm.urdf.xacro", at, None, None)]
    # gazebo_ros2_control (Gazebo classic) looks sensors up by name alike
    assert [f[0] for f in found(tmp_path / "classic", monkeypatch, urdf_arm_urdf_xacro=_simulated(
        "tcp_fts_sensor", "gazebo_ros2_control/GazeboSystem"))] == ["UL716"]


def test_a_sensor_named_after_its_gazebo_sensor_or_of_real_hardware_is_not_reported(
        tmp_path, monkeypatch):
    assert found(tmp_path, monkeypatch, urdf_arm_urdf_xacro=_simulated("tcp_fts")) == []
    # mock or real hardware: the sensor's name is the hardware plugin's (ros2_control_demos'
    # tcp_fts_sensor names no link, joint or Gazebo sensor)
    assert found(tmp_path / "mock", monkeypatch, urdf_arm_urdf_xacro=_simulated(
        "tcp_fts_sensor", "mock_components/GenericSystem")) == []


# -- UL717: MoveIt controllers against the SRDF's groups ----------------------------------------
def test_a_moveit_controller_joint_in_no_group_relates_to_the_group_it_serves(tmp_path, monkeypatch):
    """The arm group shrank to joint1; the arm controller still drives joint2: reported at its
    YAML line, related to the arm group's SRDF line."""
    srdf = SRDF.replace('<chain base_link="base_link" tip_link="link2"/>', '<joint name="joint1"/>')
    yaml = MOVEIT_CONTROLLERS.replace("joints: [joint1, joint2]", "joints:\n      - joint1\n      - joint2")
    assert found(tmp_path, monkeypatch, config_arm_srdf=srdf, config_moveit_controllers_yaml=yaml) == [
        ("UL717", "warning", "config/moveit_controllers.yaml", line_of(yaml, "- joint2"),
         "config/arm.srdf", line_of(srdf, '<group name="arm">'))]


def test_a_controller_of_no_group_relates_to_the_robot_joint(tmp_path, monkeypatch):
    """A controller whose joints are in no group at all: the related location is the joint's
    xacro line; the mimic finger (in no group) driven by the hand controller likewise."""
    yaml = MOVEIT_CONTROLLERS.replace("joints: [finger_a_joint]", "joints: [finger_a_joint, finger_b_joint]")
    srdf = SRDF.replace('<joint name="finger_a_joint"/>', '<link name="finger_a"/>')
    got = found(tmp_path, monkeypatch, config_moveit_controllers_yaml=yaml, config_arm_srdf=srdf)
    assert got == [("UL717", "warning", "config/moveit_controllers.yaml", line_of(yaml, "finger_b_joint"),
                    "config/arm.srdf", line_of(srdf, '<group name="hand">'))]
    yaml = MOVEIT_CONTROLLERS + "  base_controller:\n    joints: [finger_b_joint]\n"
    got = found(tmp_path / "b", monkeypatch, config_moveit_controllers_yaml=yaml)
    assert got == [("UL717", "warning", "config/moveit_controllers.yaml", len(yaml.splitlines()),
                    "urdf/arm.urdf.xacro", line_of(XACRO, 'joint name="finger_b_joint"'))]


# -- UL756: the virtual joint ------------------------------------------------------------------
VJ = '<virtual_joint name="world_joint" type="fixed" parent_frame="world" child_link="base_link"/>'


def test_a_virtual_joint_whose_parent_is_a_robot_link(tmp_path, monkeypatch):
    srdf = SRDF.replace(VJ, VJ.replace('parent_frame="world"', 'parent_frame="link2"'))
    assert found(tmp_path, monkeypatch, config_arm_srdf=srdf) == [
        ("UL756", "warning", "config/arm.srdf", 2, "urdf/arm.urdf.xacro",
         line_of(XACRO, 'link name="link${n}"'))]


def test_a_virtual_joint_moveit_skips(tmp_path, monkeypatch):
    """A child that is not the root link, an empty parent frame: MoveIt skips the joint."""
    root = line_of(XACRO, '<link name="base_link"')
    srdf = SRDF.replace(VJ, VJ.replace('child_link="base_link"', 'child_link="link1"'))
    assert found(tmp_path, monkeypatch, config_arm_srdf=srdf) == [
        ("UL756", "warning", "config/arm.srdf", 2, "urdf/arm.urdf.xacro", root)]
    srdf = SRDF.replace(VJ, VJ.replace('parent_frame="world"', 'parent_frame=""'))
    assert found(tmp_path / "b", monkeypatch, config_arm_srdf=srdf) == [
        ("UL756", "warning", "config/arm.srdf", 2, "urdf/arm.urdf.xacro", root)]


def test_the_gazebo_world_link_pattern_is_information(tmp_path, monkeypatch):
    """A URDF rooted at a `world` link (for Gazebo) and an SRDF attaching base_link to `world`
    again: MoveIt skips the virtual joint and plans in `world`: information, not a warning."""
    xacro = SOLID.replace('<link name="base_link">', '<link name="world"/>\n  <joint name="world_fixed" '
                          'type="fixed"><parent link="world"/><child link="base_link"/></joint>\n'
                          '  <link name="base_link">')
    got = found(tmp_path, monkeypatch, urdf_arm_urdf_xacro=xacro)
    assert got == [("UL756", "info", "config/arm.srdf", 2, "urdf/arm.urdf.xacro",
                    line_of(xacro, '<link name="world"/>'))]


def test_the_virtual_joint_may_be_a_group_joint(tmp_path, monkeypatch):
    """A mobile manipulator's base group names the virtual joint: MoveIt's SRDF parser accepts
    it, so UL751 does not report it (it did)."""
    base = '  <group name="base">\n    <joint name="world_joint"/>\n  </group>\n'
    srdf = SRDF.replace(VJ, VJ.replace('type="fixed"', 'type="planar"')).replace(
        "  <group_state", base + "  <group_state")
    assert found(tmp_path, monkeypatch, config_arm_srdf=srdf) == []


# -- UL757: disable_collisions pairs MoveIt never uses ---------------------------------------------
def test_a_pair_with_a_link_without_collision_geometry_and_a_repeated_pair(tmp_path, monkeypatch):
    """The clean package's Adjacent pair is needed (MoveIt computes no adjacency) while both
    links have collision geometry; without it on base_link, or written twice, it is information."""
    pair = '<disable_collisions link1="base_link" link2="link1" reason="Adjacent"/>'
    assert found(tmp_path, monkeypatch, urdf_arm_urdf_xacro=XACRO) == [
        ("UL757", "info", "config/arm.srdf", line_of(SRDF, pair), "urdf/arm.urdf.xacro",
         line_of(XACRO, '<link name="base_link"'))]
    srdf = SRDF.replace(pair, pair + "\n  " + pair.replace('link1="base_link" link2="link1"',
                                                          'link1="link1" link2="base_link"'))
    assert found(tmp_path / "b", monkeypatch, config_arm_srdf=srdf) == [
        ("UL757", "info", "config/arm.srdf", line_of(SRDF, pair) + 1, "urdf/arm.urdf.xacro",
         line_of(XACRO, '<link name="link${n}"'))]


# -- one model file checked alone, and `diff` ------------------------------------------------------
def test_checking_the_model_file_alone_checks_its_configuration(tmp_path, monkeypatch):
    """`check urdf/arm.urdf.xacro` (what the hook and diff's base revision do) ties the
    package's SRDF and YAML as `check .` does: the file's own folder, a root of the run, does
    not hide the package.xml above it."""
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import RunRequest, run_check
    srdf = SRDF.replace(VJ, VJ.replace('parent_frame="world"', 'parent_frame="link2"'))
    pkg = make_package(tmp_path, "arm_config", {**FILES, "urdf/arm.urdf.xacro": SOLID,
                                                "config/arm.srdf": srdf})
    monkeypatch.chdir(pkg)
    cfg = load_config(None)
    cfg.select = CODES
    paths = ["urdf/arm.urdf.xacro"]
    res = run_check(RunRequest(paths, cfg, build_resolver(paths, cfg), in_process=True))
    assert [(f.code, os.path.relpath(f.file, pkg)) for f in res.findings] == [
        ("UL756", "config/arm.srdf")]


def test_diff_of_an_srdf_change_shows_the_robot_element(tmp_path, monkeypatch, capsys):
    """Only the SRDF changes: diff reports just the pair it broke, not the virtual joint
    finding both revisions have (the base revision is checked against its configuration too),
    with the robot element's xacro line, in text, JSON and markdown."""
    import json
    import subprocess
    from urdf_lint.cli.main import main
    base = SRDF.replace(VJ, VJ.replace('parent_frame="world"', 'parent_frame="link2"'))
    pkg = make_package(tmp_path, "arm_config", {**FILES, "urdf/arm.urdf.xacro": SOLID,
                                                "config/arm.srdf": base})
    for cmd in (["init", "-q"], ["add", "-A"],
                ["-c", "user.email=t@t", "-c", "user.name=t", "commit", "-qm", "base"]):
        subprocess.run(["git", *cmd], cwd=pkg, check=True)
    srdf = base.replace('link2="link1"', 'link2="link_1"')
    (pkg / "config" / "arm.srdf").write_text(srdf)
    monkeypatch.chdir(pkg)
    at = "urdf/arm.urdf.xacro:" + str(line_of(SOLID, 'link name="link${n}"'))
    main(["diff", "HEAD", "--no-cache", "--format", "json"])
    (m,) = json.loads(capsys.readouterr().out)["models"]
    assert [(f["code"], f["file"], f["line"], f["related"][:2]) for f in m["findings_introduced"]] == [
        ("UL752", "config/arm.srdf", line_of(srdf, "link_1"), [at.split(":")[0], int(at.split(":")[1])])]
    assert m["findings_fixed"] == []
    main(["diff", "HEAD", "--no-cache"])
    out = capsys.readouterr().out
    assert f"UL752 config/arm.srdf:{line_of(srdf, 'link_1')}:3" in out and \
        f"\n      robot element at {at}\n" in out, out
    main(["diff", "HEAD", "--no-cache", "--format", "markdown"])
    assert f"<sub>robot element at {at}</sub>" in capsys.readouterr().out


def test_a_moveit_controller_split_over_groups(tmp_path, monkeypatch):
    """One controller for the arm and the finger, an arm group and a hand group but none of
    both: reported once at the controller's `joints` key, related to the arm group; a group
    of both (a subgroup set) makes it fine."""
    yaml = MOVEIT_CONTROLLERS.replace("joints: [joint1, joint2]", "joints: [joint1, joint2, finger_a_joint]")
    assert found(tmp_path, monkeypatch, config_moveit_controllers_yaml=yaml) == [
        ("UL717", "warning", "config/moveit_controllers.yaml", line_of(yaml, "finger_a_joint]"),
         "config/arm.srdf", line_of(SRDF, '<group name="arm">'))]
    both = SRDF.replace("  <group_state", '  <group name="arm_hand">\n    <group name="arm"/>\n'
                        '    <group name="hand"/>\n  </group>\n  <group_state')
    assert found(tmp_path / "b", monkeypatch, config_moveit_controllers_yaml=yaml,
                 config_arm_srdf=both) == []


def test_a_related_srdf_line_is_not_called_a_robot_element(tmp_path, monkeypatch, capsys):
    """UL717's related location is the SRDF group: the text and SARIF say "related
    configuration line", not "robot element"."""
    import json
    from urdf_lint.cli.main import main
    srdf = SRDF.replace('<chain base_link="base_link" tip_link="link2"/>', '<joint name="joint1"/>')
    pkg = make_package(tmp_path, "arm_config", {**FILES, "urdf/arm.urdf.xacro": SOLID,
                                                "config/arm.srdf": srdf})
    monkeypatch.chdir(pkg)
    at = "config/arm.srdf:" + str(line_of(srdf, '<group name="arm">'))
    main(["check", ".", "--no-cache", "--select", "UL717"])
    assert f"related configuration line at {at}" in capsys.readouterr().out
    main(["check", ".", "--no-cache", "--select", "UL717", "--output-format", "sarif"])
    (res,) = json.loads(capsys.readouterr().out)["runs"][0]["results"]
    assert [r["message"]["text"] for r in res["relatedLocations"]] == ["related configuration line here"]


def test_checking_one_of_several_robots_keeps_the_others_controllers_apart(tmp_path, monkeypatch):
    """A package with two robots (the 2F-85 and 2F-140 grippers of robotiq_description) and a
    controller YAML for one: checking the other robot's file alone does not check that YAML
    against it, as `check .` does not (the package holds several robot files)."""
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import RunRequest, run_check
    other = '<robot name="other"><link name="o"/><link name="p"/>\n<joint name="o_joint" ' \
            'type="fixed"><parent link="o"/><child link="p"/></joint></robot>\n'
    pkg = make_package(tmp_path, "grippers", {"urdf/arm.urdf.xacro": SOLID, "urdf/other.urdf": other,
                                              "config/arm_controllers.yaml": FILES["config/ros2_controllers.yaml"]})
    monkeypatch.chdir(pkg)
    cfg = load_config(None)
    cfg.select = ["UL710", "UL711"]
    for paths in (["."], ["urdf/other.urdf"]):
        res = run_check(RunRequest(paths, cfg, build_resolver(paths, cfg), in_process=True))
        assert [f.code for f in res.findings] == [], paths
    # the YAML is still checked against the robot it names
    (pkg / "config" / "arm_controllers.yaml").write_text(
        FILES["config/ros2_controllers.yaml"].replace("[joint1, joint2]", "[joint1, joint_2]"))
    paths = ["urdf/arm.urdf.xacro"]
    res = run_check(RunRequest(paths, cfg, build_resolver(paths, cfg), in_process=True))
    assert [f.code for f in res.findings] == ["UL710"]
