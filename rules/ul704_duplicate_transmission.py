"""Two `<transmission>` elements with the same name, or two actuators of the same name.

Why: URDF requires unique names, but urdfdom ignores transmissions, so ROS tools load the file.
urchin 0.0.30 rejects two transmissions of one name (measured).
Drake 1.51.1 names its joint actuators after the `<actuator>` elements and rejects two of one name
("already contains a joint actuator"), but loads two transmissions of one name whose actuators
differ (both measured with pydrake). An error for `python`, and for `drake` where an actuator
name repeats; a warning for the other targets, since ros_control and ros2_control then drive
only one of the two.

How to fix: Give each transmission and each actuator a unique name (macros usually need a
prefix parameter in the name).
"""
CODE = "UL704"
NAME = "duplicate-transmission"
SEVERITY = "warning"
TARGETS = {"drake": "error", "urchin": "error"}
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="continuous"><parent link="a"/><child link="b"/></joint>
  <joint name="j2" type="continuous"><parent link="a"/><child link="c"/></joint>
  <transmission name="trans"><type>transmission_interface/SimpleTransmission</type>
    <joint name="j1"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="motor"/></transmission>
  <transmission name="trans"><type>transmission_interface/SimpleTransmission</type>
    <joint name="j2"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="motor"/></transmission>
  <transmission name="trans3"><type>transmission_interface/SimpleTransmission</type>
    <joint name="j2"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="motor"/></transmission>
</robot>
"""
FAIL_AT = [(8, 3), (13, 5)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="continuous"><parent link="a"/><child link="b"/></joint>
  <joint name="j2" type="continuous"><parent link="a"/><child link="c"/></joint>
  <transmission name="trans1"><type>transmission_interface/SimpleTransmission</type>
    <joint name="j1"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="motor1"/></transmission>
  <transmission name="trans2"><type>transmission_interface/SimpleTransmission</type>
    <joint name="j2"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="motor2"/></transmission>
</robot>
"""


from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    """A transmission named like an earlier one (urchin rejects it; Drake too when an actuator
    name repeats as well, as it does when one macro is called twice), and an actuator named
    like one of another transmission (Drake rejects it)."""
    seen: dict[Any, Any] = {}
    actuators: dict[Any, Any] = {}
    for t in model.root.findall("transmission"):
        n = t.get("name")
        first = seen.get(n) if n else None
        names = [a.get("name") for a in t.findall("actuator") if a.get("name")]
        shared = [a for a in names if a in actuators and actuators[a] is not t]
        if first is not None:
            who = "Drake and urchin reject" if shared else "urchin rejects"
            yield Report(t, f"transmission '{n}' is defined twice (first at "
                            f"{model.origin(first).place()}); {who} the model, ros_control "
                            "drives only one",
                         targets={"drake": "error", "urchin": "error"} if shared else
                         {"urchin": "error"})
        elif n:
            seen[n] = t
        for a in t.findall("actuator"):
            an = a.get("name")
            if first is None and an in shared:
                yield Report(a, f"actuator '{an}' of transmission '{n}' is also the actuator of "
                                f"transmission '{actuators[an].get('name')}'; Drake rejects the "
                                "model (one joint actuator per name)", targets={"drake": "error"})
        for an in names:
            actuators.setdefault(an, t)
