"""Consumer targets (issue 25): the config key ``targets`` / ``--target``, per-target severities
declared by the rules, findings that name the target that makes them errors, and the severity
corrections measured against real consumers (/work/shared/notes/consumer-facts.md)."""
from __future__ import annotations

import json

import pytest

from conftest import make_package, run_cli

LIMIT = '<limit lower="-1" upper="1" effort="1" velocity="1"/>'


def lint(pkg, *extra):
    p = run_cli("check", ".", "--no-cache", "--format", "json", "--fail-on", "never", *extra,
                cwd=pkg)
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)["findings"]


def of(fs, code):
    return [(f["severity"], f.get("severity_from", [])) for f in fs if f["code"] == code]


def pkg_with(tmp_path, body, name="urdf/r.urdf"):
    return make_package(tmp_path, "p", {name: body})


def inertial(mass, t="ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\""):
    return f'<inertial><mass value="{mass}"/><inertia {t}/></inertial>'


MOVING_NO_INERTIAL = f"""<robot name="r">
  <link name="base"/><link name="arm"/>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>{LIMIT}</joint>
</robot>
"""


# -- the key and the flag ----------------------------------------------------------------------
def test_targets_key_is_validated(tmp_path):
    pkg = pkg_with(tmp_path, MOVING_NO_INERTIAL)
    (pkg / "urdf-lint.toml").write_text('targets = ["mujocoo"]\n')
    p = run_cli("check", ".", "--no-cache", cwd=pkg)
    assert p.returncode == 2 and "urdf-lint.toml:1: invalid value for targets" in p.stderr, p.stderr
    assert 'did you mean "mujoco"' in p.stderr, p.stderr
    (pkg / "urdf-lint.toml").write_text('targets = []\n')
    p = run_cli("check", ".", "--no-cache", cwd=pkg)
    assert p.returncode == 2 and "not empty" in p.stderr, p.stderr
    (pkg / "urdf-lint.toml").unlink()
    p = run_cli("check", ".", "--no-cache", "--target", "gazeboo", cwd=pkg)
    assert p.returncode == 2 and "--targets: invalid value" in p.stderr, p.stderr


def test_default_target_is_ros_and_mujoco_raises_ul601(tmp_path):
    pkg = pkg_with(tmp_path, MOVING_NO_INERTIAL)
    assert of(lint(pkg), "UL601") == [("warning", [])]
    assert of(lint(pkg, "--target", "mujoco"), "UL601") == [("error", ["mujoco"])]
    # several targets: the highest wins, and the targets that make it an error are named
    # (issue 38: sdformat 12 drops the link, measured: an error for gazebo too)
    assert of(lint(pkg, "--target", "ros,pybullet", "--target", "mujoco"), "UL601") == \
        [("error", ["mujoco"])]
    # (and no link at all has an <inertial>: sdformat refuses the model, one more finding)
    assert of(lint(pkg, "--target", "ros,gazebo", "--target", "mujoco"), "UL601") == \
        [("error", ["gazebo"]), ("error", ["gazebo", "mujoco"])]
    assert of(lint(pkg, "--target", "pybullet"), "UL601") == [("warning", [])]
    (pkg / "urdf-lint.toml").write_text('targets = ["ros", "mujoco"]\n')
    assert of(lint(pkg), "UL601") == [("error", ["mujoco"])]
    # a severity override still wins
    (pkg / "urdf-lint.toml").write_text('targets = ["mujoco"]\nseverity = { UL601 = "info" }\n')
    assert of(lint(pkg), "UL601") == [("info", [])]


def test_text_and_exit_code_name_the_target(tmp_path):
    pkg = pkg_with(tmp_path, MOVING_NO_INERTIAL)
    p = run_cli("check", ".", "--no-cache", "--select", "UL601", cwd=pkg)
    assert p.returncode == 0 and "[missing-inertial]\n" in p.stdout, p.stdout
    p = run_cli("check", ".", "--no-cache", "--select", "UL601", "--target", "mujoco", cwd=pkg)
    assert p.returncode == 1 and "[missing-inertial] [mujoco]\n" in p.stdout, p.stdout
    p = run_cli("check", ".", "--no-cache", "--select", "UL601", "--target", "mujoco",
                "--format", "sarif", cwd=pkg)
    (res,) = json.loads(p.stdout)["runs"][0]["results"]
    assert res["level"] == "error" and res["properties"]["severityFrom"] == ["mujoco"]


