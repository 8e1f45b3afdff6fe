"""A COLLADA mesh has a broken internal reference: a `<surface>`, sampler, effect, material or
image id that points at nothing inside the file.

Why: pycollada then drops every `<instance_geometry>` bound to that material, so loaders built
on it (trimesh, and through it yourdfpy) see an empty mesh, while assimp-based viewers (RViz,
Gazebo) show the geometry untextured. urdf-lint loads the geometry without the materials (so
UL404 does not call a valid mesh empty) and reports the reference here.

How to fix: Fix the id in the exporter, or re-export the mesh.
"""
CODE = "UL408"
NAME = "mesh-broken-reference"
SEVERITY = "warning"
NEEDS = {"meshes"}
FAIL = """<robot name="r">
  <link name="a"><visual><geometry><mesh filename="package://example_pkg/meshes/skin.dae"/></geometry></visual></link>
</robot>
"""
FAIL_AT = [(2, 36)]
PASS = """<robot name="r">
  <link name="a"><visual><geometry><mesh filename="package://example_pkg/meshes/plain.dae"/></geometry></visual></link>
</robot>
"""
from urdf_lint.engine.api import Report
from urdf_lint.rules._meshes import BROKEN_SURFACE_DAE, PLAIN_DAE, resolved_meshes

EXAMPLE_FILES = {"meshes/skin.dae": BROKEN_SURFACE_DAE, "meshes/plain.dae": PLAIN_DAE}


def check(model, ctx):
    for m, uri, path in resolved_meshes(model, ctx):
        facts = ctx.mesh_facts(path)
        broken = facts.broken_refs
        if facts.ok and broken:
            more = f" (and {len(broken) - 1} more)" if len(broken) > 1 else ""
            yield Report(m, (f"mesh '{uri}' has a broken internal reference: {broken[0]}{more}; its "
                             "geometry loads, its material or texture is lost"))
