"""A mesh `scale` is not three finite, non-zero numbers.

Why: A zero scale flattens the mesh; a malformed one is rejected by parsers.

How to fix: Write three non-zero numbers, e.g. `scale="0.001 0.001 0.001"`.
"""
CODE = "UL405"
NAME = "mesh-scale"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="a"><visual><geometry><mesh filename="package://example_pkg/meshes/part.stl" scale="0.001 0.001"/></geometry></visual></link>
</robot>
"""
FAIL_AT = [(2, 36)]
PASS = """<robot name="r">
  <link name="a"><visual><geometry><mesh filename="package://example_pkg/meshes/part.stl" scale="0.001 0.001 0.001"/></geometry></visual></link>
</robot>
"""
from urdf_lint.rules._meshes import TETRA_STL
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, numbers

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._schema import urdf_iter

EXAMPLE_FILES = {"meshes/part.stl": TETRA_STL}


def check(model: "Model", ctx: "Context") -> "Checked":
    for m in urdf_iter(model, "mesh"):
        s = m.get("scale")
        if s is None:
            continue
        v = numbers(s, 3)
        if v is None:
            yield Report(m, f"mesh scale=\"{s}\" must be three numbers")
        elif any(x == 0 for x in v):
            yield Report(m, f"mesh scale=\"{s}\" has a zero factor (the mesh collapses)")
