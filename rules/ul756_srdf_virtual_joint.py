"""An SRDF virtual joint MoveIt would skip or that attaches the robot to itself: an empty parent frame, a parent frame that is a link of the robot, or a child link that is not the robot's root link.

Why: the virtual joint attaches the robot's root link to a frame outside it (`world`, `odom`,
`map`: the planning frame). MoveIt's robot model uses it only when its `child_link` is the
URDF's root link and its `parent_frame` is not empty ("Skipping virtual joint 'X' because its
child frame 'Y' does not match the URDF frame 'Z'"); otherwise the robot is planned as fixed
at its root, which a mobile base (a `planar` or `floating` virtual joint) is not. A parent
frame that is a link of the robot itself makes the planning frame one of the robot's own
links: a loop, or, for a URDF whose root is a `world` link (what Gazebo needs), a second
attachment of the root that MoveIt skips (information: MoveIt then plans in the URDF's
`world` link, which is what was meant; remove the virtual joint or make `world` its child).
A child link the robot does not have is UL750's.

Consumers: ros (MoveIt) only: the other consumers do not read SRDF files.

How to fix: Make `child_link` the robot's root link and `parent_frame` a frame outside the
robot (`world` for a fixed arm, `odom` for a mobile base).
"""
CODE = "UL756"
NAME = "srdf-virtual-joint"
SEVERITY = "warning"
TARGETS = {"*": "off", "ros": "warning"}
from urdf_lint.rules._config import example_robot
FAIL = example_robot(("j1", "base", "l1"))
PASS = FAIL
EXAMPLE_FILES = {"config/r.srdf": """<robot name="r">
  <virtual_joint name="world_joint" type="fixed" parent_frame="l1" child_link="base"/>
</robot>
"""}
PASS_FILES = {"config/r.srdf": """<robot name="r">
  <virtual_joint name="world_joint" type="fixed" parent_frame="world" child_link="base"/>
</robot>
"""}
EXAMPLE_AT = "config/r.srdf"
FAIL_AT = [(2, 3)]
from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import parent_of, srdfs


def check(model: "Model", ctx: "Context") -> "Checked":
    par = parent_of(model)
    roots = [n for n in model.links if n not in par]
    root = roots[0] if len(roots) == 1 else None      # a broken tree is UL101's
    for doc in srdfs(ctx):
        for el in doc.root.iterfind("virtual_joint"):
            yield from _check(model, doc, el, par, root)


def _check(model: "Model", doc: Any, el: Any, par: Any, root: Any) -> Any:
    name, parent, child = el.get("name"), el.get("parent_frame"), el.get("child_link")
    if child not in model.links:
        return                                    # UL750 (or no child at all)
    what = f"virtual joint '{name}'"
    if not parent:
        yield Report(doc.at(el), f"{what} has an empty parent frame: MoveIt skips it",
                     related=model.links[child])
    elif parent in model.links:
        up = par.get(child)
        if parent == root and up is not None and up[1] == root:
            yield Report(doc.at(el), f"{what}: parent frame '{parent}' is the robot's root link, "
                         f"which joint '{up[0].get('name')}' already attaches '{child}' to: "
                         f"MoveIt skips the virtual joint and plans in '{parent}'",
                         targets={"*": "off", "ros": "info"}, related=model.links[parent])
        else:
            yield Report(doc.at(el), f"{what}: parent frame '{parent}' is a link of robot "
                         f"'{model.name}' itself, not a frame outside it (world, odom, map)",
                         related=model.links[parent])
    elif root is not None and child != root:
        yield Report(doc.at(el), f"{what}: child link '{child}' is not the robot's root link "
                     f"'{root}': MoveIt skips the virtual joint", related=model.links[root])
