"""MoveIt's `joint_limits.yaml` allows more than the URDF: a `max_velocity` or `max_effort` above the joint's `<limit>`, or a `max_position`/`min_position` beyond its range.

Why: MoveIt takes the YAML's value over the URDF's, so it plans trajectories the hardware
interface and the controllers (which read the URDF's limits) reject or clamp mid-motion; the
YAML is meant to tighten limits for planning, not to widen them. A value equal to the URDF's
is fine.

Consumers: ros (MoveIt) only.

How to fix: Lower the YAML value to at most the URDF's (the related location is the joint's
`<limit>` in the xacro), or raise the URDF's limit if the hardware allows it.
"""
CODE = "UL761"
NAME = "joint-limits-exceed-urdf"
SEVERITY = "warning"
TARGETS = {"*": "off", "ros": "warning"}
from urdf_lint.rules._config import example_robot, LIMIT, LIMITS_EXAMPLE_FILES
FAIL = example_robot(("joint1", "base", "l1", LIMIT.replace('velocity="1"', 'velocity="0.25"')))
PASS = FAIL.replace('velocity="0.25"', 'velocity="1"')
EXAMPLE_FILES = LIMITS_EXAMPLE_FILES
EXAMPLE_AT = "config/joint_limits.yaml"
FAIL_AT = [(4, 19)]
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, fmt

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import joint_limits, limit_entries, scalar

SLACK = 1e-9


def check(model: "Model", ctx: "Context") -> "Checked":
    for doc, name, node in limit_entries(ctx):
        if name not in model.joints:
            continue
        lo, hi, vel, eff, _ = joint_limits(model, name)
        lim = model.joints[name].find("limit")
        for key, urdf, above, flag, what in (
                ("max_velocity", vel, True, "has_velocity_limits", "velocity"),
                ("max_effort", eff, True, "has_effort_limits", "effort"),
                ("max_position", hi, True, "has_position_limits", "upper"),
                ("min_position", lo, False, "has_position_limits", "lower")):
            v = scalar(node.get(key))
            on = node.get(flag)
            if v is None or urdf is None or (on is not None and on.value is False):
                continue
            if (v > urdf + SLACK) if above else (v < urdf - SLACK):
                yield Report(doc.at(node.get(key)), f"{key} {fmt(v)} of joint '{name}' is "
                             f"{'above' if above else 'below'} the URDF's {what} "
                             f"{fmt(urdf)}: MoveIt plans beyond what the robot's limit allows",
                             related=lim)
