"""A moving link's declared inertia does not match its geometry: a principal moment is more than
`max-ratio` times, or less than `min-ratio` times, the moment of its collision geometry (visual when it has no
collision, or when the collision shape is clearly a proxy: spheres of at most 1 cm, or a
bounding box under an eighth of the visual's, and the visual is larger than it; nothing when
the visual cannot be measured;
the message says which was used) filled uniformly with the declared mass.

Why: Real links are not uniform, so a factor of two or three is normal; a factor of ten is an
inertia copied from another part, computed for the wrong axis or in the wrong units (g·mm²,
kg·mm²), or a placeholder. Simulated joints then react far too slowly or jitter. Principal
moments are compared smallest to smallest, largest to largest, each about its own centre of
mass. Boxes, cylinders and spheres are exact; meshes are measured with trimesh (an open mesh
through its convex hull, as the message says). Links whose geometry cannot be measured (a
missing mesh) are skipped.

How to fix: Compute the inertia from the CAD model or from the geometry and the real mass.

Options: `min-ratio` (default 0.1) and `max-ratio` (default 10) bound the accepted ratio of
declared to geometric principal moment.
"""
CODE = "UL605"
NAME = "inertia-geometry-mismatch"
SEVERITY = "warning"
NEEDS = {"meshes"}
OPTIONS = {"min-ratio": 0.1, "max-ratio": 10.0}
from urdf_lint.rules._physics import example, declared_matrix, hull_note, measured_links
FAIL = example(1, 0.5, 0.5, 0.5)
FAIL_AT = [(4, 32)]
PASS = example(1, 0.0017, 0.0017, 0.0017)
from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report, fmt

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model

WHICH = ("smallest", "middle", "largest")


def _axis(vec: Any) -> Any:
    i = max(range(3), key=lambda k: abs(vec[k]))
    return "xyz"[i] if abs(vec[i]) > 0.9 else "a tilted axis"


def check(model: "Model", ctx: "Context") -> "Checked":
    lo_r = float(ctx.options.get("min-ratio", 0.1))
    hi_r = float(ctx.options.get("max-ratio", 10.0))
    for lk, m, t, inr, g in measured_links(model, ctx):
        import numpy as np
        declared = np.linalg.eigvalsh(declared_matrix(t, inr, np))
        if declared[0] <= 0:
            continue  # not positive definite: UL603 reports it
        expected, vecs = np.linalg.eigh(g.inertia(m))
        bad = []
        for k in range(3):
            if expected[k] <= 0:
                continue
            ratio = declared[k] / expected[k]
            if ratio > hi_r or ratio < lo_r:
                bad.append(f"{WHICH[k]} principal moment (about ≈{_axis(vecs[:, k])}) "
                           f"{fmt(declared[k])} vs {fmt(expected[k])} kg·m² ({ratio:.3g}x)")
        if bad:
            yield Report(inr.find("inertia"), (
                       f"link '{lk.get('name')}': declared inertia does not match its {g.source} geometry "
                       f"filled uniformly with {fmt(m)} kg: " + "; ".join(bad)
                       + f" (allowed {fmt(lo_r)}x-{fmt(hi_r)}x){hull_note(g)}"))
