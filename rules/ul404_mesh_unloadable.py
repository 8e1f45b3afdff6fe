"""A mesh file cannot be loaded, is empty, or has non-finite vertices.

Why: A truncated download, a Git LFS pointer committed instead of the file, or an exporter bug
all end here, and viewers show nothing. Meshes are loaded with trimesh (DAE through pycollada);
their facts are cached by file content.

How to fix: Re-export the mesh, or fetch the real file (`git lfs pull`).
"""
CODE = "UL404"
NAME = "mesh-unloadable"
SEVERITY = "error"
NEEDS = {"meshes"}
FAIL = """<robot name="r">
  <link name="a"><visual><geometry><mesh filename="package://example_pkg/meshes/broken.stl"/></geometry></visual></link>
</robot>
"""
FAIL_AT = [(2, 36)]
PASS = """<robot name="r">
  <link name="a"><visual><geometry><mesh filename="package://example_pkg/meshes/part.stl"/></geometry></visual></link>
</robot>
"""
from urdf_lint.engine.api import Report
from urdf_lint.rules._meshes import TETRA_STL, resolved_meshes

EXAMPLE_FILES = {"meshes/part.stl": TETRA_STL,
                 "meshes/broken.stl": "version https://git-lfs.github.com/spec/v1\noid sha256:00\nsize 12\n"}


def check(model, ctx):
    for m, uri, path in resolved_meshes(model, ctx):
        facts = ctx.mesh_facts(path)
        if not facts.ok:
            yield Report(m, f"mesh '{uri}' cannot be loaded: {facts.error}")
        elif facts.vertices == 0:
            yield Report(m, f"mesh '{uri}' is empty (no vertices)")
        elif not facts.finite:
            yield Report(m, f"mesh '{uri}' has non-finite (NaN/inf) vertices")
