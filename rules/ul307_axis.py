"""A joint axis of zero length (no direction), or one that is not a unit vector.

Why: a zero axis has no direction at all: MuJoCo 4.0.0 and Drake 1.51.1 reject the model,
Pinocchio 4.1.0 and PyBullet 3.2.7 load it with NaN joint motion (measured). It is an error, but a warning for `pinocchio` and `pybullet`, which load it. A non-unit axis is
normalised by every consumer measured (urdfdom 6.0.0, MuJoCo, Pinocchio, PyBullet, Drake, the
Python parsers): a warning, since a hand-written `0 0 2` usually hides another mistake.

How to fix: Write a unit vector.

Fix: safe, for a non-zero axis: `--fix` writes the normalised vector where `xyz` is written.

Options: `tolerance` (default 0.001): non-unit axes are reported when their length differs from
1 by more than this.
"""
CODE = "UL307"
NAME = "joint-axis"
SEVERITY = "error"
OPTIONS = {"tolerance": 1e-3}
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 0"/></joint>
</robot>
"""
FAIL_AT = [(3, 72)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>
</robot>
"""
import math

from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, fmt, numbers, set_attrs

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    tol = float(ctx.options.get("tolerance", 1e-3))
    for j in model.top_joints():
        if j.get("type") in ("fixed", "floating"):
            continue
        ax = j.find("axis")
        if ax is None:
            continue
        v = numbers(ax.get("xyz", "1 0 0"), 3)
        if v is None:
            continue  # UL207 reports the format
        n = math.sqrt(sum(x * x for x in v))
        if n == 0:
            yield Report(ax, (f"joint '{j.get('name')}': axis xyz=\"{ax.get('xyz')}\" has zero length"), targets={"pinocchio": "warning", "pybullet": "warning", "python": "warning", "idyntree": "warning"})
            continue
        elif abs(n - 1) > tol:
            unit = " ".join(fmt(round(x / n, 6)) for x in v)
            yield Report(ax, (f"joint '{j.get('name')}': axis xyz=\"{ax.get('xyz')}\" has length "
                              f"{n:.4g}, not 1; consumers normalise it (use \"{unit}\")"), severity="warning", fix=set_attrs({"xyz": unit}, "normalise the axis to unit length"))
