"""The PNG of a snapshot: a z-buffer rasterization in numpy, anti-aliased with Pillow,
headless on a CPU and byte-identical from run to run; and the before/after/difference images of
``urdf-lint diff --render``, drawn with one framing.

Rasterization is deferred: the z-buffer keeps the nearest triangle of every pixel, then each
visible pixel is shaded once (its part's colour, or its texture sampled at the pixel's
interpolated UV). Back faces get a small depth bias, so a coincident back face never stripes the
front one. Silhouettes and part edges are darkened (lightened on dark parts), so a black robot
stays readable. A visual that is missing is replaced by the link's collision geometry, ghosted
and labelled with the link name; a thin skeleton joins the link origins.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from urdf_lint.render.scene import _transform, part_mesh

PNG_SIZE = (960, 720)           # the long side of a single view is PNG_SIZE[0]
CELL = 560                      # the long side of one view of a sheet
CAPTION_H = 24                  # the caption strip above the drawing
# ~500k triangles draw in about 1.5 s (single view; the corpus's biggest robot has ~170k),
# so the cap only guards against pathological meshes
MAX_TRIANGLES = 1_000_000
VIEW_NAMES = ("front", "side", "top", "3/4")

_SS = 2  # supersampling for anti-aliasing
_BACKGROUND = np.array([236, 238, 241])
_GHOST_RGB = np.array([0.62, 0.64, 0.68])
_SKELETON = (70, 72, 84)


# -- what is drawn ---------------------------------------------------------------------------
@dataclass
class Geometry:
    """What a PNG shows, in world coordinates: plain arrays, so a worker can compute it from
    the meshes it may read and the parent can draw several revisions with one framing."""
    name: str
    tris: list                 # per part: (faces, 3, 3) float array
    cols: list                 # per part: (faces, 3) rgb in 0..1
    wires: list                # world positions of placeholders for missing geometry
    link_pts: np.ndarray       # (links, 3) link origins
    links: int
    part_links: list = field(default_factory=list)   # the link of each entry of ``tris``
    wire_links: list = field(default_factory=list)   # the link of each entry of ``wires``
    uvs: list = field(default_factory=list)          # per part: (faces, 3, 2) or None
    texs: list = field(default_factory=list)         # per part: (h, w, 3) uint8 or None
    ghost: list = field(default_factory=list)        # per part: collision shown for a missing visual
    labels: list = field(default_factory=list)       # (link, world position) of each placeholder
    bones: np.ndarray = field(default_factory=lambda: np.zeros((0, 2, 3)))  # joint tree

    def __post_init__(self) -> None:
        n = len(self.tris)
        self.uvs = list(self.uvs) or [None] * n
        self.texs = list(self.texs) or [None] * n
        self.ghost = list(self.ghost) or [False] * n

    def only(self, links) -> "Geometry":
        """The parts of the given links in black (for highlight masks: a white part would be
        too close to the background to tell)."""
        keep = [i for i, lk in enumerate(self.part_links) if lk in links]
        wk = [i for i, lk in enumerate(self.wire_links) if lk in links]
        return Geometry(self.name, [self.tris[i] for i in keep],
                        [np.zeros_like(self.cols[i]) for i in keep],
                        [self.wires[i] for i in wk], self.link_pts, self.links,
                        [self.part_links[i] for i in keep], [self.wire_links[i] for i in wk],
                        [None] * len(keep), [None] * len(keep), [False] * len(keep))

    @property
    def placeholders(self) -> list:
        return sorted({lk for lk, _ in self.labels})


def scene_geometry(scene: Any, ctx: Any) -> Geometry:
    """The visual parts of ``scene``; a link whose visual cannot be drawn shows its collision
    geometry (ghosted) instead, or a red wire box when it has none."""
    visual: dict = {}
    collision: dict = {}
    for part in scene.parts:
        (visual if part.kind == "visual" else collision).setdefault(part.link, []).append(part)
    g = Geometry(scene.name, [], [], [], np.zeros((1, 3)), len(scene.links))
    g.uvs, g.texs, g.ghost = [], [], []

    def add(part, got, ghost) -> None:
        v, f, fc = got
        scale = part.params.get("scale") or (1, 1, 1)
        if np.prod(np.sign(np.asarray(scale, dtype=float))) < 0:  # a mirror flips the winding
            f = f[:, ::-1]
        vw = _transform(part.T, v).astype(np.float32)
        g.tris.append(vw[f])
        g.part_links.append(part.link)
        g.ghost.append(ghost)
        base = np.asarray(part.rgba[:3], dtype=float)
        if ghost:
            g.cols.append(np.tile(_GHOST_RGB, (len(f), 1)))
        else:
            g.cols.append(fc if fc is not None and len(fc) == len(f) else np.tile(base, (len(f), 1)))
        tex = None if ghost else part.params.get("texture")
        if tex is not None and len(tex[0]) == len(v):
            g.uvs.append(np.asarray(tex[0], dtype=np.float32)[f])
            g.texs.append(tex[1])
        else:
            g.uvs.append(None)
            g.texs.append(None)

    for link, parts in visual.items():
        missing = []
        for part in parts:
            got = part_mesh(part, ctx) if part.shape != "missing" else None
            if got is None:
                missing.append(part)
            else:
                add(part, got, False)
        if not missing:
            continue
        stand_in = False
        for part in collision.get(link, []):
            got = part_mesh(part, ctx) if part.shape != "missing" else None
            if got is not None:
                add(part, got, True)
                stand_in = True
        if stand_in:
            pts = np.concatenate([t.reshape(-1, 3) for t, lk, gh in
                                  zip(g.tris, g.part_links, g.ghost, strict=True) if lk == link and gh])
            g.labels.append((link, (pts.min(axis=0) + pts.max(axis=0)) / 2))
        else:
            for part in missing:
                g.wires.append(part.T[:3, 3].copy())
                g.wire_links.append(link)
            g.labels.append((link, missing[0].T[:3, 3].copy()))
    if scene.links:
        g.link_pts = np.array([T[:3, 3] for T in scene.links.values()])
    bones = [(scene.links[p][:3, 3], scene.links[c][:3, 3]) for p, _j, c in scene.tree
             if p in scene.links and c in scene.links]
    bones = [b for b in bones if np.linalg.norm(b[1] - b[0]) > 1e-9]
    g.bones = np.array(bones, dtype=float).reshape(-1, 2, 3)
    return g


# -- framing ---------------------------------------------------------------------------------
@dataclass
class View:
    """A camera for one snapshot view: its axes, centre and scale."""
    name: str
    center: np.ndarray
    right: np.ndarray
    up: np.ndarray
    fwd: np.ndarray            # into the screen (depth grows along it)
    view: np.ndarray           # towards the camera
    scale: float               # supersampled pixels per metre
    ox: float                  # supersampled pixel of the centre, inside the cell
    oy: float
    x0: int                    # the cell in the final image
    y0: int
    w: int
    h: int


@dataclass
class Frame:
    """The framing of one picture: one or four views, the image size and the placeholder box
    size. Before/after images of ``diff`` share one Frame."""
    views: list
    size: tuple
    box: float


_BOX_EDGES = ((0, 1), (0, 2), (0, 4), (1, 3), (1, 5), (2, 3), (2, 6), (3, 7), (4, 5), (4, 6),
              (5, 7), (6, 7))


def _box_corners(c, box):
    return np.array([[x, y, z] for x in (-box, box) for y in (-box, box) for z in (-box, box)]) + c


def view_axes(name: str, forward: str = "+x"):
    """(right, up, towards-camera) of a named view for a robot facing ``forward``."""
    f = np.array({"+x": (1, 0, 0), "-x": (-1, 0, 0), "+y": (0, 1, 0), "-y": (0, -1, 0)}[forward],
                 dtype=float)
    z = np.array([0, 0, 1.0])
    left = np.cross(z, f)
    if name == "top":
        return np.cross(f, z), f, z
    if name == "front":
        d = f
    elif name == "side":
        d = left
    else:  # 3/4: from the front left, 25 degrees up
        el, az = math.radians(25), math.radians(45)
        d = math.cos(el) * (math.cos(az) * f + math.sin(az) * left) + math.sin(el) * z
    right = np.cross(-d, z)
    right /= np.linalg.norm(right)
    up = np.cross(right, -d)
    return right, up, d


def _points(geoms):
    pts = []
    for g in geoms:
        pts += [np.asarray(t, dtype=float).reshape(-1, 3) for t in g.tris] + [g.link_pts]
    return pts


def frame_for(geoms, size=None, views="single", forward="+x") -> Frame:
    """One framing for all ``geoms``, fitted to their union: a 3/4 view (``single``) or a 2x2
    sheet of front, side, top and 3/4 views. The image is cropped to the robot's shape, so
    tall robots fill it."""
    pts = _points(geoms)
    allv = np.concatenate(pts)
    lo, hi = allv.min(axis=0), allv.max(axis=0)
    diag = float(np.linalg.norm(hi - lo)) or 0.2
    box = max(0.02, 0.04 * diag)
    wires = [c for g in geoms for c in g.wires]
    pts = pts + [_box_corners(c, box) for c in wires]
    q_all = np.concatenate(pts)
    lo, hi = q_all.min(axis=0), q_all.max(axis=0)
    center = (lo + hi) / 2
    names = ("3/4",) if views == "single" else VIEW_NAMES
    spans = []
    for name in names:
        right, up, d = view_axes(name, forward)
        q = q_all - center
        px, py = q @ right, q @ up
        spans.append((name, right, up, d, px.min(), px.max(), py.min(), py.max()))

    def aspect(s):
        return max(s[5] - s[4], 1e-6) / max(s[7] - s[6], 1e-6)
    if views == "single":
        a = min(2.0, max(0.5, aspect(spans[0])))
        long_side = size[0] if size else PNG_SIZE[0]
        cw, ch = (long_side, round(long_side / a)) if a >= 1 else (round(long_side * a), long_side)
        label_h = 0
        cells = [(0, CAPTION_H)]
        W, H = cw, ch + CAPTION_H
    else:
        a = math.exp(sum(math.log(aspect(s)) for s in spans) / len(spans))
        a = min(1.8, max(0.6, a))
        long_side = size[0] // 2 if size else CELL
        cw, ch = (long_side, round(long_side / a)) if a >= 1 else (round(long_side * a), long_side)
        label_h = 16
        ch += label_h
        cells = [(0, CAPTION_H), (cw, CAPTION_H), (0, CAPTION_H + ch), (cw, CAPTION_H + ch)]
        W, H = 2 * cw, 2 * ch + CAPTION_H
    out = []
    S = _SS
    for (name, right, up, d, x0, x1, y0, y1), (cx, cy) in zip(spans, cells, strict=True):
        avail_w, avail_h = cw * 0.92, (ch - label_h) * 0.92
        scale = S * min(avail_w / max(x1 - x0, 1e-6), avail_h / max(y1 - y0, 1e-6))
        ox = cw * S / 2 - scale * (x0 + x1) / 2
        oy = (label_h + (ch - label_h) / 2) * S + scale * (y0 + y1) / 2
        out.append(View(name, center, right, up, -d, d, scale, ox, oy, cx, cy, cw, ch))
    return Frame(out, (W, H), box)


# -- drawing ---------------------------------------------------------------------------------
def draw(g: Geometry, fr: Frame, annotate: bool = True):
    """The anti-aliased image of one geometry through one frame (no caption); without
    ``annotate``, the parts alone (no view names, triads, labels or skeleton)."""
    return draw_many({0: (g, annotate)}, fr, threads=1)[0]


def _prepare(g: Geometry):
    """All triangles of ``g`` in one array, with their part, colour, texture and ghost flag."""
    if not g.tris:
        return None
    T3 = np.concatenate([np.asarray(t, dtype=np.float64) for t in g.tris])
    part = np.concatenate([np.full(len(t), i, dtype=np.int32) for i, t in enumerate(g.tris)])
    C = np.concatenate([np.asarray(c, dtype=np.float64) for c in g.cols])
    n = np.cross(T3[:, 1] - T3[:, 0], T3[:, 2] - T3[:, 0])
    nn = np.linalg.norm(n, axis=1)
    ok = nn > 0
    if len(T3) > MAX_TRIANGLES:  # keep the largest triangles within the budget
        area = np.where(ok, nn, 0)
        keep = np.zeros(len(T3), dtype=bool)
        keep[np.argsort(-area, kind="stable")[:MAX_TRIANGLES]] = True
        ok &= keep
    idx = np.nonzero(ok)[0]
    uv = None
    if any(u is not None for u in g.uvs):
        uv = np.zeros((len(T3), 3, 2), dtype=np.float32)
        tex_id = np.full(len(T3), -1, dtype=np.int32)
        start = 0
        for i, t in enumerate(g.tris):
            if g.uvs[i] is not None and g.texs[i] is not None:
                uv[start:start + len(t)] = g.uvs[i]
                tex_id[start:start + len(t)] = i
            start += len(t)
        uv, tex_id = uv[idx], tex_id[idx]
    else:
        tex_id = None
    ghost = np.array(g.ghost, dtype=bool)[part[idx]] if g.ghost else np.zeros(len(idx), bool)
    return {"T": T3[idx], "n": n[idx] / nn[idx][:, None], "part": part[idx], "C": C[idx],
            "uv": uv, "tex": tex_id, "ghost": ghost}


def _project(v: View, p):
    q = np.asarray(p, dtype=float) - v.center
    return (v.ox + v.scale * (q @ v.right), v.oy - v.scale * (q @ v.up), q @ v.fwd)


def _draw_view(g: Geometry, solid, v: View, fr: Frame, annotate: bool = True):
    from PIL import Image, ImageDraw
    S = _SS
    Ws, Hs = v.w * S, v.h * S
    colour = np.tile(_BACKGROUND.astype(np.uint8), (Hs, Ws, 1))
    zbuf = np.full((Hs, Ws), np.inf)
    if solid is not None:
        X, Y, Z = _project(v, solid["T"].reshape(-1, 3))   # every corner, once per view
        solid = dict(solid, X=X.reshape(-1, 3), Y=Y.reshape(-1, 3), Z=Z.reshape(-1, 3))
        opaque = ~solid["ghost"]
        zbuf, ids = _raster_ids(solid, opaque, v, Hs, Ws)
        _shade(colour, ids, solid, v, g)
        _outline_edges(colour, ids, zbuf, solid["part"])
        if solid["ghost"].any():
            zg, gids = _raster_ids(solid, solid["ghost"], v, Hs, Ws)
            front = (gids >= 0) & (zg < zbuf)
            ghost_col = np.zeros_like(colour)
            _shade(ghost_col, gids, solid, v, g)
            mix = 0.55 * ghost_col[front] + 0.45 * colour[front]
            colour[front] = mix.clip(0, 255).astype(np.uint8)
            zero = np.full_like(gids, -1)
            _outline_edges(colour, np.where(front, gids, zero), np.where(front, zg, np.inf),
                           solid["part"], strength=0.35)
    if annotate and len(g.bones) and (g.labels or solid is None):  # holds a torn robot together
        _skeleton(colour, zbuf, g.bones, v)
    img = Image.fromarray(colour, "RGB")
    dr = ImageDraw.Draw(img)
    for c in g.wires:
        X, Y, _ = _project(v, _box_corners(c, fr.box))
        for a, b in _BOX_EDGES:
            dr.line([(X[a], Y[a]), (X[b], Y[b])], fill=(220, 30, 30), width=3 * S)
    img = img.resize((v.w, v.h), Image.Resampling.LANCZOS)
    if not annotate:
        return img
    dr = ImageDraw.Draw(img)
    if len(fr.views) > 1:
        dr.text((6, 2), v.name, fill=(90, 90, 100))
    if solid is None and not g.wires:   # nothing to draw: say so, and mark the link frames
        X, Y, _ = _project(v, g.link_pts)
        for x, y in zip(X / S, Y / S, strict=True):
            dr.ellipse((x - 3, y - 3, x + 3, y + 3), outline=_SKELETON, width=1)
        text = "(nothing to draw: no visual geometry)"
        box = dr.textbbox((0, 0), text)
        dr.text(((v.w - box[2]) / 2, v.h / 2 + 12), text, fill=(90, 90, 100))
    _triad(dr, v)
    taken: list = []
    for link, pos in g.labels:
        X, Y, _ = _project(v, np.asarray(pos, dtype=float)[None, :])
        x, y = float(X[0]) / S + 6, float(Y[0]) / S - 6
        box = dr.textbbox((x, y), link)
        for _ in range(12):  # step down past labels already placed
            hit = next((b for b in taken if box[0] < b[2] + 3 and b[0] < box[2] + 3
                        and box[1] < b[3] + 2 and b[1] < box[3] + 2), None)
            if hit is None:
                break
            y += hit[3] + 3 - box[1]
            box = dr.textbbox((x, y), link)
        taken.append(box)
        dr.rectangle((box[0] - 2, box[1] - 1, box[2] + 2, box[3] + 1), fill=(255, 255, 255),
                     outline=(150, 150, 160))
        dr.text((x, y), link, fill=(150, 20, 20))
    return img


def _raster_ids(solid, which, v: View, Hs, Ws):
    """(depth, triangle index) per supersampled pixel of the triangles selected by ``which``."""
    idx = np.nonzero(which)[0]
    zbuf = np.full((Hs, Ws), np.inf)
    ids = np.full((Hs, Ws), -1, dtype=np.int64)
    if not len(idx):
        return zbuf, ids
    X, Y, Z = solid["X"][idx], solid["Y"][idx], solid["Z"][idx]
    # back faces lose ties with front faces, and a coincident face of a later part loses to
    # the earlier one (no z-fighting speckle): tiny depth biases, far below any real gap
    back = solid["n"][idx] @ v.view < 0
    span = float(Z.max() - Z.min()) or 1.0
    bias = np.where(back, 2e-5, 0.0) + 1e-8 * np.minimum(solid["part"][idx], 1000)
    Z = Z + (bias * span)[:, None]
    raster_ids(zbuf, ids, X, Y, Z, idx)
    return zbuf, ids


def _shade(colour, ids, solid, v: View, g: Geometry) -> None:
    """Colour every covered pixel: its part's colour or its texture at the interpolated UV,
    times a two-sided diffuse term."""
    m = ids >= 0
    if not m.any():
        return
    light = v.view + 0.3 * v.right + 0.5 * v.up
    light /= np.linalg.norm(light)
    shade = 0.38 + 0.62 * np.abs(solid["n"] @ light)
    flat = (np.clip(solid["C"] * shade[:, None], 0, 1) * 255).astype(np.uint8)
    if solid["tex"] is None:
        colour[m] = flat[ids[m]]
        return
    t = ids[m]
    out = flat[t]
    tt = solid["tex"][t]
    has = tt >= 0
    if has.any():
        ys, xs = np.nonzero(m)
        ys, xs, tri = ys[has] + 0.5, xs[has] + 0.5, t[has]
        X, Y = solid["X"][tri], solid["Y"][tri]
        dx1, dx2 = X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]
        dy1, dy2 = Y[:, 1] - Y[:, 0], Y[:, 2] - Y[:, 0]
        den = dx1 * dy2 - dx2 * dy1
        den = np.where(np.abs(den) < 1e-12, 1e-12, den)
        l1 = np.clip(((xs - X[:, 0]) * dy2 - (ys - Y[:, 0]) * dx2) / den, 0, 1)
        l2 = np.clip(((ys - Y[:, 0]) * dx1 - (xs - X[:, 0]) * dy1) / den, 0, 1)
        l0 = np.clip(1 - l1 - l2, 0, 1)
        uvt = solid["uv"][tri]
        uv = (uvt[:, 0] * l0[:, None] + uvt[:, 1] * l1[:, None] + uvt[:, 2] * l2[:, None]) % 1.0
        sampled = np.zeros((len(tri), 3))
        for i in np.unique(tt[has]):
            arr = g.texs[int(i)]
            sel = tt[has] == i
            h, w = arr.shape[:2]
            px = np.clip((uv[sel, 0] * w).astype(np.int64), 0, w - 1)
            py = np.clip(((1.0 - uv[sel, 1]) * h).astype(np.int64), 0, h - 1)
            sampled[sel] = arr[py, px, :3] / 255.0
        out[has] = (np.clip(sampled * shade[tri][:, None], 0, 1) * 255).astype(np.uint8)
    colour[m] = out


def _outline_edges(colour, ids, zbuf, part, strength=0.6) -> None:
    """Darken silhouettes and part boundaries (lighten them on dark parts): a black robot on a
    dark background, or a white one on a light background, keeps its outline."""
    covered = ids >= 0
    if not covered.any():
        return
    key = np.where(covered, part[np.maximum(ids, 0)], -1)
    edge = np.zeros_like(covered)
    finite = np.where(covered, zbuf, 0.0)
    zr = float(finite.max() - finite.min()) if covered.any() else 1.0
    jump = 0.02 * (zr or 1.0)
    for axis in (0, 1):
        a = np.swapaxes(key, 0, axis)
        z = np.swapaxes(finite, 0, axis)
        d = (a[1:] != a[:-1]) | (np.abs(z[1:] - z[:-1]) > jump)
        e = np.swapaxes(edge, 0, axis)
        e[1:] |= d
        e[:-1] |= d
    # two supersampled pixels wide (one after anti-aliasing), on the object's side of a
    # silhouette
    edge[1:, :] |= edge[:-1, :]
    edge[:, 1:] |= edge[:, :-1]
    edge &= covered
    if not edge.any():
        return
    px = colour[edge].astype(float)
    lum = px @ np.array([0.299, 0.587, 0.114])
    dark = lum < 70
    px[~dark] *= 1 - strength
    px[dark] = px[dark] + (200 - px[dark]) * strength
    colour[edge] = px.clip(0, 255).astype(np.uint8)


def _skeleton(colour, zbuf, bones, v: View) -> None:
    """Thin lines between link origins along the joint tree, hidden where geometry is in
    front of them."""
    Hs, Ws = zbuf.shape
    a = np.asarray(bones[:, 0], dtype=float)
    b = np.asarray(bones[:, 1], dtype=float)
    ax, ay, az = _project(v, a)
    bx, by, bz = _project(v, b)
    n = np.maximum(2, np.ceil(np.hypot(bx - ax, by - ay) * 1.5)).astype(np.int64)
    k = np.repeat(np.arange(len(n)), n)
    s = (np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)) / np.repeat(n - 1, n)
    x = ax[k] + (bx[k] - ax[k]) * s
    y = ay[k] + (by[k] - ay[k]) * s
    z = az[k] + (bz[k] - az[k]) * s
    span = float(np.ptp(np.concatenate([az, bz]))) or 1.0
    for dx, dy in ((0, 0), (1, 0), (0, 1), (1, 1)):
        xi, yi = np.floor(x).astype(np.int64) + dx, np.floor(y).astype(np.int64) + dy
        ok = (xi >= 0) & (xi < Ws) & (yi >= 0) & (yi < Hs)
        xi, yi, zz = xi[ok], yi[ok], z[ok]
        vis = zz <= zbuf[yi, xi] + 1e-4 * span
        colour[yi[vis], xi[vis]] = _SKELETON


def _triad(dr, v: View) -> None:
    """A small x/y/z triad (red/green/blue) in the bottom left corner of a view."""
    cx, cy, L = 26, v.h - 22, 14
    dr.rounded_rectangle((4, cy - L - 10, cx + L + 12, v.h - 2), radius=4, fill=(250, 250, 252),
                         outline=(205, 207, 212))  # legible over the robot too
    axes = [(np.array([1.0, 0, 0]), (210, 40, 40), "x"), (np.array([0, 1.0, 0]), (30, 150, 40), "y"),
            (np.array([0, 0, 1.0]), (40, 70, 220), "z")]
    # the axis pointing most into the screen is drawn first
    for vec, col, name in sorted(axes, key=lambda t: -float(t[0] @ v.fwd)):
        ex, ey = cx + L * float(vec @ v.right), cy - L * float(vec @ v.up)
        dr.line([(cx, cy), (ex, ey)], fill=col, width=2)
        if math.hypot(ex - cx, ey - cy) > 4:
            dr.text((ex + (3 if ex >= cx else -8), ey - (10 if ey <= cy else 0)), name, fill=col)


# -- captions and files ----------------------------------------------------------------------
def caption(img, text) -> None:
    from PIL import ImageDraw
    ImageDraw.Draw(img).text((8, 6), text, fill=(40, 40, 40))


LEGEND_H = 18   # the strip at the bottom of the difference image that holds the legend


def legend(img) -> None:
    """The difference image's legend, in the bottom-left corner (``LEGEND_H`` rows)."""
    from PIL import ImageDraw
    d = ImageDraw.Draw(img)
    y = img.size[1] - LEGEND_H + 2
    d.rectangle((8, y + 2, 18, y + 12), fill=(230, 0, 160))
    d.rectangle((150, y + 2, 160, y + 12), outline=(30, 60, 200), width=2)
    d.text((22, y), "changed, now", fill=(40, 40, 40))
    d.text((164, y), "where it was", fill=(40, 40, 40))


