"""The root link is empty (no `<inertial>`, `<visual>` or `<collision>`): Isaac Sim's URDF
importer makes it the articulation root.

Why: ROS descriptions often start with an empty `base_footprint` (or `world`) link joined to the
body by a fixed joint; it is what UL604 recommends for KDL. Isaac Sim's URDF importer crashed on
it ("RuntimeError: Used null prim", isaac-sim/IsaacSim#532, reproduced by its maintainers on
Isaac Sim 6.0.0-rc.13 with `merge_fixed_joints` on and off, and reported on 4.5.0 in
unitreerobotics/unitree_ros#118); since 6.0.0-rc.22 it imports the link with "a small isotropic
inertia matrix" and a warning, a body of invented mass at the root of the articulation. Isaac
Sim does not install from the package index, so this is from those threads, not measured here.
A warning for `isaac`; off for the other targets, which load the link as a frame.

How to fix: For Isaac Sim before 6.0, import with the importer's "fix base" option and delete
the empty link from the imported asset, or generate a URDF for Isaac without it (a xacro
argument); with later versions, check the mass the importer gave it.
"""
CODE = "UL609"
NAME = "isaac-empty-root"
SEVERITY = "warning"
TARGETS = {"*": "off", "isaac": "warning"}
EXAMPLE_TARGETS = ["isaac"]
FAIL = """<robot name="r">
  <link name="base_footprint"/>
  <link name="base"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <joint name="j" type="fixed"><parent link="base_footprint"/><child link="base"/></joint>
</robot>
"""
FAIL_AT = [(2, 3)]
PASS = """<robot name="r">
  <link name="base"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="arm"/>
  <joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>
</robot>
"""


PARTS = ("inertial", "visual", "collision")


from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model

def check(model: "Model", ctx: "Context") -> "Checked":
    links = model.top_links()
    has_parent = model.parents_of_links()
    roots = [lk for lk in links if lk.get("name") and lk.get("name") not in has_parent]
    for lk in roots if len(links) > 1 else ():     # one link alone articulates nothing
        if all(lk.find(part) is None for part in PARTS):
            yield Report(lk, (f"root link '{lk.get('name')}' is empty (no inertial, visual or "
                       "collision); Isaac Sim's URDF importer makes it the articulation root: it "
                       "crashes before 6.0 ('Used null prim') and gives it an invented inertia "
                       "since"))
