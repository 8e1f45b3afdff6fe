"""Zero false errors and the physics checks (issue 11): one small fixture per class of false
finding or miss, end to end through the CLI, plus the physical plausibility rules checked
against inertias computed by hand."""
from __future__ import annotations

import json

import pytest

from conftest import DESCRIPTIONS, make_package, run_cli, run_main
from urdf_lint.rules._meshes import BROKEN_SURFACE_DAE, TETRA_STL

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
LIMIT = '<limit lower="-1" upper="1" effort="1" velocity="1"/>'


def lint(pkg, *extra, fail_on="never"):
    p = run_main("check", ".", "--no-cache", "--format", "json", "--fail-on", fail_on, *extra,
                cwd=pkg)
    assert p.returncode in (0, 1), p.stderr
    return json.loads(p.stdout)["findings"]


def only(fs, code):
    return [f for f in fs if f["code"] == code]


def pkg_with(tmp_path, body, name="urdf/r.urdf", files=None):
    return make_package(tmp_path, "p", {name: body, **(files or {})})


def inertial(mass, i=(0, 0, 0)):
    return (f'<inertial><mass value="{mass}"/><inertia ixx="{i[0]}" ixy="0" ixz="0" '
            f'iyy="{i[1]}" iyz="0" izz="{i[2]}"/></inertial>')


# -- 1. UL602 on massless frames ----------------------------------------------------------------
def test_massless_sensor_frame_on_fixed_joint_is_valid(tmp_path):
    body = f"""<robot name="r">
  <link name="base"/>
  <link name="arm">{inertial(1, (0.01, 0.01, 0.01))}</link>
  <link name="camera_optical_frame">{inertial(0)}</link>
  <link name="tool0">{inertial(0)}</link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>{LIMIT}</joint>
  <joint name="cam" type="fixed"><parent link="arm"/><child link="camera_optical_frame"/></joint>
  <joint name="flange" type="fixed"><parent link="camera_optical_frame"/><child link="tool0"/></joint>
</robot>"""
    assert not only(lint(pkg_with(tmp_path, body)), "UL602")


def test_massless_moving_body_is_an_error(tmp_path):
    # 'paddle' moves and only massless frames are fixed to it: the whole body has no mass
    body = f"""<robot name="r">
  <link name="base"/>
  <link name="paddle">{inertial(0)}</link>
  <link name="paddle_tip">{inertial(0)}</link>
  <link name="heavy">{inertial(2, (0.01, 0.01, 0.01))}</link>
  <link name="frame_on_heavy">{inertial(0)}</link>
  <joint name="j" type="revolute"><parent link="base"/><child link="paddle"/><axis xyz="0 0 1"/>{LIMIT}</joint>
  <joint name="tip" type="fixed"><parent link="paddle"/><child link="paddle_tip"/></joint>
  <joint name="j2" type="revolute"><parent link="base"/><child link="heavy"/><axis xyz="0 0 1"/>{LIMIT}</joint>
  <joint name="f" type="fixed"><parent link="heavy"/><child link="frame_on_heavy"/></joint>
</robot>"""
    fs = only(lint(pkg_with(tmp_path, body)), "UL602")
    assert sorted(f["message"].split("'")[1] for f in fs) == ["paddle", "paddle_tip"]
    assert all(f["severity"] == "error" and "joint 'j'" in f["message"] for f in fs)


def test_massless_intermediate_body_is_a_warning(tmp_path):
    # a universal joint as two revolutes: the cross between them is massless, the leg is not
    body = f"""<robot name="r">
  <link name="base"/>
  <link name="cross">{inertial(0)}</link>
  <link name="leg">{inertial(3, (0.02, 0.02, 0.005))}</link>
  <joint name="yaw" type="revolute"><parent link="base"/><child link="cross"/><axis xyz="0 0 1"/>{LIMIT}</joint>
  <joint name="roll" type="revolute"><parent link="cross"/><child link="leg"/><axis xyz="1 0 0"/>{LIMIT}</joint>
</robot>"""
    fs = only(lint(pkg_with(tmp_path, body)), "UL602")
    assert len(fs) == 1 and fs[0]["severity"] == "warning" and "'cross'" in fs[0]["message"]
    assert "MuJoCo and Gazebo refuse" in fs[0]["message"]


