"""A joint's lower limit is above its upper limit, so no position is allowed.

Why: Controllers and planners refuse or clamp every position (Drake 1.51.1 rejects the model;
MuJoCo 4.0.0, Pinocchio 4.1.0 and PyBullet 3.2.7 load it with an empty range: a warning for
`mujoco`, `pinocchio` and `pybullet`, measured with MuJoCo 4.0.0, Pinocchio 4.1.0, PyBullet 3.2.7). Usually the two were swapped, or a
sign was lost in a mirrored (`reflect`) macro.

How to fix: Swap the two values, or fix the sign.

Fix: safe. `--fix` swaps the two values where they are written (the element, a
`xacro:property`, a macro call's argument or a YAML scalar).
"""
CODE = "UL302"
NAME = "limit-order"
SEVERITY = "error"
TARGETS = {"mujoco": "warning", "pinocchio": "warning", "pybullet": "warning", "python": "warning",
           "idyntree": "warning", "isaac": "warning", "gazebo": "warning"}
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="2.1" upper="-2.1" effort="10" velocity="1"/></joint>
</robot>
"""
FAIL_AT = [(4, 5)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-2.1" upper="2.1" effort="10" velocity="1"/></joint>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, fmt, set_attrs

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._joints import ranged


def check(model: "Model", ctx: "Context") -> "Checked":
    for j, lim, lo, hi in ranged(model):
        if lo > hi:
            yield Report(lim, (f"joint '{j.get('name')}': lower {fmt(lo)} > upper {fmt(hi)} "
                               "(swap them?)"), fix=set_attrs({"lower": lim.get("upper", "0"),
                                                           "upper": lim.get("lower", "0")},
                                                          "swap lower and upper"))
