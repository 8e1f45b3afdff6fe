"""The robot, a link or a joint has no `name` (or an empty one).

Why: Names are how joints, transmissions, controllers and TF refer to things; URDF parsers
reject nameless robots, links and joints.

How to fix: Add a unique `name`.
"""
CODE = "UL201"
NAME = "missing-name"
SEVERITY = "error"
FAIL = """<robot>
  <link/>
</robot>
"""
FAIL_AT = [(1, 1), (2, 3)]
PASS = """<robot name="r">
  <link name="a"/>
</robot>
"""


from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    if not (model.root.get("name") or "").strip():
        yield Report(model.root, "<robot> has no name attribute")
    for e in model.root:
        if e.tag in ("link", "joint") and not (e.get("name") or "").strip():
            yield Report(e, f"<{e.tag}> has no name attribute")
