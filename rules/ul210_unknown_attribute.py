"""An attribute URDF does not define on that element: usually a typo (`raduis`, `xzy`).

Why: Parsers ignore unknown attributes, so the value you meant is silently lost.

How to fix: Fix the attribute's name (the message suggests the closest known one).

Fix: safe, when there is a single "did you mean" candidate that the element does not already
have: `--fix` renames the attribute in the source.
"""
CODE = "UL210"
NAME = "unknown-attribute"
SEVERITY = "warning"
FAIL = """<robot name="r">
  <link name="a">
    <visual><geometry><sphere raduis="1"/></geometry></visual>
  </link>
</robot>
"""
FAIL_AT = [(3, 23)]
PASS = """<robot name="r">
  <link name="a">
    <visual><geometry><sphere radius="1"/></geometry></visual>
  </link>
</robot>
"""
from urdf_lint.fixes import rename_attr
from urdf_lint.ruleutil import did_you_mean, single_candidate
from urdf_lint.rules._schema import ATTRIBUTES, checked_elements


def check(model, ctx):
    for el in checked_elements(model):
        allowed = ATTRIBUTES.get(el.tag)
        if allowed is None:
            continue
        for a in el.attrib:
            if a.startswith("{") or ":" in a:
                continue
            if a not in allowed:
                to = single_candidate(a, allowed)
                yield el, (f"unknown attribute '{a}' on <{el.tag}>" + did_you_mean(a, allowed)
                           + "; URDF parsers ignore it"), (
                    rename_attr(a, to) if to and to not in el.attrib else None)
