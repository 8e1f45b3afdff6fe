"""A mesh resolves (after symlinks) outside the package roots and the linted repository.

Why: Such a path works only on the author's machine, and a description under review could point
a viewer at a secret (rerun embeds the bytes of whatever a mesh path names). urdf-lint never
reads it.

How to fix: Keep meshes inside the package and use `package://`.
"""
CODE = "UL403"
NAME = "mesh-outside-roots"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="a"><visual><geometry><mesh filename="file:///etc/hostname"/></geometry></visual></link>
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
    yield from resolution_problems(model, ctx, {MeshStatus.OUTSIDE_ROOTS})
