"""Every corpus entry model expands byte-identically to stock xacro (same package map, same
args), and link/joint counts match the corpus MANIFEST."""
from __future__ import annotations

import pytest
from lxml import etree

from conftest import CORPUS, corpus_entries
from stock_xacro import stock_xacro

# links/joints per MANIFEST.md (entry, sorted args) -> (links, joints)
EXPECTED = {
    "urdf_tutorial/urdf/01-myfirst.urdf": (1, 0), "urdf_tutorial/urdf/02-multipleshapes.urdf": (2, 1),
    "urdf_tutorial/urdf/03-origins.urdf": (2, 1), "urdf_tutorial/urdf/04-materials.urdf": (3, 2),
    "urdf_tutorial/urdf/05-visual.urdf": (16, 15), "urdf_tutorial/urdf/06-flexible.urdf": (16, 15),
    "urdf_tutorial/urdf/07-physics.urdf": (16, 15), "urdf_tutorial/urdf/08-macroed.urdf.xacro": (16, 15),
    **{f"ur_description/urdf/{t}.xacro": (11, 10) for t in
       ("ur3", "ur3e", "ur5", "ur5e", "ur10", "ur10e", "ur16e", "ur20", "ur30")},
    "franka_description/robots/panda/panda.urdf.xacro": (17, 16),
    "franka_description/robots/panda/panda.urdf.xacro hand=true": (22, 21),
    "franka_description/robots/panda/panda.urdf.xacro gazebo=true hand=true": (23, 22),
    "franka_description/robots/fr3/fr3.urdf.xacro hand=true": (22, 21),
    "franka_description/robots/dual_panda/dual_panda_example.urdf.xacro": (45, 44),
    "franka_description/robots/common/hand.urdf.xacro": (5, 4),
    "turtlebot3_description/urdf/turtlebot3_burger.urdf.xacro": (7, 6),
    "turtlebot3_description/urdf/turtlebot3_burger_for_autorace.urdf.xacro": (10, 9),
    "turtlebot3_description/urdf/turtlebot3_burger_for_autorace_2020.urdf.xacro": (10, 9),
    "turtlebot3_description/urdf/turtlebot3_waffle.urdf.xacro": (13, 12),
    "turtlebot3_description/urdf/turtlebot3_waffle_for_open_manipulator.urdf.xacro": (13, 12),
    "turtlebot3_description/urdf/turtlebot3_waffle_pi.urdf.xacro": (11, 10),
    "turtlebot3_description/urdf/turtlebot3_waffle_pi_for_open_manipulator.urdf.xacro": (11, 10),
    "robotiq_description/urdf/robotiq_2f_85_gripper.urdf.xacro": (10, 9),
    "robotiq_description/urdf/robotiq_2f_140_gripper.urdf.xacro": (13, 12),
    "ros2_control_demos/ros2_control_demo_example_7/urdf/r6bot.urdf.xacro": (10, 9),
    "ros2_control_demos/ros2_control_demo_example_11/urdf/carlikebot.urdf.xacro": (8, 7),
    "ros2_control_demos/ros2_control_demo_example_13/urdf/three_robots.urdf.xacro": (14, 13),
    "fanuc/fanuc_lrmate200ic_support/urdf/lrmate200ic.xacro": (10, 9),
    "fanuc/fanuc_lrmate200ic_support/urdf/lrmate200ic5l.xacro": (10, 9),
    "fanuc/fanuc_lrmate200ic_support/urdf/lrmate200ic5f.xacro": (9, 8),
    "fanuc/fanuc_lrmate200ic_support/urdf/lrmate200ic5h.xacro": (9, 8),
    "fanuc/fanuc_lrmate200ic_support/urdf/lrmate200ic5hs.xacro": (9, 8),
    "fanuc/fanuc_m10ia_support/urdf/m10ia.xacro": (10, 9),
    "fanuc/fanuc_m10ia_support/urdf/m10ia7l.xacro": (10, 9),
    "robot_properties_fingers/xacro_files/finger.urdf.xacro": (7, 6),
    "robot_properties_fingers/xacro_files/finger_with_stage.urdf.xacro": (8, 7),
    "robot_properties_fingers/xacro_files/trifinger.urdf.xacro": (17, 16),
    "robot_properties_fingers/xacro_files/trifinger_with_stage.urdf.xacro": (19, 18),
    "robot_properties_fingers/xacro_files/edu/fingeredu.urdf.xacro": (6, 5),
    "robot_properties_fingers/xacro_files/edu/trifingeredu.urdf.xacro": (17, 16),
    "robot_properties_fingers/xacro_files/edu/trifingeredu_with_stage.urdf.xacro": (19, 18),
    "robot_properties_fingers/xacro_files/pro/fingerpro.urdf.xacro": (9, 8),
    "robot_properties_fingers/xacro_files/pro/trifingerpro.urdf.xacro": (23, 22),
    "robot_properties_fingers/xacro_files/pro/trifingerpro_with_stage.urdf.xacro": (25, 24),
    "robot_properties_fingers/xacro_files/stage.urdf.xacro": (1, 0),
    "robot_properties_fingers/xacro_files/trifinger_stage.urdf.xacro": (2, 2),
    "robot_properties_fingers/xacro_files/edu/trifingeredu_stage.urdf.xacro": (2, 2),
    "airo_models/grippers/schunk_egk40/urdf/schunk_egk40.urdf": (3, 2),
    "airo_models/grippers/schunk_egk40_magneto/schunk_egk40_magneto.urdf": (8, 7),
    "airo_models/grippers/fingertips/urdf/magneto_fingertip.urdf": (2, 1),
    "airo_models/mobile_platforms/kelo_robile/urdf/battery_brick.urdf": (4, 3),
    "airo_models/mobile_platforms/kelo_robile/urdf/cpu_brick.urdf": (4, 3),
    "airo_models/mobile_platforms/kelo_robile/urdf/wheel_brick.urdf": (5, 4),
    "airo_models/mobile_platforms/kelo_robile/urdf/mobi.urdf": (2, 1),
    "airo_models/environment/tables/table8080.urdf": (7, 6),
    "airo_models/environment/mounting_plates/mounting_plate_ur3e.urdf": (3, 2),
    "airo_models/environment/mounting_plates/mounting_plate_ur5e.urdf": (3, 2),
}
# every rrbot / diffbot demo is 5 links / 4 joints
RRBOT_LIKE = (5, 4)

