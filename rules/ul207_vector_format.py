"""`origin xyz/rpy` or `axis xyz` is not three finite numbers.

Why: Two or four numbers, stray characters (`"0 0 1 }"`) or `nan` make URDF parsers fail or
produce NaN transforms.

How to fix: Write exactly three numbers separated by spaces.
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
from urdf_lint.ruleutil import numbers

SKIP_UNDER = {"gazebo", "ros2_control", "transmission"}


def _skip(el):
    p = el.getparent()
    while p is not None:
        if p.tag in SKIP_UNDER:
            return True
        p = p.getparent()
    return False


def check(model, ctx):
    for tag, attrs in (("origin", ("xyz", "rpy")), ("axis", ("xyz",))):
        for e in model.root.iter(tag):
            if _skip(e):
                continue
            for a in attrs:
                v = e.get(a)
                if v is not None and numbers(v, 3) is None:
                    yield e, f"<{tag} {a}=\"{v}\"> must be three finite numbers"
