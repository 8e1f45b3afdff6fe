"""A joint's `<dynamics>` sets damping or friction, which Isaac Sim's URDF importer drops.

Why: Isaac Sim 6.1.0's URDF importer (`isaacsim.asset.importer.urdf` 3.11.10) imports a joint
with `<dynamics damping="..." friction="...">` without them: the PhysX drive gets no damping,
`physxJoint:jointFriction` is never set, and the MuJoCo actuators get no gains, with no warning
(isaac-sim/IsaacSim#841, open; the converter writes the values under an attribute name the
importer does not read). The robot then simulates differently from every other consumer. Isaac
Sim does not install from the package index, so this is from that report, not measured here.
A warning for `isaac`; off for the other targets, which read `<dynamics>` (MuJoCo, PyBullet,
Gazebo, Drake) or have no use for it (ROS).

How to fix: Set the joint's damping and friction in Isaac Sim after the import (the joint
drive's damping, the PhysX joint friction), or in Isaac Lab's actuator config.
"""
CODE = "UL310"
NAME = "isaac-joint-dynamics"
SEVERITY = "warning"
TARGETS = {"*": "off", "isaac": "warning"}
EXAMPLE_TARGETS = ["isaac"]
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <dynamics damping="0.5" friction="0.1"/></joint>
</robot>
"""
FAIL_AT = [(4, 5)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <dynamics damping="0" friction="0"/></joint>
</robot>
"""


from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model

def _set(value: Any) -> bool:
    """A damping or friction that is there and not zero (a malformed number is UL207's)."""
    try:
        return value is not None and float(value) != 0.0
    except ValueError:
        return False


def check(model: "Model", ctx: "Context") -> "Checked":
    for j in model.top_joints():
        for d in j.findall("dynamics"):
            what = [a for a in ("damping", "friction") if _set(d.get(a))]
            if what and j.get("type") not in (None, "fixed"):
                yield Report(d, (f"joint '{j.get('name')}' sets {' and '.join(what)}; Isaac Sim's URDF "
                          "importer drops them silently (IsaacSim#841): set them after the "
                          "import"))
