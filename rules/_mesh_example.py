"""A tiny ASCII STL used by the mesh rules' examples (not a rule)."""
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
