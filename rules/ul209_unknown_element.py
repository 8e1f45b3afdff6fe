"""An element URDF does not define at that place: usually a typo such as `<orgin>` or `<inertia>`
directly under `<link>`.

Why: URDF parsers skip unknown elements silently, so the value you meant is lost. Extension
blocks (`<gazebo>`, `<transmission>`, `<ros2_control>`, `<mujoco>`) and namespaced elements
(`drake:...`) are not checked.

Three cases say more, because a consumer silently loses data there (none of them warns but
urdf_parser_py): a misspelled element that changes the
kinematics or the dynamics (`<orgin>`, `<axsi>`, `<mas>` in a joint, inertial, visual or
collision: the origin, axis or mass is silently dropped) is an error; a xacro directive or a
macro call that lost its `xacro:` prefix (`<insert_block name="origin"/>`, `<sensor_d435 .../>`)
is named as such, an error where it was meant to produce an origin, geometry or inertia (in a
joint, inertial, visual, collision or geometry), else a warning; a second `<mass>`, `<origin>`,
`<inertia>` ... where URDF reads only one is reported: the parsers read the first and ignore the
rest.

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
from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report, did_you_mean, rename_tag, single_candidate

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._schema import CHILDREN, SINGLE, XACRO_WORDS, checked_elements, macro_names

# a misspelling of one of these, where it is, changes the robot's kinematics or dynamics
DROPS_DATA = {"origin", "axis", "parent", "child", "mass", "inertia", "geometry", "limit",
              "mimic"}
# a lost xacro directive or macro call here was meant to write an origin, geometry or inertia
PRODUCES = {"joint", "inertial", "visual", "collision", "geometry"}


def _lost_prefix(model: "Model", el: Any, c: Any) -> Any:
    """(message, severity) when ``c`` is a xacro directive or a macro call without its prefix."""
    macro = c.tag in macro_names(model)
    if c.tag not in XACRO_WORDS and not macro:
        return None
    what = f"a call of the macro '{c.tag}'" if macro else f"the xacro directive <xacro:{c.tag}>"
    block = c.get("name", "") if c.tag == "insert_block" else ""
    lost = el.tag in PRODUCES or any(w in block for w in ("origin", "geometry", "inertia"))
    return (f"<{c.tag}> in <{el.tag}> is {what} without its 'xacro:' prefix: xacro copied it "
            "into the URDF as it is, and URDF parsers ignore it"
            + (f", so this <{el.tag}> loses what it was meant to write" if lost else "")
            + f"; write <xacro:{c.tag}>"), ("error" if lost else "warning")


def check(model: "Model", ctx: "Context") -> "Checked":
    for el in checked_elements(model):
        allowed = CHILDREN.get(el.tag)
        if allowed is None:
            continue
        once: set[Any] = set()
        for c in el:
            if not isinstance(c.tag, str) or c.tag.startswith("{") or ":" in c.tag:
                continue
            if c.tag in SINGLE.get(el.tag, ()):
                if c.tag in once:
                    yield Report(c, (f"a second <{c.tag}> in <{el.tag}>: URDF parsers read the first one "
                                     "and ignore this one"))
                once.add(c.tag)
            if c.tag not in allowed:
                lost = _lost_prefix(model, el, c)
                if lost is not None:
                    yield Report(c, lost[0], severity=lost[1])
                    continue
                to = single_candidate(c.tag, allowed)
                clash = to is None or el.find(to) is not None
                if to in DROPS_DATA and el.tag in ("joint", "inertial", "visual", "collision") \
                        and el.find(to) is None:
                    yield Report(c, (f"unknown element <{c.tag}> in <{el.tag}> (did you mean '{to}'?): "
                                     f"every URDF parser ignores it silently, so this <{el.tag}> has no "
                                     f"<{to}> and its default is used instead"), severity="error", fix=rename_tag(c.tag, to) if to is not None and not clash else None)
                    continue
                yield Report(c, (f"unknown element <{c.tag}> in <{el.tag}>" + did_you_mean(c.tag, allowed)
                                 + "; URDF parsers ignore it"), fix=rename_tag(c.tag, to) if to is not None and not clash else None)
