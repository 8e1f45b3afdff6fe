"""A planning group's joints are not all driven by the controllers MoveIt executes with: no controller in `moveit_controllers.yaml` (or, with MoveIt's ros2_control manager, in the controller YAML) commands some of them.

Why: MoveIt plans for the group and then cannot execute the trajectory ("Unable to identify any
set of controllers that can actuate the specified joints"): the configuration lists the joints
of an older robot, or a group was added without its controller. Mimic and passive joints
follow others and need no controller; groups of fixed joints are skipped. With several MoveIt
controller files (`moveit_controllers.yaml`, `gripper_moveit_controllers.yaml`: alternatives a
launch file picks from), a joint driven in any of them counts.

Consumers: ros (MoveIt) only.

How to fix: Add the missing joints to the controller serving the group (the related location is
the first uncovered joint), or add a controller for them.
"""
CODE = "UL715"
NAME = "moveit-controller-coverage"
SEVERITY = "warning"
TARGETS = {"*": "off", "ros": "warning"}
from urdf_lint.rules._config import ARM_SRDF_EXAMPLE, example_robot, LIMIT, moveit_controllers_example
FAIL = example_robot(*((j, p, c, LIMIT + ' acceleration="1"') for j, p, c in
                       (("joint1", "base", "l1"), ("joint2", "l1", "l2"))), links=("base", "l1", "l2"))
PASS = FAIL.replace('<joint name="joint2" type="revolute">', '<joint name="joint2" type="fixed">')
EXAMPLE_FILES = {"config/r.srdf": ARM_SRDF_EXAMPLE, "config/moveit_controllers.yaml": moveit_controllers_example("joint1")}
EXAMPLE_AT = "config/r.srdf"
FAIL_AT = [(2, 3)]
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import (actuated, controller_joints, controllers, docs, group_joints,
                                     groups, moveit_controllers, names, resolve_name, srdfs)

EXECUTING = ("joint_trajectory_controller/", "position_controllers/GripperActionController",
             "effort_controllers/GripperActionController",
             "parallel_gripper_action_controller/")


def driven(ctx: "Context") -> set[str] | None:
    """The joints MoveIt's controllers drive, or None when no controller is configured for
    MoveIt (nothing to compare with)."""
    out: set[str] = set()
    simple = False
    for _, _, node in moveit_controllers(ctx):
        if isinstance(node.value, dict):
            simple = True
            out |= {resolve_name(ctx, n.value)[0] for n in names(node.get("joints"))}
    if simple:
        return out
    if not docs(ctx, "moveit-controllers"):
        return None
    # MoveIt's ros2_control manager: the controller_manager's trajectory and gripper controllers
    for doc in docs(ctx, "controllers"):
        for _, ctype, params in controllers(doc):
            if ctype.startswith(EXECUTING):
                out |= {resolve_name(ctx, n.value)[0] for n in controller_joints(params)}
    return out or None


def check(model: "Model", ctx: "Context") -> "Checked":
    have = driven(ctx)
    if have is None:
        return
    for doc in srdfs(ctx):
        passive = {p.get("name") for p in doc.root.iterfind("passive_joint")}
        for name, g in groups(doc.root).items():
            active = [j for j in group_joints(model, doc.root, name)
                      if actuated(model, j) and j not in passive]
            missing = [j for j in active if j not in have]
            if missing:
                yield Report(doc.at(g), f"no MoveIt controller drives {', '.join(repr(m) for m in missing)}"
                             f" of group '{name}': its trajectories cannot be executed",
                             related=model.joints[missing[0]])
