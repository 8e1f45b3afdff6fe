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
from urdf_lint.rules._config import example_robot, LIMIT
FAIL = example_robot(("j1", "base", "l1"), ("j2", "l1", "l2"), ("j3", "l2", "l3"), links=("base", "l1", "l2"),
                     tail='  <link name="l3"/>\n')
PASS = example_robot(("j1", "base", "l1"), ("j2", "l1", "l2", LIMIT.replace('upper="1"', 'upper="2"')),
                     links=("base", "l1", "l2"))
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
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, fmt, number

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import actuated, group_joints, joint_limits, srdfs

SLACK = 1e-9


def check(model: "Model", ctx: "Context") -> "Checked":
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
                       if actuated(model, j) and j not in named]
            if missing:
                yield Report(doc.at(gs), f"group state '{gs.get('name')}' of group "
                             f"'{gs.get('group')}' gives no value for "
                             f"{', '.join(repr(m) for m in missing)}",
                             related=model.joints[missing[0]])