def drawn_alike(a: "Geometry", b: "Geometry", link: str) -> bool:
    """Is ``link`` drawn the same in ``a`` and ``b`` (the same parts and placeholders)?"""
    def parts(g):
        return ([g.tris[i] for i, lk in enumerate(g.part_links) if lk == link],
                [g.cols[i] for i, lk in enumerate(g.part_links) if lk == link],
                [g.wires[i] for i, lk in enumerate(g.wire_links) if lk == link])
    for xs, ys in zip(parts(a), parts(b), strict=True):
        if len(xs) != len(ys) or not all(
                (x is None) == (y is None) and (x is None or np.array_equal(x, y))
                for x, y in zip(xs, ys, strict=True)):
            return False
    return True


def save_png(img, path) -> None:
    from urdf_lint.core import fsbound  # the snapshot folder, checked by the CLI (and Landlock here)
    with fsbound.temp_path(path, os.path.dirname(os.path.abspath(path)), ".png") as tmp:
        img.save(tmp, format="PNG", optimize=False)


def model_caption(name, links, placeholders, findings=None) -> str:
    text = f"{name or 'robot'}  ({links} links"
    if placeholders:
        text += f", {placeholders} without visual shown as placeholders"
    if findings is not None:
        text += f", {findings} finding{'s' if findings != 1 else ''}"
    return text + ")"


