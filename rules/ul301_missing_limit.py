"""A revolute or prismatic joint has no `<limit>`.

Why: URDF requires `<limit effort=... velocity=...>` (and usually `lower`/`upper`) on these
joints; urdfdom, Pinocchio and PyBullet refuse the model without it. MuJoCo 4.0.0 loads it as
an unlimited joint: a warning for `mujoco` (measured with MuJoCo 4.0.0, Pinocchio 4.1.0, PyBullet 3.2.7).

How to fix: Add the limit. If the joint really has no position limits, make it `continuous`.
"""
CODE = "UL301"
NAME = "missing-limit"
SEVERITY = "error"
TARGETS = {"mujoco": "warning", "yourdfpy": "warning", "urdf_parser_py": "warning",
           "idyntree": "warning", "isaac": "warning", "drake": "warning"}
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>
</robot>
"""
FAIL_AT = [(3, 3)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._joints import moving


def check(model: "Model", ctx: "Context") -> "Checked":
    for j in model.top_joints():
        if moving(j) and j.find("limit") is None:
            yield Report(j, (f"{j.get('type')} joint '{j.get('name')}' has no <limit>; add "
                             "<limit lower=... upper=... effort=... velocity=...>"))
