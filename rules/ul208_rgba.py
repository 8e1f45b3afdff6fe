"""A `<color rgba>` is not four numbers, each in [0, 1].

Why: Values like `255 0 0 1` (0-255 scale) or three numbers are rejected or clipped by viewers.

How to fix: Write four numbers between 0 and 1 (divide 0-255 values by 255).
"""
CODE = "UL208"
NAME = "rgba"
SEVERITY = "error"
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
from urdf_lint.ruleutil import numbers
from urdf_lint.rules._schema import urdf_iter


def check(model, ctx):
    for c in urdf_iter(model, "color"):
        if c.getparent() is None or c.getparent().tag != "material":
            continue
        v = c.get("rgba")
        if v is None:
            yield c, "<color> needs rgba=\"r g b a\""
            continue
        vals = numbers(v, 4)
        if vals is None:
            yield c, f"<color rgba=\"{v}\"> must be four numbers"
        elif any(x < 0 or x > 1 for x in vals):
            hint = " (0-255 values? divide by 255)" if any(x > 1 for x in vals) else ""
            yield c, f"<color rgba=\"{v}\"> values must be within [0, 1]{hint}"
