"""A value read from YAML is located at its YAML line through the patterns real descriptions
use (issue 33): a property holding the loaded dict or a sub-dict (UR), item and attribute
access, a macro parameter carrying a dict (Franka, per-link macros), arithmetic; the finding
names the YAML line in every format, the hook counts it for a YAML commit, and ``--fix`` edits
the YAML scalar when the value is written there (and only then)."""
from __future__ import annotations

import json
import subprocess

from conftest import make_package, run_main

PKG = "arm_description"

UR_YAML = """# UR-style joint limits
joint_limits:
  shoulder:
    min_position: 1.5   # swapped on purpose
    max_position: -1.5
  elbow: {min_position: -3.0, max_position: 3.0}
"""
# UR: a macro reads the file, a property holds one joint's sub-dict, attribute and item access
UR = """<?xml version="1.0"?>
<robot name="ur" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm" params="limits_file">
    <xacro:property name="config" value="${xacro.load_yaml(limits_file)}"/>
    <xacro:property name="sec" value="${config['joint_limits']}"/>
    <link name="base"/>
    <xacro:macro name="rev" params="name">
      <xacro:property name="lim" value="${sec[name]}"/>
      <link name="${name}_link"/>
      <joint name="${name}" type="revolute">
        <parent link="base"/><child link="${name}_link"/><axis xyz="0 0 1"/>
        <limit lower="${lim.min_position}" upper="${lim['max_position']}" effort="1" velocity="1"/>
      </joint>
    </xacro:macro>
    <xacro:rev name="shoulder"/>
    <xacro:rev name="elbow"/>
  </xacro:macro>
  <xacro:arm limits_file="$(find arm_description)/config/limits.yaml"/>
</robot>
"""
# Franka: the dict is a macro parameter; per-link macro: a dict of link properties
FRANKA = """<?xml version="1.0"?>
<robot name="fr" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="cfg" value="${load_yaml('../config/limits.yaml')}"/>
  <xacro:macro name="hinge" params="name ext">
    <link name="${name}_link"/>
    <joint name="${name}" type="revolute">
      <parent link="base"/><child link="${name}_link"/><axis xyz="0 0 1"/>
      <limit lower="${ext['min_position']}" upper="${ext['max_position']}" effort="1" velocity="1"/>
    </joint>
  </xacro:macro>
  <link name="base"/>
  <xacro:hinge name="shoulder" ext="${cfg['joint_limits']['shoulder']}"/>
</robot>
"""
ARITH = FRANKA.replace("lower=\"${ext['min_position']}\"", "lower=\"${ext['min_position'] * 1.0}\"")


def _lint(pkg, *args):
    p = run_main("check", ".", "--no-cache", "--output-format", "json", *args, cwd=pkg)
    assert p.returncode in (0, 1), p.stderr
    return json.loads(p.stdout)["findings"]


def _ul302(findings):
    return [f for f in findings if f["code"] == "UL302"]


def test_ur_style_property_sub_dict_names_the_yaml_line(tmp_path):
    pkg = make_package(tmp_path, PKG, {"config/limits.yaml": UR_YAML,
                                       "urdf/ur.urdf.xacro": UR})
    (f,) = _ul302(_lint(pkg))
    assert f["file"].endswith("urdf/ur.urdf.xacro") and f["line"] == 12
    assert f["value_from"][0].endswith("config/limits.yaml") and f["value_from"][1] == 4, f
    text = run_main("check", ".", "--no-cache", cwd=pkg).stdout
    assert "value from config/limits.yaml:4" in text, text
    sarif = json.loads(run_main("check", ".", "--no-cache", "--output-format", "sarif",
                                cwd=pkg).stdout)
    res = [r for r in sarif["runs"][0]["results"] if r["ruleId"] == "UL302"]
    rel = [r["physicalLocation"] for r in res[0]["relatedLocations"]
           if r["physicalLocation"]["artifactLocation"]["uri"].endswith("config/limits.yaml")]
    assert [r["region"]["startLine"] for r in rel] == [4], res[0]["relatedLocations"]


