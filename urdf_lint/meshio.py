"""Mesh readers for the facts the rules need (counts, bounds, finiteness, mass properties):
vertex and face arrays, without building a processed ``trimesh.Trimesh``.

* Binary STL is read with numpy straight from its 50-byte records, in chunks of
  ``STL_CHUNK_TRIANGLES`` (so a 5M-triangle file never needs gigabytes); ASCII STL with one
  solid is parsed like trimesh parses it (``np.fromstring`` of the ``vertex`` lines).
* Every other format (COLLADA, OBJ, ...) is loaded by ``trimesh.load_scene(process=False)`` and
  its instances are placed and stacked with numpy, which is what ``Scene.to_mesh`` computes
  without the copies, visual merging and array hashing it pays for.

Anything these fast paths do not recognise exactly (a binary STL whose length does not match
its header, an ASCII file with several solids) goes through trimesh as before, so the facts
are the same numbers trimesh gives.
"""
from __future__ import annotations

import os
from typing import Iterator

import numpy as np

STL_RECORD = np.dtype([("n", "<f4", (3,)), ("v", "<f4", (3, 3)), ("a", "<u2")])
STL_CHUNK_TRIANGLES = 1 << 20        # 50 MB of records per chunk


def binary_stl_triangles(path: str) -> int | None:
    """The triangle count of a well-formed binary STL (its size matches its header), else None
    (ASCII, or a file trimesh would try to read as ASCII)."""
    try:
        with open(path, "rb") as f:
            head = f.read(84)
            size = os.fstat(f.fileno()).st_size
    except OSError:
        return None
    if len(head) < 84:
        return None
    n = int(np.frombuffer(head, dtype="<u4", count=1, offset=80)[0])
    return n if size - 84 == n * STL_RECORD.itemsize else None


def iter_binary_stl(path: str, chunk: int | None = None) -> Iterator[np.ndarray]:
    """The triangles of a binary STL as float32 arrays of shape (k, 3, 3), ``chunk`` at a time."""
    chunk = chunk or STL_CHUNK_TRIANGLES
    with open(path, "rb") as f:
        f.seek(84)
        while True:
            rec = np.fromfile(f, dtype=STL_RECORD, count=chunk)
            if not len(rec):
                return
            yield rec["v"]


def read_ascii_stl(path: str):
    """(vertices float64 (n, 3), faces) of an ASCII STL holding exactly one solid, parsed as
    trimesh parses it; None for anything else (the caller lets trimesh decide)."""
    with open(path, "rb") as f:
        data = f.read()
    try:
        raw = data.decode("utf-8").strip().lower()
    except UnicodeDecodeError:
        return None
    start, end = raw.find("solid"), raw.find("endsolid")
    if start < 0 or end < 0 or start > end or raw.find("endsolid", end + 8) >= 0 \
            or raw.find("solid", end + 8) >= 0:
        return None
    parts = raw[start:end].split("vertex")
    try:
        v = np.fromstring(" ".join(line[: line.find("\n")] for line in parts[1:]), sep=" ",
                          dtype=np.float64)
    except ValueError:
        return None     # trimesh says what is wrong
    if len(v) < 3 or len(v) % 3 != 0:
        return None
    v = v.reshape((-1, 3))
    if len(v) % 3 != 0:
        return None     # trimesh would fail building the faces: let it say how
    return v, np.arange(len(v)).reshape((-1, 3))


def scene_arrays(scene):
    """(vertices, faces) of every Trimesh instance of a trimesh Scene placed by its transform,
    stacked in graph order: ``Scene.to_mesh()``'s numbers, without building the mesh."""
    from trimesh import Trimesh, transformations, util
    eye4, eye3 = np.eye(4), np.eye(3)
    verts, faces, offset = [], [], 0
    for node in scene.graph.nodes_geometry:
        transform, name = scene.graph[node]
        g = scene.geometry[name]
        if not isinstance(g, Trimesh):
            continue
        v = np.asarray(g.vertices, dtype=np.float64)
        f = np.asarray(g.faces, dtype=np.int64)
        matrix = np.asanyarray(transform, order="C", dtype=np.float64)
        if not util.allclose(matrix, eye4, 1e-8):
            v = transformations.transform_points(v, matrix=matrix)
            if not util.allclose(matrix[:3, :3], eye3, atol=1e-6) and \
                    transformations.flips_winding(matrix):
                f = np.fliplr(f)
        verts.append(v)
        if len(f):
            faces.append(f + offset)
        offset += len(v)
    v = np.vstack(verts) if verts else np.zeros((0, 3))
    f = np.vstack(faces).astype(np.int64) if faces else np.zeros((0, 3), dtype=np.int64)
    return v.reshape((-1, 3)), f.reshape((-1, 3))