def render_image(scene, ctx, views="single", forward="+x"):
    """(uncaptioned image, facts) of one model: drawn in the worker, captioned by the parent
    once the run's findings are final."""
    g = scene_geometry(scene, ctx)
    img = draw(g, frame_for([g], views=views, forward=forward))
    return img, {"triangles": int(sum(len(t) for t in g.tris)),
                 "placeholders": len(g.placeholders), "links": len(scene.links)}


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
                changed_links=frozenset(), views="sheet", forward="+x", threads=None,
                unseen: str = "") -> dict:
    """``stem.before.png`` and ``stem.after.png`` with identical framing (byte-identical when
    nothing changed), and ``stem.diff.png`` highlighting ``changed_links``; ``unseen``: what
    changed that no picture shows (limits, masses, ...), said in the difference's caption.
    The views are drawn by ``threads`` threads (:func:`draw_many`)."""
    from PIL import Image
    geoms = [g for g in (before, after) if g is not None]
    fr = frame_for(geoms, views=views, forward=forward)
    asked = frozenset(changed_links)
    if before is not None and after is not None:
        # a link drawn alike on both sides (its mesh missing on both, a change no picture
        # shows) is not marked changed
        changed_links = frozenset(lk for lk in asked if not drawn_alike(before, after, lk))
    out: dict = {}
    blank = Image.new("RGB", fr.size, tuple(int(x) for x in _BACKGROUND))
    same = before is not None and after is not None and same_geometry(before, after)
    wanted: dict = {}
    for side, g in (("before", before), ("after", None if same else after)):
        if g is not None:
            wanted[side] = (g, True)
            if changed_links:   # where the changed links are drawn (no labels, skeleton, triads)
                wanted[side + ".mask"] = (g.only(changed_links), False)
    drawn = draw_many(wanted, fr, threads)
    if same:
        drawn["after"] = drawn["before"]
        if changed_links:
            drawn["after.mask"] = drawn["before.mask"]
    masks: dict = {}
    after_img = blank
    pngs: dict = {}
    for side, g in (("before", before), ("after", after)):
        if g is None:
            img = blank.copy()
            caption(img, "(no model)")
            masks[side] = np.zeros((fr.size[1], fr.size[0]), dtype=bool)
        else:
            img = drawn[side].copy()
            masks[side] = _mask(drawn[side + ".mask"]) if changed_links else \
                np.zeros((fr.size[1], fr.size[0]), dtype=bool)
            if side == "after":
                after_img = drawn[side]
            caption(img, model_caption(g.name, g.links, len(g.placeholders)))
        out[side] = f"{stem}.{side}.png"
        pngs[out[side]] = img
    from concurrent.futures import ThreadPoolExecutor
    # PNG encoding lets go of the GIL: the two pictures are encoded while the difference
    # image is made (the same picture twice is encoded once)
    with ThreadPoolExecutor(max_workers=2) as pool:
        saving = [pool.submit(_save_same, pngs)] if same else \
            [pool.submit(save_png, img, path) for path, img in pngs.items()]
        diff = difference_image(after_img, masks["before"], masks["after"])
        n = int((masks["before"] | masks["after"]).sum())
        shown = ", ".join(sorted(changed_links)[:6]) or ("nothing visible" if unseen
                                                          else "nothing")
        said = (f"changed: {shown}"
                + (f" and {len(changed_links) - 6} more" if len(changed_links) > 6 else "")
                + (" (no visible change)" if asked and not changed_links and not unseen
                   else "")
                + (f"; not drawn: {unseen}" if unseen else ""))
        caption(diff, said)
        legend(diff)
        saving.append(pool.submit(save_png, diff, f"{stem}.diff.png"))
        for f in saving:
            f.result()
    out["diff"], out["changed_pixels"], out["caption"] = f"{stem}.diff.png", n, said
    return out