# entries that fail in stock xacro too (MANIFEST: ur.xacro with empty YAML paths; airo files
# with an undeclared drake: prefix that expat rejects)
EXPECTED_FAILURES = {
    ("ur_description/urdf/ur.xacro", (("robot_model", "ur5e"),)),
    ("airo_models/arms/ur5e/ur5e.urdf", ()),
    ("airo_models/grippers/robotiq_2f_85/urdf/robotiq_2f_85.urdf", ()),
}


def _key(f, args):
    return f + "".join(f" {k}={v}" for k, v in sorted(args.items()))


ENTRIES = corpus_entries()


@pytest.mark.parametrize("entry,args", ENTRIES, ids=[_key(f, a)[:90] for f, a in ENTRIES])
def test_byte_identical_to_stock_xacro(entry, args, corpus, corpus_resolver):
    from urdf_lint.expansion import expand_file
    path = str(corpus / entry)
    ours = expand_file(path, args, corpus_resolver, display_name=path)
    rc, out, err = stock_xacro(path, args, corpus_resolver.scanned)
    if (entry, tuple(sorted(args.items()))) in EXPECTED_FAILURES:
        assert rc != 0 and ours.error is not None, "expected both to fail"
        assert ours.error.line >= 1 and ours.error.file
        return
    assert rc == 0, err
    assert ours.error is None, ours.error
    assert ours.xml == out
    root = etree.fromstring(ours.xml.encode())
    links = len(root.findall("link"))
    joints = len(root.findall("joint"))
    key = _key(entry, args)
    if key in EXPECTED:
        assert (links, joints) == EXPECTED[key]
    elif entry.startswith("ros2_control_demos/") and ("rrbot" in entry or "diffbot" in entry):
        assert (links, joints) == RRBOT_LIKE
    elif entry.startswith("ur_description/urdf/ur.xacro"):
        assert (links, joints) == (11, 10)
    # every element of the output has a source origin in a real file
    assert len(ours.origins) == len(list(root.iter(tag=etree.Element)))
    assert all(o is not None and o[1] >= 1 for o in ours.origins)


def test_counts_table_covers_manifest(corpus):
    """Guard against the table above drifting from entries.json."""
    keys = {_key(f, a) for f, a in ENTRIES}
    missing = [k for k in EXPECTED if k not in keys]
    assert not missing, missing
