"""Two `<transmission>` elements with the same name, or two actuators of the same name.

Why: URDF requires unique names, but urdfdom ignores transmissions, so ROS tools load the file;
Drake 1.51.1 rejects it (its joint actuators are named after them: "already contains a joint
actuator") and so does urchin 0.0.30 (measured: /work/shared/notes/consumer-facts.md). An error
for `drake` and `python`; a warning for the other targets, since ros_control and ros2_control
then drive only one of the two.

How to fix: Give each transmission and each actuator a unique name (macros usually need a
prefix parameter in the name).
"""
CODE = "UL704"
NAME = "duplicate-transmission"
SEVERITY = "warning"
TARGETS = {"drake": "error", "python": "error"}
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


from urdf_lint.engine.api import Report


def check(model, ctx):
    seen: dict = {}
    actuators: dict = {}
    for t in model.root.findall("transmission"):
        n = t.get("name")
        twice = bool(n) and n in seen
        if n:
            if twice:
                line = model.origin(seen[n]).line
                yield Report(t, (f"transmission '{n}' is defined twice (first at line {line}); Drake and "
                                 "urchin reject the model, ros_control drives only one"))
            else:
                seen[n] = t
        for a in t.findall("actuator"):
            an = a.get("name")
            if not an:
                continue
            if an in actuators and actuators[an] is not t and not twice:
                yield Report(a, (f"actuator '{an}' of transmission '{n}' is also the actuator of "
                                 f"transmission '{actuators[an].get('name')}'; Drake rejects the model "
                                 "(one joint actuator per name)"))
            else:
                actuators.setdefault(an, t)
