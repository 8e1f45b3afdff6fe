"""A link mass that is negative, zero on a body that moves, or implausibly tiny.

Why: Negative masses break every physics engine. A zero mass is fine on a frame attached by a
`fixed` joint (sensor, marker and tool frames): KDL, Pinocchio and Gazebo merge it into its
parent. It is an error only where the link can move on its own, that is when it belongs to a
body (the link that a non-fixed joint moves, plus everything fixed to it) with no mass at all,
and nothing below it has mass either: the joint then moves nothing, and simulators refuse such
a body or let it accelerate without bound. A massless moving body that carries massive links
(two joints in a row, as in a universal joint) is a warning: KDL and Pinocchio accept it,
MuJoCo and Gazebo do not (an error for `mujoco`: MuJoCo 4.0.0 rejects massless moving bodies,
"mass and inertia of moving bodies must be larger than mjMINVAL"; Gazebo drops links below
1e-6 kg silently, gazebosim/sdformat#199). Tiny masses on a link a joint moves usually mean
grams or millimetre-based units were written as kilograms; on a frame attached by a `fixed`
joint a tiny mass (1e-9 kg) is a common placeholder that every consumer measured loads
(measured) and is left alone.

A tiny mass on a moving link is an error (a unit mistake), but a warning for `mujoco`,
`pinocchio` and `pybullet`, which load 1e-9 kg as it is. A negative mass is an error, but a
warning for `pinocchio` and `pybullet`, which load it
(measured with MuJoCo 4.0.0, Pinocchio 4.1.0, PyBullet 3.2.7).

How to fix: Write the mass in kilograms; give a moving body its real mass.

Options: `min-mass` (default 1e-06): masses below this many kilograms are reported as
implausibly tiny.
"""
CODE = "UL602"
NAME = "mass"
SEVERITY = "error"
OPTIONS = {"min-mass": 1e-6}
# a zero mass on a moving leaf: MuJoCo rejects it, the others load it as written (measured)
ZERO_LOADS = {"pinocchio": "warning", "pybullet": "warning", "python": "warning",
              "idyntree": "warning", "isaac": "warning", "drake": "warning"}
FAIL = """<robot name="r">
  <link name="base"/>
  <link name="a"><inertial><mass value="0"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""
FAIL_AT = [(3, 28)]
PASS = """<robot name="r">
  <link name="base"/>
  <link name="a"><inertial><mass value="0.5"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="camera_frame"><inertial><mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="cam" type="fixed"><parent link="a"/><child link="camera_frame"/></joint>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, number

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._inertial import Bodies, mass


def check(model: "Model", ctx: "Context") -> "Checked":
    tiny = float(ctx.options.get("min-mass", 1e-6))
    bodies = None
    for lk in model.top_links():
        m = lk.find("inertial/mass")
        if m is None:
            continue
        v = number(m.get("value"))
        if v is None:
            continue  # UL206
        name = lk.get("name")
        if v < 0:
            yield Report(m, (f"link '{name}': mass {v:g} must not be negative (MuJoCo rejects it; "
                             "Pinocchio and PyBullet load it with a wrong dynamics)"), targets={"pinocchio": "warning", "pybullet": "warning", "python": "warning", "idyntree": "warning", "isaac": "warning", "drake": "warning"})
        elif v == 0:
            bodies = bodies or Bodies(model)
            body = bodies.moving_body(name)
            if body is None or any((mass(o) or 0) > 0 for o in body[2]):
                continue  # a fixed frame, or part of a body that has mass: merged, valid
            root, j, links = body
            via = "" if root == name else f" (fixed to '{root}')"
            if bodies.subtree_mass(root) > 0:
                # a massless intermediate body (two joints in a row): the links it carries
                # have mass, so KDL and Pinocchio cope; MuJoCo and Gazebo refuse it
                yield Report(m, (f"link '{name}': mass 0 on a body that moves{via} (joint "
                                 f"'{j.get('name')}'); KDL and Pinocchio accept it because the links it "
                                 "carries have mass, but MuJoCo and Gazebo refuse massless moving "
                                 "bodies: give it a small real mass and inertia"), severity="warning", targets={"mujoco": "error"})
                continue
            yield Report(m, (f"link '{name}': mass 0 on a body that moves{via} (joint '{j.get('name')}') "
                             "and nothing it carries has mass; give it its real mass (zero mass is only "
                             "valid on frames attached by fixed joints to a body with mass, or on bodies "
                             "that carry massive links)"), targets=ZERO_LOADS)
        elif v < tiny:
            bodies = bodies or Bodies(model)
            root, j = bodies.root_of(name)
            if root != name or j is None:
                continue  # a frame fixed to its parent (or the root): a placeholder mass
            yield Report(m, (f"link '{name}': mass {v:g} kg is implausibly small (grams?)"
                             + ("; Gazebo drops links below 1e-6 kg" if v < 1e-6 else "")), targets={"mujoco": "warning", "pinocchio": "warning", "pybullet": "warning", "python": "warning", "idyntree": "warning", "isaac": "warning", "drake": "warning"})