def test_rules_page_shows_the_targets_table():
    p = run_cli("rules", "--format", "markdown")
    assert p.returncode == 0, p.stderr
    assert "## Consumer targets" in p.stdout
    # (issue 38: the programs behind `python` and iDynTree are targets; gazebo measured)
    assert "| Code | ros | gazebo | mujoco | drake | pinocchio | pybullet | isaac | python | " \
           "yourdfpy | urdf_parser_py | urchin | idyntree |" in p.stdout
    assert "| [UL601](#ul601-missing-inertial) | warn | error | error | warn | warn | warn | warn " \
           "| warn | warn | warn | warn | warn |" in p.stdout
    p = run_cli("rule", "UL601")
    assert "Per consumer target (config 'targets'): mujoco error, gazebo error" in p.stdout


def test_a_rule_table_is_checked():
    import types
    from urdf_lint.engine.registry import rule_from_module
    mod = types.ModuleType("urdf_lint.rules.ul997_fake")
    mod.CODE, mod.NAME, mod.SEVERITY, mod.check = "UL997", "fake", "error", lambda m, c: iter(())
    mod.TARGETS = {"mojuco": "error"}
    with pytest.raises(RuntimeError, match="unknown target 'mojuco'"):
        rule_from_module(mod)
    mod.TARGETS = {"mujoco": "fatal"}
    with pytest.raises(RuntimeError, match="must be one of"):
        rule_from_module(mod)


def test_resolve():
    from urdf_lint.core.targets import resolve
    assert resolve({"mujoco": "error"}, "warning", ["ros"]) == ("warning", ())
    assert resolve({"mujoco": "error"}, "warning", ["ros", "mujoco"]) == ("error", ("mujoco",))
    assert resolve({"*": "off", "mujoco": "warning"}, "warning", ["ros"]) == (None, ())
    assert resolve({"*": "off", "mujoco": "warning"}, "warning", ["mujoco", "drake"]) == \
        ("warning", ("mujoco",))
    assert resolve({"drake": "error", "python": "error"}, "warning",
                   ["drake", "python", "ros"]) == ("error", ("drake", "python"))


# -- severity corrections ----------------------------------------------------------------------
def test_ul602_zero_mass_between_joints_is_an_error_for_mujoco_only(tmp_path):
    body = f"""<robot name="r">
  <link name="base"/>
  <link name="cross">{inertial(0)}</link>
  <link name="leg">{inertial(3)}</link>
  <joint name="yaw" type="revolute"><parent link="base"/><child link="cross"/>
    <axis xyz="0 0 1"/>{LIMIT}</joint>
  <joint name="roll" type="revolute"><parent link="cross"/><child link="leg"/>
    <axis xyz="1 0 0"/>{LIMIT}</joint>
</robot>
"""
    pkg = pkg_with(tmp_path, body)
    assert of(lint(pkg), "UL602") == [("warning", [])]
    assert of(lint(pkg, "--target", "mujoco"), "UL602") == [("error", ["mujoco"])]


def test_ul602_tiny_mass_on_a_fixed_frame_is_a_placeholder(tmp_path):
    body = f"""<robot name="r">
  <link name="base">{inertial(1)}</link>
  <link name="arm">{inertial(1)}</link>
  <link name="tool0">{inertial("1e-9")}</link>
  <link name="finger">{inertial("1e-9")}</link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>{LIMIT}</joint>
  <joint name="t" type="fixed"><parent link="arm"/><child link="tool0"/></joint>
  <joint name="f" type="revolute"><parent link="arm"/><child link="finger"/><axis xyz="0 0 1"/>{LIMIT}</joint>
</robot>
"""
    fs = [f for f in lint(pkg_with(tmp_path, body)) if f["code"] == "UL602"]
    assert [f["message"] for f in fs] == [
        "link 'finger': mass 1e-09 kg is implausibly small (grams?); Gazebo drops links below "
        "1e-6 kg"]


