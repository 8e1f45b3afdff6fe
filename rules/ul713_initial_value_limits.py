"""An initial joint position is outside the joint's limits: a `<ros2_control>` state interface's `initial_value`, or an entry of `initial_positions.yaml`.

Why: the mock hardware (and gz_ros2_control) starts the joint there; the joint trajectory
controller then refuses every trajectory that starts out of bounds, and MoveIt reports the start
state as invalid ("Joint 'X' from the starting state is outside bounds"): the simulated robot
cannot move until the value is fixed.

Consumers: ros and gazebo (gz_ros2_control reads the same initial values).

How to fix: Use a value within the joint's `<limit lower upper>` (the related location).
"""
CODE = "UL713"
NAME = "initial-value-limits"
SEVERITY = "warning"
TARGETS = {"*": "off", "ros": "warning", "gazebo": "warning"}
from urdf_lint.rules._config import example_robot
FAIL = example_robot(("joint1", "base", "l1"))
PASS = FAIL.replace('upper="1"', 'upper="2"')
EXAMPLE_FILES = {"config/r.srdf": """<robot name="r">
</robot>
""", "config/initial_positions.yaml": """initial_positions:
  joint1: 1.5
"""}
EXAMPLE_AT = "config/initial_positions.yaml"
FAIL_AT = [(2, 11)]
from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report, fmt, number

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import docs, joint_limits, resolve_name, ros2_control_joints, scalar

SLACK = 1e-9


def _outside(model: "Model", name: str, v: float | None) -> Any:
    lo, hi, *_ = joint_limits(model, name)
    if lo is None or hi is None or v is None or lo - SLACK <= v <= hi + SLACK:
        return None
    return f"outside the limits [{fmt(lo)}, {fmt(hi)}] of joint '{name}'"


def check(model: "Model", ctx: "Context") -> "Checked":
    for name, (el, _, _) in ros2_control_joints(model).items():
        for p in el.iterfind("state_interface[@name='position']/param"):
            if p.get("name") != "initial_value":
                continue
            why = _outside(model, name, number(p.text))
            if why:
                yield Report(p, f"initial_value {p.text.strip()} of <ros2_control> joint is {why}",
                             related=None)
    for doc in docs(ctx, "initial-positions"):
        pos = doc.root.get("initial_positions") if doc.root is not None else None
        for raw, node in (pos.items() if pos is not None else ()):
            name, _ = resolve_name(ctx, raw)
            v = scalar(node)
            why = _outside(model, name, v)
            if why and v is not None:
                yield Report(doc.at(node), f"initial position {fmt(v)} is {why}",
                             related=model.joints[name].find("limit"))
