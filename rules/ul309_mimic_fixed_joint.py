"""A `<mimic>` on a joint that cannot move (fixed), or one that follows a joint that is not
single-degree-of-freedom (fixed, floating, planar).

Why: A mimic relation couples two one-degree-of-freedom joints. Typical cause: a joint frozen
to `fixed` (for a variant without the gripper's motion) keeps its `<mimic>` line. Drake 1.51.1
rejects the model ("has 0 DOF cannot mimic"); urdfdom 6.0.0, MuJoCo 4.0.0, Pinocchio 4.1.0 and
PyBullet 3.2.7 load it and ignore the relation (measured).
An error for `drake`, a warning for the other targets.

How to fix: Remove the `<mimic>` from the fixed joint, or point it at a revolute, continuous or
prismatic joint.
"""
CODE = "UL309"
NAME = "mimic-fixed-joint"
SEVERITY = "warning"
TARGETS = {"drake": "error"}
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="j2" type="fixed"><parent link="a"/><child link="c"/><mimic joint="j1"/></joint>
</robot>
"""
FAIL_AT = [(4, 68)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>
  <joint name="j2" type="continuous"><parent link="a"/><child link="c"/><axis xyz="0 0 1"/><mimic joint="j1"/></joint>
</robot>
"""
ONE_DOF = ("revolute", "continuous", "prismatic")


from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    for j in model.top_joints():
        m = j.find("mimic")
        if m is None:
            continue
        name, kind = j.get("name"), j.get("type")
        if kind not in ONE_DOF and kind:
            yield Report(m, (f"joint '{name}' is {kind} but has a <mimic>: Drake rejects it (0 DOF "
                             "cannot mimic), the other consumers ignore it"))
            continue
        target = model.joints.get(m.get("joint") or "")
        if target is not None and target is not j and (target.get("type") or "") not in ONE_DOF:
            yield Report(m, (f"joint '{name}' mimics '{target.get('name')}', a {target.get('type')} "
                             "joint: Drake rejects it (mimic only between 1-DoF joints), the other "
                             "consumers ignore the relation"))
