"""A mesh path exists only with different letter case (`Base.STL` vs `base.stl`).

Why: It works on macOS and Windows, whose file systems ignore case, and fails on Linux, where
ROS, CI and most robots run.

How to fix: Write the name exactly as the file is called.
"""
CODE = "UL402"
NAME = "mesh-case-mismatch"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="a"><visual><geometry><mesh filename="package://example_pkg/meshes/Part.STL"/></geometry></visual></link>
</robot>
"""
FAIL_AT = [(2, 36)]
PASS = """<robot name="r">
  <link name="a"><visual><geometry><mesh filename="package://example_pkg/meshes/part.stl"/></geometry></visual></link>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.rules._meshes import MeshStatus, TETRA_STL, resolution_problems

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model

EXAMPLE_FILES = {"meshes/part.stl": TETRA_STL}


def check(model: "Model", ctx: "Context") -> "Checked":
    yield from resolution_problems(model, ctx, {MeshStatus.CASE_MISMATCH})