def test_franka_style_macro_parameter_dict_names_the_yaml_line(tmp_path):
    pkg = make_package(tmp_path, PKG, {"config/limits.yaml": UR_YAML,
                                       "urdf/fr.urdf.xacro": FRANKA})
    (f,) = _ul302(_lint(pkg))
    assert f["value_from"][0].endswith("config/limits.yaml") and f["value_from"][1] == 4, f


def test_fix_swaps_the_yaml_scalars_keeping_comments_and_flow_style(tmp_path):
    pkg = make_package(tmp_path, PKG, {"config/limits.yaml": UR_YAML,
                                       "urdf/ur.urdf.xacro": UR})
    p = run_main("check", ".", "--no-cache", "--fix", cwd=pkg)
    assert "Fixed 1 finding" in p.stderr, p.stderr
    assert (pkg / "config/limits.yaml").read_text() == UR_YAML.replace(
        "min_position: 1.5   #", "min_position: -1.5   #").replace(
        "max_position: -1.5\n", "max_position: 1.5\n")
    assert (pkg / "urdf/ur.urdf.xacro").read_text() == UR
    assert not _ul302(_lint(pkg))


def test_fix_swaps_unit_tagged_yaml_scalars_in_their_unit(tmp_path):
    """The real UR writes its limits as ``!degrees  360.0`` (xacro reads them in radians).
    ``--fix`` writes the swapped limits back in degrees, after the tag, only the numbers'
    bytes changed; it refused before ("the literal '370.0' is not the expanded value")."""
    yml = UR_YAML.replace("min_position: 1.5   #", "min_position: !degrees  370.0   #").replace(
        "max_position: -1.5\n", "max_position: !degrees -12.5\n")
    pkg = make_package(tmp_path, PKG, {"config/limits.yaml": yml, "urdf/ur.urdf.xacro": UR})
    (f,) = _ul302(_lint(pkg))
    assert f["value_from"][1] == 4, f
    p = run_main("check", ".", "--no-cache", "--fix", cwd=pkg)
    assert "Fixed 1 finding" in p.stderr, p.stderr
    assert (pkg / "config/limits.yaml").read_text() == yml.replace(
        "!degrees  370.0   #", "!degrees  -12.5   #").replace(
        "!degrees -12.5\n", "!degrees 370.0\n")
    assert not _ul302(_lint(pkg))


def test_a_grouped_finding_names_each_yaml_line_its_instances_come_from(tmp_path):
    """Two joints of one macro line, each with its limits swapped in its own YAML line: one
    finding "in 2 joints", and the text names both lines (it named none: the instances'
    values come from different places)."""
    yml = UR_YAML.replace("{min_position: -3.0, max_position: 3.0}",
                          "{min_position: 3.0, max_position: -3.0}")
    pkg = make_package(tmp_path, PKG, {"config/limits.yaml": yml, "urdf/ur.urdf.xacro": UR})
    (f,) = _ul302(_lint(pkg))
    assert sorted(i["value_from"][1] for i in f["instances"]) == [4, 6], f
    for fmt in ("text", "github", "concise"):
        out = run_main("check", ".", "--no-cache", "--output-format", fmt, cwd=pkg).stdout
        assert "values from config/limits.yaml:4, config/limits.yaml:6" in out, (fmt, out)


def test_a_unit_literal_is_the_shortest_number_read_back_exactly():
    import math
    from urdf_lint.fix.fixes import Refuse, YamlScalar, unit_literal
    deg = YamlScalar("-360.0", 0, 6, "", "!degrees")
    assert unit_literal(deg, str(math.radians(-360.0)), str(math.radians(360.0))) == "360.0"
    assert unit_literal(deg, str(math.radians(-360.0)), str(math.radians(-13.75))) == "-13.75"
    mm = YamlScalar("5", 0, 1, "", "!millimeters")
    assert unit_literal(mm, "0.005", "0.25") == "250"
    for expanded in ("0.1", None):                       # not what the literal gives
        try:
            unit_literal(deg, expanded, "1.0")
        except Refuse:
            pass
        else:
            raise AssertionError(expanded)
    try:
        unit_literal(YamlScalar("pi", 0, 2, "", "!degrees"), "0.05", "1.0")   # an expression
    except Refuse:
        pass
    else:
        raise AssertionError("an expression is not written back")


