"""A joint `<limit>` lacks `effort` or `velocity`, or one of them is not positive.

Why: URDF parsers require both on revolute and prismatic joints. A velocity of 0 loads in
every consumer measured (urdfdom 6.0.0, MuJoCo 4.0.0, Pinocchio 4.1.0, PyBullet 3.2.7, Drake
1.51.1, the Python parsers), often as a placeholder, but
the joint can never move under ros2_control or MoveIt (they clamp to it): a warning. `effort="0"` is different: it is
the ROS-Industrial convention for position-controlled industrial arms, whose drives are not
torque-controlled (the vendor packages of FANUC, ABB, Motoman ... write it on purpose). It is
reported as a warning naming that convention, because it still breaks effort-based controllers
and simulators.

A missing `effort` is rejected by urdfdom, Pinocchio and the Python parsers; MuJoCo 4.0.0 and
PyBullet 3.2.7 load it (a warning for `mujoco` and `pybullet`) (measured with MuJoCo 4.0.0, Pinocchio 4.1.0, PyBullet 3.2.7).

URDF 1.2's `acceleration`, `deceleration` and `jerk` must be numbers of at least 0: urdfdom
6.0.0 rejects a negative or non-numeric one (measured through Pinocchio 4.1.0); 0 is a warning.

How to fix: Set both to the actuator's real maxima (N or Nm, m/s or rad/s).

Options: `zero-effort` (`"warning"`, the default, or `"error"`) is the severity of
`effort="0"`; `"error"` makes it strict, e.g. under `[tool.urdf-lint.rule-options.UL304]`
write `zero-effort = "error"`.
"""
CODE = "UL304"
NAME = "effort-velocity"
SEVERITY = "error"
OPTIONS = {"zero-effort": "warning"}
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" velocity="0"/></joint>
</robot>
"""
FAIL_AT = [(4, 5)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="30" velocity="2"/></joint>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, number

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model

ZERO_EFFORT = ("a ROS-Industrial convention for position-controlled arms, but effort-based "
               "controllers and simulators cannot move the joint; write the drive's rated torque "
               "or force if you know it")


def check(model: "Model", ctx: "Context") -> "Checked":
    zero_effort = str(ctx.options.get("zero-effort", "warning")).lower()
    zero_effort = zero_effort if zero_effort in ("warning", "error", "info") else "warning"
    for j in model.top_joints():
        lim = j.find("limit")
        if lim is None:
            continue
        required = j.get("type") in ("revolute", "prismatic")
        for a in ("effort", "velocity"):
            v = lim.get(a)
            if v is None:
                if required:
                    yield Report(lim, f"joint '{j.get('name')}': <limit> has no {a}", targets={"mujoco": "warning", "pybullet": "warning", "yourdfpy": "warning", "idyntree": "warning", "isaac": "warning", "drake": "warning"} if a == "effort" else None)
                continue
            n = number(v)
            if n is None:
                yield Report(lim, f"joint '{j.get('name')}': limit {a}={v!r} is not a number")
            elif n == 0 and a == "effort" and required:
                yield Report(lim, f"joint '{j.get('name')}': limit effort=0 is {ZERO_EFFORT}", severity=zero_effort)
            elif n == 0 and a == "velocity" and required:
                yield Report(lim, (f"joint '{j.get('name')}': limit velocity=0: every consumer loads it, "
                                   "but ros2_control and MoveIt can never move the joint"), severity="warning")
            elif n <= 0 and required:
                yield Report(lim, f"joint '{j.get('name')}': limit {a}={v} must be positive")
        for a in ("acceleration", "deceleration", "jerk"):   # URDF 1.2
            v = lim.get(a)
            if v is None:
                continue
            n = number(v)
            if n is None or n < 0:
                yield Report(lim, (f"joint '{j.get('name')}': limit {a}={v!r} must be a positive number "
                                   "(urdfdom 6 rejects the model)"))
            elif n == 0:
                yield Report(lim, (f"joint '{j.get('name')}': limit {a}=0: the joint could never "
                                   "accelerate under a planner that reads it"), severity="warning")
