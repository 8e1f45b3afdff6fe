"""A link mass that is not positive, or implausibly tiny.

Why: Zero or negative masses break every physics engine; tiny masses usually mean grams or
millimetre-based units were written as kilograms.

How to fix: Write the mass in kilograms.

Options: `min-mass` (default 1e-06): masses below this many kilograms are reported as
implausibly tiny.
"""
CODE = "UL602"
NAME = "mass"
SEVERITY = "error"
OPTIONS = {"min-mass": 1e-6}
FAIL = """<robot name="r">
  <link name="a"><inertial><mass value="0"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
</robot>
"""
FAIL_AT = [(2, 28)]
PASS = """<robot name="r">
  <link name="a"><inertial><mass value="0.5"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
</robot>
"""
from urdf_lint.ruleutil import number


def check(model, ctx):
    tiny = float(ctx.options.get("min-mass", 1e-6))
    for lk in model.top_links():
        m = lk.find("inertial/mass")
        if m is None:
            continue
        v = number(m.get("value"))
        if v is None:
            continue  # UL206
        if v <= 0:
            yield m, f"link '{lk.get('name')}': mass {v:g} must be positive"
        elif v < tiny:
            yield m, f"link '{lk.get('name')}': mass {v:g} kg is implausibly small (grams?)"
