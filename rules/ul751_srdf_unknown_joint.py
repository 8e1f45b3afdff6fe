"""An SRDF names a joint the robot does not have: a group's joint, a group state's joint or a passive joint.

Why: MoveIt drops a group with an unknown joint ("Joint 'X' declared as part of group 'arm'
is not known to the URDF"), ignores the value of a group state for it, and a passive joint
that does not exist leaves the real one planned as active. The usual cause is a joint renamed
in the xacro and not in the MoveIt configuration package. The SRDF's own virtual joint is a
joint MoveIt knows (the `base` group of a mobile manipulator names it): not reported.

Consumers: ros (MoveIt) only: the other consumers do not read SRDF files.

How to fix: Rename the joint in the SRDF (the related location is where the robot's joints are
written).

Fix: unsafe, when the name has one close candidate among the robot's joints (the element renamed
in the xacro): `--fix --unsafe-fixes` renames it on the reported line, verified by re-linting.
"""
CODE = "UL751"
NAME = "srdf-unknown-joint"
SEVERITY = "error"
TARGETS = {"*": "off", "ros": "error"}
from urdf_lint.rules._config import example_robot
FAIL = example_robot(("j1", "base", "l1"), ("joint_2", "l1", "l2"), links=("base", "l1", "l2"))
PASS = FAIL.replace("joint_2", "j2")
EXAMPLE_FILES = {"config/r.srdf": """<robot name="r">
  <group name="arm">
    <joint name="j1"/>
    <joint name="j2"/>
  </group>
  <group_state name="home" group="arm">
    <joint name="j1" value="0"/>
    <joint name="j2" value="0"/>
  </group_state>
  <passive_joint name="j2"/>
</robot>
"""}
EXAMPLE_AT = "config/r.srdf"
FAIL_AT = [(4, 5), (8, 5), (10, 3)]
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import closest, rename_fix, srdfs

WHERE = (("group/joint", "group '{g}' joint"), ("group_state/joint", "group state '{g}' joint"),
         ("passive_joint", "passive joint"))


def check(model: "Model", ctx: "Context") -> "Checked":
    for doc in srdfs(ctx):
        # a group (a state, a passive joint) may name the SRDF's own virtual joint: MoveIt's
        # SRDF parser accepts it (the base group of a mobile manipulator)
        virtual = {v.get("name") for v in doc.root.iterfind("virtual_joint")}
        for path, what in WHERE:
            for el in doc.root.iterfind(path):
                name = el.get("name")
                if not name or name in model.joints or name in virtual:
                    continue
                label = what.format(g=el.getparent().get("name"))
                # the joint closest by name is the related location, else the robot
                near, rel = closest(model, name, model.joints)
                yield Report(doc.at(el), f"SRDF {label} '{name}' is not a joint of robot "
                             f"'{model.name}'" + near, related=rel,
                             fix=rename_fix(doc.at(el), name, model.joints, doc))