def _save_same(pngs: dict) -> None:
    """Save path -> image for equal images: encoded once, written to every path."""
    import io
    from urdf_lint.core import fsbound
    buf = io.BytesIO()
    next(iter(pngs.values())).save(buf, format="PNG", optimize=False)
    for path in pngs:
        fsbound.write_bytes(path, buf.getvalue(), os.path.dirname(os.path.abspath(path)))


def draw_many(items: dict, fr: Frame, threads=None) -> dict:
    """name -> the image :func:`draw` gives, for ``items`` (name -> (geometry, annotate)).
    Every view is drawn on its own, by ``threads`` threads (default: two on a machine with
    two cores or more; numpy lets go of the GIL in the rasterizer's array operations), and
    pasted where :func:`draw` pastes it: the pixels are the same."""
    from PIL import Image
    solids = {name: _prepare(g) for name, (g, _annotate) in items.items()}
    tasks = [(name, i) for name in items for i in range(len(fr.views))]

    def one(task):
        name, i = task
        g, annotate = items[name]
        return _draw_view(g, solids[name], fr.views[i], fr, annotate)
    if threads is None:
        threads = 2 if (os.cpu_count() or 1) > 1 else 1
    if threads > 1 and len(tasks) > 1:
        from concurrent.futures import ThreadPoolExecutor
        with ThreadPoolExecutor(max_workers=threads) as pool:
            views = dict(zip(tasks, pool.map(one, tasks), strict=True))
    else:
        views = {t: one(t) for t in tasks}
    out = {}
    for name in items:
        img = Image.new("RGB", fr.size, tuple(int(x) for x in _BACKGROUND))
        for i, v in enumerate(fr.views):
            img.paste(views[(name, i)], (v.x0, v.y0))
        out[name] = img
    return out


