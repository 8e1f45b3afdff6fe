"""An SRDF names a link the robot does not have: a group's link, a chain's base or tip, an end effector's parent link or the virtual joint's child link.

Why: MoveIt's SRDF parser drops the group (or the end effector, the virtual joint) with an
error like "Link 'X' declared as part of a chain in group 'arm' is not known to the URDF":
planning for it fails at start-up, far from the line that caused it. The usual cause is a link
renamed in the xacro and not in the MoveIt configuration package.

Consumers: ros (MoveIt) only: the other consumers do not read SRDF files.

How to fix: Rename the link in the SRDF (the related location is where the robot's links are
written), or regenerate the SRDF with the MoveIt Setup Assistant.

Fix: unsafe, when the name has one close candidate among the robot's links (the element renamed
in the xacro): `--fix --unsafe-fixes` renames it on the reported line, verified by re-linting.
"""
CODE = "UL750"
NAME = "srdf-unknown-link"
SEVERITY = "error"
TARGETS = {"*": "off", "ros": "error"}
from urdf_lint.rules._config import example_robot
FAIL = example_robot(("j1", "base", "l1"), ("j2", "l1", "link2"), links=("base", "l1", "link2"))
PASS = FAIL.replace("link2", "l2")
EXAMPLE_FILES = {"config/r.srdf": """<robot name="r">
  <virtual_joint name="world_joint" type="fixed" parent_frame="world" child_link="base"/>
  <group name="arm">
    <chain base_link="base" tip_link="l2"/>
  </group>
  <end_effector name="tool" parent_link="l2" group="arm"/>
</robot>
"""}
EXAMPLE_AT = "config/r.srdf"
FAIL_AT = [(4, 5), (6, 3)]
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import closest, rename_fix, srdfs

WHERE = (("group/link", "name", "group '{g}' link"), ("group/chain", "base_link", "chain base"),
         ("group/chain", "tip_link", "chain tip"),
         ("end_effector", "parent_link", "end effector '{n}' parent link"),
         ("virtual_joint", "child_link", "virtual joint '{n}' child link"))


def check(model: "Model", ctx: "Context") -> "Checked":
    for doc in srdfs(ctx):
        seen = set()
        for path, attr, what in WHERE:
            for el in doc.root.iterfind(path):
                name = el.get(attr)
                if not name or name in model.links or (el, name) in seen:
                    continue
                seen.add((el, name))
                owner = el.getparent() if el.getparent() is not doc.root else el
                label = what.format(g=owner.get("name"), n=el.get("name"))
                near, rel = closest(model, name, model.links)
                yield Report(doc.at(el), f"SRDF {label} '{name}' is not a link of robot "
                             f"'{model.name}'" + near, related=rel,
                             fix=rename_fix(doc.at(el), name, model.links, doc))
