"""A `<mesh filename>` does not resolve to a file: a missing file, a wrong path, or an unknown
package.

Why: Viewers and simulators show nothing for the part, and collision checking ignores it.
`package://pkg/...` and `$(find pkg)` resolve through package.xml files (no ROS needed),
`file://` and absolute paths as written, and relative paths against the URDF's folder.

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
from urdf_lint.rules._meshes import NOT_FOUND, TETRA_STL, resolution_problems

EXAMPLE_FILES = {"meshes/part.stl": TETRA_STL}


def check(model, ctx):
    yield from resolution_problems(model, ctx, NOT_FOUND)
