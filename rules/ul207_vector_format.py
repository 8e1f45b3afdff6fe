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
from urdf_lint.rules._schema import urdf_iter


def check(model, ctx):
    for tag, attrs in (("origin", ("xyz", "rpy")), ("axis", ("xyz",))):
        for e in urdf_iter(model, tag):
            for a in attrs:
                v = e.get(a)
                if v is not None and numbers(v, 3) is None:
                    yield e, f"<{tag} {a}=\"{v}\"> must be three finite numbers"
