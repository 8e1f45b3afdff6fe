"""A revolute or prismatic joint whose lower and upper limits are equal cannot move.

Why: This includes leaving both out, when they default to 0: the joint is silently frozen.

How to fix: If the joint should not move, make it `fixed`; otherwise set the range.
"""
CODE = "UL303"
NAME = "limit-empty-range"
SEVERITY = "warning"
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="slider" type="prismatic"><parent link="a"/><child link="b"/><axis xyz="1 0 0"/>
    <limit effort="10" velocity="1"/></joint>
</robot>
"""
FAIL_AT = [(4, 5)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="slider" type="prismatic"><parent link="a"/><child link="b"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.2" effort="10" velocity="1"/></joint>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, fmt

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._joints import ranged


def check(model: "Model", ctx: "Context") -> "Checked":
    for j, lim, lo, hi in ranged(model):
        if lo == hi:
            why = " (both default to 0)" if lim.get("lower") is None and lim.get("upper") is None else ""
            yield Report(lim, (f"joint '{j.get('name')}': lower == upper == {fmt(lo)}{why}, so it cannot "
                               "move; set the range or make the joint fixed"))