def test_negative_mass_is_always_an_error(tmp_path):
    body = f'<robot name="r"><link name="a">{inertial(-1, (1, 1, 1))}</link></robot>'
    fs = only(lint(pkg_with(tmp_path, body)), "UL602")
    assert len(fs) == 1 and "must not be negative" in fs[0]["message"]


# -- 2. UL404 on a valid DAE with a broken internal reference -----------------------------------
def test_dae_with_dangling_surface_is_not_empty(tmp_path):
    body = ('<robot name="r"><link name="a"><visual><geometry>'
            '<mesh filename="package://p/meshes/skin.dae"/></geometry></visual></link></robot>')
    pkg = pkg_with(tmp_path, body, files={"meshes/skin.dae": BROKEN_SURFACE_DAE})
    fs = lint(pkg)
    assert not only(fs, "UL404"), fs
    broken = only(fs, "UL408")
    assert len(broken) == 1 and "Missing surface skin-surface" in broken[0]["message"]
    assert broken[0]["severity"] == "warning"


def test_lenient_dae_load_keeps_the_geometry(tmp_path):
    from urdf_lint.meshes import resolve as meshes
    p = tmp_path / "skin.dae"
    p.write_text(BROKEN_SURFACE_DAE)
    facts = meshes.mesh_facts(str(p))
    assert facts["ok"] and facts["vertices"] > 0 and facts["faces"] == 4
    assert facts["broken_refs"] and "DaeBrokenRefError: Missing surface" in facts["broken_refs"][0]


def test_loader_errors_name_their_type_once():
    import collada
    from urdf_lint.meshes.resolve import error_text
    msg = error_text(collada.common.DaeMalformedError("Corrupted index in triangleset"))
    assert msg == "DaeMalformedError: Corrupted index in triangleset"
    assert error_text(ValueError("bad")) == "ValueError: bad"


# -- 3. rules about URDF elements stay out of <gazebo> (SDF) ------------------------------------
def test_sdf_inside_gazebo_is_not_urdf(tmp_path):
    body = """<robot name="r">
  <link name="a"><visual><geometry><box size="1 1 1"/></geometry><material name="nope"/></visual></link>
  <gazebo reference="a">
    <visual><material><ambient>0.1 0.1 0.1 1</ambient><script><name>Gazebo/Red</name></script></material></visual>
    <collision><geometry><box><size>1 1 1</size></box></geometry></collision>
    <material>Gazebo/Red</material>
  </gazebo>
  <gazebo><plugin name="x" filename="libx.so"><origin>a b</origin></plugin></gazebo>
</robot>"""
    fs = lint(pkg_with(tmp_path, body))
    undefined = only(fs, "UL502")
    # the URDF reference is still found; nothing inside <gazebo> is
    assert [f["line"] for f in undefined] == [2], undefined
    assert not [f for f in fs if f["line"] >= 3 and f["code"] in
                ("UL502", "UL503", "UL504", "UL205", "UL207", "UL208")], fs


def test_every_rule_walks_only_the_urdf_part():
    """No rule iterates the whole document by tag: they use _schema.urdf_iter or
    checked_elements, so <gazebo>/<ros2_control> content is never taken for URDF."""
    import pathlib
    import re
    rules = pathlib.Path(__file__).resolve().parents[1] / "rules"
    offenders = []
    for f in sorted(rules.glob("*.py")):
        text = f.read_text()
        for m in re.finditer(r"model\.root\.iter\((\"\w+\")?\)", text):
            if f.name in ("_schema.py", "ul702_ros2_control_joint.py", "ul701_transmission_joint.py"):
                continue  # the schema itself, and rules about the extension blocks
            offenders.append(f"{f.name}: {m.group(0)}")
    assert not offenders, offenders