def test_a_value_computed_from_yaml_is_located_but_not_written_back(tmp_path):
    pkg = make_package(tmp_path, PKG, {"config/limits.yaml": UR_YAML,
                                       "urdf/fr.urdf.xacro": ARITH})
    (f,) = _ul302(_lint(pkg))
    assert f["value_from"][0].endswith("config/limits.yaml") and f["value_from"][1] == 4, f
    assert f["fix"].get("refused"), f["fix"]
    run_main("check", ".", "--no-cache", "--fix", cwd=pkg)
    assert (pkg / "config/limits.yaml").read_text() == UR_YAML


def test_per_link_macro_dict_locates_a_mass(tmp_path):
    yaml = "links:\n  upper_arm:\n    mass: -2.0\n    size: 0.1\n"
    xacro = """<?xml version="1.0"?>
<robot name="m" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="params" value="${load_yaml('../config/links.yaml')}"/>
  <xacro:macro name="solid" params="name props">
    <link name="${name}">
      <inertial>
        <mass value="${props['mass']}"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
      </inertial>
    </link>
  </xacro:macro>
  <link name="base"/>
  <joint name="j" type="fixed"><parent link="base"/><child link="upper_arm"/></joint>
  <xacro:solid name="upper_arm" props="${params['links']['upper_arm']}"/>
</robot>
"""
    pkg = make_package(tmp_path, PKG, {"config/links.yaml": yaml, "urdf/m.urdf.xacro": xacro})
    mass = [f for f in _lint(pkg) if f["code"] == "UL602"]
    assert mass and mass[0]["value_from"][0].endswith("config/links.yaml"), mass
    assert mass[0]["value_from"][1] == 3


