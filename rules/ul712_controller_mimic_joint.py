"""A controller commands a mimic joint.

Why: a mimic joint follows the joint it mimics; ros2_control's hardware (mock components,
gz_ros2_control) sets it from that joint, and since ros2_control 4 a `<ros2_control>` mimic
joint has no command interface of its own. A controller claiming it fails to activate, or (older
versions) fights the mimic relation: the gripper finger jitters or the mimic is ignored.

Consumers: ros and gazebo (gz_ros2_control loads the same controller YAML).

How to fix: Command the joint it mimics (the related location is the `<mimic>` element), and
list the mimic joint only in state broadcasters.
"""
CODE = "UL712"
NAME = "controller-mimic-joint"
SEVERITY = "warning"
TARGETS = {"*": "off", "ros": "warning", "gazebo": "warning"}
FAIL = """<robot name="r">
  <link name="base"/><link name="f1"/><link name="f2"/>
  <joint name="finger1" type="prismatic"><parent link="base"/><child link="f1"/>
    <axis xyz="0 1 0"/><limit lower="0" upper="0.04" effort="10" velocity="1"/></joint>
  <joint name="finger2" type="prismatic"><parent link="base"/><child link="f2"/>
    <axis xyz="0 -1 0"/><limit lower="0" upper="0.04" effort="10" velocity="1"/>
    <mimic joint="finger1"/></joint>
</robot>
"""
PASS = FAIL.replace('<mimic joint="finger1"/>', "")
EXAMPLE_FILES = {"config/r_controllers.yaml": """controller_manager:
  ros__parameters:
    hand_controller:
      type: position_controllers/JointGroupPositionController

hand_controller:
  ros__parameters:
    joints: [finger1, finger2]
"""}
EXAMPLE_AT = "config/r_controllers.yaml"
FAIL_AT = [(8, 23)]
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import controller_joints, controllers, docs, resolve_name

READ_ONLY = ("joint_state_broadcaster/",)


def check(model: "Model", ctx: "Context") -> "Checked":
    for doc in docs(ctx, "controllers"):
        for cname, ctype, params in controllers(doc):
            if ctype.startswith(READ_ONLY):
                continue
            for n in controller_joints(params):
                name, _ = resolve_name(ctx, n.value)
                j = model.joints.get(name)
                mimic = j.find("mimic") if j is not None else None
                if mimic is not None:
                    yield Report(doc.at(n), f"controller '{cname}' commands joint '{name}', "
                                 f"which mimics '{mimic.get('joint')}'", related=mimic)
