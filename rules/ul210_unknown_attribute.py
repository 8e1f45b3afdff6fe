"""An attribute URDF does not define on that element: usually a typo (`raduis`, `xzy`).

Why: Parsers ignore unknown attributes, so the value you meant is silently lost.

A full symmetric inertia tensor (`iyx`, `izx`, `izy` written out) is told apart from a typo:
URDF reads only the upper triangle, so the lower entries are ignored (an info when they equal
their twins, a warning when they differ: the upper one is used).

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
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, did_you_mean, number, rename_attr, single_candidate

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._schema import ATTRIBUTES, checked_elements


# the lower triangle of a symmetric tensor, and the upper-triangle entry URDF reads instead
LOWER = {"iyx": "ixy", "izx": "ixz", "izy": "iyz"}


def check(model: "Model", ctx: "Context") -> "Checked":
    for el in checked_elements(model):
        allowed = ATTRIBUTES.get(el.tag)
        if allowed is None:
            continue
        for a in el.attrib:
            if a.startswith("{") or ":" in a:
                continue
            if el.tag == "inertia" and a in LOWER:
                up = LOWER[a]
                mine, theirs = number(el.get(a)), number(el.get(up, "0"))
                same = mine is not None and theirs is not None and mine == theirs
                yield Report(el, (f"'{a}' on <inertia>: URDF reads only the upper triangle of the "
                                  f"symmetric tensor (ixy, ixz, iyz), so '{a}' is ignored"
                                  + ("" if same else f", and it differs from {up}={el.get(up, '0')}: "
                                     f"{up} is the value used")), severity="info" if same else "warning")
                continue
            if a not in allowed:
                to = single_candidate(a, allowed)
                yield Report(el, (f"unknown attribute '{a}' on <{el.tag}>" + did_you_mean(a, allowed)
                                  + "; URDF parsers ignore it"), fix=
                           rename_attr(a, to) if to and to not in el.attrib else None)