def _tensor_robot(t, mass="0.01", extra=""):
    return f"""<robot name="r">
  <link name="base"/>
  <link name="a"><inertial><mass value="{mass}"/><inertia {t}/></inertial></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>{LIMIT}</joint>
{extra}</robot>
"""


def test_ul603_principal_moments(tmp_path):
    # the hand tensor: the diagonal passes, the principal moments do not
    t = 'ixx="4.70e-6" ixy="0" ixz="2.5e-6" iyy="3.65e-6" iyz="0" izz="4.70e-6"'
    pkg = pkg_with(tmp_path, _tensor_robot(t))
    fs = lint(pkg)
    assert of(fs, "UL603") == [("warning", [])]
    assert "principal moments 2.2e-06, 3.65e-06, 7.2e-06 break the triangle inequality" in \
        [f for f in fs if f["code"] == "UL603"][0]["message"]
    assert of(lint(pkg, "--target", "mujoco"), "UL603") == [("error", ["mujoco"])]
    # a written diagonal that fails stays an error for every target
    t = 'ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.5"'
    assert of(lint(pkg_with(tmp_path / "d", _tensor_robot(t))), "UL603") == [("error", [])]


def test_ul603_float_noise_is_treated_like_zero(tmp_path):
    body_noise = _tensor_robot('ixx="1e-20" ixy="1e-21" ixz="0" iyy="1e-20" iyz="0" izz="0"',
                               mass="0")
    body_zero = _tensor_robot('ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"', mass="0")
    assert of(lint(pkg_with(tmp_path / "n", body_noise)), "UL603") == []
    assert of(lint(pkg_with(tmp_path / "z", body_zero)), "UL603") == []
    # noise in the products of a real tensor is not a defect either
    t = 'ixx="0.01" ixy="1e-19" ixz="-3e-20" iyy="0.01" iyz="0" izz="0.005"'
    assert of(lint(pkg_with(tmp_path / "p", _tensor_robot(t))), "UL603") == []
    # with mass, both twins are the same finding (a body that spins freely)
    for sub, t in (("mn", 'ixx="1e-20" ixy="0" ixz="0" iyy="1e-20" iyz="0" izz="1e-20"'),
                   ("mz", 'ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"')):
        fs = [f for f in lint(pkg_with(tmp_path / sub, _tensor_robot(t, mass="1")))
              if f["code"] == "UL603"]
        assert len(fs) == 1 and "all-zero inertia tensor" in fs[0]["message"], (sub, fs)


def test_ul603_all_equal_placeholder_on_a_dummy_link(tmp_path):
    t = 'ixx="1e-6" ixy="1e-6" ixz="1e-6" iyy="1e-6" iyz="1e-6" izz="1e-6"'
    assert of(lint(pkg_with(tmp_path / "d", _tensor_robot(t, mass="1e-6"))), "UL603") == []
    # the same tensor on a real mass is not a placeholder
    assert of(lint(pkg_with(tmp_path / "r", _tensor_robot(t, mass="2"))), "UL603") == \
        [("error", [])]


def test_axis_material_velocity_are_warnings(tmp_path):
    body = """<robot name="r">
  <link name="a"><visual><geometry><box size="1 1 1"/></geometry><material name="nope"/></visual></link>
  <link name="b"/><link name="c"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 2"/>
    <limit lower="-1" upper="1" effort="1" velocity="0"/></joint>
  <joint name="k" type="revolute"><parent link="a"/><child link="c"/><axis xyz="0 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="-1"/></joint>
</robot>
"""
    fs = lint(pkg_with(tmp_path, body))
    assert sorted(of(fs, "UL307")) == [("error", []), ("warning", [])]
    assert of(fs, "UL502") == [("warning", [])]
    assert sorted(of(fs, "UL304")) == [("error", []), ("warning", [])]


# -- new rules and UL001 -----------------------------------------------------------------------
TRANSMISSIONS = """<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="j2" type="fixed"><parent link="a"/><child link="c"/><mimic joint="j1"/></joint>
  <transmission name="t"><joint name="j1"/><actuator name="m1"/></transmission>
  <transmission name="t"><joint name="j2"/><actuator name="m2"/></transmission>
  <transmission name="u"><joint name="j2"/><actuator name="m1"/></transmission>
</robot>
"""


