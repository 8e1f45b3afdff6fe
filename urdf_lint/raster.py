"""The PNG of a snapshot: a z-buffer rasterization in numpy, anti-aliased with Pillow,
headless on a CPU and byte-identical from run to run; and the before/after/difference images of
``urdf-lint diff --render``, drawn with one framing.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .scene import _transform, part_mesh

PNG_SIZE = (960, 720)
MAX_TRIANGLES = 120_000


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
