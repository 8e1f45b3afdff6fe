"""A `<transmission>` names a joint that the model does not define.

Why: ros_control / gazebo_ros_control then fail at start-up with a message far from the cause.
Typical after renaming a joint or changing a `prefix`.

How to fix: Fix the joint name in the transmission.
"""
CODE = "UL701"
NAME = "transmission-joint"
SEVERITY = "error"
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
from urdf_lint.ruleutil import did_you_mean


def check(model, ctx):
    for t in model.root.iter("transmission"):
        for j in t.findall("joint"):
            n = j.get("name")
            if n and n not in model.joints:
                yield j, (f"transmission '{t.get('name')}' names unknown joint '{n}'"
                          + did_you_mean(n, model.joints))
