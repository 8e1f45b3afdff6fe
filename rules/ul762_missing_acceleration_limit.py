"""A moving joint of a planning group has no acceleration limit: neither MoveIt's `joint_limits.yaml` (`has_acceleration_limits: true` with `max_acceleration`) nor the URDF's `<limit acceleration>` (URDF 1.2) gives one.

Why: MoveIt 2's time parameterisation (TOTG, the default request adapter) refuses to time a
trajectory for a joint without an acceleration limit ("No acceleration limit was defined for
joint X! You have to define acceleration limits in the URDF or joint_limits.yaml",
moveit/moveit2#3504): planning succeeds and execution fails. Checked for the joints of the
SRDF's groups, when a `joint_limits.yaml` is tied to the robot.

Consumers: ros (MoveIt) only.

How to fix: Add `has_acceleration_limits: true` and `max_acceleration` for the joint in
`joint_limits.yaml` (at the reported line), or an `acceleration` to its `<limit>`.
"""
CODE = "UL762"
NAME = "missing-acceleration-limit"
SEVERITY = "warning"
TARGETS = {"*": "off", "ros": "warning"}
from urdf_lint.rules._config import ARM_SRDF_EXAMPLE, example_robot
FAIL = example_robot(("joint1", "base", "l1"), ("joint2", "l1", "l2"), links=("base", "l1", "l2"))
PASS = FAIL.replace('<joint name="joint2" type="revolute">', '<joint name="joint2" type="fixed">')
EXAMPLE_FILES = {"config/r.srdf": ARM_SRDF_EXAMPLE, "config/joint_limits.yaml": """joint_limits:
  joint1:
    has_acceleration_limits: true
    max_acceleration: 1.0
  joint2:
    has_acceleration_limits: false
    max_acceleration: 0
"""}
EXAMPLE_AT = "config/joint_limits.yaml"
FAIL_AT = [(5, 3)]
from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Origin, Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import (actuated, group_joints, groups, joint_limits, limit_entries,
                                     scalar, srdfs)


def check(model: "Model", ctx: "Context") -> "Checked":
    entries = {name: (doc, node) for doc, name, node in limit_entries(ctx)}
    if not entries or not srdfs(ctx):
        return
    doc0 = next(iter(entries.values()))[0]
    planned: dict[Any, Any] = {}
    for sd in srdfs(ctx):
        for g in groups(sd.root):
            for j in group_joints(model, sd.root, g):
                planned.setdefault(j, g)
    for j, g in planned.items():
        if not actuated(model, j):
            continue
        if joint_limits(model, j)[4]:
            continue
        doc, node = entries.get(j, (doc0, None))
        if node is not None:
            on, acc = node.get("has_acceleration_limits"), scalar(node.get("max_acceleration"))
            if on is not None and on.value is True and acc:
                continue
        top = doc.root.get("joint_limits")
        at = doc.key_at(node) if node is not None else doc.key_at(top) if top is not None \
            else Origin(doc.path, 1, 1)
        yield Report(at, f"joint '{j}' of group '{g}' has no acceleration limit (none in "
                     "joint_limits.yaml nor in the URDF): MoveIt 2's time parameterisation "
                     "refuses its trajectories", related=model.joints[j])
