"""Review snapshots: a rerun recording (.rrd) and a PNG per model, headless on a CPU.

Geometry comes from the same resolved, confined mesh paths and the same mesh loader (and
in-memory cache) as the lint rules; nothing that the package resolver did not vet is ever read
or handed to rerun. Both outputs are deterministic: a fixed recording id, static data only, no
wall-clock; the PNG is a z-buffer rasterization in numpy, anti-aliased with Pillow.
"""
from __future__ import annotations

import hashlib
import math
import os
import sys
import threading
from dataclasses import dataclass, field

import numpy as np

from .meshes import MeshStatus
from .ruleutil import numbers

PNG_SIZE = (960, 720)
MAX_TRIANGLES = 120_000
MAX_TEXTURE = 1024
MISSING_RGBA = (0.9, 0.1, 0.1, 1.0)
DEFAULT_RGBA = (0.72, 0.74, 0.78, 1.0)


# -- kinematics ------------------------------------------------------------------------------
def rpy_matrix(rpy):
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def origin_matrix(el):
    T = np.eye(4)
    o = el.find("origin") if el is not None else None
    if o is not None:
        T[:3, :3] = rpy_matrix(numbers(o.get("rpy", "0 0 0"), 3) or [0, 0, 0])
        T[:3, 3] = numbers(o.get("xyz", "0 0 0"), 3) or [0, 0, 0]
    return T


@dataclass
class Part:
    link: str
    kind: str                  # "visual" | "collision"
    index: int
    T: np.ndarray              # world transform of the geometry frame
    local: np.ndarray          # transform relative to the link frame
    shape: str                 # box | cylinder | sphere | mesh | missing
    params: dict = field(default_factory=dict)
    rgba: tuple = DEFAULT_RGBA
    problem: str = ""


@dataclass
class Scene:
    name: str
    links: dict                # link -> world transform
    tree: list                 # (parent_link, joint_element, child_link) in DFS order
    roots: list
    parts: list


def kinematic_tree(model):
    joints_by_parent: dict = {}
    has_parent = set()
    for j in model.top_joints():
        p, c = j.find("parent"), j.find("child")
        if p is None or c is None or not p.get("link") or not c.get("link"):
            continue
        joints_by_parent.setdefault(p.get("link"), []).append(j)
        has_parent.add(c.get("link"))
    names = [lk.get("name") for lk in model.top_links() if lk.get("name")]
    roots = [n for n in dict.fromkeys(names) if n not in has_parent] or names[:1]
    world, tree, seen = {}, [], set()

    def visit(link, T):
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


def material_colors(model):
    out = {}
    for m in model.root.iter("material"):
        c = m.find("color")
        v = numbers(c.get("rgba"), 4) if c is not None else None
        if m.get("name") and v and m.get("name") not in out:
            out[m.get("name")] = tuple(min(1.0, max(0.0, x)) for x in v)
    return out


def build_scene(model, ctx) -> Scene:
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
                rgba = DEFAULT_RGBA
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
def part_mesh(part, ctx):
    """(vertices in the part frame, faces, per-face rgb or None) or None when unavailable."""
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


def _texture(vis):
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


def _sample_texture(tex, faces):
    """Per-face colour: the texture at each face's centroid UV (wrapped, v flipped)."""
    uv, arr = tex
    h, w = arr.shape[:2]
    c = uv[faces].mean(axis=1) % 1.0
    px = np.clip((c[:, 0] * (w - 1)).astype(int), 0, w - 1)
    py = np.clip(((1.0 - c[:, 1]) * (h - 1)).astype(int), 0, h - 1)
    return arr[py, px].astype(float) / 255.0


def _transform(T, v):
    return v @ T[:3, :3].T + T[:3, 3]


