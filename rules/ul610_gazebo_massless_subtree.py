"""A link with no mass of its own or fixed to it (at most 1e-6 kg) carries links that move:
Gazebo's URDF conversion drops it and everything below it.

Why: Gazebo reads a URDF through sdformat's converter, which merges each link attached by a
`fixed` joint into its parent, from the leaves up, and drops a link whose merged mass is at
most 1e-6 kg together with every link below it (gazebosim/sdformat#199). A massless frame at
a leaf (`tool0`, a camera frame) loses nothing, but a massless link that joints hang from
takes them with it: the finger of robot_properties_fingers' `fingerpro.urdf` (a massless
`finger_base_link` fixed to the base) loads as one link, and `trifingerpro.urdf` (a massless
base with massless finger bases) loads as none ("A model must have at least one link"). The
same holds for the root: an empty root link that a joint moves links from (no fixed link with
mass below it) leaves Gazebo no link at all (measured with sdformat 12.3.0, Gazebo Fortress,
`sdf::Root::Load`; a link named `world` is no exception). KDL, MoveIt, MuJoCo, Pinocchio and
the Python loaders keep the links (a massless fixed frame is fine there), so this is an error
for `gazebo` and off for the other targets.

How to fix: Give the link its mass (the part it stands for), or fix a link with mass to it:
UL604's massless root joined by a fixed joint to the body is fine, because the body's mass is
merged into it.
"""
CODE = "UL610"
NAME = "gazebo-massless-subtree"
SEVERITY = "error"
TARGETS = {"*": "off", "gazebo": "error"}
EXAMPLE_TARGETS = ["gazebo"]
FAIL = """<robot name="r">
  <link name="base"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="finger_base"/>
  <joint name="mount" type="fixed"><parent link="base"/><child link="finger_base"/></joint>
  <link name="finger"><inertial><mass value="0.2"/><inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>
  <joint name="j" type="revolute"><parent link="finger_base"/><child link="finger"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""
FAIL_AT = [(3, 3)]
PASS = FAIL.replace('<link name="finger_base"/>', '<link name="finger_base"><inertial><mass value="0.1"/><inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>')

from typing import TYPE_CHECKING

from urdf_lint.engine.api import Report
from urdf_lint.rules._inertial import SDF_DROPPED as DROPPED, Bodies

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    bodies = Bodies(model)
    merged_mass = bodies.merged_mass
    if all(lk.find("inertial") is None for lk in model.top_links()):
        return   # no link has an <inertial>: UL601 says Gazebo refuses the model

    def lost(name: str) -> list[str]:
        """Every link below ``name`` that a non-fixed joint moves, or that hangs below one."""
        out: list[str] = []
        todo, moving = [(name, False)], False
        seen: set[str] = set()
        while todo:
            n, moving = todo.pop()
            if n in seen:
                continue
            seen.add(n)
            if moving:
                out.append(n)
            todo.extend((c, moving or j.get("type") != "fixed") for j, c in bodies.children.get(n, ()))
        return out

    roots = [lk.get("name") for lk in model.top_links()
             if lk.get("name") and lk.get("name") not in bodies.parent_joint]
    todo = list(roots)
    seen: set[str] = set()
    while todo:   # top down: a dropped link is reported, what is below it is not visited
        n = todo.pop()
        if n in seen:
            continue
        seen.add(n)
        parent = bodies.parent_joint.get(n)
        if parent is not None and parent.get("type") != "fixed" and merged_mass(n) <= DROPPED:
            continue   # a massless link a joint moves: UL601 and UL602 report it
        # (a root named world is Gazebo's world frame, not a link: what is below it is seen)
        gone = lost(n) if merged_mass(n) <= DROPPED and n != "world" else []
        lk = model.links.get(n)
        if gone and lk is not None:
            shown = ", ".join(f"'{g}'" for g in gone[:4]) + (f" and {len(gone) - 4} more"
                                                           if len(gone) > 4 else "")
            if n in roots:
                yield Report(lk, f"root link '{n}' and the links fixed to it have no mass: "
                                 "Gazebo's URDF conversion (sdformat) drops it and every link "
                                 f"below it ({shown}), and loads no link at all; give the base "
                                 "its mass")
            else:
                yield Report(lk, f"link '{n}' and the links fixed to it have no mass: Gazebo's "
                                 f"URDF conversion (sdformat) drops it and the "
                                 f"{len(gone)} link(s) below it that joints move ({shown}); give "
                                 "it the mass of the part it stands for")
            continue
        todo.extend(c for _j, c in bodies.children.get(n, ()))
