"""A mesh is far too large for a robot part: it was probably exported in millimetres while URDF is
in metres.

Why: The part is drawn and collides a thousand times too large.

How to fix: Add `scale="0.001 0.001 0.001"` or re-export in metres.

Options: `max-size` (default 5.0): reported when the scaled bounding box is larger than this
many metres.
"""
CODE = "UL406"
NAME = "mesh-units"
SEVERITY = "warning"
NEEDS = {"meshes"}
OPTIONS = {"max-size": 5.0}
FAIL = """<robot name="r">
  <link name="a"><visual><geometry><mesh filename="package://example_pkg/meshes/part_mm.stl"/></geometry></visual></link>
</robot>
"""
FAIL_AT = [(2, 36)]
PASS = """<robot name="r">
  <link name="a"><visual><geometry><mesh filename="package://example_pkg/meshes/part_mm.stl" scale="0.001 0.001 0.001"/></geometry></visual></link>
</robot>
"""
from urdf_lint.rules._meshes import resolved_meshes, scaled
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, numbers

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model

EXAMPLE_FILES = {"meshes/part_mm.stl": scaled(1000.0)}


def check(model: "Model", ctx: "Context") -> "Checked":
    limit = float(ctx.options.get("max-size", 5.0))
    for m, uri, path in resolved_meshes(model, ctx):
        facts = ctx.mesh_facts(path)
        if not facts.ok or not facts.bounds:
            continue
        scale = numbers(m.get("scale", "1 1 1"), 3) or [1, 1, 1]
        lo, hi = facts.bounds
        size = max(abs(s) * (b - a) for s, a, b in zip(scale, lo, hi, strict=False))
        if size > limit:
            hint = " (millimetres? add scale=\"0.001 0.001 0.001\")" if size / 1000 < limit else ""
            yield Report(m, f"mesh '{uri}' is {size:.4g} m across{hint}")
