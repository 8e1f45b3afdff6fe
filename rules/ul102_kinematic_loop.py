"""A link is the child of more than one joint (a kinematic loop), or a joint connects a link to
itself.

Why: URDF describes trees: every link but the root has exactly one parent joint, and parsers
refuse anything else.

How to fix: Open closed chains (parallel grippers, four-bar linkages) in URDF and close them in
the simulator (e.g. with a mimic joint or an SDF/MuJoCo equality constraint).
"""
CODE = "UL102"
NAME = "kinematic-loop"
SEVERITY = "error"
FAIL = """<robot name="linkage">
  <link name="A"/><link name="B"/><link name="C"/><link name="D"/>
  <joint name="jA" type="fixed"><parent link="A"/><child link="B"/></joint>
  <joint name="jB" type="fixed"><parent link="A"/><child link="C"/></joint>
  <joint name="jC" type="fixed"><parent link="B"/><child link="D"/></joint>
  <joint name="jD" type="fixed"><parent link="C"/><child link="D"/></joint>
</robot>
"""
FAIL_AT = [(6, 3)]
PASS = """<robot name="linkage">
  <link name="A"/><link name="B"/><link name="C"/>
  <joint name="jA" type="fixed"><parent link="A"/><child link="B"/></joint>
  <joint name="jB" type="fixed"><parent link="A"/><child link="C"/></joint>
</robot>
"""


from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    for child, joints in model.parents_of_links().items():
        if len(joints) > 1:
            names = ", ".join(f"'{j.get('name')}'" for j in joints)
            for j in joints[1:]:
                yield Report(j, (f"link '{child}' has {len(joints)} parent joints ({names}): a kinematic "
                                 "loop; URDF allows one parent per link"))
    for j in model.top_joints():
        p, c = j.find("parent"), j.find("child")
        if p is not None and c is not None and p.get("link") and p.get("link") == c.get("link"):
            yield Report(j, f"joint '{j.get('name')}' connects link '{p.get('link')}' to itself")
