"""MoveIt's `joint_limits.yaml` sets limits for a joint the robot does not have.

Why: MoveIt reads the limits of the robot's joints only, so the entry is silently ignored: the
joint it was meant for (renamed in the xacro) runs with the URDF's limits, or with none.

Consumers: ros (MoveIt) only.

How to fix: Rename the entry to the joint's new name (the related location is the closest
joint of the robot), or remove it.

Fix: unsafe, when the name has one close candidate among the robot's joints (the element renamed
in the xacro): `--fix --unsafe-fixes` renames it on the reported line, verified by re-linting.
"""
CODE = "UL760"
NAME = "joint-limits-unknown-joint"
SEVERITY = "warning"
TARGETS = {"*": "off", "ros": "warning"}
from urdf_lint.rules._config import example_robot, LIMITS_EXAMPLE_FILES
FAIL = example_robot(("joint_1", "base", "l1"))
PASS = FAIL.replace("joint_1", "joint1")
EXAMPLE_FILES = LIMITS_EXAMPLE_FILES
EXAMPLE_AT = "config/joint_limits.yaml"
FAIL_AT = [(2, 3)]
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import closest, limit_entries, rename_fix


def check(model: "Model", ctx: "Context") -> "Checked":
    for doc, name, node in limit_entries(ctx):
        if name in model.joints:
            continue
        near, rel = closest(model, name, model.joints)
        yield Report(doc.key_at(node), f"joint_limits.yaml sets limits for joint '{name}', which "
                     f"robot '{model.name}' does not have" + near, related=rel,
                             fix=rename_fix(doc.key_at(node), name, model.joints, doc))
