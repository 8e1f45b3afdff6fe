"""The scene of a snapshot: the kinematic tree at the zero configuration (world transform of
every link), the visual and collision parts with their colours, and their triangles.

Mesh parts use the resolved, confined paths and the mesh loader (with its in-memory cache) of
the lint rules; nothing the package resolver did not vet is ever read.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Sequence

import numpy as np

from urdf_lint.meshes.resolve import MeshStatus
from urdf_lint.engine.api import numbers

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.engine.lint import Context
    from urdf_lint.engine.model import Model

Element = Any      # an lxml element (lxml ships no type information here)
# a part's triangles: vertices (n, 3), faces (m, 3), per-face colours (m, 3) or None
MeshArrays = tuple[np.ndarray, np.ndarray, "np.ndarray | None"]

MAX_TEXTURE = 1024
DEFAULT_RGBA = (0.72, 0.74, 0.78, 1.0)


# -- kinematics ------------------------------------------------------------------------------
def rpy_matrix(rpy: Sequence[float]) -> np.ndarray:
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def origin_matrix(el: Element | None) -> np.ndarray:
    T = np.eye(4)
    o = el.find("origin") if el is not None else None
    if o is not None:
        T[:3, :3] = rpy_matrix(numbers(o.get("rpy", "0 0 0"), 3) or [0, 0, 0])
        T[:3, 3] = numbers(o.get("xyz", "0 0 0"), 3) or [0, 0, 0]
    return T


@dataclass
class Part:
    """One visual or collision geometry of a link, placed in the world at the zero configuration."""
    link: str
    kind: str                  # "visual" | "collision"
    index: int
    T: np.ndarray              # world transform of the geometry frame
    local: np.ndarray          # transform relative to the link frame
    shape: str                 # box | cylinder | sphere | mesh | missing
    params: dict[str, Any] = field(default_factory=dict)
    rgba: tuple[float, ...] = DEFAULT_RGBA
    problem: str = ""


@dataclass
class Scene:
    """A robot ready to draw: link transforms, the kinematic tree, and its geometry parts."""
    name: str
    links: dict[str, np.ndarray]   # link -> world transform
    tree: list[tuple[str, Element, str]]   # (parent_link, joint_element, child_link), DFS
    roots: list[str]
    parts: list[Part]


def kinematic_tree(model: "Model"
                   ) -> tuple[dict[str, np.ndarray], list[tuple[str, Element, str]], list[str]]:
    joints_by_parent: dict[str, list[Element]] = {}
    has_parent = set()
    for j in model.top_joints():
        p, c = j.find("parent"), j.find("child")
        if p is None or c is None or not p.get("link") or not c.get("link"):
            continue
        joints_by_parent.setdefault(p.get("link"), []).append(j)
        has_parent.add(c.get("link"))
    names = [lk.get("name") for lk in model.top_links() if lk.get("name")]
    roots = [n for n in dict.fromkeys(names) if n not in has_parent] or names[:1]
    world: dict[str, np.ndarray] = {}
    tree: list[tuple[str, Element, str]] = []
    seen: set[str] = set()

    def visit(link: str, T: np.ndarray) -> None:
        if link in seen:
            return
        seen.add(link)
        world[link] = T
        for j in joints_by_parent.get(link, []):
            child = j.find("child").get("link")
            if child in seen:
                continue
            tree.append((link, j, child))
            visit(child, T @ origin_matrix(j))
    for r in roots:
        visit(r, np.eye(4))
    for n in names:  # unreachable links (loops, missing parents) sit at the origin
        if n not in world:
            roots.append(n)
            visit(n, np.eye(4))
    return world, tree, roots


def material_colors(model: "Model") -> dict[str, tuple[float, ...]]:
    out: dict[str, tuple[float, ...]] = {}
    for m in model.root.iter("material"):
        c = m.find("color")
        v = numbers(c.get("rgba"), 4) if c is not None else None
        if m.get("name") and v and m.get("name") not in out:
            out[m.get("name")] = tuple(min(1.0, max(0.0, x)) for x in v)
    return out


def build_scene(model: "Model", ctx: "Context") -> Scene:
    world, tree, roots = kinematic_tree(model)
    colors = material_colors(model)
    parts = []
    for lk in model.top_links():
        name = lk.get("name")
        if name not in world:
            continue
        for kind in ("visual", "collision"):
            for i, el in enumerate(lk.findall(kind)):
                local = origin_matrix(el)
                T = world[name] @ local
                rgba: tuple[float, ...] = DEFAULT_RGBA
                mat = el.find("material")
                if mat is not None:
                    c = mat.find("color")
                    v = numbers(c.get("rgba"), 4) if c is not None else None
                    rgba = tuple(v) if v else colors.get(mat.get("name"), DEFAULT_RGBA)
                g = el.find("geometry")
                shape = next((s for s in g if isinstance(s.tag, str)), None) if g is not None else None
                part = Part(name, kind, i, T, local, "missing", {}, rgba)
                if shape is None:
                    part.problem = "no geometry"
                elif shape.tag == "box":
                    size = numbers(shape.get("size"), 3)
                    part.shape, part.params = ("box", {"size": size}) if size else ("missing", {})
                elif shape.tag in ("cylinder", "capsule"):
                    r, ln = numbers(shape.get("radius"), 1), numbers(shape.get("length"), 1)
                    if r and ln:
                        part.shape, part.params = "cylinder", {"radius": r[0], "length": ln[0]}
                elif shape.tag == "sphere":
                    r = numbers(shape.get("radius"), 1)
                    if r:
                        part.shape, part.params = "sphere", {"radius": r[0]}
                elif shape.tag == "mesh":
                    uri = shape.get("filename") or ""
                    ref = ctx.mesh_ref(model, uri) if uri else None
                    scale = numbers(shape.get("scale", "1 1 1"), 3) or [1, 1, 1]
                    if ref is not None and ref.status is MeshStatus.OK and ref.path:
                        part.shape, part.params = "mesh", {"path": ref.path, "scale": scale, "uri": uri}
                    else:
                        part.problem = ref.message if ref else "mesh without filename"
                parts.append(part)
    return Scene(model.name, world, tree, roots, parts)


# -- triangles -------------------------------------------------------------------------------
def part_mesh(part: Part, ctx: "Context") -> MeshArrays | None:
    """(vertices in the part frame, faces, per-face rgb or None) or None when unavailable.
    Prepared once per part: the picture and the recording of a render draw the same parts."""
    if "arrays" not in part.params:
        part.params["arrays"] = _part_mesh(part, ctx)
    got: MeshArrays | None = part.params["arrays"]
    return got


def _part_mesh(part: Part, ctx: "Context") -> MeshArrays | None:
    import trimesh
    if part.shape == "box" and all(s > 0 for s in part.params["size"]):
        m = trimesh.creation.box(extents=part.params["size"])
    elif part.shape == "cylinder" and part.params["radius"] > 0 and part.params["length"] > 0:
        m = trimesh.creation.cylinder(radius=part.params["radius"], height=part.params["length"],
                                      sections=28)
    elif part.shape == "sphere" and part.params["radius"] > 0:
        m = trimesh.creation.icosphere(subdivisions=2, radius=part.params["radius"])
    elif part.shape == "mesh":
        try:
            m = ctx.mesh(part.params["path"])
        except Exception as e:  # noqa: BLE001 - an unloadable mesh becomes a placeholder
            part.problem = f"cannot load: {type(e).__name__}"
            return None
        v = np.asarray(m.vertices, dtype=float) * np.asarray(part.params["scale"], dtype=float)
        if not len(v) or not np.isfinite(v).all():
            part.problem = "empty mesh"
            return None
        faces = np.asarray(m.faces)
        fc, tex = None, None
        try:
            vis = m.visual
            if vis is not None and vis.kind in ("face", "vertex"):
                fc = np.asarray(vis.face_colors, dtype=float)[:, :3] / 255.0
            elif vis is not None and vis.kind == "texture":
                tex = _texture(vis)
                if tex is not None:
                    fc = _sample_texture(tex, faces)
                else:
                    main = getattr(vis.material, "main_color", None)
                    if main is not None:
                        fc = np.tile(np.asarray(main[:3], dtype=float) / 255.0, (len(faces), 1))
        except Exception:  # noqa: BLE001 - colours are best effort
            fc, tex = None, None
        part.params["texture"] = tex
        return v, faces, fc
    else:
        return None
    return np.asarray(m.vertices, dtype=float), np.asarray(m.faces), None


def _texture(vis: Any) -> tuple[np.ndarray, np.ndarray] | None:
    """(uv per vertex, RGB image array) of a textured trimesh visual, or None."""
    uv = getattr(vis, "uv", None)
    mat = vis.material
    img = getattr(mat, "image", None)
    if img is None:
        img = getattr(mat, "baseColorTexture", None)
    if uv is None or img is None or len(uv) == 0:
        return None
    if max(img.size) > MAX_TEXTURE:  # plenty for a review snapshot, and bounded memory
        img = img.copy()
        img.thumbnail((MAX_TEXTURE, MAX_TEXTURE))
    arr = np.asarray(img.convert("RGB"))
    return np.asarray(uv, dtype=float), arr


def _sample_texture(tex: tuple[np.ndarray, np.ndarray], faces: np.ndarray) -> np.ndarray:
    """Per-face colour: the texture at each face's centroid UV (wrapped, v flipped)."""
    uv, arr = tex
    h, w = arr.shape[:2]
    c = uv[faces].mean(axis=1) % 1.0
    px = np.clip((c[:, 0] * (w - 1)).astype(int), 0, w - 1)
    py = np.clip(((1.0 - c[:, 1]) * (h - 1)).astype(int), 0, h - 1)
    colours: np.ndarray = arr[py, px].astype(float) / 255.0
    return colours


def _transform(T: np.ndarray, v: np.ndarray) -> np.ndarray:
    placed: np.ndarray = v @ T[:3, :3].T + T[:3, 3]
    return placed
