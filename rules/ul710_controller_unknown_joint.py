"""A ros2_control configuration file names a joint the robot does not have: a controller's `joints` (or `joint`, a diff drive's wheels) in the controller YAML, an entry of `initial_positions.yaml`, or a joint of a controller in `moveit_controllers.yaml`.

Why: the controller_manager refuses to configure the controller ("joint 'X' not found" /
"Command interface 'X/position' does not exist"), the mock hardware ignores the initial
position, and MoveIt's controller manager cannot execute trajectories for the group: the robot
does not move, and the error shows only when the launch file runs. The usual cause is a joint
renamed, or prefixed, in the xacro.

A name built by a launch substitution (`$(var tf_prefix)joint1`) is resolved with the model's
xacro args of the same name; when the prefix is not known, UL714 says the name was not checked.

Consumers: ros and gazebo (gz_ros2_control loads the same controller YAML); the other consumers
do not read it.

How to fix: Rename the joint in the YAML file (the related location is the closest joint of the
robot, or the robot).

Fix: unsafe, when the name has one close candidate among the robot's joints (the element renamed
in the xacro): `--fix --unsafe-fixes` renames it on the reported line, verified by re-linting.
"""
CODE = "UL710"
NAME = "controller-unknown-joint"
SEVERITY = "error"
TARGETS = {"*": "off", "ros": "error", "gazebo": "error"}
from urdf_lint.rules._config import example_robot, forward_controller_example, ROS2_CONTROL_EXAMPLE
FAIL = example_robot(("joint_1", "base", "l1"), tail=ROS2_CONTROL_EXAMPLE.replace("joint1", "joint_1"))
PASS = FAIL.replace("joint_1", "joint1")
EXAMPLE_FILES = {"config/r_controllers.yaml": forward_controller_example("joint1")}
EXAMPLE_AT = "config/r_controllers.yaml"
FAIL_AT = [(9, 9)]
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import closest, named_joints, rename_fix, resolve_name


def check(model: "Model", ctx: "Context") -> "Checked":
    for doc, node, raw, what in named_joints(ctx):
        name, left = resolve_name(ctx, raw)
        if left or name in model.joints:
            continue
        near, rel = closest(model, name, model.joints)
        at = doc.key_at(node) if what == "initial_positions.yaml" else doc.at(node)
        yield Report(at, f"{what} names joint '{name}', which robot '{model.name}' does not "
                     "have" + near, related=rel,
                             fix=rename_fix(at, name, model.joints, doc))
