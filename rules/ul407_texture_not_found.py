"""A mesh refers to a texture or material file that does not exist (a DAE ``<init_from>`` image,
an OBJ ``mtllib`` or a ``map_Kd`` in its MTL), or a ``<texture filename>`` does not resolve.

Viewers then show the mesh untextured or fail to load it.
"""
CODE = "UL407"
NAME = "texture-not-found"
SEVERITY = "warning"
FAIL = """<robot name="r">
  <material name="skin"><texture filename="package://example_pkg/materials/missing.png"/></material>
  <link name="a"/>
</robot>
"""
PASS = """<robot name="r">
  <material name="skin"><color rgba="1 1 1 1"/></material>
  <link name="a"/>
</robot>
"""
import os

from urdf_lint.rules._meshes import resolved_meshes
from urdf_lint.rules._schema import urdf_iter


def check(model, ctx):
    from urdf_lint.meshes import texture_refs
    for m, uri, path in resolved_meshes(model, ctx):
        for t in texture_refs(path):
            if not os.path.exists(t):
                yield m, f"mesh '{uri}' refers to '{os.path.basename(t)}', which does not exist"
    for t in urdf_iter(model, "texture"):
        uri = t.get("filename")
        if uri:
            ref = ctx.mesh_ref(model, uri)
            if ref.problem == "UL401":
                yield t, ref.message.replace("mesh", "texture", 1)