# -- 4. UL304 effort="0" -------------------------------------------------------------------------
EFFORT0 = """<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="0" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="a"/><child link="c"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="-1"/></joint>
</robot>"""
# (j2 had velocity="0", an error until issue 25 made it a warning: every consumer loads it;
# tests/test_targets.py covers it. A negative velocity is still an error.)


def test_zero_effort_is_a_warning(tmp_path):
    fs = only(lint(pkg_with(tmp_path, EFFORT0), "--select", "UL304"), "UL304")
    sev = {f["message"].split("'")[1]: f["severity"] for f in fs}
    assert sev == {"j1": "warning", "j2": "error"}
    assert "ROS-Industrial convention" in next(f["message"] for f in fs if "'j1'" in f["message"])
    p = run_main("check", ".", "--no-cache", "--select", "UL304", cwd=pkg_with(tmp_path, EFFORT0))
    assert p.returncode == 1  # the velocity=0 error


def test_zero_effort_can_be_made_strict(tmp_path):
    pkg = pkg_with(tmp_path, EFFORT0, files={"pyproject.toml": (
        '[tool.urdf-lint]\nselect = ["UL304"]\n'
        '[tool.urdf-lint.rule-options.UL304]\nzero-effort = "error"\n')})
    fs = only(lint(pkg), "UL304")
    assert {f["severity"] for f in fs} == {"error"} and len(fs) == 2


# -- 5. wording ----------------------------------------------------------------------------------
def test_arg_declared_after_its_first_use(tmp_path):
    body = f"""<robot name="r" {X}>
  <link name="$(arg base_name)"/>
  <xacro:arg name="base_name" default="base_link"/>
</robot>"""
    fs = only(lint(pkg_with(tmp_path, body, name="urdf/r.urdf.xacro")), "UL005")
    assert len(fs) == 1 and "used before it is declared" in fs[0]["message"]
    assert "r.urdf.xacro:3" in fs[0]["message"] and "no default" not in fs[0]["message"]


def test_missing_arg_without_default_keeps_its_wording(tmp_path):
    body = f'<robot name="r" {X}><link name="$(arg base_name)"/></robot>'
    fs = only(lint(pkg_with(tmp_path, body, name="urdf/r.urdf.xacro")), "UL005")
    assert len(fs) == 1 and "has no default and no value was given" in fs[0]["message"]


def test_missing_yaml_says_yaml_file(tmp_path):
    body = f"""<robot name="r" {X}>
  <xacro:property name="cfg" value="${{xacro.load_yaml('missing.yaml')}}"/>
  <link name="${{cfg['name']}}"/>
</robot>"""
    fs = only(lint(pkg_with(tmp_path, body, name="urdf/r.urdf.xacro")), "UL003")
    assert len(fs) == 1 and fs[0]["message"].startswith("YAML file not found")
    inc = f'<robot name="r" {X}><xacro:include filename="nope.xacro"/><link name="a"/></robot>'
    fs = only(lint(pkg_with(tmp_path / "b", inc, name="urdf/r.urdf.xacro")), "UL003")
    assert len(fs) == 1 and fs[0]["message"].startswith("included file not found")


def test_anonymous_inline_materials_are_counted(tmp_path):
    vis = ('<visual><geometry><box size="1 1 1"/></geometry><material name="{n}">'
           '<color rgba="0 0 1 1"/></material></visual>')
    body = ('<robot name="r">'
            f'<link name="a">{vis.format(n="m1")}</link><link name="b">{vis.format(n="")}</link>'
            f'<link name="c">{vis.format(n="")}</link>'
            '<joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>'
            '<joint name="j2" type="fixed"><parent link="a"/><child link="c"/></joint></robot>')
    fs = only(lint(pkg_with(tmp_path, body), "--select", "UL504"), "UL504")
    assert len(fs) == 1 and "(names 'm1', 2 anonymous)" in fs[0]["message"]
    assert "''" not in fs[0]["message"]


