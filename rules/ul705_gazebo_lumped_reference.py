"""A `<gazebo reference="...">` names a link that Gazebo's URDF to SDF conversion merges away.

Why: Gazebo (Classic and the new Gazebo) converts a URDF to SDFormat first, and that conversion
"lumps" every fixed joint: the child link's contents are merged into the parent link and the
joint is discarded (gazebosim/sdf_tutorials, docs/urdf/sdf_extensions.md, "Fixed joint
lumping"; libsdformat 9.9.0 and later keep only a `<frame>` for the pose). What a `<gazebo>`
block sets for the merged link (a sensor, a plugin's frame, friction, a material) is moved to
the parent or applies to all of the parent's geometry, and the link's own frame is gone
(gazebosim/sdformat#199). Not measured with Gazebo itself:
the behaviour is the documented one. A warning for `gazebo`; off for the other targets, which
keep the link. The joint is kept when its own `<gazebo reference>` sets `<preserveFixedJoint>`
or `<disableFixedJointLumping>` to true; a fixed joint to a link named `world` attaches the
model to the world and is not lumped.

How to fix: Add `<gazebo reference="JOINT"><preserveFixedJoint>true</preserveFixedJoint></gazebo>`
for the fixed joint (give the child link an `<inertial>` with positive mass then), or put the
block on the parent link with the pose folded in.
"""
CODE = "UL705"
NAME = "gazebo-lumped-reference"
SEVERITY = "warning"
TARGETS = {"*": "off", "gazebo": "warning"}
EXAMPLE_TARGETS = ["gazebo"]
FAIL = """<robot name="r">
  <link name="base"/><link name="camera"/>
  <joint name="camera_joint" type="fixed"><parent link="base"/><child link="camera"/></joint>
  <gazebo reference="camera"><sensor name="cam" type="camera"/></gazebo>
</robot>
"""
FAIL_AT = [(4, 3)]
PASS = """<robot name="r">
  <link name="base"/><link name="camera"/>
  <joint name="camera_joint" type="fixed"><parent link="base"/><child link="camera"/></joint>
  <gazebo reference="camera"><sensor name="cam" type="camera"/></gazebo>
  <gazebo reference="camera_joint"><preserveFixedJoint>true</preserveFixedJoint></gazebo>
</robot>
"""
KEEPS = ("preserveFixedJoint", "disableFixedJointLumping")


from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model

def _kept(model: "Model") -> set[str]:
    """The joints whose own <gazebo> block turns lumping off."""
    out = set()
    for g in model.root:
        if g.tag == "gazebo" and g.get("reference"):
            if any((k.text or "").strip().lower() in ("true", "1")
                   for tag in KEEPS for k in g.findall(tag)):
                out.add(g.get("reference"))
    return out


def check(model: "Model", ctx: "Context") -> "Checked":
    kept = _kept(model)
    lumped = {}                          # child link -> (fixed joint, parent link)
    for j in model.top_joints():
        c, p = j.find("child"), j.find("parent")
        if j.get("type") != "fixed" or c is None or p is None or j.get("name") in kept:
            continue
        if p.get("link") != "world":
            lumped[c.get("link")] = (j.get("name"), p.get("link"))
    for g in model.root:
        if g.tag != "gazebo" or g.get("reference") not in lumped:
            continue
        if not [e for e in g if isinstance(e.tag, str)]:
            continue                     # an empty block sets nothing
        link = g.get("reference")
        joint, parent = lumped[link]
        yield Report(g, (f"<gazebo reference=\"{link}\">: Gazebo's URDF to SDF conversion merges link "
                  f"'{link}' into '{parent}' (fixed joint '{joint}' is lumped), so what this "
                  f"block sets moves to '{parent}' and '{link}' has no frame of its own; set "
                  f"<preserveFixedJoint> on '{joint}' to keep it"))
