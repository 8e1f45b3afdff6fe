"""A suppression comment urdf-lint cannot understand: an unknown directive (`disabel-next`) or a
code that names no rule (`UL999`), like ruff's invalid-noqa.

Why: Such a comment suppresses nothing, so the finding it was written for is still reported,
or, worse, a suppression you believe is in place is not.

How to fix: Use the directive or code the message suggests. Directives are `disable-next`,
`disable`, `enable` and `disable-file`; codes are rule codes, code prefixes (`UL3`) or rule
names (`limit-order`).
"""
CODE = "UL010"
NAME = "invalid-suppression"
SEVERITY = "warning"
ORIGIN = "engine"
FAIL = """<robot name="r">
  <!-- urdf-lint: disabel-next UL103 -->
  <link name="a"/>
</robot>
"""
FAIL_AT = [(2, 3)]
PASS = """<robot name="r">
  <link name="a"/>
  <!-- urdf-lint: disable-next missing-link, UL1 -->
  <joint name="j" type="fixed"><parent link="a"/><child link="c"/></joint>
</robot>
"""