# -- PNG -------------------------------------------------------------------------------------
@dataclass
class Geometry:
    """What a PNG shows, in world coordinates: plain arrays, so a worker can compute it from
    the meshes it may read and the parent can draw several revisions with one framing."""
    name: str
    tris: list                 # per visual part: (faces, 3, 3) float array
    cols: list                 # per visual part: (faces, 3) rgb in 0..1
    wires: list                # world positions of placeholders for missing geometry
    link_pts: np.ndarray       # (links, 3) link origins
    links: int
    part_links: list = field(default_factory=list)   # the link of each entry of ``tris``
    wire_links: list = field(default_factory=list)   # the link of each entry of ``wires``

    def only(self, links) -> "Geometry":
        """The parts of the given links in black (for highlight masks: a white part would be
        too close to the background to tell)."""
        keep = [i for i, lk in enumerate(self.part_links) if lk in links]
        wk = [i for i, lk in enumerate(self.wire_links) if lk in links]
        return Geometry(self.name, [self.tris[i] for i in keep],
                        [np.zeros_like(self.cols[i]) for i in keep],
                        [self.wires[i] for i in wk], self.link_pts, self.links,
                        [self.part_links[i] for i in keep], [self.wire_links[i] for i in wk])


@dataclass
class Frame:
    center: np.ndarray
    right: np.ndarray
    up: np.ndarray
    fwd: np.ndarray
    view: np.ndarray
    scale: float
    ox: float
    oy: float
    box: float
    size: tuple


_SS = 2  # supersampling for anti-aliasing


def scene_geometry(scene, ctx) -> Geometry:
    tris, cols, wires, plinks, wlinks = [], [], [], [], []
    for part in scene.parts:
        if part.kind != "visual":
            continue
        got = part_mesh(part, ctx) if part.shape != "missing" else None
        if got is None:
            wires.append(part.T[:3, 3].copy())
            wlinks.append(part.link)
            continue
        v, f, fc = got
        vw = _transform(part.T, v)
        tris.append(vw[f])
        plinks.append(part.link)
        base = np.asarray(part.rgba[:3], dtype=float)
        cols.append(fc if fc is not None and len(fc) == len(f) else np.tile(base, (len(f), 1)))
    link_pts = np.array([T[:3, 3] for T in scene.links.values()]) if scene.links else np.zeros((1, 3))
    return Geometry(scene.name, tris, cols, wires, link_pts, len(scene.links), plinks, wlinks)


_BOX_EDGES = ((0, 1), (0, 2), (0, 4), (1, 3), (1, 5), (2, 3), (2, 6), (3, 7), (4, 5), (4, 6),
              (5, 7), (6, 7))


def _box_corners(c, box):
    return np.array([[x, y, z] for x in (-box, box) for y in (-box, box) for z in (-box, box)]) + c


