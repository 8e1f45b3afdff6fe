"""Two links, or two joints, share a name.

Why: URDF parsers reject the model (urdfdom: "link/joint is not unique"; PyBullet 3.2.7
crashes on a duplicate joint); with xacro this usually means a macro was called twice without a
distinct `prefix`. MuJoCo 4.0.0 loads two joints of one name (a warning for `mujoco`) (measured with MuJoCo 4.0.0, Pinocchio 4.1.0, PyBullet 3.2.7).

How to fix: Rename one of them, or pass each macro call its own prefix.
"""
CODE = "UL105"
NAME = "duplicate-name"
SEVERITY = "error"
# a joint named like a link: only sdformat 12 refuses it (measured)
SHARED = {"*": "off", "gazebo": "error"}
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/><link name="b"/>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>
"""
FAIL_AT = [(2, 35)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>
"""


from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    for tag in ("link", "joint"):
        first: dict[Any, Any] = {}
        for e in model.root:
            if e.tag != tag or not e.get("name"):
                continue
            n = e.get("name")
            if n in first:
                yield Report(e, (f"duplicate {tag} name '{n}' (first defined at "
                                 f"{model.origin(first[n]).place()}); give each a unique name"),
                             )
            else:
                first[n] = e
    links = {e.get("name"): e for e in model.root if e.tag == "link" and e.get("name")}
    for j in model.root:
        if j.tag == "joint" and j.get("name") in links:
            yield Report(j, (f"joint '{j.get('name')}' has the name of a link (line "
                             f"{model.origin(links[j.get('name')]).line}): URDF allows it, SDFormat "
                             "does not (Gazebo: \"Joint with non-unique name\")"), targets=SHARED)
