"""A URDF 1.1 or 1.2 element that the robot's declared version does not include, or that a
selected consumer target does not read.

URDF 1.1 adds `quat_xyzw` on `<origin>` and the `<capsule>` shape; 1.2 adds `acceleration`,
`deceleration` and `jerk` on `<limit>`. urdfdom 6.0.0 reads them when `<robot version>` is at
least their version.

Why: Where they are not read, the data is silently lost. Measured with MuJoCo 4.0.0, Pinocchio
4.1.0 (urdfdom 6.0.0) and PyBullet 3.2.7: MuJoCo and PyBullet ignore
`quat_xyzw` (the frame keeps the identity orientation: a warning for `mujoco` and `pybullet`)
and have no acceleration or jerk limits (an info for them); both read `<capsule>` whatever the
version. Pinocchio reads all of them, but only from the declared version on: with `version`
absent or `1.0` it ignores `quat_xyzw` and drops a capsule geometry ("Could not parse visual
element"): a warning for `ros` and `pinocchio`. Not run here, from the notes in
urdf_parser_py 0.0.4 does not read them (its support is an
open pull request, ros/urdf_parser_py#95): a warning for `python`. urdfdom before 6 (the ROS 2
distributions before it) refuses `version="1.1"` altogether, per urdfdom's compatibility table;
Gazebo, Drake and Isaac Sim were not checked, so this rule says nothing for them.

How to fix: Declare `<robot version="1.1">` (or `"1.2"` for the limits) when you use them. For a
consumer that does not read them, write `rpy` instead of `quat_xyzw`, a cylinder (plus spheres)
instead of a capsule, and keep acceleration limits in the planner's config (e.g. MoveIt's
joint_limits.yaml).
"""
CODE = "UL213"
NAME = "urdf-version-feature"
SEVERITY = "warning"
TARGETS = {"*": "off", "ros": "warning", "pinocchio": "warning", "mujoco": "warning",
           "pybullet": "warning", "python": "warning", "idyntree": "error"}
EXAMPLE_TARGETS = ["ros", "mujoco"]
FAIL = """<robot name="r">
  <link name="a"><visual><geometry><capsule radius="0.1" length="0.5"/></geometry></visual></link>
  <link name="b"/>
  <joint name="j" type="revolute"><origin xyz="0 0 1" quat_xyzw="0 0 0.7071068 0.7071068"/>
    <parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1" acceleration="2"/></joint>
</robot>
"""
FAIL_AT = [(2, 36), (4, 35), (6, 5)]
PASS = """<robot name="r" version="1.2">
  <link name="a"><visual><geometry><capsule radius="0.1" length="0.5"/></geometry></visual></link>
  <link name="b"/>
  <joint name="j" type="revolute"><origin xyz="0 0 1" rpy="0 0 1.5707963"/>
    <parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""
import re

from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._schema import urdf_iter

# what a feature is, the version that defines it, and per target what happens where it is not
# read (the rule's docstring says where each entry comes from)
QUAT = ("quat_xyzw on <origin>", (1, 1), "the frame keeps the identity orientation",
        {"mujoco": "warning", "pybullet": "warning", "python": "warning"},
        "MuJoCo 4.0.0, PyBullet 3.2.7 and urdf_parser_py ignore it")
CAPSULE = ("<capsule>", (1, 1), "the model is refused",
           {"python": "error", "idyntree": "error"},
           "yourdfpy, urdf_parser_py and urchin reject it and iDynTree 15.1 crashes on it (MuJoCo "
           "and PyBullet read it)")
LIMITS = ("{attr} on <limit>", (1, 2), "no such limit is applied",
          {"mujoco": "info", "pybullet": "info", "python": "warning"},
          "MuJoCo 4.0.0 and PyBullet 3.2.7 have no such limit, urdf_parser_py does not read it")


def _version(model: "Model") -> tuple[int, int] | None:
    m = re.fullmatch(r"(\d+)\.(\d+)", model.root.get("version") or "1.0")
    return (int(m.group(1)), int(m.group(2))) if m else None


def _finding(feature: Any, declared: Any, attr: str = "") -> Any:
    what, since, lost, table, who = feature
    what = what.format(attr=attr)
    table = {"*": "off", **table}
    low = declared is not None and declared < since
    msg = f"{what} is URDF {since[0]}.{since[1]}"
    if low:
        table.update(ros="warning", pinocchio="warning")
        msg += (f", but the robot declares version {declared[0]}.{declared[1]}: urdfdom 6 "
                f"(ROS, Pinocchio) ignores it there, so {lost}; declare "
                f"version=\"{since[0]}.{since[1]}\"; also, {who}")
    else:
        msg += f": {who}, so there {lost}"
    return msg, table


def check(model: "Model", ctx: "Context") -> "Checked":
    declared = _version(model)
    for o in urdf_iter(model, "origin"):
        if o.get("quat_xyzw") is not None:
            msg, table = _finding(QUAT, declared)
            yield Report(o, msg, targets=table)
    for c in urdf_iter(model, "capsule"):
        if c.getparent() is not None and c.getparent().tag == "geometry":
            msg, table = _finding(CAPSULE, declared)
            yield Report(c, msg, targets=table)
    for lim in urdf_iter(model, "limit"):
        for attr in ("acceleration", "deceleration", "jerk"):
            if lim.get(attr) is not None:
                msg, table = _finding(LIMITS, declared, attr)
                yield Report(lim, msg, targets=table)
