"""A link has a visual but no collision geometry.

Why: It is drawn but passes through everything in simulation and motion planning. Often intended
(decorative parts); this is information, not an error.

How to fix: Add a collision (a simple box or cylinder is enough), or ignore this rule for
decorative links.
"""
CODE = "UL801"
NAME = "visual-without-collision"
SEVERITY = "info"
FAIL = """<robot name="r">
  <link name="a"><visual><geometry><box size="1 1 1"/></geometry></visual></link>
</robot>
"""
FAIL_AT = [(2, 3)]
PASS = """<robot name="r">
  <link name="a"><visual><geometry><box size="1 1 1"/></geometry></visual>
    <collision><geometry><box size="1 1 1"/></geometry></collision></link>
</robot>
"""


from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    for lk in model.top_links():
        if lk.find("visual") is not None and lk.find("collision") is None:
            yield Report(lk, f"link '{lk.get('name')}' has a visual but no collision")