def test_mimic_did_you_mean_never_names_the_joint_itself(tmp_path):
    body = """<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="finger_joint" type="continuous"><parent link="a"/><child link="b"/></joint>
  <joint name="finger_joint2" type="continuous"><parent link="a"/><child link="c"/><mimic joint="finger_joint3"/></joint>
</robot>"""
    fs = only(lint(pkg_with(tmp_path, body), "--select", "UL308"), "UL308")
    assert len(fs) == 1 and "did you mean 'finger_joint'?" in fs[0]["message"]
    assert "'finger_joint2'?" not in fs[0]["message"]


# -- 6. mass > 0 with an all-zero inertia tensor on a moving link --------------------------------
def test_massive_moving_link_with_zero_inertia(tmp_path):
    body = f"""<robot name="r">
  <link name="base"/>
  <link name="arm">{inertial(0.5)}</link>
  <link name="marker">{inertial(0.1)}</link>
  <link name="hand">{inertial(0.2)}</link>
  <link name="hand_pad">{inertial(0.1, (0.001, 0.001, 0.001))}</link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>{LIMIT}</joint>
  <joint name="m" type="fixed"><parent link="base"/><child link="marker"/></joint>
  <joint name="h" type="revolute"><parent link="base"/><child link="hand"/><axis xyz="0 0 1"/>{LIMIT}</joint>
  <joint name="pad" type="fixed"><parent link="hand"/><child link="hand_pad"/></joint>
</robot>"""
    fs = only(lint(pkg_with(tmp_path, body)), "UL603")
    # arm fires; marker is fixed to the root; hand's body gets inertia from its pad
    assert len(fs) == 1 and "'arm'" in fs[0]["message"] and "all-zero inertia" in fs[0]["message"]


# -- 7. unknown codes in suppression comments ----------------------------------------------------
SUPPRESSED = """<robot name="r">
  <link name="a"/>
  <!-- urdf-lint: disable-next UL999 -->
  <joint name="j1" type="fixed"><parent link="a"/><child link="x"/></joint>
  <!-- urdf-lint: disabel-next UL103 -->
  <joint name="j2" type="fixed"><parent link="a"/><child link="y"/></joint>
  <!-- urdf-lint: disable-next missing-lnk -->
  <joint name="j3" type="fixed"><parent link="a"/><child link="z"/></joint>
  <!-- urdf-lint: disable-next missing-link UL1 -->
  <joint name="j4" type="fixed"><parent link="a"/><child link="w"/></joint>
</robot>
"""


def test_unknown_suppression_codes_are_findings(tmp_path):
    fs = lint(pkg_with(tmp_path, SUPPRESSED))
    bad = {f["line"]: f for f in only(fs, "UL010")}
    assert sorted(bad) == [3, 5, 7]
    assert "unknown code 'UL999'" in bad[3]["message"] and "did you mean" in bad[3]["message"]
    assert "did you mean 'disable-next'?" in bad[5]["message"]
    assert "did you mean 'missing-link'?" in bad[7]["message"]
    assert all(f["severity"] == "warning" and f["models"] == [] for f in bad.values())
    # they suppress nothing: the UL103s are reported, and not also as unused suppressions
    assert sorted(f["line"] for f in only(fs, "UL103")) == [4, 6, 8]
    assert not only(fs, "UL009")


def test_invalid_suppression_is_selectable_and_suppressible(tmp_path):
    pkg = pkg_with(tmp_path, SUPPRESSED)
    assert not only(lint(pkg, "--ignore", "UL010"), "UL010")
    assert only(lint(pkg, "--select", "UL010"), "UL010")
    quiet = SUPPRESSED.replace("<robot name=\"r\">",
                               "<robot name=\"r\">\n  <!-- urdf-lint: disable-file UL010 -->")
    fs = lint(pkg_with(tmp_path / "q", quiet))
    assert not only(fs, "UL010") and not only(fs, "UL009")