def test_duplicate_transmissions_and_mimic_on_fixed_per_target(tmp_path):
    pkg = pkg_with(tmp_path, TRANSMISSIONS)
    fs = lint(pkg)
    assert of(fs, "UL704") == [("warning", []), ("warning", [])]
    assert of(fs, "UL309") == [("warning", [])]
    fs = lint(pkg, "--target", "ros,drake,python")
    # urchin rejects the second "t"; Drake only the actuator name used twice (m1): it loads two
    # transmissions of one name whose actuators differ (pydrake 1.51.1)
    assert of(fs, "UL704") == [("error", ["python"]), ("error", ["drake"])]
    # one macro called twice repeats both names: then Drake rejects the transmission too
    twice = TRANSMISSIONS.replace('<actuator name="m2"/>', '<actuator name="m1"/>')
    fs = lint(pkg_with(tmp_path / "twice", twice), "--target", "ros,drake,python")
    assert of(fs, "UL704") == [("error", ["drake", "python"]), ("error", ["drake"])]
    assert of(fs, "UL309") == [("error", ["drake"])]
    assert of(lint(pkg, "--target", "python"), "UL309") == [("warning", [])]


def test_ul001_namespace_and_declaration_are_reported_and_the_rest_linted(tmp_path):
    body = """<?xml verison="1.0"?>
<robot name="r">
  <link name="a"><drake:proximity_properties><drake:mu value="1"/></drake:proximity_properties></link>
  <link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""
    pkg = pkg_with(tmp_path, body)
    fs = lint(pkg)
    got = [(f["line"], f["col"], f["severity"]) for f in fs if f["code"] == "UL001"]
    assert got == [(1, 7, "warning"), (3, 45, "warning")], fs
    # (issue 38: yourdfpy loads it, measured)
    assert "yourdfpy load it, urdf_parser_py and urchin reject it" in fs[0]["message"]
    # every other rule ran, at the real lines
    assert [(f["line"], f["col"]) for f in fs if f["code"] == "UL307"] == [(5, 70)]
    assert of(lint(pkg, "--target", "python"), "UL001") == [("error", ["python"])] * 2
    # a file that is not well-formed still stops at the syntax error
    (pkg / "urdf/r.urdf").write_text('<robot name="r">\n  <link name="a">\n</robot>\n')
    fs = lint(pkg)
    assert [(f["code"], f["severity"]) for f in fs] == [("UL001", "error")]


# -- issue 24, items 15 and 16: a lost xacro prefix, misspelled kinematics, the lower triangle --
X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
LOST = f"""<?xml version="1.0"?>
<robot name="r" {X}>
  <xacro:macro name="solid_cuboid_inertia" params="m">
    <mass value="${{m}}"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
  </xacro:macro>
  <xacro:macro name="marker"><link name="marker"/></xacro:macro>
  <link name="a"/>
  <link name="b"><inertial><solid_cuboid_inertia m="1"/></inertial>
    <visual><insert_block name="origin"/><geometry><box size="1 1 1"/></geometry></visual></link>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/><orgin xyz="0 0 1"/></joint>
  <marker/>
  <link name="c"><inertial><mass value="1"/><mass value="2"/>
    <inertia ixx="1" ixy="0.1" ixz="0" iyy="1" iyz="0" izz="1" iyx="0.1" izy="0.2"/></inertial></link>
  <joint name="k" type="fixed"><parent link="a"/><child link="c"/></joint>
