"""A material name is defined twice with different colours.

Why: URDF keeps the first definition and silently ignores the rest, so some links are not the
colour their author wrote.

How to fix: Give each colour its own name, or define the material once at the top level and
refer to it by name.
"""
CODE = "UL501"
NAME = "material-redefined"
SEVERITY = "warning"
FAIL = """<robot name="r">
  <material name="blue"><color rgba="0 0 0.8 1"/></material>
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <link name="a"/>
</robot>
"""
FAIL_AT = [(3, 3)]
PASS = """<robot name="r">
  <material name="blue"><color rgba="0 0 0.8 1"/></material>
  <material name="light_blue"><color rgba="0 0 1 1"/></material>
  <link name="a"/>
</robot>
"""
from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report, display_path

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._materials import all_materials


def check(model: "Model", ctx: "Context") -> "Checked":
    first: dict[Any, Any] = {}
    for el, name, rgba, _top in all_materials(model):
        if not name or rgba is None:
            continue
        if name in first and first[name][1] != rgba:
            o = model.origin(first[name][0])
            yield Report(el, (f"material '{name}' redefined as rgba {' '.join(f'{x:g}' for x in rgba)}; the first "
                              f"definition ({' '.join(f'{x:g}' for x in first[name][1])}, at "
                              f"{display_path(o.file)}:{o.line}) wins"))
        first.setdefault(name, (el, rgba))
