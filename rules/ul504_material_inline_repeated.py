"""The same colour is written inline again and again (under different names, or anonymously) where
one named material should be defined once and reused by name.

Why: Repeated inline colours drift apart when someone edits only one of them; the URDF tutorial
teaches named materials for this reason.

How to fix: Define the material once at the top level and refer to it by name.

Fix: unsafe (`--unsafe-fixes`), when every inline colour is a literal written outside macros:
each becomes `<material name="NAME"/>`, and `NAME` is defined once after the `<robot>` tag
(the most common inline name, or an existing top-level material of that colour).

Options: `min-repeats` (default 3): reported when one colour appears inline in at least this
many visuals.
"""
CODE = "UL504"
NAME = "material-inline-repeated"
SEVERITY = "info"
OPTIONS = {"min-repeats": 3}
FAIL = """<robot name="r">
  <link name="a"><visual><geometry><box size="1 1 1"/></geometry><material name="m1"><color rgba="0 0 1 1"/></material></visual></link>
  <link name="b"><visual><geometry><box size="1 1 1"/></geometry><material name="m2"><color rgba="0 0 1 1"/></material></visual></link>
  <link name="c"><visual><geometry><box size="1 1 1"/></geometry><material name=""><color rgba="0 0 1 1"/></material></visual></link>
  <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="j2" type="fixed"><parent link="a"/><child link="c"/></joint>
</robot>
"""
FAIL_AT = [(2, 66)]
PASS = """<robot name="r">
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <link name="a"><visual><geometry><box size="1 1 1"/></geometry><material name="blue"/></visual></link>
  <link name="b"><visual><geometry><box size="1 1 1"/></geometry><material name="blue"/></visual></link>
  <link name="c"><visual><geometry><box size="1 1 1"/></geometry><material name="blue"/></visual></link>
  <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="j2" type="fixed"><parent link="a"/><child link="c"/></joint>
</robot>
"""
from collections import Counter

from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report, named_material

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._materials import all_materials, rgba as rgba_of


def _fix(model: "Model", rgba: Any, items: Any) -> Any:
    for name, m in model.materials.items():
        if rgba_of(m) == rgba:
            return named_material([el for el, _ in items], name, m.find("color").get("rgba"),
                                  define=False)
    named = Counter(nm for _, nm in items if nm)
    taken = set(model.materials)
    found = next((nm for nm, _ in named.most_common() if nm not in taken), None)
    name = found if found is not None else ""
    if found is None:
        name = "rgba_" + "".join(f"{round(x * 255):02x}" for x in rgba)
    if name in taken:
        return None
    return named_material([el for el, _ in items], name, items[0][0].find("color").get("rgba"),
                          define=True)


def check(model: "Model", ctx: "Context") -> "Checked":
    n = int(ctx.options.get("min-repeats", 3))
    groups: dict[Any, Any] = {}
    for el, name, rgba, top in all_materials(model):
        if not top and rgba is not None:
            groups.setdefault(rgba, []).append((el, name))
    for rgba, items in groups.items():
        names = {nm for _, nm in items}
        if len(items) >= n and (len(names) > 1 or "" in names or None in names):
            named = sorted(repr(x) for x in names if x)
            anon = sum(1 for _, nm in items if not nm)
            shown = (f"names {', '.join(named)}" if named else "") + \
                ((", " if named else "") + f"{anon} anonymous" if anon else "")
            yield Report(items[0][0], (f"colour rgba {' '.join(f'{x:g}' for x in rgba)} is written inline in "
                                       f"{len(items)} visuals ({shown}); define one named "
                                       "<material> at the top and refer to it by name"), fix=_fix(model, rgba, items))
