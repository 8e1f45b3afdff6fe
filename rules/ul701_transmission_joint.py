"""A `<transmission>` names a joint that the model does not define.

Why: ros_control / gazebo_ros_control then fail at start-up with a message far from the cause.
Typical after renaming a joint or changing a `prefix`.

How to fix: Fix the joint name in the transmission.

Fix: safe, when the name has a single close "did you mean" candidate that no other transmission names: `--fix`
writes it where the name is written.
"""
CODE = "UL701"
NAME = "transmission-joint"
SEVERITY = "error"
TARGETS = {"mujoco": "warning", "pinocchio": "warning", "pybullet": "warning", "yourdfpy": "warning",
           "urdf_parser_py": "warning", "idyntree": "warning", "isaac": "warning"}
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="elbow" type="continuous"><parent link="a"/><child link="b"/></joint>
  <transmission name="t"><type>transmission_interface/SimpleTransmission</type>
    <joint name="elbo"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>
</robot>
"""
FAIL_AT = [(5, 5)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="elbow" type="continuous"><parent link="a"/><child link="b"/></joint>
  <transmission name="t"><type>transmission_interface/SimpleTransmission</type>
    <joint name="elbow"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, did_you_mean

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._joints import unknown_joint_refs


def check(model: "Model", ctx: "Context") -> "Checked":
    pairs = [(t, j) for t in model.root.iter("transmission") for j in t.findall("joint")]
    for t, j, n, fix in unknown_joint_refs(model, pairs):
        yield Report(j, (f"transmission '{t.get('name')}' names unknown joint '{n}'"
                         + did_you_mean(n, model.joints)), fix=fix)