# -- 8. physical plausibility --------------------------------------------------------------------
def arm(inr, collision, joint="revolute"):
    return f"""<robot name="r">
  <link name="base"/>
  <link name="arm">{inr}<collision>{collision}</collision></link>
  <joint name="j" type="{joint}"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>{LIMIT}</joint>
</robot>"""


CYL = '<origin xyz="0 0 0.15"/><geometry><cylinder radius="0.03" length="0.3"/></geometry>'


def test_inertia_matching_its_cylinder_is_clean(tmp_path):
    # solid cylinder m=2, r=0.03, h=0.3: axial m r²/2 = 0.0009, transverse m(3r²+h²)/12 = 0.01545
    body = arm(f'<inertial><origin xyz="0 0 0.15"/>{inertial(2, (0.01545, 0.01545, 0.0009))[10:]}', CYL)
    fs = lint(pkg_with(tmp_path, body), "--select", "UL6")
    assert not [f for f in fs if f["code"] in ("UL605", "UL606", "UL607", "UL608")], fs


def test_inertia_far_from_its_geometry(tmp_path):
    body = arm(inertial(2, (0.5, 0.5, 0.0009)), CYL)
    fs = only(lint(pkg_with(tmp_path, body)), "UL605")
    assert len(fs) == 1
    msg = fs[0]["message"]
    # the two transverse moments are 32x too big; the axial one is right and not named
    assert "largest principal moment" in msg and "0.5 vs 0.01545" in msg and "32.4x" in msg
    assert "smallest" not in msg


def test_inertia_band_is_an_option(tmp_path):
    body = arm(inertial(2, (0.05, 0.05, 0.0009)), CYL)   # 3.2x
    assert not only(lint(pkg_with(tmp_path, body)), "UL605")
    pkg = pkg_with(tmp_path / "strict", body, files={"pyproject.toml": (
        '[tool.urdf-lint.rule-options.UL605]\nmax-ratio = 2.0\n')})
    assert only(lint(pkg), "UL605")


def test_com_outside_geometry(tmp_path):
    body = arm(f'<inertial><origin xyz="0 0 0.6"/>{inertial(2, (0.01545, 0.01545, 0.0009))[10:]}', CYL)
    fs = only(lint(pkg_with(tmp_path, body)), "UL606")
    assert len(fs) == 1 and "along z" in fs[0]["message"] and "[0, 0.3]" in fs[0]["message"]


def test_com_inside_visual_but_outside_a_partial_collision(tmp_path):
    # the collision is a plate on top of the part; the visual is the whole part
    body = arm(f'<inertial><origin xyz="0 0 0.15"/>{inertial(2, (0.01545, 0.01545, 0.0009))[10:]}',
               '<origin xyz="0 0 0.29"/><geometry><box size="0.06 0.06 0.02"/></geometry>')
    body = body.replace("<collision>", f"<visual>{CYL}</visual><collision>")
    assert not only(lint(pkg_with(tmp_path, body)), "UL606")
    no_visual = body.replace(f"<visual>{CYL}</visual>", "")
    assert only(lint(pkg_with(tmp_path / "nv", no_visual)), "UL606")


def test_density_catches_grams(tmp_path):
    # a 5 cm cube: 1.25e-4 m³. 337 "kg" is 2.7e6 kg/m³ (337 g of aluminium)
    box = '<geometry><box size="0.05 0.05 0.05"/></geometry>'
    fs = only(lint(pkg_with(tmp_path, arm(inertial(337, (0.14, 0.14, 0.14)), box))), "UL607")
    assert len(fs) == 1 and "2.7e+06 kg/m³" in fs[0]["message"] and "grams" in fs[0]["message"]
    fs = only(lint(pkg_with(tmp_path / "ok", arm(inertial(0.337, (1.4e-4,) * 3), box))), "UL607")
    assert not fs


