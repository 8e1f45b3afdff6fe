"""A `<visual>` or `<collision>` needs one `<geometry>` holding exactly one shape.

Why: An empty geometry, two shapes in one geometry, or an unknown shape is rejected by URDF
parsers (or silently drops the shape). An empty `<geometry/>` is rejected by MuJoCo 4.0.0 and
PyBullet 3.2.7 (iDynTree segfaults); Pinocchio 4.1.0 loads it without the shape (a warning for
`pinocchio`) (measured with MuJoCo 4.0.0, Pinocchio 4.1.0, PyBullet 3.2.7).

How to fix: Keep exactly one of box, cylinder, sphere, mesh or capsule (URDF 1.1) in each geometry; split two shapes
into two visuals or collisions.
"""
CODE = "UL204"
NAME = "geometry-shape"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="a">
    <visual><geometry><box size="1 1 1"/><sphere radius="1"/></geometry></visual>
  </link>
</robot>
"""
FAIL_AT = [(3, 42)]
PASS = """<robot name="r">
  <link name="a">
    <visual><geometry><box size="1 1 1"/></geometry></visual>
  </link>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, did_you_mean

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model

SHAPES = ("box", "cylinder", "sphere", "mesh", "capsule")   # capsule: URDF 1.1 (UL213)


def check(model: "Model", ctx: "Context") -> "Checked":
    for lk in model.top_links():
        for part in lk:
            if part.tag not in ("visual", "collision"):
                continue
            geoms = part.findall("geometry")
            if not geoms:
                yield Report(part, f"link '{lk.get('name')}': <{part.tag}> has no <geometry>")
                continue
            for g in geoms[1:]:
                yield Report(g, f"link '{lk.get('name')}': <{part.tag}> has more than one <geometry>")
            g = geoms[0]
            shapes = [c for c in g if isinstance(c.tag, str)]
            if not shapes:
                yield Report(g, f"link '{lk.get('name')}': empty <geometry> in <{part.tag}>", targets={"pinocchio": "warning", "isaac": "warning", "gazebo": "warning"})
            for s in shapes:
                if s.tag not in SHAPES:
                    yield Report(s, (f"link '{lk.get('name')}': unknown shape <{s.tag}>"
                                     + did_you_mean(s.tag, SHAPES)))
            if len(shapes) > 1:
                yield Report(shapes[1], (f"link '{lk.get('name')}': <geometry> holds {len(shapes)} shapes "
                                         f"({', '.join(s.tag for s in shapes)}); use one <{part.tag}> per shape"))
