"""`origin xyz/rpy` or `axis xyz` is not three finite numbers, or `origin quat_xyzw` (URDF 1.1)
is not a unit quaternion of four numbers, or is written together with `rpy`.

Why: Two or four numbers, stray characters (`"0 0 1 }"`) or `nan` make URDF parsers fail or
produce NaN transforms (`nan` is rejected by urdfdom and Pinocchio; MuJoCo 4.0.0 and PyBullet
3.2.7 load it: a warning for `mujoco` and `pybullet`). urdfdom 6.0.0 (through Pinocchio 4.1.0, measured) rejects `quat_xyzw`
together with `rpy` (MuJoCo 4.0.0 and PyBullet 3.2.7 then use the `rpy`), and normalises a
quaternion that is not of unit length: a warning, since `0 0 1 1` is usually a typo.

How to fix: Write exactly three numbers separated by spaces (four, x y z w, of unit length for
`quat_xyzw`), and one of `rpy` and `quat_xyzw`.
"""
CODE = "UL207"
NAME = "vector-format"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="continuous">
    <origin xyz="0 0 1 }" rpy="0 0"/>
    <parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
  </joint>
</robot>
"""
FAIL_AT = [(4, 5)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="continuous">
    <origin xyz="0 0 1" rpy="0 0 0"/>
    <parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
  </joint>
</robot>
"""
import math

NOT_FINITE = ("nan", "inf", "infinity")
# a NaN or infinite value: urdfdom 6.0.0 (Pinocchio 4.1.0) rejects it, MuJoCo 4.0.0 and PyBullet
# 3.2.7 load it (measured)
LOADS_NAN: dict[str, str] = {}   # issue 38: loaded with a NaN pose is a different robot: an error

from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, numbers

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._schema import urdf_iter


def check(model: "Model", ctx: "Context") -> "Checked":
    for tag, attrs in (("origin", ("xyz", "rpy")), ("axis", ("xyz",))):
        for e in urdf_iter(model, tag):
            for a in attrs:
                v = e.get(a)
                if v is not None and numbers(v, 3) is None:
                    nan = len(v.split()) == 3 and any(x.lower().lstrip("+-") in NOT_FINITE
                                                      for x in v.split())
                    yield Report(e, f"<{tag} {a}=\"{v}\"> must be three finite numbers", targets=LOADS_NAN if nan else None)
    for e in urdf_iter(model, "origin"):
        v = e.get("quat_xyzw")
        if v is None:
            continue
        q = numbers(v, 4)
        n = math.sqrt(sum(x * x for x in q)) if q is not None else 0.0
        if q is None or n == 0:
            yield Report(e, f"<origin quat_xyzw=\"{v}\"> must be four finite numbers, x y z w, not all 0")
        elif e.get("rpy") is not None:
            yield Report(e, ("<origin> has both rpy and quat_xyzw: urdfdom 6 rejects it, MuJoCo and "
                             "PyBullet use the rpy; keep one"))
        elif abs(n - 1) > 1e-3:
            unit = " ".join(f"{x / n:.6g}" for x in q)
            yield Report(e, (f"<origin quat_xyzw=\"{v}\"> has length {n:.4g}, not 1: urdfdom normalises "
                             f"it (\"{unit}\"); write the unit quaternion"), severity="warning")