</robot>
"""


def test_lost_xacro_prefix_and_misspelled_origin(tmp_path):
    fs = [f for f in lint(pkg_with(tmp_path, LOST, "urdf/r.urdf.xacro")) if f["code"] == "UL209"]
    by_line = {f["line"]: (f["severity"], f["message"]) for f in fs}
    sev, msg = by_line[8]
    assert sev == "error" and "a call of the macro 'solid_cuboid_inertia' without its 'xacro:' " \
        "prefix" in msg and "this <inertial> loses what it was meant to write" in msg
    sev, msg = by_line[9]
    assert sev == "error" and "the xacro directive <xacro:insert_block> without" in msg
    sev, msg = by_line[10]
    assert sev == "error" and "(did you mean 'origin'?)" in msg and "has no <origin>" in msg
    sev, msg = by_line[11]   # at the top level: nothing is lost in a link or joint
    assert sev == "warning" and "a call of the macro 'marker'" in msg
    sev, msg = by_line[12]
    assert sev == "warning" and msg.startswith("a second <mass> in <inertial>: URDF parsers read "
                                               "the first one")


def test_lower_triangle_of_the_inertia(tmp_path):
    fs = [f for f in lint(pkg_with(tmp_path, LOST, "urdf/r.urdf.xacro")) if f["code"] == "UL210"]
    assert [(f["severity"], f["message"]) for f in fs] == [
        ("info", "'iyx' on <inertia>: URDF reads only the upper triangle of the symmetric tensor "
                 "(ixy, ixz, iyz), so 'iyx' is ignored"),
        ("warning", "'izy' on <inertia>: URDF reads only the upper triangle of the symmetric "
                    "tensor (ixy, ixz, iyz), so 'izy' is ignored, and it differs from iyz=0: iyz "
                    "is the value used")]
    assert not [f for f in fs if "did you mean" in f["message"]]


# -- URDF 1.1 and 1.2 --------------------------------------------------------------------------
V12 = """<?xml version="1.0"?>
<robot name="v12" version="1.2">
  <link name="base"/>
  <link name="arm">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <visual><origin xyz="0 0 0.25" quat_xyzw="0 0 0 1"/>
      <geometry><capsule radius="0.05" length="0.4"/></geometry></visual>
    <collision><geometry><capsule radius="0.05" length="0.4"/></geometry></collision>
  </link>
  <joint name="j" type="revolute"><origin xyz="0 0 0.1" quat_xyzw="0 0 0.7071068 0.7071068"/>
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1" acceleration="2" deceleration="3" jerk="20"/></joint>
</robot>
"""


def test_urdf_1_2_robot_passes_for_ros_and_mujoco_says_what_it_does_not_read(tmp_path):
    pkg = pkg_with(tmp_path, V12)
    p = run_cli("check", ".", "--no-cache", "--select", "ALL", cwd=pkg)
    assert p.returncode == 0 and p.stdout == "All checks passed: 1 model(s).\n", p.stdout
    fs = lint(pkg, "--select", "ALL", "--target", "mujoco")
    assert [(f["code"], f["line"], f["severity"], f["severity_from"]) for f in fs] == [
        ("UL213", 6, "warning", ["mujoco"]), ("UL213", 10, "warning", ["mujoco"]),
        ("UL213", 12, "info", ["mujoco"]), ("UL213", 12, "info", ["mujoco"]),
        ("UL213", 12, "info", ["mujoco"])]
    assert [f["message"].split(" is URDF")[0] for f in fs] == [
        "quat_xyzw on <origin>", "quat_xyzw on <origin>", "acceleration on <limit>",
        "deceleration on <limit>", "jerk on <limit>"]
    assert "MuJoCo 4.0.0, PyBullet 3.2.7 and urdf_parser_py ignore it" in fs[0]["message"]
    # pinocchio reads all of it (measured: tests/test_consumers.py)
    assert lint(pkg, "--select", "ALL", "--target", "pinocchio") == []


def test_urdf_1_1_elements_need_the_declared_version(tmp_path):
    pkg = pkg_with(tmp_path, V12.replace(' version="1.2"', ""))
    fs = [f for f in lint(pkg) if f["code"] == "UL213"]
    assert len(fs) == 7 and {f["severity"] for f in fs} == {"warning"}
    assert "but the robot declares version 1.0: urdfdom 6 (ROS, Pinocchio) ignores it there" \
        in fs[0]["message"]
    pkg = pkg_with(tmp_path / "v11", V12.replace('version="1.2"', 'version="1.1"'))
    fs = [f for f in lint(pkg) if f["code"] == "UL213"]
    assert [f["message"].split(" is URDF")[0] for f in fs] == [
        "acceleration on <limit>", "deceleration on <limit>", "jerk on <limit>"]


def test_urdf_1_1_values_are_validated(tmp_path):
    body = V12.replace('quat_xyzw="0 0 0 1"', 'quat_xyzw="0 0 1 1"').replace(
        'quat_xyzw="0 0 0.7071068 0.7071068"', 'quat_xyzw="0 0 0.7071068 0.7071068" rpy="0 0 1"'
    ).replace('acceleration="2"', 'acceleration="-2"').replace('jerk="20"', 'jerk="0"').replace(
        'length="0.4"/></geometry></collision>', 'length="0"/></geometry></collision>')
    fs = lint(pkg_with(tmp_path, body))
    got = sorted((f["code"], f["line"], f["severity"]) for f in fs)
    assert got == [("UL205", 8, "error"), ("UL207", 6, "warning"), ("UL207", 10, "error"),
                   ("UL304", 12, "error"), ("UL304", 12, "warning")], fs
    assert of(lint(pkg_with(tmp_path / "v", V12.replace('"1.2"', '"1.3"'))), "UL211") == \
        [("error", [])]


def test_principal_moments_match_numpy():
    import numpy as np
    from urdf_lint.rules.ul603_inertia_tensor import principal_moments
    rng = np.random.default_rng(3)
    for _ in range(200):
        a = rng.normal(size=(3, 3)) * 10.0 ** rng.integers(-8, 2)
        m = a @ a.T if rng.random() < 0.7 else (a + a.T) / 2
        got = principal_moments(m[0, 0], m[1, 1], m[2, 2], m[0, 1], m[0, 2], m[1, 2])
        want = np.linalg.eigvalsh(m)
        assert np.allclose(got, want, rtol=1e-9, atol=1e-12 * np.abs(m).max()), (m, got, want)


def test_gazebo_lumped_reference_only_where_sdformat_lumps(tmp_path):
    """UL705: a <gazebo reference> on the child of a fixed joint is reported for the gazebo
    target only, and not where the joint is kept (preserveFixedJoint, disableFixedJointLumping),
    attaches to `world`, or the block is empty."""
    fixed = '<joint name="{j}" type="fixed"><parent link="{p}"/><child link="{c}"/></joint>'
    body = f"""<robot name="r">
  <link name="world"/><link name="base"/><link name="cam"/><link name="imu"/><link name="tof"/>
  <link name="bare"/>
  {fixed.format(j="world_joint", p="world", c="base")}
  {fixed.format(j="cam_joint", p="base", c="cam")}
  {fixed.format(j="imu_joint", p="base", c="imu")}
  {fixed.format(j="tof_joint", p="base", c="tof")}
  {fixed.format(j="bare_joint", p="base", c="bare")}
  <gazebo reference="base"><material>Gazebo/Grey</material></gazebo>
  <gazebo reference="cam"><sensor name="c" type="camera"/></gazebo>
  <gazebo reference="imu"><sensor name="i" type="imu"/></gazebo>
  <gazebo reference="imu_joint"><preserveFixedJoint>true</preserveFixedJoint></gazebo>
  <gazebo reference="tof"><sensor name="t" type="gpu_lidar"/></gazebo>
  <gazebo reference="tof_joint"><disableFixedJointLumping>true</disableFixedJointLumping></gazebo>
  <gazebo reference="bare"><!-- nothing --></gazebo>
