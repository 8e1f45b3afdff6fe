"""A joint of a MoveIt controller (`moveit_controllers.yaml`) belongs to no planning group of the SRDF.

Why: MoveIt executes a trajectory planned for one group by sending each controller the part of
it for that controller's joints; a controller is meant to serve a group (the arm's trajectory
controller, the hand's gripper controller). A controller joint that no group contains is never
planned for: the joint trajectory controller receives goals missing that joint and rejects
them unless `allow_partial_joints_goal` is set, and the group it was meant for (a joint
renamed in the SRDF, a group removed) is not what the controller drives. Joints the robot does
not have are UL710's; MoveIt's ros2_control manager (no joint lists in the file) is not checked.

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
from urdf_lint.engine.api import Report
from urdf_lint.rules._config import group_joints, groups, moveit_controllers, names, resolve_name, srdfs


def check(model, ctx):
    docs = srdfs(ctx)
    if not docs:
        return
    # every group of every SRDF tied to the model: (doc, group element, its joints)
    served = [(doc, g, set(group_joints(model, doc.root, name)))
              for doc in docs for name, g in groups(doc.root).items()]
    grouped = set().union(*(js for _, _, js in served))
    for doc, cname, node in moveit_controllers(ctx):
        if not isinstance(node.value, dict):
            continue
        joints = [(n, resolve_name(ctx, n.value)) for n in names(node.get("joints"))]
        have = {name for _, (name, left) in joints if not left and name in model.joints}
        for n, (name, left) in joints:
            if left or name not in model.joints or name in grouped:
                continue      # unresolved (UL714) or unknown (UL710), or planned for
            best = max(served, key=lambda s: len(s[2] & have), default=None)
            serves = best if best is not None and best[2] & have else None
            yield Report(doc.at(n), f"MoveIt controller '{cname}' drives joint '{name}', which "
                         "no planning group of the SRDF contains"
                         + (f" (the controller serves group '{serves[1].get('name')}')"
                            if serves else "")
                         + ": MoveIt never plans for it",
                         related=serves[0].at(serves[1]) if serves else model.joints[name])
