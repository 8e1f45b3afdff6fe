"""A `<mesh filename>` does not resolve to a file: a missing file, a wrong path, or an unknown
package.

Why: Viewers and simulators show nothing for the part, and collision checking ignores it.
`package://pkg/...` and `$(find pkg)` resolve through package.xml files (no ROS needed),
`file://` and absolute paths as written, and relative paths against the URDF's folder.

Per target (measured, bench/consumers/harness.py): urdf_parser_py and iDynTree never open a
mesh (a warning for them); MuJoCo 4.0.0 discards visual geometry unless the file keeps it
(`<mujoco><compiler discardvisual="false"/>`), so a missing visual mesh is a warning for
`mujoco`; yourdfpy, PyBullet and the Isaac importer load the robot without the part (an error:
a different robot), Pinocchio and urchin refuse it.

How to fix: Fix the path or add the file.
"""
CODE = "UL401"
NAME = "mesh-not-found"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="a"><visual><geometry><mesh filename="package://example_pkg/meshes/missing.stl"/></geometry></visual></link>
</robot>
"""
FAIL_AT = [(2, 36)]
PASS = """<robot name="r">
  <link name="a"><visual><geometry><mesh filename="package://example_pkg/meshes/part.stl"/></geometry></visual></link>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.rules._meshes import NOT_FOUND, TETRA_STL, resolution_problems

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model

EXAMPLE_FILES = {"meshes/part.stl": TETRA_STL}


# consumers that never open a mesh file
NOT_READ = {"urdf_parser_py": "warning", "idyntree": "warning"}
# and MuJoCo, which discards visuals unless the model keeps them
VISUAL_NOT_READ = {**NOT_READ, "mujoco": "warning"}


def check(model: "Model", ctx: "Context") -> "Checked":
    import dataclasses
    for r in resolution_problems(model, ctx, NOT_FOUND):
        if r.cause is not None:
            yield r
            continue
        geom = r.element.getparent()
        part = geom.getparent() if geom is not None else None
        kept = model.root.find("mujoco/compiler[@discardvisual='false']") is not None
        visual = part is not None and part.tag == "visual" and not kept
        yield dataclasses.replace(r, targets=VISUAL_NOT_READ if visual else NOT_READ)
