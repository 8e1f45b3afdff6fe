"""A collision mesh whose vertices all lie in one plane (or on one line): it has no volume; or
a closed one whose volume is below MuJoCo's `mjMINVAL` (1e-15 m^3).

Why: MuJoCo computes the convex hull of every collision mesh, and of every visual mesh it keeps,
for contact and inertia. Measured with MuJoCo 4.0.0: a flat collision
mesh rejects the model ("mesh 'plate' has coplanar vertices, cannot compute convex hull"), a
tilted plane as well as one in a coordinate plane; a flat visual mesh kept by `<compiler
discardvisual="false"/>` too ("mesh volume is too small"). Pinocchio 4.1.0 and PyBullet 3.2.7
load such a mesh, and so does ROS: an error for `mujoco` only. As for
UL409, a description carrying a `<mujoco>` block says that MuJoCo loads it, and the finding is
then an info for the other targets. A mesh MuJoCo cannot decode at all is UL409's, not this
rule's; a zero in `scale` is UL405's.

How to fix: Use a primitive for the collision (a thin `<box>` for a plate), or give the mesh a
thickness; keep the flat mesh as a visual only.
"""
CODE = "UL410"
NAME = "mesh-flat-consumer"
SEVERITY = "error"
NEEDS = {"meshes"}
# "*": info so that the rule runs under every target: each finding carries its own table
TARGETS = {"*": "info", "mujoco": "error"}
EXAMPLE_TARGETS = ["mujoco"]
FAIL = """<robot name="r">
  <link name="a">
    <visual><geometry><mesh filename="package://example_pkg/meshes/plate.obj"/></geometry></visual>
    <collision><geometry><mesh filename="package://example_pkg/meshes/plate.obj"/></geometry></collision>
  </link>
</robot>
"""
FAIL_AT = [(4, 26)]
PASS = """<robot name="r">
  <link name="a">
    <visual><geometry><mesh filename="package://example_pkg/meshes/plate.obj"/></geometry></visual>
    <collision><geometry><box size="0.1 0.1 0.002"/></geometry></collision>
  </link>
</robot>
"""
import os

from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._consumers import geometry_meshes, mujoco_loads, mujoco_problem, wanted

# a tilted square plate: no two coordinates constant, every vertex in one plane
EXAMPLE_FILES = {"meshes/plate.obj": ("v 0 0 0\nv 0.1 0 0\nv 0 0.1 0.05\nv 0.1 0.1 0.05\n"
                                      "f 1 2 3\nf 2 4 3\n")}

# MuJoCo's hull (qhull) on float32 vertices: a plane tilted off the axes is flat to within the
# float32 rounding of its coordinates, about 1e-7 of the mesh's size
FLAT = 1e-6
# MuJoCo's mjMINVAL: a closed mesh enclosing less is refused ("mesh volume is too small",
# measured with MuJoCo 4.0.0 on a 2 micrometre cube)
MJ_MINVAL = 1e-15


def _scale(m: Any) -> float:
    """The factor ``<mesh scale>`` applies to a volume (1 when absent or unreadable)."""
    from urdf_lint.engine.api import numbers
    s = numbers(m.get("scale") or "1 1 1")
    return abs(s[0] * s[1] * s[2]) if s and len(s) == 3 else 1.0


def flat(vertices: Any) -> bool:
    """Whether the vertices span less than three dimensions (relative to their extent)."""
    import numpy as np
    v = np.asarray(vertices, dtype=float)
    if len(v) < 4:
        return True
    s = np.linalg.svd(v - v.mean(axis=0), compute_uv=False)
    return bool(s[0] == 0 or s[2] <= FLAT * s[0])


def check(model: "Model", ctx: "Context") -> "Checked":
    if not wanted(model, ctx, ("mujoco",)):
        return                            # every finding would be off in this run
    kinds, others = mujoco_loads(model)
    for m, uri, path, kind in geometry_meshes(model, ctx):
        if kind not in kinds or mujoco_problem(path, os.path.splitext(path)[1].lower()):
            continue                      # UL409: MuJoCo does not get as far as the hull
        mass = ctx.mass_facts(path)
        volume = abs(mass.volume) * _scale(m) if mass.ok else None
        if volume is not None and volume >= MJ_MINVAL:
            continue                      # it has a volume (the common case: no load here)
        facts = ctx.mesh_facts(path)
        if not facts.ok or not facts.vertices or not facts.finite:
            continue                      # UL404 says why
        mesh = ctx.mesh(path)
        if flat(mesh.vertices):
            yield Report(m, f"{kind} mesh '{uri}' is flat (all its vertices lie in one plane); "
                         "MuJoCo cannot compute its convex hull and rejects the model",
                         targets={"*": others, "mujoco": "error"})
            continue
        if volume is None:                # urdf-lint's own facts keep no volume below 1e-15
            closed = mesh.copy()
            closed.merge_vertices()       # a loader may keep each face's corners apart
            if not closed.is_watertight:
                continue                  # an open surface: no volume to judge
            volume = abs(float(closed.volume)) * _scale(m)
        if volume < MJ_MINVAL:
            yield Report(m, (f"{kind} mesh '{uri}' encloses {volume:.3g} m^3, below MuJoCo's "
                             f"{MJ_MINVAL:g}: MuJoCo rejects the model (\"mesh volume is too "
                             "small\"); use a primitive or the part's real size"),
                         targets={"*": others, "mujoco": "error"})
