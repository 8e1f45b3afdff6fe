"""A mesh refers to a texture or material file that does not exist (a DAE `<init_from>` image, an
OBJ `mtllib` or a `map_Kd` in its MTL), or a `<texture filename>` does not resolve.

Why: Viewers then show the mesh untextured or fail to load it.

How to fix: Add the file or fix the reference in the mesh or the URDF.
"""
CODE = "UL407"
NAME = "texture-not-found"
SEVERITY = "warning"
FAIL = """<robot name="r">
  <material name="skin"><texture filename="package://example_pkg/materials/missing.png"/></material>
  <link name="a"/>
</robot>
"""
FAIL_AT = [(2, 25)]
PASS = """<robot name="r">
  <material name="skin"><color rgba="1 1 1 1"/></material>
  <link name="a"/>
</robot>
"""
import os
from dataclasses import replace

from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._meshes import NOT_FOUND, resolution_problems, resolved_meshes


def check(model: "Model", ctx: "Context") -> "Checked":
    for m, uri, path in resolved_meshes(model, ctx):
        for t in ctx.texture_refs(path):   # (references outside the roots are not read)
            if not os.path.exists(t):
                yield Report(m, f"mesh '{uri}' refers to '{os.path.basename(t)}', which does not exist")
    for r in resolution_problems(model, ctx, NOT_FOUND, tag="texture"):
        yield replace(r, message=r.message.replace("mesh", "texture", 1))
