"""A controller's joint is not declared in `<ros2_control>`, or lacks a command or state interface the controller type needs.

Why: the controller_manager activates a controller only when every interface it claims exists
("Command interface with 'joint1/velocity' does not exist"): a joint trajectory controller
claims its `command_interfaces` and `state_interfaces` for each joint, a forward command
controller its `interface_name`, `position_controllers/JointGroupPositionController` position,
a gripper action controller position (effort for the effort variant) and the position state, a
diff drive velocity and the position state (velocity with `position_feedback: false`). A
controller of a type urdf-lint does not know has only its joints checked (UL710); the joint
state broadcaster reads whatever is declared.

Checked only when the robot declares some `<ros2_control>` block (a URDF without one gets its
hardware description elsewhere).

Consumers: ros and gazebo (gz_ros2_control loads the same controller YAML).

How to fix: Declare the interface in the xacro's `<ros2_control>` joint (the related location),
or configure the controller for the interfaces the hardware has.
"""
CODE = "UL711"
NAME = "controller-interface"
SEVERITY = "error"
TARGETS = {"*": "off", "ros": "error", "gazebo": "error"}
from urdf_lint.rules._config import example_robot, ROS2_CONTROL_EXAMPLE
FAIL = example_robot(("joint1", "base", "l1"), tail=ROS2_CONTROL_EXAMPLE)
PASS = FAIL.replace('<command_interface name="position"/>',
                    '<command_interface name="position"/><command_interface name="velocity"/>')
EXAMPLE_FILES = {"config/r_controllers.yaml": """controller_manager:
  ros__parameters:
    arm_controller:
      type: joint_trajectory_controller/JointTrajectoryController

arm_controller:
  ros__parameters:
    joints: [joint1]
    command_interfaces: [position, velocity]
    state_interfaces: [position]
"""}
EXAMPLE_AT = "config/r_controllers.yaml"
FAIL_AT = [(8, 14)]
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import (controller_joints, controllers, docs, needed_interfaces,
                                     resolve_name, ros2_control_joints)


def check(model: "Model", ctx: "Context") -> "Checked":
    declared = ros2_control_joints(model)
    if model.root.find("ros2_control") is None:
        return
    for doc in docs(ctx, "controllers"):
        for cname, ctype, params in controllers(doc):
            need = needed_interfaces(ctype, params)
            if need is None:
                continue
            cmd, st = need
            for n in controller_joints(params):
                name, left = resolve_name(ctx, n.value)
                if left or name not in model.joints:
                    continue                  # UL714, UL710
                if name not in declared:
                    yield Report(doc.at(n), f"controller '{cname}' ({ctype}) uses joint "
                                 f"'{name}', which no <ros2_control> block declares",
                                 related=model.joints[name])
                    continue
                el, have_cmd, have_st = declared[name]
                lack = [f"command interface '{c}'" for c in cmd if c not in have_cmd] + \
                       [f"state interface '{s}'" for s in st if s not in have_st]
                if lack:
                    yield Report(doc.at(n), f"controller '{cname}' ({ctype}) needs "
                                 f"{' and '.join(lack)} of joint '{name}', which its "
                                 "<ros2_control> joint does not declare", related=el)
