"""A `name`, `reference` or `link` attribute holds a literal `{var}` where `var` is a xacro
property or macro parameter: the `$` of `${var}` was forgotten.

Why: xacro copies `{prefix}link` as is, so the robot gets a link literally called
`{prefix}link`; joints, transmissions and Gazebo blocks that use the intended name no longer
find it.

How to fix: Write `${var}`.

Fix: safe: `--fix` adds the `$` where the attribute is written.
"""
CODE = "UL212"
NAME = "missing-dollar"
SEVERITY = "error"
FAIL = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="prefix" value="left_"/>
  <link name="${prefix}base"/>
  <link name="{prefix}tool"/>
  <joint name="${prefix}tool_joint" type="fixed"><parent link="${prefix}base"/><child link="${prefix}tool"/></joint>
</robot>
"""
FAIL_AT = [(4, 3)]
PASS = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="prefix" value="left_"/>
  <link name="${prefix}base"/>
  <link name="${prefix}tool"/>
  <joint name="${prefix}tool_joint" type="fixed"><parent link="${prefix}base"/><child link="${prefix}tool"/></joint>
</robot>
"""
import re

from urdf_lint.fixes import add_dollar, names_in_scope

ATTRS = ("name", "reference", "link")
_BRACED = re.compile(r"(?<![$\w}]){([A-Za-z_]\w*)}")


def check(model, ctx):
    known = None
    for el in model.root.iter():
        if not isinstance(el.tag, str):
            continue
        for a in ATTRS:
            v = el.get(a)
            if not v or "{" not in v:
                continue
            hits = _BRACED.findall(v)
            if not hits:
                continue
            if known is None:
                known = names_in_scope(model)
            names = [h for h in hits if h in known]
            if names:
                yield el, (f"{a}=\"{v}\" holds a literal '{{{names[0]}}}', and '{names[0]}' is a "
                           f"xacro property or parameter: did you mean '${{{names[0]}}}'?"), \
                    add_dollar(a, names)
