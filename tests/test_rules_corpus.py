"""Each rule on real robots nobody here wrote: a real finding at an exact file and line, or a
clean result. Also: every defect the corpus MANIFEST names is found, and every urdfdom fixture
that urdfdom rejects gets at least one error."""
from __future__ import annotations

import pytest

from conftest import CORPUS

# code -> (file, line, col) of a real finding in the corpus
REAL = {
    "UL001": ("airo_models/arms/ur5e/ur5e.urdf", 167, 44),
    "UL005": ("ur_description/urdf/ur.xacro", 2, 1),
    "UL006": ("peer-tests/urdfdom/inline/URDF_VERSION.test_version_wrong_type.urdf", 1, 1),
    "UL101": ("peer-tests/urdfdom/robot_model/fail_pr2_desc_loop.urdf", 3, 1),
    "UL102": ("peer-tests/urdfdom/inline/URDF_UNIT_TEST.parse_color_doubles.urdf", 1, 109),
    "UL103": ("robot_properties_fingers/urdf/edu/trifingeredu_stage.urdf", 51, 5),
    "UL104": ("peer-tests/urdfdom/robot_model/fail_pr2_desc_double_joint.urdf", 30, 5),
    "UL105": ("peer-tests/urdfdom/robot_model/fail_pr2_desc_double.urdf", 31, 5),
    "UL106": ("urdf_tutorial/urdf/05-visual.urdf", 2, 1),
    "UL203": ("peer-tests/urdfdom/robot_model/fail_pr2_desc_no_filename_in_mesh.urdf", 2297, 14),
    "UL205": ("peer-tests/urdfdom/robot_model/fail_pr2_desc_no_filename_in_mesh.urdf", 99, 11),
    "UL206": ("airo_models/environment/mounting_plates/mounting_plate_ur3e.urdf", 24, 9),
    "UL207": ("peer-tests/urdfdom/robot_model/fail_pr2_desc_bracket.urdf", 9, 7),
    "UL209": ("airo_models/grippers/robotiq_2f_85/urdf/robotiq_2f_85.urdf", 8, 7),
    "UL210": ("franka_description/robots/common/franka_arm.xacro", 36, 7),
    "UL211": ("peer-tests/urdfdom/inline/URDF_VERSION.test_version_one_int.urdf", 1, 1),
    "UL303": ("peer-tests/urdfdom/robot_model/fail_pr2_desc_bracket.urdf", 6, 7),
    "UL304": ("fanuc/fanuc_lrmate200ic_support/urdf/lrmate200ic5f_macro.xacro", 104, 7),
    "UL306": ("peer-tests/urdfdom/robot_model/fail_pr2_desc_no_filename_in_mesh.urdf", 2300, 7),
    "UL401": ("turtlebot3_description/urdf/turtlebot3_waffle.urdf.xacro", 23, 9),
    "UL407": ("urdf_tutorial/urdf/05-visual.urdf", 170, 9),
    "UL501": ("peer-tests/urdfdom/urdf_parser_py-0.4.1/calvin/calvin.urdf", 573, 7),
    "UL503": ("ros2_control_demos/ros2_control_demo_description/carlikebot/urdf/carlikebot.materials.xacro", 12, 3),
    "UL504": ("airo_models/grippers/robotiq_2f_85/urdf/robotiq_2f_85.urdf", 21, 7),
    "UL601": ("fanuc/fanuc_m10ia_support/urdf/m10ia_macro.xacro", 37, 5),
    # romeo's fingers: revolute joints moving links with mass 0 and nothing massive below
    "UL602": ("peer-tests/urdfdom/urdf_parser_py-0.4.1/romeo/romeo.urdf", 551, 7),
    # (the generated fingeredu.urdf is identical to today's expansion: its findings are the
    # xacro's, issue 24)
    "UL603": ("robot_properties_fingers/xacro_files/edu/fingeredu_macro.xacro", 128, 17),
    "UL604": ("airo_models/grippers/schunk_egk40/urdf/schunk_egk40.urdf", 4, 9),
    # gripper_pole: a 0.05 kg, r=0.01 m cylinder has 2.5e-6 kg·m² about its axis, not 0.001
    "UL605": ("urdf_tutorial/urdf/07-physics.urdf", 261, 7),
    "UL606": ("peer-tests/urdfdom/robot_model/fail_pr2_desc_no_filename_in_mesh.urdf", 92, 9),
    # the 2020 autorace burger's wheels weigh 2.85 kg (the burger's: 0.0285 kg)
    "UL607": ("turtlebot3_description/urdf/turtlebot3_burger_for_autorace_2020.urdf.xacro", 64, 7),
    "UL608": ("ros2_control_demos/ros2_control_demo_description/r6bot/urdf/inc/create_link.xacro", 25, 9),
    "UL701": ("peer-tests/urdfdom/urdf_parser_py-0.4.1/transmission/test.urdf", 8, 5),
    # urdfdom's own test: a fixed joint that keeps a <mimic> (Drake rejects it)
    "UL309": ("peer-tests/urdfdom/inline/URDF_UNIT_TEST.parse_joint_doubles.urdf", 1, 422),
    "UL703": ("peer-tests/urdfdom/robot_model/fail_pr2_desc_no_filename_in_mesh.urdf", 736, 14),
    "UL801": ("robot_properties_fingers/xacro_files/pro/fingerpro_macro.xacro", 88, 9),
    # package:// names no package.xml declares: one root cause per package (issue 24)
    "UL004": ("peer-tests/urdfdom/urdf_parser_py-0.4.1/calvin/calvin.urdf", 12, 9),
    # only with gazebo:=true, a variant branch exploration lints (docs/coverage.md): each
    # joint's transmission is declared again by the gazebo macros
    "UL704": ("franka_description/robots/common/utils.xacro", 124, 5),
}
# rules with no defect in these robots: a clean result on every corpus model
# (UL201: the corpus's only nameless <robot>s are the empty outputs of macro-only xacros, such as
# robot_properties_fingers/urdf/finger_macro.urdf: empty by design, so not models)
CLEAN = ["UL201", "UL002", "UL003", "UL007", "UL012", "UL009", "UL010", "UL011", "UL408", "UL202", "UL204",
         "UL208", "UL212", "UL301", "UL302", "UL305", "UL307", "UL308", "UL402", "UL403", "UL404",
         "UL405", "UL406",
         "UL502", "UL702", "UL901", "UL902", "UL903", "UL904", "UL213", "UL013", "UL411",
         "UL014",   # no constant condition in the corpus hides a body
         # the configuration next to a robot (SRDF, controllers, MoveIt limits): the corpus's
         # controller YAML is clean (tests/test_srdf.py plants each mismatch)
         "UL710", "UL711", "UL712", "UL713", "UL714", "UL715", "UL750", "UL751", "UL752",
         "UL753", "UL754", "UL755", "UL760", "UL761", "UL762", "UL799",
         # no Gazebo-simulated <ros2_control> sensor, MoveIt controller file, SRDF virtual
         # joint or disable_collisions pair in the corpus (tests/test_srdf_groups.py plants them)
         "UL716", "UL717", "UL756", "UL757",
         # off for ros, the target of this run (tests/test_targets.py covers their targets)
         "UL409", "UL410", "UL705", "UL609", "UL310", "UL610"]


