"""A joint has no `type`, or one that URDF does not know.

Why: Parsers refuse the joint, and with it the model.

How to fix: Use one of: revolute, continuous, prismatic, fixed, floating, planar.
"""
CODE = "UL202"
NAME = "joint-type"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="rotational"><parent link="a"/><child link="b"/></joint>
</robot>
"""
FAIL_AT = [(3, 3)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, did_you_mean

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model

TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")


def check(model: "Model", ctx: "Context") -> "Checked":
    for j in model.top_joints():
        t = j.get("type")
        if t is None:
            yield Report(j, f"joint '{j.get('name')}' has no type (one of {', '.join(TYPES)})")
        elif t not in TYPES:
            yield Report(j, f"joint '{j.get('name')}': unknown type '{t}'" + did_you_mean(t, TYPES))