def frame_for(geoms, size=PNG_SIZE) -> Frame:
    """One camera for all ``geoms`` (a 3/4 view from the front left, fitted to their union)."""
    W, H = size
    pts = []
    for g in geoms:
        pts += [t.reshape(-1, 3) for t in g.tris] + [g.link_pts]
    allv = np.concatenate(pts)
    lo, hi = allv.min(axis=0), allv.max(axis=0)
    diag = float(np.linalg.norm(hi - lo)) or 0.2
    box = max(0.02, 0.04 * diag)
    wires = [c for g in geoms for c in g.wires]
    for c in wires:  # placeholders for missing meshes: a red wire box at the link frame
        lo, hi = np.minimum(lo, c - box), np.maximum(hi, c + box)
    center = (lo + hi) / 2
    az, el = math.radians(-135 + 180), math.radians(25)
    d = np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])
    fwd = -d
    right = np.cross(fwd, [0, 0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    frame_pts = pts + [_box_corners(c, box) for c in wires]
    q = np.concatenate(frame_pts) - center
    pc = np.stack([q @ right, q @ up], axis=-1)
    span = max(pc[:, 0].max() - pc[:, 0].min(), (pc[:, 1].max() - pc[:, 1].min()) * W / H, 1e-6)
    S = _SS
    scale = 0.86 * W * S / span
    ox = W * S / 2 - scale * (pc[:, 0].max() + pc[:, 0].min()) / 2
    oy = H * S / 2 + scale * (pc[:, 1].max() + pc[:, 1].min()) / 2
    return Frame(center, right, up, fwd, d, scale, ox, oy, box, (W, H))


def draw(g: Geometry, fr: Frame):
    """The anti-aliased image of one geometry through one frame (no caption)."""
    from PIL import Image, ImageDraw
    W, H = fr.size
    S = _SS

    def project(p):
        q = p - fr.center
        return np.stack([q @ fr.right, q @ fr.up, q @ fr.fwd], axis=-1)
    background = np.array([236, 238, 241], dtype=np.uint8)
    colour = np.tile(background, (H * S, W * S, 1))
    if g.tris:
        T3 = np.concatenate(g.tris)
        C = np.concatenate(g.cols)
        if len(T3) > MAX_TRIANGLES:  # keep the largest triangles within the budget
            area = np.linalg.norm(np.cross(T3[:, 1] - T3[:, 0], T3[:, 2] - T3[:, 0]), axis=1)
            keep = np.sort(np.argsort(-area, kind="stable")[:MAX_TRIANGLES])
            T3, C = T3[keep], C[keep]
        n = np.cross(T3[:, 1] - T3[:, 0], T3[:, 2] - T3[:, 0])
        nn = np.linalg.norm(n, axis=1)
        ok = nn > 0
        T3, C, n = T3[ok], C[ok], n[ok] / nn[ok][:, None]
        light = fr.view + np.array([0.3, -0.2, 0.6])
        light /= np.linalg.norm(light)
        shade = 0.38 + 0.62 * np.abs(n @ light)
        rgb8 = (np.clip(C * shade[:, None], 0, 1) * 255).astype(np.uint8)
        P = project(T3.reshape(-1, 3)).reshape(-1, 3, 3)
        X = fr.ox + fr.scale * P[:, :, 0]
        Y = fr.oy - fr.scale * P[:, :, 1]
        Z = P[:, :, 2]
        rasterize(colour, X, Y, Z, rgb8)
    img = Image.fromarray(colour, "RGB")
    dr = ImageDraw.Draw(img)
    for c in g.wires:
        q = project(_box_corners(c, fr.box))
        q2 = [(fr.ox + fr.scale * a, fr.oy - fr.scale * b) for a, b, _ in q]
        for a, b in _BOX_EDGES:
            dr.line([q2[a], q2[b]], fill=(220, 30, 30), width=3 * S)
    return img.resize((W, H), Image.Resampling.LANCZOS)


def _caption(img, text):
    from PIL import ImageDraw
    ImageDraw.Draw(img).text((12, 10), text, fill=(40, 40, 40))


def _save_png(img, path):
    from .atomic import atomic_path
    with atomic_path(path, ".png") as tmp:
        img.save(tmp, format="PNG", optimize=False)


def render_png(scene, ctx, path, findings_count=None, size=PNG_SIZE):
    g = scene_geometry(scene, ctx)
    img = draw(g, frame_for([g], size))
    caption = scene.name or "robot"
    caption += f"  ({len(scene.links)} links"
    if g.wires:
        caption += f", {len(g.wires)} missing geometry shown as red boxes"
    if findings_count:
        caption += f", {findings_count} findings"
    caption += ")"
    _caption(img, caption)
    _save_png(img, path)
    return {"triangles": int(sum(len(t) for t in g.tris)), "placeholders": len(g.wires)}


_BACKGROUND = np.array([236, 238, 241])


def _mask(img) -> np.ndarray:
    return np.abs(np.asarray(img.convert("RGB"), dtype=np.int16) - _BACKGROUND).max(axis=2) > 12


def _outline(mask) -> np.ndarray:
    inner = mask.copy()
    inner[1:, :] &= mask[:-1, :]
    inner[:-1, :] &= mask[1:, :]
    inner[:, 1:] &= mask[:, :-1]
    inner[:, :-1] &= mask[:, 1:]
    return mask & ~inner


def difference_image(after, before_changed, after_changed):
    """The after image washed out, the changed links tinted magenta where they are now, and
    outlined in blue where they were: what moved stands out, the rest stays as context."""
    from PIL import Image
    b = np.asarray(after.convert("RGB"), dtype=float)
    grey = b.mean(axis=2, keepdims=True)
    out = 255 - (255 - np.repeat(grey, 3, axis=2)) * 0.35
    out[after_changed] = 0.4 * out[after_changed] + 0.6 * np.array([230, 0, 160])
    edge = _outline(before_changed)
    thick = edge | np.roll(edge, 1, axis=0) | np.roll(edge, 1, axis=1)
    out[thick] = (30, 60, 200)
    return Image.fromarray(out.clip(0, 255).astype(np.uint8), "RGB")


def render_pair(before: Geometry | None, after: Geometry | None, stem: str,
                changed_links=frozenset()) -> dict:
    """``stem.before.png`` and ``stem.after.png`` with identical framing (byte-identical when
    nothing changed), and ``stem.diff.png`` highlighting ``changed_links``."""
    from PIL import Image
    geoms = [g for g in (before, after) if g is not None]
    fr = frame_for(geoms)
    out: dict = {}
    blank = Image.new("RGB", fr.size, tuple(int(x) for x in _BACKGROUND))
    masks = {}
    after_img = blank
    for side, g in (("before", before), ("after", after)):
        if g is None:
            img = blank.copy()
            _caption(img, "(no model)")
            masks[side] = np.zeros((fr.size[1], fr.size[0]), dtype=bool)
        else:
            img = draw(g, fr)
            if side == "after":
                after_img = img.copy()
            masks[side] = _mask(draw(g.only(changed_links), fr)) if changed_links else \
                np.zeros((fr.size[1], fr.size[0]), dtype=bool)
            _caption(img, f"{g.name or 'robot'}  ({g.links} links)")
        path = f"{stem}.{side}.png"
        _save_png(img, path)
        out[side] = path
    diff = difference_image(after_img, masks["before"], masks["after"])
    n = int((masks["before"] | masks["after"]).sum())
    _caption(diff, f"changed: {', '.join(sorted(changed_links)[:6]) or 'nothing'}"
             + (f" and {len(changed_links) - 6} more" if len(changed_links) > 6 else ""))
    _save_png(diff, f"{stem}.diff.png")
    out["diff"], out["changed_pixels"] = f"{stem}.diff.png", n
    return out


def _write_nearest(colour, zbuf, pix, z, c):
    """Depth-test samples (flat pixel index, depth, colour) into the buffers; nearest wins,
    equal depths go to the later sample (numpy assigns repeated indices in order)."""
    if not len(pix):
        return
    flat_z = zbuf.reshape(-1)
    np.minimum.at(flat_z, pix, z)
    win = z <= flat_z[pix]
    colour.reshape(-1, 3)[pix[win]] = c[win]


def rasterize(colour, X, Y, Z, rgb8, pixels_per_batch=1 << 20):
    """Z-buffer triangles (pixel coordinates X, Y; depth Z, smaller is nearer) into ``colour``.

    Vectorized scanline rasterization: every (triangle, row) gets its covered x-span from the
    edges, spans expand to pixels, and depth is interpolated from the triangle's plane, so the
    cost follows the covered pixels, not bounding boxes. Batches bound the memory. Pixel
    centres are sampled; equal depths resolve by triangle order (deterministic).
    """
    Hs, Ws = colour.shape[:2]
    zbuf = np.full((Hs, Ws), np.inf)
    # depth plane z = a*x + b*y + c per triangle
    x0_, x1_, x2_ = X[:, 0], X[:, 1], X[:, 2]
    y0_, y1_, y2_ = Y[:, 0], Y[:, 1], Y[:, 2]
    den = (x1_ - x0_) * (y2_ - y0_) - (x2_ - x0_) * (y1_ - y0_)
    ok = np.abs(den) > 1e-12
    X, Y, Z, rgb8, den = X[ok], Y[ok], Z[ok], rgb8[ok], den[ok]
    dz1, dz2 = Z[:, 1] - Z[:, 0], Z[:, 2] - Z[:, 0]
    dx1, dx2 = X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]
    dy1, dy2 = Y[:, 1] - Y[:, 0], Y[:, 2] - Y[:, 0]
    pa = (dz1 * dy2 - dz2 * dy1) / den
    pb = (dz2 * dx1 - dz1 * dx2) / den
    pc = Z[:, 0] - pa * X[:, 0] - pb * Y[:, 0]
    ys = np.clip(np.ceil(Y.min(axis=1) - 0.5), 0, Hs).astype(np.int64)       # first row
    ye = np.clip(np.floor(Y.max(axis=1) - 0.5), -1, Hs - 1).astype(np.int64)  # last row
    rows = np.maximum(0, ye - ys + 1)
    width = np.clip(np.ceil(X.max(axis=1)) - np.floor(X.min(axis=1)) + 1, 1, Ws)
    cost = np.cumsum(rows * width)
    start = 0
    while start < len(X):
        stop = int(np.searchsorted(cost, (cost[start - 1] if start else 0) + pixels_per_batch,
                                   side="right"))
        stop = max(stop, start + 1)
        _scan(colour, zbuf, slice(start, stop), X, Y, ys, rows, pa, pb, pc, rgb8, Ws)
        start = stop


def _scan(colour, zbuf, sl, X, Y, ys, rows, pa, pb, pc, rgb8, Ws):
    idx = np.arange(sl.start, sl.stop)
    n = rows[idx]
    keep = n > 0
    idx, n = idx[keep], n[keep]
    if not len(idx):
        return
    t = np.repeat(idx, n)                                   # triangle of each row
    first = np.repeat(np.cumsum(n) - n, n)
    yr = ys[t] + (np.arange(len(t)) - first)                # row index
    yc = yr + 0.5
    xl = np.full(len(t), np.inf)
    xr = np.full(len(t), -np.inf)
    for a, b in ((0, 1), (1, 2), (2, 0)):
        xa, xb, ya, yb = X[t, a], X[t, b], Y[t, a], Y[t, b]
        lo, hi = np.minimum(ya, yb), np.maximum(ya, yb)
        cross = (yc >= lo) & (yc <= hi) & (hi > lo)
        with np.errstate(divide="ignore", invalid="ignore"):
            xi = xa + (yc - ya) * (xb - xa) / (yb - ya)
        xl = np.where(cross, np.minimum(xl, xi), xl)
        xr = np.where(cross, np.maximum(xr, xi), xr)
    px0 = np.clip(np.ceil(xl - 0.5), 0, Ws).astype(np.int64)
    px1 = np.clip(np.floor(xr - 0.5), -1, Ws - 1).astype(np.int64)
    cnt = np.where(np.isfinite(xl) & np.isfinite(xr), np.maximum(0, px1 - px0 + 1), 0)
    if not cnt.sum():
        return
    tt = np.repeat(t, cnt)
    yy = np.repeat(yr, cnt)
    xx = np.repeat(px0, cnt) + (np.arange(int(cnt.sum())) - np.repeat(np.cumsum(cnt) - cnt, cnt))
    z = pa[tt] * (xx + 0.5) + pb[tt] * (yy + 0.5) + pc[tt]
    _write_nearest(colour, zbuf, yy * Ws + xx, z, rgb8[tt])


# -- rerun recording -------------------------------------------------------------------------
def entity_paths(scene):
    """link -> entity path following the kinematic tree: /robot/<root>/<joint>/<child>/..."""
    paths = {r: f"robot/{_safe(r)}" for r in scene.roots}
    joints = {}
    for parent, j, child in scene.tree:
        jp = f"{paths[parent]}/{_safe(j.get('name') or 'joint')}"
        joints[j.get("name")] = jp
        paths[child] = f"{jp}/{_safe(child)}"
    return paths, joints


def _safe(s):
    return "".join(ch if ch.isalnum() or ch in "_-." else "_" for ch in str(s)) or "_"


def record_rrd(scene, ctx, findings, path, recording_id, prefix=""):
    """Log ``scene`` to ``path``; ``prefix`` (e.g. ``"head/"``) puts every entity under one
    root, so that two revisions can share a recording."""
    from .atomic import atomic_path
    with atomic_path(path) as tmp:
        return _record_rrd(scene, ctx, findings, tmp, recording_id, prefix)


def _record_rrd(scene, ctx, findings, tmp, recording_id, prefix):
    import rerun as rr
    rec = rr.RecordingStream("urdf-lint", recording_id=recording_id, send_properties=False)
    rec.save(tmp)

    def log(entity, *a, **kw):
        rec.log(prefix + entity, *a, **kw)
    log("robot", rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
    paths, joint_paths = entity_paths(scene)
    # the kinematic tree twice: /robot (frames, axes, visuals, findings) and /collision
    # (collision geometry only, so that it toggles as one subtree)
    for root in ("robot", "collision"):
        for _parent, j, _child in scene.tree:
            T = origin_matrix(j)
            jp = root + joint_paths[j.get("name")][len("robot"):]
            log(jp, rr.Transform3D(translation=T[:3, 3], mat3x3=T[:3, :3]), static=True)
    for _parent, j, child in scene.tree:
        if j.get("type") not in ("fixed", None):
            ax = j.find("axis")
            axis = numbers(ax.get("xyz") if ax is not None else "1 0 0", 3) or [1, 0, 0]
            log(f"{paths[child]}/joint_axis",
                    rr.Arrows3D(origins=[[0, 0, 0]], vectors=[np.asarray(axis) * 0.1],
                                colors=[[250, 200, 0]], labels=[j.get("name") or ""]), static=True)
    for _link, p in paths.items():
        log(p, rr.TransformAxes3D(0.05), static=True)
    logged = 0
    for part in scene.parts:
        root = "robot" if part.kind == "visual" else "collision"
        base = f"{root}{paths[part.link][len('robot'):]}/{part.kind}/{part.index}"
        log(base, rr.Transform3D(translation=part.local[:3, 3], mat3x3=part.local[:3, :3]), static=True)
        got = part_mesh(part, ctx) if part.shape != "missing" else None
        if got is None:
            log(f"{base}/missing", rr.Boxes3D(half_sizes=[[0.03, 0.03, 0.03]], colors=[[230, 30, 30]],
                                                 labels=[part.problem or "missing geometry"]), static=True)
            continue
        v, f, fc = got
        rgba = [int(255 * x) for x in part.rgba]
        if part.kind == "collision":
            rgba = [80, 160, 255, 110]
        kwargs = {"vertex_positions": v.astype(np.float32), "triangle_indices": f.astype(np.uint32),
                  "albedo_factor": rgba}
        tex = part.params.get("texture") if part.kind == "visual" else None
        if tex is not None and len(tex[0]) == len(v):
            kwargs["vertex_texcoords"] = tex[0].astype(np.float32)
            kwargs["albedo_texture"] = tex[1]
            kwargs["albedo_factor"] = [255, 255, 255, 255]
        elif fc is not None and len(fc) == len(f) and part.kind == "visual":
            vc = np.zeros((len(v), 3))
            vc[f.reshape(-1)] = np.repeat(fc, 3, axis=0)
            kwargs["vertex_colors"] = (vc * 255).astype(np.uint8)
        log(f"{base}/mesh", rr.Mesh3D(**kwargs), static=True)
        logged += 1
    # findings, on the entity of the link or joint they concern
    levels = {"error": "ERROR", "warning": "WARN", "info": "INFO"}
    for n, fd in enumerate(findings):
        target = fd.target
        ent = "robot"
        if target and target[0] == "link" and target[1] in paths:
            ent = paths[target[1]]
        elif target and target[0] == "joint" and target[1] in joint_paths:
            ent = joint_paths[target[1]]
        text = f"{fd.code} {fd.message} ({os.path.basename(fd.file)}:{fd.line})"
        log(f"{ent}/findings/{n}", rr.TextLog(text, level=levels.get(fd.severity, "WARN")),
                static=True)
        log(f"{ent}/findings/{n}", rr.Points3D([[0, 0, 0]], radii=[0.01], colors=[[230, 30, 30]],
                                                  labels=[fd.code]), static=True)
    rec.flush()
    rec.disconnect()
    return {"meshes": logged}


def _import_rerun():
    try:
        import rerun  # noqa: F401
    except Exception:  # noqa: BLE001 - reported by render_model when it imports again
        pass


# -- orchestration -----------------------------------------------------------------------------
def snapshot_name(entry, args, base):
    from .locations import display_path
    rel = display_path(entry, base)
    stem = rel.replace(os.sep, "__")
    for ext in (".urdf.xacro", ".xacro", ".urdf"):
        if stem.endswith(ext):
            stem = stem[: -len(ext)]
    if args:
        stem += "__" + "_".join(f"{k}-{v}" for k, v in sorted(args.items()))
        digest = hashlib.blake2b(repr(sorted(args.items())).encode(), digest_size=4).hexdigest()
        stem = stem[:150] + "_" + digest
    return "".join(ch if ch.isalnum() or ch in "_-.@" else "_" for ch in stem)


def render_model(model, ctx, findings, out_dir, base, rrd=True):
    """Write <name>.png (and <name>.rrd); return a summary dict. Never raises for model problems."""
    os.makedirs(out_dir, exist_ok=True)
    importer = None
    if rrd and "rerun" not in sys.modules:
        # rerun's import (~0.5 s) overlaps with the PNG rasterization
        importer = threading.Thread(target=_import_rerun, daemon=True)
        importer.start()
    name = snapshot_name(model.entry, model.args, base)
    scene = build_scene(model, ctx)
    info = {"name": name, "png": os.path.join(out_dir, name + ".png"), "rrd": None, "problems": []}
    try:
        info.update(render_png(scene, ctx, info["png"], findings_count=len(findings)))
    except Exception as e:  # noqa: BLE001
        info["problems"].append(f"png: {type(e).__name__}: {e}")
        info["png"] = None
    if rrd:
        if importer is not None:
            importer.join()
        try:
            import rerun  # noqa: F401
        except ImportError:
            info["problems"].append("rrd: rerun-sdk is not installed (pip install 'urdf-lint[render]')")
        else:
            path = os.path.join(out_dir, name + ".rrd")
            try:
                info.update(record_rrd(scene, ctx, findings, path, recording_id=f"urdf-lint/{name}"))
                info["rrd"] = path
            except Exception as e:  # noqa: BLE001
                info["problems"].append(f"rrd: {type(e).__name__}: {e}")
    return info


def write_summary(result, out_dir):
    from collections import Counter
    from .locations import display_path
    from .report.escape import escape_markdown, escape_markdown_code
    lines = ["# urdf-lint snapshots", "",
             "| model | links | joints | meshes | errors | warnings | info |",
             "|---|---:|---:|---:|---:|---:|---:|"]
    images = []
    for m in result.models:
        c = Counter(f.severity for f in result.findings if m.label in f.models)
        label = escape_markdown(m.label)  # names are the description's: no HTML, no links
        lines.append(f"| `{escape_markdown_code(m.label)}` | {m.stats.get('links', '-')} | "
                     f"{m.stats.get('joints', '-')} | "
                     f"{m.stats.get('meshes', '-')} | {c['error']} | {c['warning']} | {c['info']} |")
        snap = m.snapshot or {}
        if snap.get("png"):
            images.append(f"### {label}\n\n![{label}]({os.path.relpath(snap['png'], out_dir)})\n")
            if snap.get("rrd"):
                images.append(f"Recording: `{os.path.relpath(snap['rrd'], out_dir)}` "
                              f"(open with `rerun {display_path(snap['rrd'])}`)\n")
    text = "\n".join(lines) + "\n\n" + "\n".join(images)
    path = os.path.join(out_dir, "summary.md")
    from .atomic import atomic_write
    atomic_write(path, text)
    return path