def test_mesh_in_millimetres_and_open_mesh_hull(tmp_path):
    from urdf_lint.rules._meshes import scaled
    # the tetrahedron 0.1 m: volume 0.1³/6 = 1.667e-4 m³; in millimetres x1e9
    mm = scaled(1000.0)
    open_tetra = "\n".join(TETRA_STL.split("facet normal 1 1 1")[0].splitlines()) + "\nendsolid tetra\n"
    geo = '<geometry><mesh filename="package://p/meshes/{f}"/></geometry>'
    files = {"meshes/mm.stl": mm, "meshes/open.stl": open_tetra}
    body = arm(inertial(0.3, (1e-4, 1e-4, 1e-4)), geo.format(f="mm.stl"))
    fs = only(lint(pkg_with(tmp_path, body, files=files)), "UL607")
    assert len(fs) == 1 and "millimetres" in fs[0]["message"]
    body = arm(inertial(300, (1, 1, 1.1)), geo.format(f="open.stl"))
    fs = only(lint(pkg_with(tmp_path / "o", body, files=files)), "UL607")
    assert len(fs) == 1 and "not watertight, so its convex hull was measured" in fs[0]["message"]


def test_placeholder_inertias(tmp_path):
    fs = only(lint(pkg_with(tmp_path, arm(inertial(1, (1, 1, 1)), CYL))), "UL608")
    assert len(fs) == 1 and "identity" in fs[0]["message"]
    links, joints = [], []
    for i, size in enumerate(("0.1 0.1 0.1", "0.2 0.1 0.1", "0.3 0.1 0.1")):
        links.append(f'<link name="l{i}">{inertial(1, (0.001, 0.001, 0.001))}'
                     f'<collision><geometry><box size="{size}"/></geometry></collision></link>')
        joints.append(f'<joint name="j{i}" type="continuous"><parent link="base"/>'
                      f'<child link="l{i}"/></joint>')
    body = '<robot name="r"><link name="base"/>' + "".join(links + joints) + "</robot>"
    fs = only(lint(pkg_with(tmp_path / "same", body)), "UL608")
    assert len(fs) == 1 and "all 3 moving links declare the same inertia" in fs[0]["message"]
    wheels = body.replace("0.2 0.1 0.1", "0.1 0.1 0.1").replace("0.3 0.1 0.1", "0.1 0.1 0.1")
    assert not only(lint(pkg_with(tmp_path / "wheels", wheels)), "UL608")


def test_mass_facts_are_cached_by_content(tmp_path):
    from urdf_lint.meshes import resolve as meshes
    p = tmp_path / "part.stl"
    p.write_text(TETRA_STL)
    from urdf_lint.meshes.store import FactsStore, MeshStore, register
    facts = FactsStore(str(tmp_path / "facts"), b"k" * 32)
    register(facts)      # (the run's parent opens the user's store: its workers read it)
    store = MeshStore(cache_dir=facts.dir)
    f = meshes.mass_facts(str(p), store=store)
    assert f["ok"] and not f["hull"] and f["volume"] == pytest.approx(0.1 ** 3 / 6, rel=1e-9)
    # measured here, stored by the parent (the reader never writes the store)
    assert not list((tmp_path / "facts").glob("mass*-*.json"))
    assert facts.accept(store.measured) >= 1
    assert list((tmp_path / "facts").glob("mass*-*.json"))