# Franka's real per-link pattern (robots/common/utils.xacro): the macro's dict parameter
# defaults to the outer property (``inertial:=^``), a property of the same name shadows it
# with the link's sub-dict, attribute access two levels down, block and flow YAML alike
PER_LINK_YAML = """link1:
  origin: {xyz: 0 0 0, rpy: 0 0 0}
  mass: 2.0
  inertia: {xx: 0.01, xy: 0, xz: 0, yy: 0.01, yz: 0, zz: 0.5}
link2:
  origin:
    xyz: 0 0 0
    rpy: 0 0 0
  mass: -1.0
  inertia:
    xx: 0.01
    xy: 0
    xz: 0
    yy: 0.01
    yz: 0
    zz: 0.01
"""
PER_LINK = """<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="inertial"
      value="${xacro.load_yaml('$(find arm_description)/config/inertial.yaml')}"/>
  <xacro:macro name="inertial_props" params="name inertial:=^">
    <xacro:if value="${name in inertial}">
      <xacro:property name="inertial" value="${inertial[name]}" lazy_eval="false"/>
      <inertial>
        <origin rpy="${inertial.origin.rpy}" xyz="${inertial.origin.xyz}"/>
        <mass value="${inertial.mass}"/>
        <xacro:property name="I" value="${inertial.inertia}"/>
        <inertia ixx="${I.xx}" ixy="${I.xy}" ixz="${I.xz}" iyy="${I.yy}" iyz="${I.yz}"
                 izz="${I.zz}"/>
      </inertial>
    </xacro:if>
  </xacro:macro>
  <xacro:macro name="arm_link" params="name">
    <link name="${name}">
      <xacro:inertial_props name="${name}"/>
      <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
    </link>
  </xacro:macro>
  <link name="base"/>
  <xacro:arm_link name="link1"/>
  <xacro:arm_link name="link2"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="link1"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="link1"/><child link="link2"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""


def test_franka_per_link_macro_with_a_caret_default_names_each_links_yaml_line(tmp_path):
    pkg = make_package(tmp_path, PKG, {"config/inertial.yaml": PER_LINK_YAML,
                                       "urdf/arm.urdf.xacro": PER_LINK})
    found = {f["code"]: f for f in _lint(pkg)}
    # link2's negative mass is at line 9 of the YAML; link1's izz (flow mapping) at line 4
    assert found["UL602"]["line"] == 10, found["UL602"]
    assert found["UL602"]["value_from"][:2] == ["config/inertial.yaml", 9], found["UL602"]
    assert found["UL603"]["value_from"][:2] == ["config/inertial.yaml", 4], found["UL603"]
    for fmt in ("text", "github", "junit", "concise"):   # every format names the YAML line
        out = run_main("check", ".", "--no-cache", "--output-format", fmt, cwd=pkg).stdout
        assert "value from config/inertial.yaml:9" in out, (fmt, out)


# Motoman (motoman_es_support): ``velocity="${radians(velocities['joint_1_s'])}"``, a YAML
# value through a math function; Kinova (kortex_description): the loaded file handed straight
# to a macro parameter and read in an element's text (``<param>``), not an attribute
CALLS_YAML = "velocities:\n  joint_1: -100\n  joint_2: 100\ninitial_positions:\n  joint_1: 4.0\n"
CALLS = """<?xml version="1.0"?>
<robot name="k" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm" params="cfg">
    <link name="base"/>
    <xacro:macro name="j" params="n">
      <link name="l${n}"/>
      <joint name="joint_${n}" type="revolute">
        <parent link="base"/><child link="l${n}"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="1"
               velocity="${radians(cfg['velocities']['joint_' + str(n)])}"/>
      </joint>
    </xacro:macro>
    <xacro:j n="1"/>
    <xacro:j n="2"/>
    <ros2_control name="s" type="system">
      <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
      <joint name="joint_1">
        <command_interface name="position"/>
        <state_interface name="position">
          <param name="initial_value">${cfg['initial_positions']['joint_1']}</param>
        </state_interface>
      </joint>
    </ros2_control>
  </xacro:macro>
  <xacro:arm cfg="${xacro.load_yaml('$(find arm_description)/config/arm.yaml')}"/>
