"""A `<color rgba>` is not four numbers, each in [0, 1].

Why: Values like `255 0 0 1` (0-255 scale) or three numbers are rejected or clipped by viewers.

How to fix: Write four numbers between 0 and 1 (divide 0-255 values by 255).

Fix: safe, for 0-255 colours (r, g, b all in 0-255, alpha 0-1 or 0-255): `--fix` divides
them by 255 where `rgba` is written.
"""
CODE = "UL208"
NAME = "rgba"
SEVERITY = "error"
TARGETS = {"mujoco": "warning", "pinocchio": "warning", "pybullet": "warning",
           "urdf_parser_py": "warning", "urchin": "warning", "idyntree": "warning", "isaac": "warning",
           "gazebo": "warning"}
FAIL = """<robot name="r">
  <material name="red"><color rgba="255 0 0 1"/></material>
  <link name="a"/>
</robot>
"""
FAIL_AT = [(2, 24)]
PASS = """<robot name="r">
  <material name="red"><color rgba="1 0 0 1"/></material>
  <link name="a"/>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, numbers, set_attrs

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._schema import urdf_iter


def _by_255(vals: list[float]) -> str | None:
    """The 0-1 colour of a 0-255 one (alpha above 1 is 0-255 too), or None."""
    rgb, a = vals[:3], vals[3]
    if not all(float(x).is_integer() and 0 <= x <= 255 for x in rgb) or max(rgb) <= 1:
        return None
    if not (0 <= a <= 1 or (float(a).is_integer() and a <= 255)):
        return None
    out = [x / 255 for x in rgb] + [a / 255 if a > 1 else a]
    return " ".join(f"{round(x, 4):g}" for x in out)


def check(model: "Model", ctx: "Context") -> "Checked":
    for c in urdf_iter(model, "color"):
        if c.getparent() is None or c.getparent().tag != "material":
            continue
        v = c.get("rgba")
        if v is None:
            yield Report(c, "<color> needs rgba=\"r g b a\"")
            continue
        vals = numbers(v, 4)
        if vals is None:
            yield Report(c, f"<color rgba=\"{v}\"> must be four numbers")
        elif any(x < 0 or x > 1 for x in vals):
            hint = " (0-255 values? divide by 255)" if any(x > 1 for x in vals) else ""
            fixed = _by_255(vals)
            yield Report(c, f"<color rgba=\"{v}\"> values must be within [0, 1]{hint}", fix=
                       set_attrs({"rgba": fixed}, "divide the 0-255 colour by 255") if fixed else None)