</robot>
"""
    pkg = pkg_with(tmp_path, body)
    fs = [f for f in lint(pkg, "--target", "gazebo") if f["code"] == "UL705"]
    assert [(f["line"], f["severity"], f.get("severity_from")) for f in fs] == \
        [(10, "warning", ["gazebo"])], fs
    assert "'cam' into 'base'" in fs[0]["message"] and "cam_joint" in fs[0]["message"]
    assert not of(lint(pkg), "UL705")


def test_isaac_findings_only_for_the_isaac_target(tmp_path):
    """UL609 on an empty root link that is the root of something, UL310 on a moving joint's
    non-zero damping or friction; nothing for ros."""
    body = f"""<robot name="r">
  <link name="base_footprint"/>
  <link name="base">{inertial(1)}</link>
  <link name="a">{inertial(1)}</link><link name="b">{inertial(1)}</link>
  <joint name="fix" type="fixed"><parent link="base_footprint"/><child link="base"/>
    <dynamics damping="1"/></joint>
  <joint name="ja" type="continuous"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
    <dynamics damping="0" friction="0.2"/></joint>
  <joint name="jb" type="continuous"><parent link="base"/><child link="b"/><axis xyz="0 0 1"/>
    <dynamics damping="0.0" friction="0"/></joint>
