"""An SRDF or `kinematics.yaml` names a planning group the SRDF does not define: a group state's or end effector's group, an end effector's parent group, a subgroup, or a `kinematics.yaml` entry.

Why: MoveIt ignores the group state or end effector ("Group state 'home' specified for group
'arm', but that group is not known"; an end effector is only dropped, so it is a warning), and a kinematics solver configured for a group that does
not exist leaves the real group without one (no IK for it). The usual cause is a renamed group.

Consumers: ros (MoveIt) only: the other consumers do not read these files.

How to fix: Use the name of a group defined in the SRDF, or define the group.
"""
CODE = "UL755"
NAME = "srdf-unknown-group"
SEVERITY = "error"
TARGETS = {"*": "off", "ros": "error"}
from urdf_lint.rules._config import example_robot
FAIL = example_robot(("j1", "base", "l1"))
PASS = FAIL
EXAMPLE_FILES = {"config/r.srdf": """<robot name="r">
  <group name="arm">
    <chain base_link="base" tip_link="l1"/>
  </group>
  <group_state name="home" group="manipulator">
    <joint name="j1" value="0"/>
  </group_state>
</robot>
""", "config/kinematics.yaml": """arm:
  kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin
"""}
PASS_FILES = {"config/r.srdf": EXAMPLE_FILES["config/r.srdf"].replace("manipulator", "arm")}
EXAMPLE_AT = "config/r.srdf"
FAIL_AT = [(5, 3)]
from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report, did_you_mean

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import docs, groups, srdfs

WHERE = (("group_state", "group", "group state '{n}'"), ("end_effector", "group", "end effector '{n}'"),
         ("end_effector", "parent_group", "end effector '{n}' parent group"),
         ("group/group", "name", "subgroup of '{p}'"))


def check(model: "Model", ctx: "Context") -> "Checked":
    defined: dict[Any, Any] = {}
    for doc in srdfs(ctx):
        known = groups(doc.root)
        defined.update(known)
        for path, attr, what in WHERE:
            for el in doc.root.iterfind(path):
                g = el.get(attr)
                if g and g not in known:
                    label = what.format(n=el.get("name"), p=el.getparent().get("name"))
                    # MoveIt drops an end effector of an unknown group and plans on: a warning
                    table = {"*": "off", "ros": "warning"} if el.tag == "end_effector" else None
                    yield Report(doc.at(el), f"{label} names group '{g}', which the SRDF "
                                 "does not define" + did_you_mean(g, known), related=model.root,
                                 targets=table)
    if not defined:
        return          # no SRDF: the groups are unknown, not wrong
    for doc in docs(ctx, "kinematics"):
        for name, node in doc.root.items():
            if name not in defined and isinstance(node.value, dict):
                yield Report(doc.key_at(node), f"kinematics.yaml configures group '{name}', which "
                             "the SRDF does not define" + did_you_mean(name, defined),
                             related=model.root)

