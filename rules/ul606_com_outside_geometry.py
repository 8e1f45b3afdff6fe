"""A moving link's centre of mass (`<inertial><origin xyz>`) lies outside the bounding box of its
collision geometry (visual when it has no
collision, or when the collision shape is clearly a proxy: spheres of at most 1 cm, or a
bounding box under an eighth of the visual's, and the visual is larger than it; nothing when
the visual cannot be measured;
the message says which was used) by more than `tolerance` metres.

Why: A rigid part's centre of mass is inside its convex hull, so well inside its bounding box.
One outside means an origin in the wrong frame (the joint's, the parent's, a CAD assembly's),
millimetres written as metres, or a sign error; gravity then pulls the joint the wrong way.
When the centre of mass is outside the collision geometry but inside the link's (measurable)
visual geometry, the collision shape covers only part of the link and nothing is reported.
Boxes, cylinders and spheres are exact; meshes are measured with trimesh. Links whose geometry
cannot be measured are skipped.

How to fix: Write the centre of mass in the link frame, in metres.

Options: `tolerance` (default 0.02) is how far, in metres, the centre of mass may lie outside
the bounding box.
"""
CODE = "UL606"
NAME = "com-outside-geometry"
SEVERITY = "warning"
NEEDS = {"meshes"}
OPTIONS = {"tolerance": 0.02}
from urdf_lint.rules._physics import example, hull_note, measured_links, pose
FAIL = example(1, 0.0017, 0.0017, 0.0017, origin="0 0 0.5")
FAIL_AT = [(4, 15)]
PASS = example(1, 0.0017, 0.0017, 0.0017, origin="0 0 0.02")
from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report, fmt

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def _outside(com: Any, g: Any, tol: float) -> list[int]:
    return [k for k in range(3) if com[k] < g.lo[k] - tol or com[k] > g.hi[k] + tol]


def check(model: "Model", ctx: "Context") -> "Checked":
    tol = float(ctx.options.get("tolerance", 0.02))
    for lk, _m, _t, inr, g in measured_links(model, ctx):
        import numpy as np
        p = pose(inr, np)
        if p is None:
            continue
        com = p[1]
        out = _outside(com, g, tol)
        if out and g.source == "collision":
            # a collision shape may cover part of the link only (a plate on top of a base):
            # the visual geometry, when it can be measured, is the part too
            from urdf_lint.rules._physics import link_geometry
            vis = link_geometry(model, ctx, lk, np, kind="visual")
            if vis is not None and not _outside(com, vis, tol):
                continue
        if out:
            box = " x ".join(f"[{fmt(round(a, 4))}, {fmt(round(b, 4))}]" for a, b in zip(g.lo, g.hi, strict=True))
            where = inr.find("origin") if inr.find("origin") is not None else inr
            yield Report(where, (f"link '{lk.get('name')}': centre of mass "
                                 f"({' '.join(fmt(round(x, 4)) for x in com)}) is outside its {g.source} "
                                 f"geometry's bounding box {box} along {', '.join('xyz'[k] for k in out)} "
                                 f"(by more than {fmt(tol)} m){hull_note(g)}"))
