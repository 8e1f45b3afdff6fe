"""An element URDF does not define at that place: usually a typo such as `<orgin>` or `<inertia>`
directly under `<link>`.

Why: URDF parsers skip unknown elements silently, so the value you meant is lost. Extension
blocks (`<gazebo>`, `<transmission>`, `<ros2_control>`, `<mujoco>`) and namespaced elements
(`drake:...`) are not checked.

How to fix: Fix the element's name or move it to where URDF expects it (the message suggests the
closest known name).

Fix: safe, when there is a single "did you mean" candidate and no sibling of that name: `--fix`
renames the start and end tag in the source.
"""
CODE = "UL209"
NAME = "unknown-element"
SEVERITY = "warning"
FAIL = """<robot name="r">
  <link name="a">
    <visual><orgin xyz="0 0 1"/><geometry><sphere radius="1"/></geometry></visual>
  </link>
</robot>
"""
FAIL_AT = [(3, 13)]
PASS = """<robot name="r">
  <link name="a">
    <visual><origin xyz="0 0 1"/><geometry><sphere radius="1"/></geometry></visual>
  </link>
</robot>
"""
from urdf_lint.fixes import rename_tag
from urdf_lint.ruleutil import did_you_mean, single_candidate
from urdf_lint.rules._schema import CHILDREN, checked_elements


def check(model, ctx):
    for el in checked_elements(model):
        allowed = CHILDREN.get(el.tag)
        if allowed is None:
            continue
        for c in el:
            if not isinstance(c.tag, str) or c.tag.startswith("{") or ":" in c.tag:
                continue
            if c.tag not in allowed:
                to = single_candidate(c.tag, allowed)
                clash = to is None or el.find(to) is not None
                yield c, (f"unknown element <{c.tag}> in <{el.tag}>" + did_you_mean(c.tag, allowed)
                          + "; URDF parsers ignore it"), (None if clash else rename_tag(c.tag, to))
