"""A top-level material that no visual uses.

Why: Harmless, but often a sign of a renamed or misspelt reference.

How to fix: Remove it or fix the reference. Materials from a shared colours include file are
typical; ignore this rule for that file with `per-file-ignores`.
"""
CODE = "UL503"
NAME = "material-unused"
SEVERITY = "info"
FAIL = """<robot name="r">
  <material name="orange"><color rgba="1 0.5 0 1"/></material>
  <link name="a"/>
</robot>
"""
FAIL_AT = [(2, 3)]
PASS = """<robot name="r">
  <material name="orange"><color rgba="1 0.5 0 1"/></material>
  <link name="a"><visual><geometry><box size="1 1 1"/></geometry><material name="orange"/></visual></link>
</robot>
"""


from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._schema import urdf_iter

def check(model: "Model", ctx: "Context") -> "Checked":
    used = {m.get("name") for v in urdf_iter(model, "visual") for m in v.findall("material")}
    seen = set()
    for m in model.root:
        if m.tag == "material" and m.get("name") and m.get("name") not in used \
                and m.get("name") not in seen:
            seen.add(m.get("name"))
            yield Report(m, f"material '{m.get('name')}' is defined but no visual uses it")
