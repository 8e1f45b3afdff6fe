"""Helpers for the physical plausibility rules UL605-UL607 (not a rule).

For each moving link (the child of a non-fixed joint) with a declared mass and inertia, the
link's collision geometry (its visual geometry when it has no collision, or when the collision
shape is clearly a proxy: :func:`proxy_reason`, and the visual is larger; nothing when it is a
proxy and there is no measurable visual) is filled uniformly
and summed in the link frame: boxes, cylinders and spheres exactly, capsules and meshes through
trimesh (imported only when a link has one). Mesh volume facts are cached by file content like
every mesh fact, so a mesh is measured once per change. An open (non-watertight) mesh has no
volume: its convex hull is used, and the rules say so.

The moments are kept as unit-density volume integrals (V, ∫r dV, ∫r rᵀ dV) so that mesh
scale, origin rotation and translation, and several geometries on one link combine exactly.
"""
from __future__ import annotations

import math
from types import ModuleType
from typing import TYPE_CHECKING, Any, Iterator, Mapping, Sequence

from urdf_lint.engine.api import MeshFacts, mesh_mass_properties, number, numbers
from urdf_lint.rules._inertial import INERTIA, is_zero, mass, tensor

if TYPE_CHECKING:  # pragma: no cover
    from numpy import ndarray
    from numpy.typing import ArrayLike

    from urdf_lint.engine.api import Context, MassFacts, Model

# (volume, first, second, corners) of a piece of geometry in its own frame
Piece = tuple[float, "ArrayLike", "ArrayLike", "ArrayLike"]
# (link, mass, declared tensor, inertial element, Geometry) of a measured link
Measured = tuple[Any, float, dict[str, float], Any, "Geometry"]


class Geometry:
    """Unit-density volume integrals of a link's geometry, in the link frame."""

    def __init__(self, np: ModuleType) -> None:
        self.np = np
        self.volume = 0.0
        self.first: ndarray = np.zeros(3)
        self.second: ndarray = np.zeros((3, 3))
        self.lo: ndarray = np.full(3, np.inf)
        self.hi: ndarray = np.full(3, -np.inf)
        self.hull: list[str] = []   # uris of open meshes measured through their convex hull
        self.source = "collision"
        self.note = ""          # how it was chosen, when not simply the collision geometry

    def add(self, vol: float, first: ArrayLike, second: ArrayLike, corners: ArrayLike,
            rot: ndarray, t: ndarray) -> None:
        """Add a piece given in its own frame, placed by rotation ``rot`` and offset ``t``."""
        np = self.np
        first = np.asarray(first, float)
        second = np.asarray(second, float)
        f2 = rot @ first
        self.second += rot @ second @ rot.T + np.outer(f2, t) + np.outer(t, f2) + vol * np.outer(t, t)
        self.first += f2 + vol * t
        self.volume += vol
        pts = np.asarray(corners, float) @ rot.T + t
        self.lo = np.minimum(self.lo, pts.min(axis=0))
        self.hi = np.maximum(self.hi, pts.max(axis=0))

    @property
    def com(self) -> ndarray:
        return self.first / self.volume

    def inertia(self, m: float) -> ndarray:
        """Inertia tensor about the geometry's centre of mass, for mass ``m`` spread uniformly."""
        np = self.np
        c = self.com
        s = self.second - self.volume * np.outer(c, c)
        tensor: ndarray = (m / self.volume) * (np.trace(s) * np.eye(3) - s)
        return tensor


def rotation(rpy: Sequence[float], np: ModuleType) -> ndarray:
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    rot: ndarray = np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                             [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                             [-sp, cp * sr, cp * cr]])
    return rot


def pose(el: Any, np: ModuleType) -> tuple[ndarray, ndarray] | None:
    """(rotation, translation) of the ``<origin>`` child of ``el`` (identity when absent)."""
    o = el.find("origin") if el is not None else None
    xyz = numbers(o.get("xyz", "0 0 0"), 3) if o is not None else [0, 0, 0]
    rpy = numbers(o.get("rpy", "0 0 0"), 3) if o is not None else [0, 0, 0]
    if xyz is None or rpy is None:
        return None
    return rotation(rpy, np), np.asarray(xyz, float)