def test_broken_demo_shows_every_class():
    """The demo (`urdf-lint check descriptions/`) shows every rule firing on the broken models,
    but UL904 (a time or memory limit would make the demo wait for it), and the seeds pass."""
    from urdf_lint.engine.registry import load_rules
    p = run_cli("check", str(DESCRIPTIONS), "--no-cache", "--format", "json")
    assert p.returncode == 1, p.stderr
    doc = json.loads(p.stdout)
    fs = doc["findings"]
    assert not [f for f in fs if "/broken/" not in f["file"]], "the seed robots must pass"
    assert len([m for m in doc["models"] if "/broken/" not in m["entry"]]) == 2
    missing = sorted(set(load_rules()) - {f["code"] for f in fs})
    # a rule off for the default target (ros) fires when the demo is run for its targets
    from urdf_lint.core.targets import applies
    off = sorted(c for c, r in load_rules().items() if not applies(r.targets, r.severity, ["ros"]))
    assert missing == sorted(["UL904", *off]), missing
    targets = sorted({t for c in off for t, s in load_rules()[c].targets.items()
                      if t != "*" and s != "off"})
    p = run_cli("check", str(DESCRIPTIONS), "--no-cache", "--format", "json", "--target",
                ",".join(targets))
    assert sorted({f["code"] for f in json.loads(p.stdout)["findings"]} & set(off)) == off
    assert not [f for f in only(fs, "UL602") if "camera_optical_frame" in f["message"]]
    # the valid meshes load (no false UL404): only the truncated STL is unloadable
    assert {f["message"].split("'")[1].rsplit("/", 1)[-1] for f in only(fs, "UL404")} == \
        {"cover_truncated.stl"}
    assert not [f for f in only(fs, "UL502") if "materials.urdf.xacro" in f["file"]
                and f["line"] > 20]
    # the README's demo paragraph says what this run shows
    import re
    readme = (DESCRIPTIONS.parent / "README.md").read_text()
    s = doc["summary"]
    fired = len(set(load_rules()) - set(missing))
    said = re.search(r"It lints (\d+) models: .*?\smake\s+(\d+)\s+of\s+the\s+(\d+)\s+rules\s+fire"
                     r"\s.*?`Found (\d+) problem\(s\) \((\d+) error, (\d+) warning, (\d+) info\)"
                     r"\s+in (\d+) model\(s\)\.`", readme, re.S)
    assert said, "README's demo paragraph not found"
    assert [int(x) for x in said.groups()] == [
        len(doc["models"]), fired, len(load_rules()), len(fs), s["errors"], s["warnings"],
        s["info"], s["models"]], said.group(0)


def test_geometry_moments_follow_scale_rotation_and_offset(tmp_path):
    """The link-frame inertia of a scaled, rotated, offset mesh plus a box equals trimesh's own
    answer for the same solids moved into place."""
    import numpy as np
    import trimesh
    from urdf_lint.engine.lint import Context
    from urdf_lint.engine.model import Model, parse_urdf_bytes
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.rules._physics import link_geometry, rotation
    body = """<robot name="r"><link name="a">
  <collision><origin xyz="0.1 -0.2 0.3" rpy="0.3 0.2 0.1"/>
    <geometry><mesh filename="package://p/meshes/part.stl" scale="2 1 0.5"/></geometry></collision>
  <collision><origin xyz="0 0 -0.2" rpy="0 0.5 0"/><geometry><box size="0.1 0.2 0.05"/></geometry></collision>
</link></robot>"""
    pkg = pkg_with(tmp_path, body, files={"meshes/part.stl": TETRA_STL})
    entry = str(pkg / "urdf/r.urdf")
    root, origins, _ = parse_urdf_bytes(entry, body.encode())
    model = Model(entry=entry, args={}, root=root, origins=origins, deps=[entry],
                  resolver=PackageResolver.build([str(pkg)], extra_roots=[str(pkg)]))
    g = link_geometry(model, Context({}, None), model.links["a"], np)

    def placed(mesh, xyz, rpy):
        t = np.eye(4)
        t[:3, :3] = rotation(rpy, np)
        t[:3, 3] = xyz
        return mesh.apply_transform(t)
    tetra = trimesh.load(str(pkg / "meshes/part.stl"))
    tetra = trimesh.Trimesh(tetra.vertices * [2, 1, 0.5], tetra.faces)
    if tetra.volume < 0:
        tetra.invert()  # the example STL is wound inside out; urdf-lint flips such meshes too
    both = trimesh.util.concatenate([
        placed(tetra, (0.1, -0.2, 0.3), (0.3, 0.2, 0.1)),
        placed(trimesh.creation.box(extents=(0.1, 0.2, 0.05)), (0, 0, -0.2), (0, 0.5, 0))])
    both.density = 3.0 / both.volume
    assert g.volume == pytest.approx(both.volume, rel=1e-9)
    assert g.com == pytest.approx(both.center_mass, abs=1e-12)
    assert g.inertia(3.0) == pytest.approx(both.moment_inertia, rel=1e-9, abs=1e-15)


