"""A `<ros2_control>` block names a joint (or a transmission joint) that the model does not define.

Why: controller_manager refuses to load the hardware interface.

How to fix: Fix the joint name in the ros2_control block.

Fix: safe, when the name has a single close "did you mean" candidate that no other ros2_control joint names: `--fix`
writes it where the name is written.
"""
CODE = "UL702"
NAME = "ros2-control-joint"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="joint1" type="continuous"><parent link="a"/><child link="b"/></joint>
  <ros2_control name="sys" type="system"><hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="joint_1"><command_interface name="position"/></joint></ros2_control>
</robot>
"""
FAIL_AT = [(5, 5)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="joint1" type="continuous"><parent link="a"/><child link="b"/></joint>
  <ros2_control name="sys" type="system"><hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="position"/></joint></ros2_control>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, did_you_mean

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._joints import unknown_joint_refs


def check(model: "Model", ctx: "Context") -> "Checked":
    pairs = [(rc, j) for rc in model.root.iter("ros2_control") for j in rc.iter("joint")]
    for rc, j, n, fix in unknown_joint_refs(model, pairs):
        yield Report(j, (f"ros2_control '{rc.get('name')}' names unknown joint '{n}'"
                         + did_you_mean(n, model.joints)), fix=fix)