def scale_points(v, unit: float):
    """``Trimesh.apply_scale(unit)`` on vertices (the same arithmetic)."""
    from trimesh import transformations
    return transformations.transform_points(v, matrix=transformations.scale_and_translate(
        scale=unit))


# -- mass properties over chunks ---------------------------------------------------------------
_DIVISORS = np.array([6, 24, 24, 24, 60, 60, 60, 120, 120, 120], dtype=np.float64)


def volume_integrals(tris) -> np.ndarray:
    """The 10 volume integrals (1, x, y, z, x², y², z², xy, yz, zx) of a closed surface's
    triangles (trimesh.triangles.mass_properties' formulas); additive over chunks."""
    tris = np.asarray(tris, dtype=np.float64)
    crosses = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    p0, p1, p2 = tris[:, 0, :], tris[:, 1, :], tris[:, 2, :]
    f1 = p0 + p1 + p2
    f2 = p0 ** 2 + p1 ** 2 + p0 * p1 + p2 * f1
    f3 = p0 ** 3 + p0 ** 2 * p1 + p0 * p1 ** 2 + p1 ** 3 + p2 * f2
    g0, g1, g2 = f2 + (p0 + f1) * p0, f2 + (p1 + f1) * p1, f2 + (p2 + f1) * p2
    out = np.zeros(10)
    out[0] = (crosses[:, 0] * f1[:, 0]).sum()
    out[1:4] = (crosses * f2).sum(axis=0)
    out[4:7] = (crosses * f3).sum(axis=0)
    for i in range(3):
        j = (i + 1) % 3
        out[i + 7] = (crosses[:, i] * (p0[:, j] * g0[:, i] + p1[:, j] * g1[:, i]
                                       + p2[:, j] * g2[:, i])).sum()
    return out / _DIVISORS


def moments(integrated) -> tuple[float, np.ndarray, np.ndarray]:
    """(volume, first moment ∫r dV, second moment ∫r rᵀ dV) from summed integrals."""
    vol = float(integrated[0])
    first = np.asarray(integrated[1:4], dtype=float)
    xx, yy, zz, xy, yz, zx = (float(x) for x in integrated[4:10])
    second = np.array([[xx, xy, zx], [xy, yy, yz], [zx, yz, zz]])
    return vol, first, second


def vertex_keys(tris) -> np.ndarray:
    """One int64 per vertex of (k, 3, 3) triangles: the vertex rounded to 8 decimals (what
    ``trimesh.grouping.unique_rows(digits=8)`` merges), packed by a 64-bit mix. Used to test
    closedness of meshes too large for ``unique_rows``."""
    q = np.round(np.asarray(tris, dtype=np.float64).reshape(-1, 3) * 1e8)
    q = np.nan_to_num(q, nan=0.0, posinf=0.0, neginf=0.0)
    q = np.clip(q, -(2.0 ** 62), 2.0 ** 62).astype(np.int64).view(np.uint64)
    with np.errstate(over="ignore"):
        k = q[:, 0] * np.uint64(0x9E3779B97F4A7C15)
        k ^= (k >> np.uint64(29)) + q[:, 1] * np.uint64(0xBF58476D1CE4E5B9)
        k ^= (k >> np.uint64(31)) + q[:, 2] * np.uint64(0x94D049BB133111EB)
    return k.view(np.int64)


def edge_codes(tris):
    """(directed edge codes, their reverses) of the non-degenerate triangles of a (k, 3, 3)
    chunk: one int64 per edge from the two ends' :func:`vertex_keys`. A closed, consistently
    wound surface has every code once and the reverses are the same set."""
    k = vertex_keys(tris).view(np.uint64).reshape(-1, 3)
    k = k[(k[:, 0] != k[:, 1]) & (k[:, 1] != k[:, 2]) & (k[:, 0] != k[:, 2])]
    a, b = k.reshape(-1), np.roll(k, -1, axis=1).reshape(-1)
    with np.errstate(over="ignore"):
        code = (a * np.uint64(0xC2B2AE3D27D4EB4F)) ^ (b * np.uint64(0x165667B19E3779F9) +
                                                      np.uint64(0x27D4EB2F165667C5))
        rev = (b * np.uint64(0xC2B2AE3D27D4EB4F)) ^ (a * np.uint64(0x165667B19E3779F9) +
                                                     np.uint64(0x27D4EB2F165667C5))
    return code.view(np.int64), rev.view(np.int64)