</robot>
"""


def test_a_value_through_a_math_function_names_the_yaml_line_but_is_not_written_back(tmp_path):
    pkg = make_package(tmp_path, PKG, {"config/arm.yaml": CALLS_YAML,
                                       "urdf/k.urdf.xacro": CALLS})
    (f,) = [f for f in _lint(pkg) if f["code"] == "UL304"]
    assert f["value_from"][:2] == ["config/arm.yaml", 2], f
    run_main("check", ".", "--no-cache", "--fix", "--unsafe-fixes", cwd=pkg)
    assert (pkg / "config/arm.yaml").read_text() == CALLS_YAML   # radians(-100) is not there


def test_a_value_in_an_elements_text_names_the_yaml_line(tmp_path):
    pkg = make_package(tmp_path, PKG, {"config/arm.yaml": CALLS_YAML,
                                       "urdf/k.urdf.xacro": CALLS})
    (f,) = [f for f in _lint(pkg) if f["code"] == "UL713"]
    assert f["line"] == 20 and f["value_from"][:2] == ["config/arm.yaml", 5], f


def test_the_expansion_is_unchanged_by_tracing(tmp_path):
    """Traced values print as the plain ones: the expanded URDF is stock xacro's, byte for
    byte (here against the same expansion with the values made plain)."""
    import sys
    pkg = make_package(tmp_path, PKG, {"config/limits.yaml": UR_YAML.replace(
        "1.5", "1.5e-7").replace("3.0", "3"), "urdf/fr.urdf.xacro": ARITH})
    out = run_main("expand", "urdf/fr.urdf.xacro", cwd=pkg)
    assert out.returncode == 0, out.stderr
    # stock xacro in a process of its own (this one may have urdf-lint's hooks installed)
    stock = subprocess.run([sys.executable, "-c", "import sys, xacro; sys.stdout.write(xacro."
                            "process_file(sys.argv[1]).toprettyxml(indent='  '))",
                            str(pkg / "urdf/fr.urdf.xacro")], capture_output=True, text=True,
                           check=True).stdout
    assert "1.5e-07" in stock
    assert out.stdout.split("-->", 2)[-1] == stock.split("-->", 2)[-1]


def test_the_hook_counts_a_yaml_commit_as_its_own(tmp_path):
    pkg = make_package(tmp_path, PKG, {"config/limits.yaml": UR_YAML.replace(
        "min_position: 1.5   #", "min_position: -1.5   #").replace(
        "max_position: -1.5\n", "max_position: 1.5\n"), "urdf/ur.urdf.xacro": UR})
    for cmd in (["init", "-q"], ["add", "-A"]):
        subprocess.run(["git", *cmd], cwd=pkg, check=True)
    (pkg / "config/limits.yaml").write_text(UR_YAML)
    subprocess.run(["git", "add", "-A"], cwd=pkg, check=True)
    p = run_main("hook", "--no-cache", "--", "config/limits.yaml", cwd=pkg)
    out = p.stdout + p.stderr
    assert p.returncode == 1, out
    assert "value from config/limits.yaml:4" in out, out
    assert "1 error(s)" in out and "(1 in the committed files)" in out, out


def test_the_seed_r2d2_names_its_yaml_line_and_fixes_the_flow_mapping(tmp_path):
    """The seed R2D2 reads its limits as ``ext = limits['gripper_extension']`` (a property
    holding a sub-dict of the loaded file): a swapped limit in its YAML's flow mapping is
    reported with the YAML line, and --fix swaps the two scalars in place."""
    import shutil
    from conftest import DESCRIPTIONS
    pkg = tmp_path / "r2d2_description"
    shutil.copytree(DESCRIPTIONS / "r2d2_description", pkg)
    limits = pkg / "config" / "joint_limits.yaml"
    good = limits.read_text()
    assert "gripper_extension: {lower: -0.38, upper: 0.0," in good
    bad = good.replace("gripper_extension: {lower: -0.38, upper: 0.0,",
                       "gripper_extension: {lower: 0.0, upper: -0.38,")
    limits.write_text(bad)
    (f,) = _ul302(_lint(pkg))
    assert f["file"].endswith("urdf/r2d2.urdf.xacro")
    assert f["value_from"][0].endswith("config/joint_limits.yaml") and f["value_from"][1] == 2
    run_main("check", ".", "--no-cache", "--fix", cwd=pkg)
    assert limits.read_text() == good


ARG_BOT = """<?xml version="1.0"?>
<robot name="argbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="lower" default="1.5"/>
  <xacro:arg name="upper" default="-1.5"/>
  <link name="base"/>
  <link name="arm"/>
  <joint name="j" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="$(arg lower)" upper="$(arg upper)" effort="1" velocity="1"/>
  </joint>
