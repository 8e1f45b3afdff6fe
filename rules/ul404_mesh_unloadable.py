"""A mesh file cannot be loaded, is empty, or has non-finite vertices.

Why: A truncated download, a Git LFS pointer committed instead of the file, or an exporter bug
all end here, and viewers show nothing. Meshes are loaded with trimesh (DAE through pycollada);
their facts are cached by file content.

A COLLADA file that only the strict XML parsers refuse (whitespace before its `<?xml`
declaration, bytes after its closing `</COLLADA>`) is a warning, not an error: the Python
loaders (trimesh/pycollada, so yourdfpy and urchin, and urdf-lint's own mesh checks) refuse it,
but assimp-based consumers (RViz, Gazebo) load it. It is an error for the `python` target.

How to fix: Re-export the mesh, or fetch the real file (`git lfs pull`); for a COLLADA file
that only the strict parsers refuse, remove the whitespace before `<?xml` or the bytes after
`</COLLADA>`.
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
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, read_source

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model

# an empty mesh: urdf_parser_py and iDynTree never open it (measured; the others refuse it or
# load the robot without the part)
EMPTY_READ = {"urdf_parser_py": "warning", "idyntree": "warning"}
from urdf_lint.rules._meshes import TETRA_STL, resolved_meshes

EXAMPLE_FILES = {"meshes/part.stl": TETRA_STL,
                 "meshes/broken.stl": "version https://git-lfs.github.com/spec/v1\noid sha256:00\nsize 12\n"}


def check(model: "Model", ctx: "Context") -> "Checked":
    for m, uri, path in resolved_meshes(model, ctx):
        facts = ctx.mesh_facts(path)
        if not facts.ok:
            lenient = _strict_only(path, facts.error)
            if lenient:
                yield Report(m, (f"mesh '{uri}' has {lenient}: the Python loaders (trimesh/pycollada, "
                                 "so yourdfpy and urchin, and urdf-lint's own mesh checks) refuse it, "
                                 f"assimp-based consumers (RViz, Gazebo) load it ({facts.error})"),
                             severity="warning", targets={"python": "error"})
            else:
                yield Report(m, f"mesh '{uri}' cannot be loaded: {facts.error}")
        elif facts.vertices == 0:
            yield Report(m, f"mesh '{uri}' is empty (no vertices)", targets=EMPTY_READ)
        elif not facts.finite:
            yield Report(m, f"mesh '{uri}' has non-finite (NaN/inf) vertices")


# what lxml says of the two defects assimp's lenient XML reader passes over
_LEADING = "XML declaration allowed only at the start of the document"
_TRAILING = "Extra content at the end of the document"


def _strict_only(path: str, error: str) -> str:
    """What keeps a COLLADA file from the strict XML parsers only (``""`` when it is not one):
    whitespace before its ``<?xml`` declaration, or bytes after its closing ``</COLLADA>``."""
    if not path.lower().endswith(".dae") or (_LEADING not in error and _TRAILING not in error):
        return ""
    data = read_source(path)
    if data is None:
        return ""
    found = []
    body = data.lstrip()
    if len(body) < len(data) and body.startswith(b"<?xml"):
        found.append(f"{len(data) - len(body)} whitespace byte(s) before its '<?xml' declaration")
        data = body
    end = data.rfind(b"</COLLADA>")
    if end >= 0 and data[end + len(b"</COLLADA>"):].strip():
        found.append(f"{len(data[end + len(b'</COLLADA>'):].strip())} byte(s) after its closing "
                     "'</COLLADA>'")
    return " and ".join(found)
