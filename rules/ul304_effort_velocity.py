"""A joint `<limit>` lacks `effort` or `velocity`, or one of them is not positive.

Why: URDF parsers require both on revolute and prismatic joints; 0 means the joint can never
move under control (controllers clamp to it).

How to fix: Set both to the actuator's real maxima (N or Nm, m/s or rad/s).
"""
CODE = "UL304"
NAME = "effort-velocity"
SEVERITY = "error"
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
from urdf_lint.ruleutil import number


def check(model, ctx):
    for j in model.top_joints():
        lim = j.find("limit")
        if lim is None:
            continue
        required = j.get("type") in ("revolute", "prismatic")
        for a in ("effort", "velocity"):
            v = lim.get(a)
            if v is None:
                if required:
                    yield lim, f"joint '{j.get('name')}': <limit> has no {a}"
                continue
            n = number(v)
            if n is None:
                yield lim, f"joint '{j.get('name')}': limit {a}={v!r} is not a number"
            elif n <= 0 and required:
                yield lim, f"joint '{j.get('name')}': limit {a}={v} must be positive"