</robot>
"""


def test_a_value_from_an_arg_default_names_the_arg_line(tmp_path):
    """A limit written as an arg at its default names the <xacro:arg> line that set it; an arg
    a [[models]] entry passes does not point there. (An arg read through a property is a
    number by then, as xacro converts property text: not traced.)"""
    pkg = make_package(tmp_path, PKG, {"urdf/arg.urdf.xacro": ARG_BOT})
    (f,) = _ul302(_lint(pkg))
    assert f["value_from"][0].endswith("urdf/arg.urdf.xacro") and f["value_from"][1] == 3, f
    text = run_main("check", ".", "--no-cache", cwd=pkg).stdout
    assert "value from urdf/arg.urdf.xacro:3" in text, text
    (pkg / "urdf-lint.toml").write_text(
        '[[models]]\npath = "urdf/arg.urdf.xacro"\nargs = [{lower = "2"}]\n')
    (f,) = _ul302(_lint(pkg))
    # lower is passed: it names the config's line (the next test); upper is still its default
    assert f["value_from"] == ["urdf-lint.toml", 3, 10], f


# the forms a [[models]] entry sets args in, and the line and column ``lower`` is set at
CONFIG_FORMS = {
    "urdf-lint.toml": ('# variants\n[[models]]\npath = "urdf/arg.urdf.xacro"\n'
                       'args = { lower = "2", upper = "-2" }\n', 4, 10),
    "pyproject.toml": ('[project]\nname = "x"\n\n[[tool.urdf-lint.models]]\n'
                       'path = "urdf/arg.urdf.xacro"\n\n[tool.urdf-lint.models.args]\n'
                       'upper = "-2"\n"lower" = "2"\n', 9, 1),
}


def test_a_value_from_a_passed_arg_names_the_config_line(tmp_path):
    """A limit written as ``$(arg lower)`` that a [[models]] entry passes is located at the
    config line that sets it, inline or as a sub-table, in JSON and text; ``--fix`` does not
    write into the config."""
    for name, (config, line, col) in CONFIG_FORMS.items():
        pkg = make_package(tmp_path / name.split(".")[0], PKG,
                           {"urdf/arg.urdf.xacro": ARG_BOT})
        (pkg / name).write_text(config)
        (f,) = _ul302(_lint(pkg))
        assert f["value_from"] == [name, line, col], f
        text = run_main("check", ".", "--no-cache", cwd=pkg).stdout
        assert f"value from {name}:{line}" in text, text
        run_main("check", ".", "--no-cache", "--fix", cwd=pkg)
        assert (pkg / name).read_text() == config


def test_each_arg_set_of_a_list_names_its_own_table():
    """``args = [{...}, {...}]`` over several lines: the n-th set's arg is the n-th table's."""
    from urdf_lint.config.places import arg_places
    text = ('[[models]]\npath = "a.xacro"\n\n[[models]]\npath = "b.xacro"\nargs = [\n'
            '  {lower = "1"},  # first\n  {upper = "0", lower = "2"},\n]\n[format]\n')
    sets = [{"lower": "1"}, {"upper": "0", "lower": "2"}]
    got = arg_places("/r/urdf-lint.toml", text, 1, sets)
    assert got == [{"lower": ("/r/urdf-lint.toml", 7, 4)},
                   {"upper": ("/r/urdf-lint.toml", 8, 4), "lower": ("/r/urdf-lint.toml", 8, 17)}]
    assert arg_places("/r/urdf-lint.toml", text, 0, [{"lower": "1"}]) == [{}]


def test_the_real_franka_names_its_yaml_line(tmp_path):
    """franka_description (the corpus's copy): the limits macro reads
    ``limits = config[name]['limit']`` and writes ``${limits.lower}``; a swapped limit in
    ``robots/fr3/joint_limits.yaml`` is reported with that file's line, and --fix swaps the
    two scalars there."""
    import shutil
    import pytest
    from conftest import CORPUS
    src = CORPUS / "franka_description"
    if not (src / "robots/fr3/joint_limits.yaml").is_file():
        pytest.skip("../shared/corpus is not present")
    pkg = tmp_path / "franka_description"
    shutil.copytree(src, pkg)
    limits = pkg / "robots/fr3/joint_limits.yaml"
    good = limits.read_text()
    limits.write_text(good.replace("lower:      -2.3093\n    upper:       2.3093",
                                   "lower:      2.3093\n    upper:       -2.3093", 1))
    (pkg / "urdf-lint.toml").write_text(
        '[[models]]\npath = "robots/fr3/fr3.urdf.xacro"\n')
    # (the limit rules alone: the others read 11 MB of meshes, three seconds of the test; the
    # swap changes the soft limits derived from the same values too, which UL306 flags: with
    # UL302 alone the fix changes more than its finding and is rolled back)
    found = _ul302(_lint(pkg, "--select", "UL302,UL306"))
    assert found and all(f["value_from"][:2] == ["robots/fr3/joint_limits.yaml", 3]
                         for f in found), found
    run_main("check", ".", "--no-cache", "--fix", "--select", "UL302,UL306", cwd=pkg)
    assert limits.read_text() == good
