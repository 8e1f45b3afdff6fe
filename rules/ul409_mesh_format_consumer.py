"""A mesh file in a format the selected consumer cannot read.

Why: ROS reads meshes through assimp (rviz, Gazebo) and loads any of them, but MuJoCo and Drake
decode only a few formats and reject the whole model otherwise. Measured with MuJoCo 4.0.0:
a collision mesh other than STL, OBJ or MSH is rejected ("no decoder
found for mesh file", DAE, glTF and PLY alike); an STL must be binary with 1 to 200000
triangles ("stl_decoder: number of faces should be between 1 and 200000 ... perhaps this is an
ASCII file?"): ASCII STL is rejected. MuJoCo discards a URDF's visuals unless its `<mujoco>`
block says `<compiler discardvisual="false"/>`; then the visual meshes are decoded too, with
the same result. The extension is compared case-insensitively, as MuJoCo does. Drake 1.51.1
computes the convex hull of every collision mesh and rejects any but OBJ, VTK and glTF
(`.gltf`; it rejects binary `.glb`): "MakeConvexHull only applies to .obj, .vtk, and .gltf meshes";
its visuals load in any of these formats (measured with Drake 1.51.1 from pip, not part of the
suite's consumers). An error for `mujoco` and `drake`. For
the other targets nothing, unless the description carries a `<mujoco>` block: it says that
MuJoCo loads it, and MuJoCo's findings are then an info for the other targets.

How to fix: Convert the collision mesh (e.g. `meshio convert`, `trimesh`'s export, Blender) to
binary STL or OBJ for MuJoCo, to OBJ (or glTF, VTK) for Drake, and point `<collision>` at the
copy; keep DAE for the visuals, or, when MuJoCo keeps visuals, convert those too. Split a mesh
of more than 200000 triangles, or decimate it.
"""
CODE = "UL409"
NAME = "mesh-format-consumer"
SEVERITY = "error"
NEEDS = {"meshes"}
# "*": info so that the rule runs under every target: each finding carries its own table, in
# which the other targets are off unless the description has a <mujoco> block
TARGETS = {"*": "info", "mujoco": "error", "drake": "error"}
EXAMPLE_TARGETS = ["mujoco", "drake"]
FAIL = """<robot name="r">
  <link name="a">
    <visual><geometry><mesh filename="package://example_pkg/meshes/skin.dae"/></geometry></visual>
    <collision><geometry><mesh filename="package://example_pkg/meshes/skin.dae"/></geometry></collision>
    <collision><geometry><mesh filename="package://example_pkg/meshes/part.stl"/></geometry></collision>
  </link>
</robot>
"""
FAIL_AT = [(4, 26), (5, 26)]
PASS = """<robot name="r">
  <link name="a">
    <visual><geometry><mesh filename="package://example_pkg/meshes/skin.dae"/></geometry></visual>
    <collision><geometry><mesh filename="package://example_pkg/meshes/part.obj"/></geometry></collision>
  </link>
</robot>
"""
import os

from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._consumers import (DRAKE_FORMATS, geometry_meshes, mujoco_loads,
                                        mujoco_problem, wanted)
from urdf_lint.rules._meshes import PLAIN_DAE, TETRA_STL

TETRA_OBJ = "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
EXAMPLE_FILES = {"meshes/part.stl": TETRA_STL, "meshes/part.obj": TETRA_OBJ,
                 "meshes/skin.dae": PLAIN_DAE}

def check(model: "Model", ctx: "Context") -> "Checked":
    if not wanted(model, ctx, ("mujoco", "drake")):
        return                            # every finding would be off in this run
    kinds, others = mujoco_loads(model)
    # the consumers the message speaks of: those of the run's targets (under --target mujoco,
    # what Drake does is beside the point), or both when the run selects neither
    speak = {t for t in ("mujoco", "drake") if t in ctx.targets} or {"mujoco", "drake"}
    for m, uri, path, kind in geometry_meshes(model, ctx):
        ext = os.path.splitext(path)[1].lower()
        said, table = [], {"*": "off"}
        why = mujoco_problem(path, ext) if kind in kinds else None
        if why:
            table.update({"*": others, "mujoco": "error"})
            if "mujoco" in speak:
                said.append(f"{why} (MuJoCo rejects the model)")
        if kind == "collision" and ext not in DRAKE_FORMATS:
            table["drake"] = "error"
            if "drake" in speak:
                said.append(f"Drake computes contact only from OBJ, VTK or glTF, not "
                            f"{ext or 'this'} (Drake rejects the model)")
        if said:
            yield Report(m, f"{kind} mesh '{uri}': " + "; ".join(said), targets=table)
