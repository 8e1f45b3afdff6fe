"""Mesh helpers shared by the UL4xx rules, and a tiny ASCII STL for their examples (not a rule)."""
from urdf_lint.rules._schema import urdf_iter

TETRA_STL = """solid tetra
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 0.1 0 0
  vertex 0 0.1 0
 endloop
endfacet
facet normal 0 -1 0
 outer loop
  vertex 0 0 0
  vertex 0 0 0.1
  vertex 0.1 0 0
 endloop
endfacet
facet normal -1 0 0
 outer loop
  vertex 0 0 0
  vertex 0 0.1 0
  vertex 0 0 0.1
 endloop
endfacet
facet normal 1 1 1
 outer loop
  vertex 0.1 0 0
  vertex 0 0 0.1
  vertex 0 0.1 0
 endloop
endfacet
endsolid tetra
"""


def scaled(factor):
    out = []
    for line in TETRA_STL.splitlines():
        s = line.strip()
        if s.startswith("vertex"):
            x, y, z = (float(v) * factor for v in s.split()[1:])
            line = f"  vertex {x:g} {y:g} {z:g}"
        out.append(line)
    return "\n".join(out) + "\n"


def resolution_problems(model, ctx, code):
    """(mesh element, message) for every <mesh> whose resolution failed with ``code``."""
    for m in urdf_iter(model, "mesh"):
        uri = m.get("filename")
        if uri:
            ref = ctx.mesh_ref(model, uri)
            if ref.problem == code:
                yield m, ref.message


def resolved_meshes(model, ctx):
    """(mesh element, uri, path) for every <mesh> that resolved inside the roots."""
    for m in urdf_iter(model, "mesh"):
        uri = m.get("filename")
        if not uri:
            continue
        ref = ctx.mesh_ref(model, uri)
        if ref.problem is None and ref.path:
            yield m, uri, ref.path
