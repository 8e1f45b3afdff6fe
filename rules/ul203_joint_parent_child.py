"""A joint lacks its `<parent link=...>` or `<child link=...>`.

Why: Every joint connects exactly one parent link to one child link; parsers refuse a joint
without them.

How to fix: Add the missing element with the link it connects.
"""
CODE = "UL203"
NAME = "joint-parent-child"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="fixed"><parent link="a"/></joint>
</robot>
"""
FAIL_AT = [(3, 3)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>
"""


from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    for j in model.top_joints():
        for role in ("parent", "child"):
            found = j.findall(role)
            if not found:
                yield Report(j, f"joint '{j.get('name')}' has no <{role} link=...>")
            elif len(found) > 1:
                yield Report(found[1], f"joint '{j.get('name')}' has {len(found)} <{role}> elements")
            elif not (found[0].get("link") or "").strip():
                yield Report(found[0], f"joint '{j.get('name')}': <{role}> has no link attribute")
