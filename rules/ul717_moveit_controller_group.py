"""A joint of a MoveIt controller (`moveit_controllers.yaml`) belongs to no planning group of the SRDF, or no one group holds all of a controller's joints.

Why: MoveIt executes a trajectory planned for one group by sending each controller the part of
it for that controller's joints; a controller is meant to serve a group (the arm's trajectory
controller, the hand's gripper controller). A controller joint that no group contains is never
planned for: the joint trajectory controller receives goals missing that joint and rejects
them unless `allow_partial_joints_goal` is set, and the group it was meant for (a joint
renamed in the SRDF, a group removed) is not what the controller drives. Likewise a controller
whose joints are each in some group but in no one group together (an arm and its gripper in
one controller, with an `arm` and a `hand` group and no group of both): MoveIt sends it the
trajectory of one group, without the others' joints (reported once, at its `joints` key).
Joints the robot does not have are UL710's; MoveIt's ros2_control manager (no joint lists in the
file) is not checked.

Consumers: ros (MoveIt) only.

How to fix: Add the joint to the group the controller serves (the related location: the SRDF
group holding most of the controller's other joints), or remove it from the controller.
"""
CODE = "UL717"
NAME = "moveit-controller-group"
SEVERITY = "warning"
TARGETS = {"*": "off", "ros": "warning"}
from urdf_lint.rules._config import ARM_SRDF_EXAMPLE, example_robot, moveit_controllers_example
FAIL = example_robot(("joint1", "base", "l1"), ("joint2", "l1", "l2"), ("joint3", "l2", "l3"),
                     links=("base", "l1", "l2", "l3"))
PASS = FAIL
EXAMPLE_FILES = {"config/r.srdf": ARM_SRDF_EXAMPLE, "config/moveit_controllers.yaml":
                 moveit_controllers_example("joint1", "joint2", "joint3")}
PASS_FILES = {"config/r.srdf": ARM_SRDF_EXAMPLE.replace('tip_link="l2"', 'tip_link="l3"')}
EXAMPLE_AT = "config/moveit_controllers.yaml"
FAIL_AT = [(9, 9)]
from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import group_joints, groups, moveit_controllers, names, resolve_name, srdfs


def check(model: "Model", ctx: "Context") -> "Checked":
    docs = srdfs(ctx)
    if not docs:
        return
    # every group of every SRDF tied to the model: (doc, group element, its joints)
    served = [(doc, g, set(group_joints(model, doc.root, name)))
              for doc in docs for name, g in groups(doc.root).items()]
    grouped = set().union(*(js for _, _, js in served))
    for doc, cname, node in moveit_controllers(ctx):
        if isinstance(node.value, dict):
            yield from _controller(model, ctx, doc, cname, node, served, grouped)


def _controller(model: "Model", ctx: "Context", doc: Any, cname: str, node: Any, served: Any,
                grouped: Any) -> Any:
    joints = [(n, resolve_name(ctx, n.value)) for n in names(node.get("joints"))]
    # its joints MoveIt can know: resolved (else UL714) and the robot's (else UL710)
    have = {name for _, (name, left) in joints if not left and name in model.joints}
    best = max(served, key=lambda s: len(s[2] & have), default=None)
    serves = best if best is not None and best[2] & have else None
    also = f" (the controller serves group '{serves[1].get('name')}')" if serves else ""
    outside = [(n, name) for n, (name, left) in joints if name in have and name not in grouped]
    for n, name in outside:
        yield Report(doc.at(n), f"MoveIt controller '{cname}' drives joint '{name}', which no "
                     f"planning group of the SRDF contains{also}: MoveIt never plans for it",
                     related=serves[0].at(serves[1]) if serves else model.joints[name])
    if not outside and serves and not any(have <= js for _, _, js in served):
        split = sorted({s[1].get("name") for s in served if s[2] & have})
        yield Report(doc.key_at(node.get("joints")), f"MoveIt controller '{cname}' drives joints "
                     f"of groups {', '.join(repr(g) for g in split)} and no group holds them "
                     "all: a trajectory planned for one group reaches it without the others' "
                     "joints", related=serves[0].at(serves[1]))