def same_geometry(a: Geometry, b: Geometry) -> bool:
    """Would ``a`` and ``b`` draw the same picture (so it is drawn once)?"""
    def arrays(g):
        return [g.tris, g.cols, g.uvs, g.texs, g.wires]
    if (a.name, a.links, a.part_links, a.wire_links, a.ghost, [lk for lk, _ in a.labels]) != \
            (b.name, b.links, b.part_links, b.wire_links, b.ghost, [lk for lk, _ in b.labels]):
        return False
    for xs, ys in zip(arrays(a) + [[p for _, p in a.labels], [a.bones, a.link_pts]],
                      arrays(b) + [[p for _, p in b.labels], [b.bones, b.link_pts]], strict=True):
        if len(xs) != len(ys):
            return False
        for x, y in zip(xs, ys, strict=True):
            if (x is None) != (y is None) or (x is not None and not np.array_equal(x, y)):
                return False
    return True


# -- the rasterizer --------------------------------------------------------------------------
def _write_nearest(zbuf, ids, pix, z, t) -> None:
    """Depth-test samples (flat pixel index, depth, triangle) into the buffers; nearest wins,
    equal depths go to the later sample (numpy assigns repeated indices in order)."""
    if not len(pix):
        return
    flat_z = zbuf.reshape(-1)
    np.minimum.at(flat_z, pix, z)
    win = z <= flat_z[pix]
    ids.reshape(-1)[pix[win]] = t[win]


