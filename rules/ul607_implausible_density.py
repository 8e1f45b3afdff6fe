"""A moving link's mass divided by the volume of its collision geometry (visual when it has no
collision, or when the collision shape is clearly a proxy: spheres of at most 1 cm, or a
bounding box under an eighth of the visual's, and the visual is larger than it; nothing when
the visual cannot be measured;
the message says which was used) is not the density of any material a robot is made of.

Why: This is how unit mix-ups show: a mass in grams written as kilograms (x1000), a mesh in
millimetres without `scale` (volume x10⁹), a scale applied twice. Hollow shells and
cable-filled links still land well inside the band. Boxes, cylinders and spheres are exact;
meshes are measured with trimesh (an open mesh through its convex hull, which the message
says).

How to fix: Write the mass in kilograms and the mesh scale that makes the mesh metres.

Options: `min-density` (default 50 kg/m³, lighter than foam) and `max-density` (default
25,000 kg/m³, denser than tungsten) bound the accepted density.
"""
CODE = "UL607"
NAME = "implausible-density"
SEVERITY = "warning"
NEEDS = {"meshes"}
OPTIONS = {"min-density": 50.0, "max-density": 25000.0}
from urdf_lint.rules._physics import example, hull_note, measured_links
FAIL = example(1000, 1.7, 1.7, 1.7)
FAIL_AT = [(4, 15)]
PASS = example(2.7, 0.0045, 0.0045, 0.0045)
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, fmt

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    lo = float(ctx.options.get("min-density", 50.0))
    hi = float(ctx.options.get("max-density", 25000.0))
    for lk, m, _t, inr, g in measured_links(model, ctx):
        rho = m / g.volume
        if lo <= rho <= hi:
            continue
        hint = ("mass in grams? geometry too small (a placeholder collision shape? scale applied twice?)" if rho > hi else
                "geometry too large (a mesh in millimetres without scale?) or the mass too small")
        yield Report(inr.find("mass"), (f"link '{lk.get('name')}': implied density {rho:.3g} kg/m³ "
                                        f"({fmt(m)} kg in {g.volume:.3g} m³ of {g.source} geometry) is "
                                        f"outside {fmt(lo)}-{fmt(hi)} kg/m³: {hint}{hull_note(g)}"))
