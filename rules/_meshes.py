"""Mesh helpers shared by the UL4xx rules, and a tiny ASCII STL for their examples (not a rule)."""
from urdf_lint.meshes import MeshStatus

# the resolution statuses that mean "there is no such file" (UL401, and UL407 for textures)
NOT_FOUND = frozenset({MeshStatus.NOT_FOUND, MeshStatus.UNKNOWN_PACKAGE})
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


def resolution_problems(model, ctx, statuses, tag="mesh"):
    """(element, message) for every ``<tag filename>`` whose resolution ended in one of
    ``statuses`` (:class:`urdf_lint.meshes.MeshStatus`)."""
    for m in model.root.iter(tag):
        uri = m.get("filename")
        if uri:
            ref = ctx.mesh_ref(model, uri)
            if ref.status in statuses:
                yield m, ref.message


def resolved_meshes(model, ctx):
    """(mesh element, uri, path) for every <mesh> that resolved inside the roots."""
    for m in model.root.iter("mesh"):
        uri = m.get("filename")
        if not uri:
            continue
        ref = ctx.mesh_ref(model, uri)
        if ref.status is MeshStatus.OK and ref.path:
            yield m, uri, ref.path