def _box_corners(half: Sequence[float], np: ModuleType) -> ndarray:
    corners: ndarray = np.array([[sx * half[0], sy * half[1], sz * half[2]]
                                 for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
    return corners


def _primitive(shape: Any, np: ModuleType) -> Piece | None:
    """(volume, first, second, corners) of a box / cylinder / sphere centred at its origin, or
    None (capsules and bad values)."""
    if shape.tag == "box":
        s = numbers(shape.get("size"), 3)
        if not s or min(s) <= 0:
            return None
        a, b, c = s
        v = a * b * c
        return v, np.zeros(3), np.diag([v * a * a / 12, v * b * b / 12, v * c * c / 12]), \
            _box_corners([a / 2, b / 2, c / 2], np)
    r = number(shape.get("radius"))
    if r is None or r <= 0:
        return None
    if shape.tag == "sphere":
        v = 4 / 3 * math.pi * r ** 3
        return v, np.zeros(3), np.eye(3) * v * r * r / 5, _box_corners([r, r, r], np)
    if shape.tag == "cylinder":
        h = number(shape.get("length"))
        if h is None or h <= 0:
            return None
        v = math.pi * r * r * h
        return v, np.zeros(3), np.diag([v * r * r / 4, v * r * r / 4, v * h * h / 12]), \
            _box_corners([r, r, h / 2], np)
    return None


def _capsule(shape: Any, np: ModuleType) -> Piece | None:
    r, h = number(shape.get("radius")), number(shape.get("length"))
    if r is None or h is None or r <= 0 or h <= 0:
        return None
    import trimesh
    f = mesh_mass_properties(trimesh.creation.capsule(height=h, radius=r, count=[24, 24]))
    if not f.ok:
        return None
    return f.volume, f.first, f.second, _box_corners([r, r, h / 2 + r], np)


def link_geometry(model: Model, ctx: Context, lk: Any, np: ModuleType,
                  kind: str | None = None, box_only: bool = False) -> Geometry | None:
    """The link's Geometry (its collision, else visual, pieces; or those of ``kind``), or None
    when any piece cannot be measured (a missing or broken mesh, a bad value): no guess is
    better than a wrong one. ``box_only``: only its bounding box is wanted (``lo``, ``hi``;
    no volumes), from the meshes' bounds (``ctx.mesh_facts``), without their volume
    integrals, which a visual mesh that is not closed would take a convex hull for. Its
    corners are those of the full Geometry whenever that can be measured: a mesh's bounds
    are the same in both facts."""
    kind = kind or ("collision" if lk.findall("collision") else "visual")
    pieces = lk.findall(kind)
    if not pieces:
        return None
    g = Geometry(np)
    g.source = kind
    for piece in pieces:
        shape = piece.find("geometry")
        shape = next((s for s in shape if isinstance(s.tag, str)), None) if shape is not None else None
        p = pose(piece, np)
        if shape is None or p is None:
            return None
        rot, t = p
        if shape.tag == "mesh":
            uri = shape.get("filename")
            ref = ctx.mesh_ref(model, uri) if uri else None
            if ref is None or ref.problem is not None or not ref.path:
                return None
            f: MeshFacts | MassFacts = ctx.mesh_facts(ref.path) if box_only \
                else ctx.mass_facts(ref.path)
            scale = numbers(shape.get("scale", "1 1 1"), 3)
            if not f.ok or f.bounds is None or not scale or any(s == 0 for s in scale):
                return None
            lo, hi = f.bounds
            corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])
                                for z in (lo[2], hi[2])]) * np.asarray(scale)
            if isinstance(f, MeshFacts):       # (box_only)
                g.add(0.0, np.zeros(3), np.zeros((3, 3)), corners, rot, t)
                continue
            a = np.diag(scale)
            det = abs(scale[0] * scale[1] * scale[2])
            g.add(det * f.volume, det * (a @ np.asarray(f.first)),
                  det * (a @ np.asarray(f.second) @ a.T), corners, rot, t)
            if f.hull:
                g.hull.append(uri)
        else:
            prim = _capsule(shape, np) if shape.tag == "capsule" else _primitive(shape, np)
            if prim is None:
                return None
            vol, first, second, corners = prim
            g.add(vol, first, second, corners, rot, t)
    return g if box_only or g.volume > 0 else None


def moving_links(model: Model) -> Iterator[tuple[Any, Any]]:
    """(link, joint) for every link that a non-fixed joint moves (first joint naming it)."""
    seen: set[str | None] = set()
    for j in model.top_joints():
        if j.get("type") in (None, "fixed"):
            continue
        c = j.find("child")
        name = c.get("link") if c is not None else None
        lk = model.links.get(name) if name is not None else None
        if lk is not None and name not in seen:
            seen.add(name)
            yield lk, j


def is_identity(t: Mapping[str, float] | None) -> bool:
    return t is not None and t["ixx"] == t["iyy"] == t["izz"] == 1 and \
        t["ixy"] == t["ixz"] == t["iyz"] == 0