@pytest.fixture(scope="module")
def report(corpus_report):
    return corpus_report      # the session's one run (tests/conftest.py)


def _at(report, code, file):
    return [(f["line"], f["col"]) for f in report["findings"] if f["code"] == code and f["file"] == file]


@pytest.mark.parametrize("code", sorted(REAL))
def test_real_finding(report, code):
    file, line, col = REAL[code]
    assert (line, col) in _at(report, code, file), (code, _at(report, code, file))


@pytest.mark.parametrize("code", CLEAN)
def test_clean_on_real_robots(report, code):
    assert not [f for f in report["findings"] if f["code"] == code]


def test_every_rule_is_covered():
    from urdf_lint.engine.registry import load_rules
    covered = set(REAL) | set(CLEAN) | {"UL008"}  # UL008: xacro warnings; none in the corpus
    assert set(load_rules()) <= covered, set(load_rules()) - covered


def test_manifest_defects_are_found(report):
    f = report["findings"]

    def has(code, file_part, msg_part=""):
        return any(x["code"] == code and file_part in x["file"] and msg_part in x["message"] for x in f)
    # urdf_tutorial: DAE textures never shipped; 05 and 06 share the robot name 'visual'
    assert has("UL407", "urdf_tutorial/urdf/05-visual.urdf", "l_finger_normals.png")
    assert has("UL407", "urdf_tutorial/urdf/05-visual.urdf", "l_finger_tip_normals.png")
    assert has("UL106", "urdf_tutorial/urdf/06-flexible.urdf", "'visual'")
    # ur_description: ur.xacro cannot expand with its defaults
    assert has("UL005", "ur_description/urdf/ur.xacro", "robot_model")
    # visual meshes dropped for every type but ur5e; ur20/ur30 have none
    for t in ("ur3", "ur3e", "ur5", "ur10", "ur10e", "ur16e", "ur20", "ur30"):
        assert any(x["code"] == "UL401" and f"ur_description/urdf/{t}.xacro" in x["models"] for x in f), t
    assert not any(x["code"] == "UL401" and "ur_description/urdf/ur5e.xacro" in x["models"] for x in f)
    # robot_properties_fingers: meshes/stl/ folder that does not exist; fragments without root;
    # trifinger named finger_with_stage
    assert has("UL401", "robot_properties_fingers/", "high_table_boundary.stl")
    assert has("UL401", "robot_properties_fingers/", "trifinger_table_without_border.stl")
    assert has("UL401", "robot_properties_fingers/", "frame_wall.stl")
    assert has("UL103", "robot_properties_fingers/urdf/trifinger_stage.urdf", "base_link")
    assert has("UL106", "robot_properties_fingers/xacro_files/trifinger.urdf.xacro", "finger_with_stage")
    # macro-only outputs are <robot> without name, empty by design: placeholders, not models
    # (issue 33), so neither linted nor reported
    assert not any("robot_properties_fingers/urdf/finger_macro.urdf" in m for x in f
                   for m in x.get("models") or [x["file"]])
    # airo_models: undeclared drake: prefix
    assert has("UL001", "airo_models/arms/ur5e/ur5e.urdf", "drake")
    assert has("UL001", "airo_models/grippers/robotiq_2f_85/urdf/robotiq_2f_85.urdf", "drake")
    assert has("UL401", "airo_models/arms/ur5e/ur5e.urdf", "visual/shoulder.obj")
    # fanuc: no <inertial> anywhere
    fanuc_models = {m["entry"] for m in report["models"] if m["entry"].startswith("fanuc/")}
    assert len(fanuc_models) == 7
    for m in fanuc_models:
        assert any(x["code"] == "UL601" and m in x["models"] for x in f), m
    # turtlebot3: missing base meshes
    for robot in ("turtlebot3_waffle", "turtlebot3_waffle_for_open_manipulator",
                  "turtlebot3_waffle_pi_for_open_manipulator"):
        assert any(x["code"] == "UL401" and f"turtlebot3_description/urdf/{robot}.urdf.xacro" in x["models"]
                   for x in f), robot


