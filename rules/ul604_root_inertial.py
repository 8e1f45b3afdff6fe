"""The root link carries an `<inertial>`.

Why: KDL (robot_state_publisher, MoveIt, many IK solvers) cannot use inertia on the root link
and warns or ignores it.

How to fix: Add a massless dummy root (`base_link` → `base_footprint` or `world`) joined to the
heavy base by a fixed joint.

Fix: unsafe (`--unsafe-fixes`): inserts `<link name="NAME_root"/>` and a fixed joint
`NAME_root_joint` from it to the link, just before the link where it is written.
"""
CODE = "UL604"
NAME = "root-inertial"
SEVERITY = "warning"
FAIL = """<robot name="r">
  <link name="base"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="arm"/>
  <joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>
</robot>
"""
FAIL_AT = [(2, 21)]
PASS = """<robot name="r">
  <link name="base_footprint"/>
  <link name="base"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <joint name="j" type="fixed"><parent link="base_footprint"/><child link="base"/></joint>
</robot>
"""




from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, new_root

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    children = model.parents_of_links()
    links = model.top_links()
    if len(links) < 2:
        return
    for lk in links:
        n = lk.get("name")
        inertial = lk.find("inertial")
        if n and n not in children and inertial is not None and model.links.get(n) is lk:
            yield Report(inertial, (f"root link '{n}' has an <inertial>, which KDL ignores; add a "
                                               "massless root link joined by a fixed joint"), fix=new_root("add a massless root link joined by a fixed joint"))
