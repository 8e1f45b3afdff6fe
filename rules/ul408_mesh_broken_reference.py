"""A COLLADA mesh has a broken internal reference: a `<surface>`, sampler, effect, material or
image id that points at nothing inside the file.

Why: pycollada then drops every `<instance_geometry>` bound to that material, so loaders built
on it (trimesh, and through it yourdfpy) see an empty mesh, while assimp-based viewers (RViz,
Gazebo) show the geometry untextured. urdf-lint loads the geometry without the materials (so
UL404 does not call a valid mesh empty) and reports the reference here.

An effect is also lost when one of its values is malformed (`<color>0.0 0.0 0.01.0</color>`):
pycollada drops it and then reports the effect as missing; the message then quotes the
malformed value instead of blaming the reference.

How to fix: Fix the id (or the malformed value) in the exporter, or re-export the mesh.
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
import re

from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report, read_source

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._meshes import BROKEN_SURFACE_DAE, PLAIN_DAE, resolved_meshes

EXAMPLE_FILES = {"meshes/skin.dae": BROKEN_SURFACE_DAE, "meshes/plain.dae": PLAIN_DAE}


def check(model: "Model", ctx: "Context") -> "Checked":
    for m, uri, path in resolved_meshes(model, ctx):
        facts = ctx.mesh_facts(path)
        broken = facts.broken_refs
        if facts.ok and broken:
            bad = _malformed_value(path, broken)
            if bad:
                yield Report(m, (f"mesh '{uri}' has a malformed {bad}, so its effect is lost "
                                 f"(pycollada: {broken[0]}); its geometry loads, its material "
                                 "is lost"))
                continue
            more = f" (and {len(broken) - 1} more)" if len(broken) > 1 else ""
            yield Report(m, (f"mesh '{uri}' has a broken internal reference: {broken[0]}{more}; its "
                             "geometry loads, its material or texture is lost"))


_MISSING_EFFECT = re.compile(r"Effect not found: #?([^\s'\"]+)")
_VALUE = re.compile(rb"<(color|float)\b[^>]*>([^<]*)</\1\s*>")


def _number(word: bytes) -> bool:
    try:
        float(word)
    except ValueError:
        return False
    return True


def _malformed_value(path: str, broken: Any) -> str:
    """The first malformed ``<color>`` or ``<float>`` value (a word that is no number) of an effect
    pycollada reports missing, quoted (``""`` when there is none: the reference is broken)."""
    ids = [m.group(1) for b in broken for m in [_MISSING_EFFECT.search(b)] if m]
    data = read_source(path) if ids else None
    if data is None:
        return ""
    for eid in ids:
        start = re.search(rb"<effect\b[^>]*\bid\s*=\s*[\"']" + re.escape(eid.encode()) + rb"[\"']",
                          data)
        if start is None:
            continue
        stop = data.find(b"</effect", start.end())
        for tag, text in _VALUE.findall(data[start.end():stop if stop >= 0 else None]):
            words = text.split()
            if not words or not all(_number(w) for w in words):
                what = "colour" if tag == b"color" else "number"
                value = text.decode("utf-8", "replace").strip()
                value = value if len(value) <= 60 else value[:57] + "..."
                return f"{what} value <{tag.decode()}>{value}</{tag.decode()}> in effect '{eid}'"
    return ""
