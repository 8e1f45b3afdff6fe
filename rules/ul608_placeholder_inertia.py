"""A moving link carries a placeholder inertia: the identity tensor (`ixx=iyy=izz=1`, no
products), or the very same tensor as every other moving link of the robot although those
links differ in shape or mass (identical parts, like the four wheels of a cart, rightly share
one tensor, also when their meshes are mirrored: `wheel_left.stl` / `wheel_right.stl`).

Why: Both come from templates and copy-paste, not from the part: 1 kg·m² is the inertia of a
1 m, 12 kg bar, and no two different links share a tensor to the last digit. Simulated joints
then barely move or oscillate.

How to fix: Compute the inertia from the CAD model or from the geometry (e.g. trimesh's
`moment_inertia`), or see UL605 for what the geometry implies.

Options: `min-links` (default 3) is how many moving links must share one tensor before it
counts as a placeholder.
"""
CODE = "UL608"
NAME = "placeholder-inertia"
SEVERITY = "warning"
OPTIONS = {"min-links": 3}
from urdf_lint.rules._physics import example, is_identity, moving_links
FAIL = example(1, 1, 1, 1)
FAIL_AT = [(4, 32)]
PASS = example(1, 0.0017, 0.0017, 0.0017)
import re

from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report, fmt

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._inertial import INERTIA, is_zero, mass, tensor


_SIDE = re.compile(r"(?i)(?<![a-z0-9])(left|right|l|r|lh|rh|lft|rgt)(?![a-z0-9])")


def _unmirrored(name: str, value: str) -> str:
    """A geometry attribute as the same part mirrored would have it: the side in a mesh file
    name (``wheel_left.stl`` / ``wheel_right.stl``) and the sign of a scale do not count."""
    if name == "filename":
        return _SIDE.sub("SIDE", value)
    if name == "scale":
        return " ".join(v.lstrip("-") for v in value.split())
    return value


def _shape(lk: Any) -> Any:
    """What the link looks like (its collision, else visual, geometry without placement):
    identical parts, like the four wheels of a cart, rightly share one tensor, also when
    their meshes are mirrored."""
    pieces = lk.findall("collision") or lk.findall("visual")
    return tuple(sorted((s.tag, tuple(sorted((k, _unmirrored(k, v)) for k, v in s.attrib.items())))
                        for p in pieces for g in p.findall("geometry") for s in g
                        if isinstance(s.tag, str)))


def check(model: "Model", ctx: "Context") -> "Checked":
    need = int(ctx.options.get("min-links", 3))
    links = [(lk, tensor(lk)) for lk, _j in moving_links(model)]
    links = [(lk, t) for lk, t in links if t is not None and not is_zero(t)]
    for lk, t in links:
        if is_identity(t):
            yield Report(lk.find("inertial/inertia"), (
                       f"link '{lk.get('name')}': inertia is the identity (ixx=iyy=izz=1), a template "
                       "placeholder; give the link its real inertia"))
    rest = [(lk, t) for lk, t in links if not is_identity(t)]
    if len(rest) >= need and len({tuple(t[a] for a in INERTIA) for _, t in rest}) == 1 \
            and (len({_shape(lk) for lk, _ in rest}) > 1 or len({mass(lk) for lk, _ in rest}) > 1):
        lk, t = rest[0]
        yield Report(lk.find("inertial/inertia"), (
                   f"all {len(rest)} moving links declare the same inertia tensor "
                   f"(ixx={fmt(t['ixx'])} iyy={fmt(t['iyy'])} izz={fmt(t['izz'])}), a copy-pasted "
                   "placeholder; give each link its own inertia"))