def measured_links(model: Model, ctx: Context) -> list[Measured]:
    """(link, mass, declared tensor, inertial element, Geometry) for every moving link whose
    declared inertial and geometry can both be measured. Memoized per model on the context."""
    key = id(model)
    cache = getattr(ctx, "_physics_links", None)
    if cache is None:
        cache = {}
        ctx._physics_links = cache   # type: ignore[attr-defined]  # a memo on the context
    if key in cache:
        cached: list[Measured] = cache[key]
        return cached
    out: list[Measured] = []
    np: Any = None
    for lk, _j in moving_links(model):
        m, t, inr = mass(lk), tensor(lk), lk.find("inertial")
        if m is None or m <= 0 or t is None or is_zero(t) or is_identity(t):
            continue
        if np is None:
            import numpy as np
        g = link_geometry(model, ctx, lk, np)
        if g is not None and g.source == "collision":
            why = proxy_reason(model, ctx, lk, g, np)
            if why:   # judge the body by its visual geometry, or not at all
                vis = link_geometry(model, ctx, lk, np, kind="visual") \
                    if lk.findall("visual") else None
                if vis is not None and _box_volume(vis) <= _box_volume(g):
                    pass   # the visual is no larger (a 1 mm placeholder box): the collision is the body
                else:
                    g = vis
                    if g is not None:
                        g.note = f"; judged against the visual geometry: the collision shape {why}"
        if g is not None:
            out.append((lk, m, t, inr, g))
    cache[key] = out
    return out


PROXY_SPHERE_M = 0.01     # collision spheres this small are contact points or placeholders
PROXY_FRACTION = 1 / 8    # a collision box this much smaller than the visual one is partial


def _box_volume(g: Geometry) -> float:
    return float(max(0.0, g.hi[0] - g.lo[0]) * max(0.0, g.hi[1] - g.lo[1])
                 * max(0.0, g.hi[2] - g.lo[2]))


def proxy_reason(model: Model, ctx: Context, lk: Any, g: Geometry, np: ModuleType) -> str:
    """Why the link's collision geometry ``g`` is clearly a proxy, not the body (``""`` when
    it is not): only spheres of at most 1 cm (contact spheres, a placeholder), or a bounding
    box under an eighth of the visual geometry's (a cylinder around only the motor of a hip)."""
    shapes = [s for c in lk.findall("collision") for gm in c.findall("geometry") for s in gm
              if isinstance(s.tag, str)]
    if shapes and all(s.tag == "sphere" and (number(s.get("radius")) or 0) <= PROXY_SPHERE_M
                      for s in shapes):
        return (f"is {len(shapes)} sphere(s) of at most {PROXY_SPHERE_M * 1000:g} mm "
                "(contact points or a placeholder)")
    if not lk.findall("visual"):
        return ""
    # the visual's bounding box decides, and the volume facts behind it are measured only
    # when the box calls the collision a proxy (they may still find the visual unmeasurable)
    box = link_geometry(model, ctx, lk, np, kind="visual", box_only=True)
    if box is not None and not _partial(g, box):
        return ""
    vis = link_geometry(model, ctx, lk, np, kind="visual")
    if vis is None or not _partial(g, vis):
        return ""
    cv, vv = _box_volume(g), _box_volume(vis)
    return (f"covers only part of the link (its bounding box is {cv / vv:.0%} of the "
            "visual geometry's)")


def _partial(g: Geometry, vis: Geometry) -> bool:
    """Whether collision geometry ``g``'s bounding box is under :data:`PROXY_FRACTION` of the
    visual geometry ``vis``'s."""
    cv, vv = _box_volume(g), _box_volume(vis)
    return vv > 0 and cv < vv * PROXY_FRACTION


def declared_matrix(t: Mapping[str, float], inr: Any, np: ModuleType) -> ndarray:
    """The declared inertia in link axes (rotated by the inertial origin's rpy)."""
    m = np.array([[t["ixx"], t["ixy"], t["ixz"]], [t["ixy"], t["iyy"], t["iyz"]],
                  [t["ixz"], t["iyz"], t["izz"]]])
    p = pose(inr, np)
    rot = p[0] if p else np.eye(3)
    declared: ndarray = rot @ m @ rot.T
    return declared


def hull_note(g: Geometry) -> str:
    """What the rules' messages add about how the geometry was measured: a proxy collision
    shape replaced by the visual geometry, open meshes measured by their convex hull."""
    note: str = getattr(g, "note", "")
    if not g.hull:
        return note
    return note + (f"; '{g.hull[0]}' is not watertight, so its convex hull was measured"
                   + (f" (and {len(g.hull) - 1} more)" if len(g.hull) > 1 else ""))


def example(mass: float | str, ixx: float | str, iyy: float | str, izz: float | str,
            origin: str = "", box: str = "0.1 0.1 0.1") -> str:
    """FAIL/PASS text for the physics rules: a moving link 'arm' with a box collision."""
    o = f'<origin xyz="{origin}"/>' if origin else ""
    return f"""<robot name="r">
  <link name="base"/>
  <link name="arm">
    <inertial>{o}<mass value="{mass}"/><inertia ixx="{ixx}" ixy="0" ixz="0" iyy="{iyy}" iyz="0" izz="{izz}"/></inertial>
    <collision><geometry><box size="{box}"/></geometry></collision>
  </link>
  <joint name="j" type="continuous"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/></joint>
</robot>
"""


__all__ = ["example", "INERTIA", "measured_links", "declared_matrix", "hull_note", "is_identity",
           "moving_links", "pose"]
