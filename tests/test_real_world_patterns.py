"""False alarms, misses and bugs seen on real description repositories, each on a fixture that
reproduces the pattern."""
from __future__ import annotations

import json
import os

import pytest

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


ROOT_INERTIAL = f"""<?xml version="1.0"?>
<robot name="r" {X}>
  <link name="base"><inertial><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="arm"><inertial><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""


def generated_pkg(tmp_path, name="gen"):
    """A xacro and the URDF generated from it, checked in and named as its output."""
    pkg = make_package(tmp_path, name, {"urdf/robot.urdf.xacro": ROOT_INERTIAL})
    p = run_cli("expand", "urdf/robot.urdf.xacro", "-o", "urdf/robot.urdf", cwd=pkg)
    assert p.returncode == 0, p.stderr
    (pkg / "urdf-lint.toml").write_text('[[models]]\npath = "urdf/robot.urdf.xacro"\n'
                                        'output = "urdf/robot.urdf"\n')
    return pkg


def test_unsafe_fixes_never_rewrite_a_generated_urdf(tmp_path):
    """Item 21: the root-inertial fix (unsafe) of a stale generated URDF is refused: fixes go
    to sources only."""
    pkg = generated_pkg(tmp_path)
    xacro = pkg / "urdf/robot.urdf.xacro"
    xacro.write_text(xacro.read_text().replace('<mass value="1"/>', '<mass value="2"/>', 1))
    urdf = (pkg / "urdf/robot.urdf").read_bytes()
    doc, _ = check_json(pkg)
    (f,) = [f for f in doc["findings"] if f["code"] == "UL604" and f["file"] == "urdf/robot.urdf"]
    assert f["fix"]["refused"] == ("not fixable automatically: urdf/robot.urdf is generated from "
                                   "urdf/robot.urdf.xacro; fix the source and run urdf-lint "
                                   "generate"), f
    p = run_cli("check", ".", "--fix", "--unsafe-fixes", "--no-cache", "--isolated", cwd=pkg)
    assert (pkg / "urdf/robot.urdf").read_bytes() == urdf, p.stderr
    # the summary says which fix and why (an unsafe one only when unsafe fixes were asked for)
    why = (f"urdf/robot.urdf:{f['line']}:{f['col']}: UL604 fix not applied: urdf/robot.urdf is "
           "generated from urdf/robot.urdf.xacro; fix the source and run urdf-lint generate\n")
    assert why in p.stderr, p.stderr
    p = run_cli("check", ".", "--fix", "--no-cache", "--isolated", cwd=pkg)
    assert "UL604 fix not applied" not in p.stderr, p.stderr


def test_current_generated_urdf_is_not_linted_again(tmp_path):
    """Item 4: a generated URDF identical to today's expansion has no findings of its own
    (they are the xacro's); a stale one is linted (and UL011)."""
    pkg = generated_pkg(tmp_path)
    doc, _ = check_json(pkg)
    assert {f["file"] for f in doc["findings"]} == {"urdf/robot.urdf.xacro"}, doc["findings"]
    assert len(doc["models"]) == 2
    xacro = pkg / "urdf/robot.urdf.xacro"
    xacro.write_text(xacro.read_text().replace('<mass value="1"/>', '<mass value="2"/>', 1))
    doc, _ = check_json(pkg)
    assert {(f["code"], f["file"]) for f in doc["findings"]} >= {
        ("UL011", "urdf/robot.urdf"), ("UL604", "urdf/robot.urdf")}


def test_every_generated_urdf_of_a_xacro_is_checked(tmp_path):
    """Item 14: two URDFs whose headers name one xacro (and a [[models]] entry for it): both
    stale ones are UL011, not only the first in path order; one with other links is compared
    too (issue 32: every output of a xacro is checked, whatever its link count; this xacro
    reads no arg, so it has one variant)."""
    pkg = generated_pkg(tmp_path)
    urdf = (pkg / "urdf/robot.urdf").read_text()
    (pkg / "urdf/a_copy.urdf").write_text(urdf)
    (pkg / "urdf/variant.urdf").write_text(urdf.replace('"arm"', '"other_arm"'))
    xacro = pkg / "urdf/robot.urdf.xacro"
    xacro.write_text(xacro.read_text().replace('<mass value="1"/>', '<mass value="2"/>', 1))
    doc, _ = check_json(pkg)
    stale = sorted(f["file"] for f in doc["findings"] if f["code"] == "UL011")
    assert stale == ["urdf/a_copy.urdf", "urdf/robot.urdf", "urdf/variant.urdf"], \
        doc["findings"]


OTHER = '<robot name="o"><link name="a"/></robot>'


def test_undeclared_arg_is_a_located_warning(tmp_path):
    """Item 12: a launch file's arg no xacro:arg declares (xacro accepts it) is a UL008
    warning at the config line, and the other models are still linted (it was exit 2)."""
    src = f"""<robot name="r" {X}>
  <xacro:arg name="use_gripper" default="false"/>
  <link name="base"/>
</robot>
"""
    pkg = make_package(tmp_path, "launchargs", {"urdf/r.urdf.xacro": src,
                                                "urdf/other.urdf": OTHER})
    (pkg / "urdf-lint.toml").write_text('[[models]]\npath = "urdf/r.urdf.xacro"\n'
                                        'args = [{ use_gripper = "true", sim_mode = "false" }]\n')
    p = run_cli("check", ".", "--no-cache", "--format", "json", cwd=pkg)   # the config's
    assert p.returncode == 0, p.stderr
    doc = json.loads(p.stdout)
    (f,) = [f for f in doc["findings"] if f["code"] == "UL008"]
    assert (f["file"], f["line"], f["severity"]) == ("urdf-lint.toml", 3, "warning")
    assert "arg 'sim_mode' is not declared" in f["message"]
    assert len(doc["models"]) == 2


def test_missing_include_built_from_empty_args_names_them(tmp_path):
    """Item 10: `arms/$(arg arm)/$(arg dof)/urdf/$(arg arm)_macro.xacro` with arm and dof
    left empty: UL003 names the empty args and how to set them."""
    src = f"""<robot name="r" {X}>
  <xacro:arg name="arm" default=""/>
  <xacro:arg name="dof" default=""/>
  <xacro:include filename="$(find emptyargs)/arms/$(arg arm)/$(arg dof)/urdf/$(arg arm)_macro.xacro"/>
  <link name="base"/>
</robot>
"""
    pkg = make_package(tmp_path, "emptyargs", {"urdf/r.urdf.xacro": src})
    doc, _ = check_json(pkg)
    (f,) = [f for f in doc["findings"] if f["code"] == "UL003"]
    # (the path as every message shows it: relative, normalised; the args name the gap)
    assert "arms/urdf/_macro.xacro" in f["message"], f
    assert "args left empty: arm, dof" in f["message"] and "[[tool.urdf-lint.models]] args" in \
        f["message"], f


def _sleeper(job, settings):
    """A model that takes 2.5 s of wall-clock time and no CPU (a loaded machine, slow I/O);
    one named spin.urdf burns 30 s of CPU."""
    import time

    from conftest import carried
    if job.entry.endswith("spin.urdf"):
        t0 = time.process_time()
        while time.process_time() - t0 < 30:
            pass
    else:
        time.sleep(2.5)
    return carried(job, {"slept": True})


@pytest.mark.skipif(not os.path.exists("/proc/self/stat"), reason="needs /proc (CPU time)")
def test_time_limit_counts_cpu_time(tmp_path, monkeypatch):
    """Item 11: a job that waits (no CPU) longer than the limit is not killed; one that burns
    CPU past it is UL904."""
    from conftest import carried_data
    from urdf_lint.run import worker
    from urdf_lint.core.jobs import LintJob, LintSettings
    from urdf_lint.discovery.packages import PackageResolver
    monkeypatch.setattr(worker, "process_job", _sleeper)
    resolver = PackageResolver.build([str(tmp_path)], extra_roots=[str(tmp_path)])
    jobs = [LintJob(str(tmp_path / "wait.urdf"), kind="urdf"),
            LintJob(str(tmp_path / "spin.urdf"), kind="urdf")]
    got = {os.path.basename(j.entry): r for j, r in worker.run_jobs(
        jobs, LintSettings(resolver=resolver.to_dict(), timeout=1.0), jobs_n=2)}
    assert carried_data(got["wait.urdf"]) == {"slept": True}
    spin = got["spin.urdf"]
    assert [p.code for p in spin.problems] == ["UL904"], spin
    assert "1 s of CPU time" in spin.problems[0].message


def test_libraries_do_not_write_to_our_stderr(tmp_path):
    """Item 25: rendering a robot whose joint mimics itself (UL308) printed yourdfpy's
    "Joint 'spinner' is supposed to mimic 'spinner'" once per sweep step; only urdf-lint's own
    located lines reach the user."""
    pytest.importorskip("rerun")
    src = f"""<robot name="r" {X}>
  <link name="base"/><link name="wheel"/><link name="arm"/>
  <joint name="drive" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="spinner" type="continuous"><parent link="base"/><child link="wheel"/>
    <axis xyz="0 0 1"/><mimic joint="spinner"/></joint>
</robot>
"""
    pkg = make_package(tmp_path, "spin", {"urdf/r.urdf.xacro": src})
    p = run_cli("render", "urdf/r.urdf.xacro", "--out", tmp_path / "snap", cwd=pkg)
    assert list((tmp_path / "snap").glob("*.rrd")), p.stderr
    assert "supposed to mimic" not in p.stderr + p.stdout, p.stderr


def _ghost_mesh_robot(uri):
    return f"""<robot name="r" {X}>
  <link name="base"><visual><geometry><mesh filename="{uri}"/></geometry></visual></link>
</robot>
"""


def test_unknown_package_search_list(tmp_path):
    """Item 22: linting one file does not list "package.xml under <the .xacro>"; a
    workspace's src/ is listed; package:/// says it names no package."""
    from repo_shapes import colcon_workspace
    ws = colcon_workspace(tmp_path / "ws")
    entry = ws / "src/robot_description/urdf/robot.urdf.xacro"
    entry.write_text(entry.read_text().replace("package://robot_meshes/", "package://no_meshes/"))
    p = run_cli("check", str(entry), "--no-cache", "--isolated", "--format", "json", cwd=tmp_path)
    (f,) = [f for f in json.loads(p.stdout)["findings"] if f["code"] == "UL004"]
    assert ".xacro;" not in f["message"] and not f["message"].count(".xacro)"), f["message"]
    assert "package.xml under ws/src;" in f["message"], f["message"]   # relative (issue 22)
    pkg = make_package(tmp_path, "slashes", {"urdf/r.urdf.xacro":
                                             _ghost_mesh_robot("package:///meshes/a.stl")})
    doc, _ = check_json(pkg)
    (f,) = [f for f in doc["findings"] if f["code"] in ("UL004", "UL401")]
    assert "unknown package ''" not in f["message"] and "names no package" in f["message"], f


def test_sibling_package_outside_git_gets_a_package_path_hint(tmp_path):
    """Item 24: outside git, a package beside the linted path (under the working directory)
    is not a root (README says so now), and UL004 says how to name it."""
    make_package(tmp_path, "robot_description", {"urdf/r.urdf.xacro": _ghost_mesh_robot(
        "package://robot_meshes/meshes/body.stl")})
    make_package(tmp_path / "assets", "robot_meshes", {"meshes/body.stl": "solid x\nendsolid x\n"})
    p = run_cli("check", "robot_description", "--no-cache", "--isolated", "--format", "json",
                cwd=tmp_path)
    (f,) = [f for f in json.loads(p.stdout)["findings"] if f["code"] == "UL004"]
    want = "--package-path robot_meshes=assets/robot_meshes"   # relative to cwd (issue 22)
    assert f["message"].endswith(want), f["message"]


def test_mirrored_wheels_share_one_tensor(tmp_path):
    """Item 8: four identical wheels with mirrored meshes (wheel_left.stl / wheel_right.stl)
    rightly share one tensor: no UL608."""
    from urdf_lint.rules._meshes import TETRA_STL
    wheels = "".join(
        f"""  <link name="{n}_wheel"><inertial><mass value="2"/>
    <inertia ixx="0.01" iyy="0.02" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><mesh filename="package://cart/meshes/wheel_{side}.stl"/></geometry>
    </collision></link>
  <joint name="{n}_joint" type="continuous"><parent link="base"/><child link="{n}_wheel"/>
    <axis xyz="0 1 0"/></joint>
""" for n, side in (("fl", "left"), ("fr", "right"), ("rl", "left"), ("rr", "right")))
    src = f'<robot name="cart" {X}>\n  <link name="base"/>\n{wheels}</robot>\n'
    pkg = make_package(tmp_path, "cart", {"urdf/cart.urdf.xacro": src,
                                          "meshes/wheel_left.stl": TETRA_STL,
                                          "meshes/wheel_right.stl": TETRA_STL})
    doc, _ = check_json(pkg, "--select", "UL608")
    assert doc["findings"] == []
    # different parts (a wheel and a different mesh) with one tensor are still flagged
    (pkg / "meshes/arm.stl").write_text(TETRA_STL)
    f = pkg / "urdf/cart.urdf.xacro"
    f.write_text(f.read_text().replace("wheel_right.stl", "arm.stl", 1))
    doc, _ = check_json(pkg, "--select", "UL608")
    assert [x["code"] for x in doc["findings"]] == ["UL608"]


def test_undeclared_dependency_of_an_include(tmp_path):
    """Item 17: a macro included through $(find arm_description) from a package whose
    package.xml does not declare arm_description is UL012; declaring it (exec_depend) clears it."""
    arm = make_package(tmp_path, "arm_description", {"urdf/arm.xacro": f"""<robot {X}>
  <xacro:macro name="arm" params="parent">
    <link name="arm"/>
    <joint name="arm_joint" type="fixed"><parent link="${{parent}}"/><child link="arm"/></joint>
  </xacro:macro>
</robot>
"""})
    assert arm.is_dir()
    robot = make_package(tmp_path, "robot_description", {"urdf/robot.urdf.xacro": f"""<robot name="r" {X}>
  <xacro:include filename="$(find arm_description)/urdf/arm.xacro"/>
  <link name="base"/>
  <xacro:arm parent="base"/>
</robot>
"""})
    p = run_cli("check", ".", "--no-cache", "--isolated", "--format", "json", "--select", "UL012",
                cwd=tmp_path)
    (f,) = json.loads(p.stdout)["findings"]
    assert "package 'arm_description' is used but robot_description/package.xml does not " \
        "declare it" in f["message"], f
    pxml = robot / "package.xml"
    pxml.write_text(pxml.read_text().replace("</package>",
                                             "<exec_depend>arm_description</exec_depend></package>"))
    p = run_cli("check", ".", "--no-cache", "--isolated", "--format", "json", "--select", "UL012",
                cwd=tmp_path)
    assert json.loads(p.stdout)["findings"] == []


def _leg(collision: str, visual: str = "") -> str:
    return f"""<robot name="r" {X}>
  <link name="base"/>
  <link name="foot">
    <inertial><mass value="0.5"/>
      <inertia ixx="0.0005" iyy="0.0005" izz="0.0005" ixy="0" ixz="0" iyz="0"/></inertial>
    {visual}
    {collision}
  </link>
  <joint name="ankle" type="revolute"><parent link="base"/><child link="foot"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""


def test_physics_rules_skip_proxy_collision_shapes(tmp_path):
    """Item 7: four 5 mm contact spheres or a collision cylinder around only the motor are not
    the body: UL605-607 judge the link by its visual geometry, and say so, or skip it."""
    codes = "UL605,UL606,UL607"
    spheres = "".join(f'<collision><origin xyz="{x} {y} 0"/><geometry><sphere radius="0.005"/>'
                      '</geometry></collision>' for x in (-0.05, 0.05) for y in (-0.03, 0.03))
    # spheres and no visual: nothing to judge by (it was "implied density 2.4e+05 kg/m³")
    pkg = make_package(tmp_path, "contacts", {"urdf/r.urdf.xacro": _leg(spheres)})
    doc, _ = check_json(pkg, "--select", codes)
    assert doc["findings"] == [], doc["findings"]
    # spheres and a box visual that fits the declared inertia: judged against the visual
    body = '<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
    pkg = make_package(tmp_path, "contacts2", {"urdf/r.urdf.xacro": _leg(spheres, body)})
    doc, _ = check_json(pkg, "--select", codes)
    assert doc["findings"] == [], doc["findings"]
    # a cylinder around only the motor, and a visual body with a wrong (10 kg·m²) inertia:
    # reported against the visual, saying why
    motor = ('<collision><geometry><cylinder radius="0.01" length="0.02"/></geometry>'
             '</collision>')
    src = _leg(motor, body).replace('ixx="0.0005" iyy="0.0005" izz="0.0005"',
                                    'ixx="0.5" iyy="0.5" izz="0.5"')
    pkg = make_package(tmp_path, "motor", {"urdf/r.urdf.xacro": src})
    doc, _ = check_json(pkg, "--select", codes)
    (f,) = [f for f in doc["findings"] if f["code"] == "UL605"]
    assert "its visual geometry" in f["message"]
    assert "judged against the visual geometry: the collision shape covers only part of the " \
        "link" in f["message"], f["message"]


def test_args_left_at_defaults_that_select_variants_get_one_note(tmp_path):
    """Item 18: a robot whose args select variants (a gripper switch, an arm type in an include
    path), linted only with defaults: one info line naming the args and [[models]] args."""
    src = f"""<robot name="r" {X}>
  <xacro:arg name="use_gripper" default="false"/>
  <xacro:arg name="arm_type" default="small"/>
  <xacro:arg name="prefix" default=""/>
  <xacro:include filename="$(arg arm_type)_arm.xacro"/>
  <link name="$(arg prefix)base"/>
  <xacro:if value="$(arg use_gripper)"><link name="gripper"/></xacro:if>
</robot>
"""
    arm = f'<robot {X}><link name="arm"/></robot>\n'
    pkg = make_package(tmp_path, "variants", {"urdf/r.urdf.xacro": src,
                                              "urdf/small_arm.xacro": arm})
    # (with exploration off: on, the variants are linted instead of noted, test_explore.py)
    p = run_cli("check", ".", "--no-cache", "--isolated", "--explore", "false", cwd=pkg)
    notes = [ln for ln in p.stderr.splitlines() if "select variants" in ln]
    assert len(notes) == 1, p.stderr
    assert "(use_gripper, arm_type)" in notes[0] and "prefix" not in notes[0]
    assert "[[tool.urdf-lint.models]]" in notes[0]
    (pkg / "urdf-lint.toml").write_text('[[models]]\npath = "urdf/r.urdf.xacro"\n'
                                        'args = [{use_gripper = "true"}]\n')
    p = run_cli("check", ".", "--no-cache", cwd=pkg)
    assert "select variants" not in p.stderr, p.stderr


def test_the_variant_note_reads_each_shared_source_once_and_skips_explored_models(
        tmp_path, monkeypatch):
    """The note's scan (``variant_args``): three robots include one macro file, which is read
    once, not once per robot; an explored robot (``skip``) is neither scanned nor noted."""
    from urdf_lint.config.schema import load_config
    from urdf_lint.core import fsbound
    from urdf_lint.core.jobs import ModelReport, Status
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import variant_args
    macro = (f'<robot {X}><xacro:arg name="use_gripper" default="false"/>'
             '<xacro:macro name="arm"><link name="a"/></xacro:macro></robot>\n')
    files = {"urdf/arm.xacro": macro}
    for n in ("a", "b", "c"):
        files[f"urdf/{n}.urdf.xacro"] = (
            f'<robot name="{n}" {X}><xacro:arg name="sim_{n}" default="true"/>'
            f'<xacro:include filename="arm.xacro"/><xacro:arm/></robot>\n')
    pkg = make_package(tmp_path, "shared", files)
    cfg = load_config(None)
    resolver = build_resolver([str(pkg)], cfg)
    models = [ModelReport(str(pkg / f"urdf/{n}.urdf.xacro"), {}, Status.MODEL,
                          deps=[str(pkg / f"urdf/{n}.urdf.xacro"), str(pkg / "urdf/arm.xacro")])
              for n in ("a", "b", "c")]
    reads: list[str] = []
    real = fsbound.read_regular
    monkeypatch.setattr(fsbound, "read_regular",
                        lambda path, *a, **k: reads.append(os.path.basename(path)) or
                        real(path, *a, **k))
    got = variant_args(models, cfg, resolver, skip={models[1].entry})
    assert got == {models[0].entry: ["sim_a", "use_gripper"],
                   models[2].entry: ["sim_c", "use_gripper"]}
    assert sorted(reads) == ["a.urdf.xacro", "arm.xacro", "c.urdf.xacro"]


def test_diff_picture_marks_only_visible_changes_and_has_a_legend(tmp_path):
    """Item 23: a link drawn alike before and after (its mesh missing on both sides) is not
    marked changed; the difference image has a legend."""
    import numpy as np
    from PIL import Image

    from urdf_lint.render import raster

    def geom(z):
        tri = np.array([[[0, 0, 0], [0.2, 0, 0], [0, 0.2, z]]], float)
        wire = np.array([[x, y, w] for x in (0.5, 0.6) for y in (0, 0.1) for w in (0, 0.1)],
                        float)   # link b: a placeholder box (its mesh missing)
        return raster.Geometry("r", [tri], [np.full((1, 3), 0.7)], [wire],
                               np.zeros((2, 3)), 2, ["a"], ["b"])
    before, after = geom(0.0), geom(0.1)
    info = raster.render_pair(before, after, str(tmp_path / "x"), frozenset({"a", "b"}),
                              views="single")
    assert info["changed_pixels"] > 0                       # a moved
    same = raster.render_pair(before, before, str(tmp_path / "y"), frozenset({"b"}),
                              views="single")
    assert same["changed_pixels"] == 0
    img = np.asarray(Image.open(same["diff"]).convert("RGB")).astype(int)
    corner = img[-raster.LEGEND_H:, 8:19]
    assert ((corner[..., 0] > 200) & (corner[..., 1] < 40) & (corner[..., 2] > 130)).any(), \
        "the legend's magenta swatch"


def test_fragment_included_through_a_param_built_path_is_not_linted_alone(tmp_path):
    """Item 9: `${side}_arm.transmissions.urdf.xacro` included in a macro whose robot fails
    for lack of an arg: the fragment (which reads the macro's `name`) is not linted alone
    (it was UL002 "name 'name' is not defined" inside it)."""
    robot = f"""<robot name="$(arg robot_name)" {X}>
  <xacro:macro name="arm" params="side name">
    <link name="${{name}}_link"/>
    <xacro:include filename="${{side}}_arm.transmissions.urdf.xacro"/>
  </xacro:macro>
  <link name="base"/>
  <xacro:arm side="left" name="l"/>
</robot>
"""
    trans = f"""<robot {X}>
  <transmission name="${{name}}_trans"><joint name="${{name}}_joint"/></transmission>
</robot>
"""
    pkg = make_package(tmp_path, "arms", {"urdf/robot.urdf.xacro": robot,
                                          "urdf/left_arm.transmissions.urdf.xacro": trans})
    doc, _ = check_json(pkg)
    assert [f["code"] for f in doc["findings"]] == ["UL005"], doc["findings"]
    assert [m["entry"] for m in doc["models"]] == ["urdf/robot.urdf.xacro"]


def test_mesh_paths_of_a_fragment_start_where_its_includers_do(tmp_path):
    """Item 5: xacro/robot.xacro includes xacro/body.xacro (a complete robot by itself); the
    generated urdf/robot.urdf (header naming xacro/robot.xacro) has its meshes next to it
    (urdf/meshes/...). body.xacro linted on its own starts its relative mesh paths there too
    (it was UL401 "looked for .../xacro/meshes/...")."""
    from urdf_lint.rules._meshes import TETRA_STL
    body = f"""<robot name="body" {X}>
  <link name="base"/>
  <link name="shell"><visual><geometry><mesh filename="meshes/shell.stl"/></geometry></visual>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="shell_joint" type="fixed"><parent link="base"/><child link="shell"/></joint>
</robot>
"""
    robot = f"""<robot name="robot" {X}>
  <xacro:include filename="body.xacro"/>
</robot>
"""
    pkg = make_package(tmp_path, "meshy", {"xacro/robot.xacro": robot, "xacro/body.xacro": body,
                                           "urdf/meshes/shell.stl": TETRA_STL})
    p = run_cli("expand", "xacro/robot.xacro", "-o", "urdf/robot.urdf", cwd=pkg)
    assert p.returncode == 0, p.stderr
    doc, _ = check_json(pkg)
    assert "xacro/body.xacro" in [m["entry"] for m in doc["models"]]
    assert not [f for f in doc["findings"] if f["code"] in ("UL401", "UL004")], doc["findings"]


def test_mesh_base_above_a_file_linted_alone(tmp_path):
    """Item 5: a [[models]] mesh-base above the linted package (outside git): linting that one
    file finds the meshes there, not every mesh outside the roots (UL403)."""
    from urdf_lint.rules._meshes import TETRA_STL
    src = f"""<robot name="r" {X}>
  <link name="base"><visual><geometry><mesh filename="meshes/part.stl"/></geometry></visual>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
</robot>
"""
    make_package(tmp_path / "robots", "arm", {"urdf/arm.urdf.xacro": src})
    (tmp_path / "assets/meshes").mkdir(parents=True)
    (tmp_path / "assets/meshes/part.stl").write_text(TETRA_STL)
    (tmp_path / "urdf-lint.toml").write_text(
        '[[models]]\npath = "robots/arm/urdf/arm.urdf.xacro"\nmesh-base = "assets"\n')
    p = run_cli("check", "robots/arm/urdf/arm.urdf.xacro", "--no-cache", "--format", "json",
                cwd=tmp_path)
    doc = json.loads(p.stdout)
    assert not [f for f in doc["findings"] if f["code"].startswith("UL40")], doc["findings"]


def _siblings(tmp_path):
    """urdf/a.urdf.xacro and urdf/b.urdf.xacro both call a macro of urdf/macros.xacro that
    writes a relative mesh path (from urdf/); only a has a checked-in generated URDF, one
    folder deeper (generated/robots/a.urdf, its header naming urdf/a.urdf.xacro)."""
    from urdf_lint.rules._meshes import TETRA_STL
    macros = f"""<robot {X}>
  <xacro:macro name="part" params="n">
    <link name="${{n}}"><visual><geometry><mesh filename="../meshes/part.stl"/></geometry></visual>
      <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  </xacro:macro>
</robot>
"""
    entry = f"""<robot name="{{}}" {X}>
  <xacro:include filename="macros.xacro"/>
  <xacro:part n="base"/>
</robot>
"""
    pkg = make_package(tmp_path, "siblings", {
        "urdf/macros.xacro": macros, "urdf/a.urdf.xacro": entry.format("a"),
        "urdf/b.urdf.xacro": entry.format("b"), "meshes/part.stl": TETRA_STL})
    (pkg / "generated/robots").mkdir(parents=True)
    p = run_cli("expand", "urdf/a.urdf.xacro", "-o", "generated/robots/a.urdf", cwd=pkg)
    assert p.returncode == 0, p.stderr
    assert "urdf/a.urdf.xacro" in (pkg / "generated/robots/a.urdf").read_text()
    return pkg


def test_sibling_models_resolve_a_shared_macro_mesh_alike(tmp_path):
    """Item 6: the model with a generated URDF started the macro's relative mesh path from
    generated/robots/ (UL401 "looked for generated/meshes/part.stl") while its sibling found
    it from urdf/. Both find it; the one whose base was assumed says so once (UL411, info),
    naming both folders and the mesh-base key."""
    pkg = _siblings(tmp_path)
    doc, _ = check_json(pkg)
    assert not [f for f in doc["findings"] if f["code"] == "UL401"], doc["findings"]
    (note,) = [f for f in doc["findings"] if f["code"] == "UL411"]
    assert note["severity"] == "info" and note["file"] == "urdf/macros.xacro", note
    assert "generated/robots/" in note["message"] and "urdf/," in note["message"], note
    assert "'mesh-base'" in note["message"], note


def test_configured_mesh_base_is_not_second_guessed(tmp_path):
    """Item 6: a mesh-base the config sets is where relative paths start, found or not: no
    fallback to the xacro's folder (UL401 stays), and no UL411 once it is right."""
    pkg = _siblings(tmp_path)
    cfg = '[[models]]\npath = "urdf/a.urdf.xacro"\nmesh-base = "{}"\n'
    (pkg / "urdf-lint.toml").write_text(cfg.format("generated/robots"))
    doc = json.loads(run_cli("check", ".", "--no-cache", "--format", "json", cwd=pkg).stdout)
    codes = [f["code"] for f in doc["findings"]]
    assert "UL401" in codes and "UL411" not in codes, doc["findings"]
    (pkg / "urdf-lint.toml").write_text(cfg.format("urdf"))
    doc = json.loads(run_cli("check", ".", "--no-cache", "--format", "json", cwd=pkg).stdout)
    assert not [f for f in doc["findings"] if f["code"] in ("UL401", "UL411")], doc["findings"]


def test_stale_generated_urdf_names_its_first_difference(tmp_path):
    """Item 8: UL011 said "<robot 'r'> differs" or "<origin> differs". A checked-in URDF that
    differs only in how a number is written says so, with the element path and both values;
    one with an extra (unused) material names that, not the number formatting."""
    src = f"""<robot name="r" {X}>
  <link name="a"/>
  <link name="b"/>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/>
    <origin xyz="0 0 0.1"/></joint>
</robot>
"""
    pkg = make_package(tmp_path, "stale", {"urdf/r.urdf.xacro": src})
    p = run_cli("expand", "urdf/r.urdf.xacro", "-o", "urdf/r.urdf", cwd=pkg)
    assert p.returncode == 0, p.stderr
    out = pkg / "urdf/r.urdf"
    text = out.read_text()
    assert 'xyz="0 0 0.1"' in text
    out.write_text(text.replace('xyz="0 0 0.1"', 'xyz="0 0 0.10"'))
    doc, _ = check_json(pkg)
    (f,) = [f for f in doc["findings"] if f["code"] == "UL011"]
    assert "only number formatting differs: <joint 'j'> > <origin> xyz: '0 0 0.10' in the " \
        "file, '0 0 0.1' from the xacro" in f["message"], f
    out.write_text(out.read_text().replace(
        '<link name="a"/>', '<material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>'
        '<link name="a"/>'))
    doc, _ = check_json(pkg)
    (f,) = [f for f in doc["findings"] if f["code"] == "UL011"]
    assert "(<material 'grey'> is in the file, not in what the xacro gives)" \
        in f["message"], f


def test_load_yaml_of_a_folder_built_from_an_empty_arg_names_it(tmp_path):
    """Item 8: `load_yaml('$(find pkg)/config/$(arg limits_file)')` with the arg left empty
    said "YAML file not found: config" (a folder that exists); it says the path names a
    folder and which arg is empty."""
    src = f"""<robot name="r" {X}>
  <xacro:arg name="limits_file" default=""/>
  <xacro:property name="lim" value="${{xacro.load_yaml('$(find yarg)/config/$(arg limits_file)')}}"/>
  <link name="base"/>
  <link name="l${{lim['a']}}"/>
  <joint name="j" type="fixed"><parent link="base"/><child link="l1"/></joint>
</robot>
"""
    pkg = make_package(tmp_path, "yarg", {"urdf/r.urdf.xacro": src,
                                          "config/limits.yaml": "a: 1\n"})
    doc, _ = check_json(pkg)
    (f,) = [f for f in doc["findings"] if f["code"] == "UL003"]
    assert "YAML file path names a folder, not a file: config" in f["message"], f
    assert "args left empty: limits_file" in f["message"], f
    (pkg / "urdf-lint.toml").write_text('[[models]]\npath = "urdf/r.urdf.xacro"\n'
                                        'args = [{limits_file = "limits.yaml"}]\n')
    p = run_cli("check", ".", "--no-cache", "--format", "json", cwd=pkg)
    assert not [f for f in json.loads(p.stdout)["findings"] if f["code"] == "UL003"], p.stdout
