"""An SRDF group state leaves out a joint of its group, or sets a joint outside the robot's limits.

Why: a named state (`home`, `ready`) MoveIt moves to is checked against the joint limits when
it is used: a value outside them makes the goal invalid ("goal is not within bounds"), and a
joint left out keeps whatever value it happens to have, so the "same" state differs between
runs. The usual cause is a limit tightened in the xacro, or a joint added to the group.

Consumers: ros (MoveIt) only: the other consumers do not read SRDF files.

How to fix: Give every moving joint of the group a value within its `<limit>` (the related
location is the joint's limit in the xacro).
"""
CODE = "UL754"
NAME = "srdf-group-state"
SEVERITY = "warning"
TARGETS = {"*": "off", "ros": "warning"}
FAIL = """<robot name="r">
  <link name="base"/><link name="l1"/><link name="l2"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
  <joint name="j3" type="revolute"><parent link="l2"/><child link="l3"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
  <link name="l3"/>
</robot>
"""
PASS = """<robot name="r">
  <link name="base"/><link name="l1"/><link name="l2"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="2" effort="10" velocity="1"/></joint>
</robot>
"""
EXAMPLE_FILES = {"config/r.srdf": """<robot name="r">
  <group name="arm">
    <chain base_link="base" tip_link="l2"/>
    <joint name="j3"/>
  </group>
  <group_state name="home" group="arm">
    <joint name="j1" value="0"/>
    <joint name="j2" value="1.5"/>
  </group_state>
</robot>
"""}
EXAMPLE_AT = "config/r.srdf"
FAIL_AT = [(6, 3), (8, 5)]
from urdf_lint.engine.api import Report, fmt, number
from urdf_lint.rules._config import group_joints, joint_limits, moving_joint, srdfs

SLACK = 1e-9


def check(model, ctx):
    for doc in srdfs(ctx):
        for gs in doc.root.iterfind("group_state"):
            named = {}
            for el in gs.iterfind("joint"):
                name = el.get("name")
                named[name] = el
                lo, hi, *_ = joint_limits(model, name)
                v = number(el.get("value"))
                if lo is None or hi is None or v is None:
                    continue
                if not lo - SLACK <= v <= hi + SLACK:
                    yield Report(doc.at(el), f"group state '{gs.get('name')}' sets joint "
                                 f"'{name}' to {fmt(v)}, outside its limits [{fmt(lo)}, "
                                 f"{fmt(hi)}]", related=model.joints[name].find("limit"))
            missing = [j for j in group_joints(model, doc.root, gs.get("group"))
                       if moving_joint(model, j) and j not in named
                       and model.joints[j].find("mimic") is None]
            if missing:
                yield Report(doc.at(gs), f"group state '{gs.get('name')}' of group "
                             f"'{gs.get('group')}' gives no value for "
                             f"{', '.join(repr(m) for m in missing)}",
                             related=model.joints[missing[0]])