URDFDOM_REJECTS = [
    "inline/URDF_VERSION.test_version_one_int.urdf", "inline/URDF_VERSION.test_version_unsupported_version.urdf",
    "inline/URDF_VERSION.test_version_wrong_type.urdf", "robot_model/initxml_empty_string.urdf",
    "robot_model/fail_pr2_desc_bracket.urdf", "robot_model/fail_pr2_desc_no_joint2.urdf",
    "robot_model/fail_three_links_one_joint.urdf", "robot_model/fail_pr2_desc_double_joint.urdf",
    "robot_model/fail_pr2_desc_loop.urdf", "robot_model/fail_pr2_desc_two_trees.urdf",
    "robot_model/fail_pr2_desc_no_filename_in_mesh.urdf", "robot_model/fail_pr2_desc_double.urdf",
    "robot_model/fail_pr2_desc_parent_itself.urdf",
]


@pytest.mark.parametrize("fixture", URDFDOM_REJECTS)
def test_urdfdom_rejects_get_an_error(report, fixture):
    path = f"peer-tests/urdfdom/{fixture}"
    errors = [x for x in report["findings"] if x["file"] == path and x["severity"] == "error"]
    assert errors, path


def test_no_zero_mass_error_on_fixed_frames(report):
    """Massless frames on fixed joints (the fingers' *_visuals and base links) are valid; only
    romeo's moving, massless fingers remain."""
    f = [x for x in report["findings"] if x["code"] == "UL602"]
    assert f and all("romeo.urdf" in x["file"] and "on a body that moves" in x["message"] for x in f)
    assert not any("robot_properties_fingers" in x["file"] for x in f)


def test_zero_effort_is_a_warning_naming_the_convention(report):
    f = [x for x in report["findings"] if x["code"] == "UL304" and "effort=0" in x["message"]]
    assert len(f) >= 62 and all(x["severity"] == "warning" for x in f)
    assert all("ROS-Industrial" in x["message"] for x in f)
    # velocity=0 was an error; since issue 25 a warning (every consumer measured loads it;
    # tests/test_consumers.py), still reported
    assert any(x["code"] == "UL304" and "velocity=0" in x["message"] and x["severity"] == "warning"
               for x in report["findings"])


def test_identical_wheels_may_share_a_tensor(report):
    assert not any(x["code"] == "UL608" and "carlikebot" in x["file"] for x in report["findings"])
