"""A `name`, `reference` or `link` attribute holds a literal `{var}` where `var` is a xacro
property or macro parameter: the `$` of `${var}` was forgotten. Checked in the URDF elements,
on `<gazebo reference>`, and on the joints of `<transmission>` and `<ros2_control>` blocks (not
in the SDF inside `<gazebo>`).

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
  <link name="arm_{prefix}tip"/>
</robot>
"""
FAIL_AT = [(4, 3), (6, 3)]
PASS = FAIL.replace('<link name="{prefix}tool"/>', '<link name="${prefix}tool"/>').replace(
    '<link name="arm_{prefix}tip"/>', '<link name="arm_${prefix}tip"/>')
from typing import TYPE_CHECKING, Any, Iterator
from urdf_lint.engine.api import Report, add_dollar, names_in_scope

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._schema import BRACED, checked_elements, literal_names, urdf_iter

ATTRS = ("name", "reference", "link")


def _elements(model: "Model") -> Iterator[Any]:
    """The URDF part, the extension blocks' own tags (``<gazebo reference>``), and the joints
    and links that ``<transmission>`` and ``<ros2_control>`` blocks name (their content is
    not URDF, but its names are the robot's); SDF inside ``<gazebo>`` is left alone."""
    yield from checked_elements(model)
    for tag in ("transmission", "ros2_control"):
        for block in urdf_iter(model, tag):
            for el in block.iter():
                if el is not block and isinstance(el.tag, str):
                    yield el


def check(model: "Model", ctx: "Context") -> "Checked":
    known = None
    for el in _elements(model):
        for a in ATTRS:
            v = el.get(a)
            if not v or "{" not in v:
                continue
            if not BRACED.search(v):
                continue
            if known is None:
                known = names_in_scope(model)
            names = literal_names(model, v, known)
            if names:
                yield Report(el, (f"{a}=\"{v}\" holds a literal '{{{names[0]}}}', and '{names[0]}' is a "
                                  f"xacro property or parameter: did you mean '${{{names[0]}}}'?"), fix=add_dollar(a, names))