def test_dae_losing_only_some_instances_is_loaded_whole(tmp_path):
    """A broken material binding drops just the instance bound to it: the mesh is not empty,
    but half of it is missing. The geometry is still loaded whole, and the reference reported."""
    from urdf_lint.meshes import resolve as meshes
    second = ('<node id="t2" name="t2" type="NODE"><matrix sid="transform">1 0 0 0.5 0 1 0 0 '
              '0 0 1 0 0 0 0 1</matrix><instance_geometry url="#tetra-mesh" name="t2"/></node>\n'
              '    </visual_scene>')
    p = tmp_path / "partial.dae"
    p.write_text(BROKEN_SURFACE_DAE.replace("</visual_scene>", second))
    facts = meshes.mesh_facts(str(p))
    assert facts["vertices"] == 8 and facts["bounds"][1][0] == pytest.approx(0.6)
    assert facts["broken_refs"]


def test_readme_numbers_are_the_demos():
    """The README's numbers about the demo (models linted, rules that fire, the summary line)
    are those of a real run of the command it shows, so they cannot go stale (issue 22)."""
    import re
    from conftest import REPO
    from urdf_lint.engine.registry import load_rules
    readme = (REPO / "README.md").read_text()
    p = run_cli("check", "descriptions/", "--no-cache", cwd=REPO)
    assert p.returncode == 1, p.stderr
    summary = p.stdout.splitlines()[-1]
    assert re.fullmatch(r"Found \d+ problem\(s\) \(\d+ error, \d+ warning, \d+ info\) in \d+ "
                        r"model\(s\)\.", summary), summary
    assert f"`{summary}`" in readme.replace("\n", " "), \
        f"README.md's demo summary is stale; the demo now ends with: {summary}"
    models = int(re.search(r"in (\d+) model", summary).group(1))
    fired = {m.group(1) for m in re.finditer(r"^\S+:\d+:\d+: (UL\d{3}) ", p.stdout, re.M)}
    rules = load_rules()
    said = re.search(r"It lints (\d+) models: .*?\s+make\s+(\d+)\s+of\s+the\s+(\d+)\s+rules\s+fire",
                     readme, re.S)
    assert said, "README.md no longer says how many models the demo lints and rules fire"
    assert tuple(int(x) for x in said.groups()) == (models, len(fired), len(rules)), \
        (f"README.md says {said.group(0)!r}; the demo lints {models} models and "
         f"{len(fired)} of the {len(rules)} rules fire")
    # the paragraph is generated from a run by scripts/gen_docs.py: a new rule or broken model
    # changes it by running the script, not by hand
    from support.scripts import load_script
    gen = load_script("gen_docs")
    assert gen.render(readme, demo=True) == readme, \
        "README.md's demo paragraph is stale: run python scripts/gen_docs.py"
    checking = (REPO / "docs" / "checking.md").read_text()   # the demo's value from YAML
    assert gen.render(checking, demo=True, names={"demo-yaml"}) == checking, \
        "docs/checking.md's demo example is stale: run python scripts/gen_docs.py"