</robot>
"""
    pkg = pkg_with(tmp_path, body)
    fs = lint(pkg, "--target", "isaac")
    assert [(f["code"], f["line"], f["severity"]) for f in fs if f["code"] in ("UL609", "UL310")] \
        == [("UL609", 2, "warning"), ("UL310", 8, "warning")], fs
    assert "friction" in [f for f in fs if f["code"] == "UL310"][0]["message"]
    assert not [f for f in lint(pkg) if f["code"] in ("UL609", "UL310")]
    one = pkg_with(tmp_path / "one", '<robot name="r"><link name="only"/></robot>')
    assert not of(lint(one, "--target", "isaac"), "UL609")


def test_consumer_mesh_formats(tmp_path):
    """UL409: per mesh, what MuJoCo 4.0.0 and Drake 1.51.1 do with it (measured: see the rule's
    docstring): a binary STL (any case) is MuJoCo's, not Drake's; an ASCII STL and one of more
    than 200000 triangles neither's; visuals count for MuJoCo only when its <mujoco> block keeps
    them, and that block makes MuJoCo's findings an info for ros."""
    import struct
    from urdf_lint.rules._meshes import TETRA_STL
    tri = struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 0.1, 0, 0, 0, 0.1, 0, 0)
    files = {"meshes/ascii.stl": TETRA_STL,
             "meshes/BIN.STL": struct.pack("<80sI", b"binary", 1) + tri,
             "meshes/huge.stl": struct.pack("<80sI", b"binary", 200001) + tri * 200001,
             "meshes/part.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n"
                                "f 2 3 4\n"}

    def mesh(tag, name):
        return (f'<{tag}><geometry><mesh filename="package://p/meshes/{name}"/></geometry>'
                f'</{tag}>')
    links = [mesh("collision", "BIN.STL"), mesh("collision", "huge.stl"),
             mesh("visual", "ascii.stl"), mesh("collision", "part.obj")]
    body = '<robot name="r">{}\n' + "".join(
        f'  <link name="l{i}">{m}</link>\n' for i, m in enumerate(links)) + "</robot>\n"
    plain = make_package(tmp_path / "a", "p", {"urdf/r.urdf": body.format(""), **files})

    def ul409(pkg, target=None):
        fs = lint(pkg, *(["--target", target] if target else []))
        return [(f["line"], f["severity"], f["message"].split(": ", 1)[1])
                for f in fs if f["code"] == "UL409"]
    assert [(line, sev, msg.split(";")[0]) for line, sev, msg in ul409(plain, "mujoco")] == [
        (3, "error", "MuJoCo reads at most 200000 triangles from an STL, it has 200001 (MuJoCo "
                     "rejects the model)")]
    assert [(line, sev) for line, sev, _ in ul409(plain, "drake")] == [(2, "error"), (3, "error")]
    # each target hears of its own consumer only (under mujoco, Drake's verdict is not claimed)
    assert not any("Drake" in msg for _, _, msg in ul409(plain, "mujoco"))
    assert not any("MuJoCo" in msg for _, _, msg in ul409(plain, "drake"))
    assert ul409(plain) == []
    kept = make_package(tmp_path / "b", "p", {"urdf/r.urdf": body.format(
        '<mujoco><compiler discardvisual="false"/></mujoco>'), **files})
    assert [(line, sev) for line, sev, _ in ul409(kept, "mujoco")] == [(3, "error"), (4, "error")]
    assert [(line, sev) for line, sev, _ in ul409(kept)] == [(3, "info"), (4, "info")]
    assert "this one is ASCII" in ul409(kept)[1][2]
