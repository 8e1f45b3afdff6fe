"""Shape dimensions are invalid: a box `size` that is not three positive numbers, a cylinder
`radius`/`length` or sphere `radius` that is not a positive number, a mesh without `filename`.

Why: Parsers reject such shapes, or draw and collide with nothing. MuJoCo 4.0.0 rejects a
negative box size or a zero radius; Pinocchio 4.1.0 and PyBullet 3.2.7 load them (a warning for
`pinocchio` and `pybullet`) (measured with MuJoCo 4.0.0, Pinocchio 4.1.0, PyBullet 3.2.7).

How to fix: Write the dimensions in metres as positive numbers.
"""
CODE = "UL205"
NAME = "geometry-dimensions"
SEVERITY = "error"
TARGETS = {"pinocchio": "warning", "pybullet": "warning", "python": "warning", "idyntree": "warning",
           "isaac": "warning", "gazebo": "warning"}
FAIL = """<robot name="r">
  <link name="a">
    <visual><geometry><box size="1 1"/></geometry></visual>
    <collision><geometry><cylinder radius="-0.1" length="1"/></geometry></collision>
  </link>
</robot>
"""
FAIL_AT = [(3, 23), (4, 26)]
PASS = """<robot name="r">
  <link name="a">
    <visual><geometry><box size="1 1 0.5"/></geometry></visual>
    <collision><geometry><cylinder radius="0.1" length="1"/></geometry></collision>
  </link>
</robot>
"""
from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report, number, numbers

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._schema import urdf_iter


def _positive(model: "Model", el: Any, attr: str, what: str) -> Any:
    v = el.get(attr)
    if v is None:
        return f"{what}: <{el.tag}> needs a '{attr}' attribute"
    n = number(v)
    if n is None:
        return f"{what}: <{el.tag} {attr}=\"{v}\"> is not a number"
    if n <= 0:
        return f"{what}: <{el.tag} {attr}=\"{v}\"> must be positive"
    return None


def check(model: "Model", ctx: "Context") -> "Checked":
    for g in urdf_iter(model, "geometry"):
        lk = g.getparent().getparent() if g.getparent() is not None else None
        what = f"link '{lk.get('name')}'" if lk is not None and lk.tag == "link" else "geometry"
        for s in g:
            if s.tag == "box":
                v = s.get("size")
                vals = numbers(v, 3)
                if v is None:
                    yield Report(s, f"{what}: <box> needs size=\"x y z\"")
                elif vals is None:
                    yield Report(s, f"{what}: <box size=\"{v}\"> must be three numbers")
                elif any(x <= 0 for x in vals):
                    yield Report(s, f"{what}: <box size=\"{v}\"> must be three positive numbers")
            elif s.tag in ("cylinder", "capsule"):
                for a in ("radius", "length"):
                    msg = _positive(model, s, a, what)
                    if msg:
                        yield Report(s, msg)
            elif s.tag == "sphere":
                msg = _positive(model, s, "radius", what)
                if msg:
                    yield Report(s, msg)
            elif s.tag == "mesh" and not (s.get("filename") or "").strip():
                yield Report(s, f"{what}: <mesh> has no filename")
