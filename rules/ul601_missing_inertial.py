"""A moving link has no `<inertial>`.

Why: Gazebo's URDF to SDF conversion drops links without inertia silently, together with
everything attached to them (gazebosim/sdformat#199; Gazebo could not be run here), so the joint
does nothing in simulation: an error for `gazebo` (measured with sdformat 12.3: the link is
missing from the loaded model). MuJoCo 4.0.0 rejects the model ("mass and
inertia of moving bodies must be larger than mjMINVAL", measured on 16 real models): an error
for `mujoco` when the link has no collision geometry, even when the links it carries have mass
(issue 38: the earlier claim that MuJoCo accepts that was wrong). MuJoCo 4.0.0 computes a
missing inertial from the collision geometry (visuals are discarded): a warning then. When no
link at all has an `<inertial>`, sdformat 12 drops them all and refuses the model ("A model
must have at least one link"): an error for `gazebo` (measured, bench/consumers/harness.py).
A moving link without `<inertial>` that has links with mass fixed to it is kept by both:
MuJoCo (`fusestatic`) and sdformat merge those links into it (measured: a warning then). urdfdom 6.0.0, Pinocchio 4.1.0, PyBullet 3.2.7 and the Python parsers load it
(measured): a warning for the others. A link is "moving" when it
is the child of a non-fixed joint.

How to fix: Add an inertial. For kinematics-only models, ignore this rule.
"""
CODE = "UL601"
NAME = "missing-inertial"
SEVERITY = "warning"
TARGETS = {"mujoco": "error", "gazebo": "error"}
NO_LINK_LEFT = {"*": "off", "gazebo": "error"}
# a link whose fixed children have mass: MuJoCo (fusestatic) and sdformat merge them into it
MERGED = {"mujoco": "warning", "gazebo": "warning"}
FAIL = """<robot name="r">
  <link name="base"/><link name="arm"/>
  <joint name="j" type="continuous"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/></joint>
</robot>
"""
FAIL_AT = [(2, 22)]
PASS = """<robot name="r">
  <link name="base"/>
  <link name="arm"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="j" type="continuous"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/></joint>
</robot>
"""


from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    from urdf_lint.rules._inertial import SDF_DROPPED, Bodies
    links = model.top_links()
    if links and all(lk.find("inertial") is None for lk in links):
        # sdformat 12 drops every link without <inertial>, then refuses the empty model
        yield Report(model.root, ("no link has an <inertial>: Gazebo's URDF conversion drops every "
                                  "massless link and then refuses the model (\"A model must have at "
                                  "least one link\"); give the moving links their mass"),
                     targets=NO_LINK_LEFT)
    bodies = None
    for j in model.top_joints():
        if j.get("type") in (None, "fixed"):
            continue
        c = j.find("child")
        lk = model.links.get(c.get("link")) if c is not None else None
        if lk is not None and lk.find("inertial") is None:
            bodies = bodies or Bodies(model)
            if bodies.merged_mass(lk.get("name")) > SDF_DROPPED:
                # Gazebo merges the links fixed to it into it: it keeps the link, with their mass
                yield Report(lk, (f"link '{lk.get('name')}' moves (joint '{j.get('name')}') but has no "
                                  "<inertial> of its own; MuJoCo and Gazebo give it the mass of the "
                                  "links fixed to it"), targets=MERGED)
                continue
            if lk.find("collision/geometry") is not None:   # MuJoCo: inertia from the geometry
                yield Report(lk, (f"link '{lk.get('name')}' moves (joint '{j.get('name')}') but has no "
                                  "<inertial>; Gazebo drops the link, MuJoCo computes one from its "
                                  "collision geometry"), targets={"mujoco": "warning", "gazebo": "error"})
                continue
            if bodies.subtree_mass(lk.get("name")) > 0:
                # MuJoCo 4.0.0 rejects it all the same: no geometry to take an inertia from
                yield Report(lk, (f"link '{lk.get('name')}' moves (joint '{j.get('name')}') but has no "
                                  "<inertial> and no collision geometry; MuJoCo rejects it even though "
                                  "the links it carries have mass (\"mass and inertia of moving bodies "
                                  "must be larger than mjMINVAL\"), Gazebo drops the link"))
                continue
            yield Report(lk, (f"link '{lk.get('name')}' moves (joint '{j.get('name')}') but has no "
                              "<inertial>; MuJoCo rejects the model, Gazebo drops the link"))