def raster_ids(zbuf, ids, X, Y, Z, tri_ids, pixels_per_batch=1 << 20) -> None:
    """Z-buffer triangles into ``zbuf``, writing ``tri_ids`` of the nearest triangle to ``ids``.

    Vectorized scanline rasterization: every (triangle, row) gets its covered x-span from the
    edges, spans expand to pixels, and depth is interpolated from the triangle's plane, so the
    cost follows the covered pixels, not bounding boxes. Batches bound the memory. Pixel
    centres are sampled; equal depths resolve by triangle order (deterministic).
    """
    Hs, Ws = zbuf.shape
    x0_, x1_, x2_ = X[:, 0], X[:, 1], X[:, 2]
    y0_, y1_, y2_ = Y[:, 0], Y[:, 1], Y[:, 2]
    den = (x1_ - x0_) * (y2_ - y0_) - (x2_ - x0_) * (y1_ - y0_)
    # (elementwise min/max of the three corners: much faster than reductions over axis 1)
    xmin, xmax = np.minimum(np.minimum(x0_, x1_), x2_), np.maximum(np.maximum(x0_, x1_), x2_)
    ymin, ymax = np.minimum(np.minimum(y0_, y1_), y2_), np.maximum(np.maximum(y0_, y1_), y2_)
    first, last = np.ceil(ymin - 0.5), np.floor(ymax - 0.5)
    # triangles that cover no pixel centre (tiny, or outside the view) cost nothing
    ok = (np.abs(den) > 1e-12) & (xmax >= 0) & (xmin < Ws) & (ymax >= 0) & (ymin < Hs) \
        & (first <= last)
    X, Y, Z, den, tri_ids = X[ok], Y[ok], Z[ok], den[ok], np.asarray(tri_ids)[ok]
    xmin, xmax, first, last = xmin[ok], xmax[ok], first[ok], last[ok]
    dz1, dz2 = Z[:, 1] - Z[:, 0], Z[:, 2] - Z[:, 0]
    dx1, dx2 = X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]
    dy1, dy2 = Y[:, 1] - Y[:, 0], Y[:, 2] - Y[:, 0]
    pa = (dz1 * dy2 - dz2 * dy1) / den
    pb = (dz2 * dx1 - dz1 * dx2) / den
    pc = Z[:, 0] - pa * X[:, 0] - pb * Y[:, 0]
    ys = np.clip(first, 0, Hs).astype(np.int64)        # first row
    ye = np.clip(last, -1, Hs - 1).astype(np.int64)    # last row
    rows = np.maximum(0, ye - ys + 1)
    width = np.clip(np.ceil(xmax) - np.floor(xmin) + 1, 1, Ws)
    cost = np.cumsum(rows * width)
    start = 0
    while start < len(X):
        stop = int(np.searchsorted(cost, (cost[start - 1] if start else 0) + pixels_per_batch,
                                   side="right"))
        stop = max(stop, start + 1)
        _scan(zbuf, ids, slice(start, stop), X, Y, ys, rows, pa, pb, pc, tri_ids, Ws)
        start = stop


def _scan(zbuf, ids, sl, X, Y, ys, rows, pa, pb, pc, tri_ids, Ws) -> None:
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
    _write_nearest(zbuf, ids, yy * Ws + xx, z, tri_ids[tt])
