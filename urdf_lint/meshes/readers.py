"""Mesh readers for the facts the rules need (counts, bounds, finiteness, mass properties):
vertex and face arrays, without building a processed ``trimesh.Trimesh``.

* Binary STL is read with numpy straight from its 50-byte records, in chunks of
  ``STL_CHUNK_TRIANGLES`` (so a 5M-triangle file never needs gigabytes); ASCII STL with one
  solid is parsed like trimesh parses it (``np.fromstring`` of the ``vertex`` lines).
* COLLADA is read with lxml alone (:func:`collada_arrays_lean`: the ``<float_array>``,
  ``<p>``, ``<input>`` and node transforms parsed straight into numpy, as pycollada parses
  them) or, for what that reader does not vouch for (textures, strips, node instances...), by
  pycollada, and assembled, placed and merged exactly as trimesh's loader and scene would
  (:func:`collada_arrays`), without importing trimesh or decoding textures. A mesh's facts
  need only its bounds: :func:`collada_bounds` gives those of the merged vertices without
  merging them (grouping, as the merge does, only corners a hair apart at an extreme).
* A plain Wavefront OBJ is split by material, unmerged by texture and normal references and
  its quads split exactly as trimesh's loader does (:func:`obj_arrays`), without trimesh.
* Every other format and any COLLADA or OBJ file the readers cannot vouch for is loaded by
  ``trimesh.load_scene(process=False)`` and its instances are placed and stacked with numpy,
  which is what ``Scene.to_mesh`` computes without the copies, visual merging and array
  hashing it pays for.
* Mass properties and closedness use trimesh's formulas and grouping, copied to the bit
  (:func:`mass_properties`, :func:`merged_ids`), so STL, COLLADA and OBJ facts need no
  trimesh.

Anything these fast paths do not recognise exactly (a binary STL whose length does not match
its header, an ASCII file with several solids, an OBJ with negative indices) goes through
trimesh as before, so the facts are the same numbers trimesh gives.
"""
from __future__ import annotations

import re
from typing import Any, Iterator

import numpy as np

from urdf_lint.core import fsbound

from urdf_lint.core import lazy

# pycollada imports Pillow (~14 ms) at start-up for the images of a document, which urdf-lint
# never decodes (the texture scan reads their names): loaded on first use, if ever
lazy.defer("PIL.Image")

# vertices and faces of a mesh; a part of a scene: (vertices, faces) and its 4x4 placement
Arrays = tuple[np.ndarray, np.ndarray]
Part = tuple[Arrays, np.ndarray]
# an XML element or a pycollada object (neither library ships type information here)
Node = Any

STL_RECORD = np.dtype([("n", "<f4", (3,)), ("v", "<f4", (3, 3)), ("a", "<u2")])
STL_CHUNK_TRIANGLES = 1 << 20        # 50 MB of records per chunk
MAX_MESH_READ = 1 << 30              # a mesh read whole (meshes.MAX_MESH_BYTES)


def binary_stl_triangles(path: str) -> int | None:
    """The triangle count of a well-formed binary STL (its size matches its header), else None
    (ASCII, or a file trimesh would try to read as ASCII)."""
    try:
        with fsbound.open_regular(path) as (f, st):
            head = f.read(84)
            size = st.st_size
    except OSError:
        return None
    if len(head) < 84:
        return None
    n = int(np.frombuffer(head, dtype="<u4", count=1, offset=80)[0])
    return n if size - 84 == n * STL_RECORD.itemsize else None


def iter_binary_stl(path: str, chunk: int | None = None,
                    data: bytes | None = None) -> Iterator[np.ndarray]:
    """The triangles of a binary STL as float32 arrays of shape (k, 3, 3), ``chunk`` at a time
    (from ``data``, the file's bytes, when the caller holds them)."""
    chunk = chunk or STL_CHUNK_TRIANGLES
    if data is not None:
        rec = np.frombuffer(data, dtype=STL_RECORD, offset=84,
                            count=(len(data) - 84) // STL_RECORD.itemsize)
        for i in range(0, len(rec), chunk):
            yield rec["v"][i:i + chunk]
        return
    with fsbound.open_regular(path) as (f, _):
        f.seek(84)
        while True:
            rec = np.fromfile(f, dtype=STL_RECORD, count=chunk)
            if not len(rec):
                return
            yield rec["v"]


def bounds(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(min, max) per column of (n, 3) points: NaN where a column holds a NaN, like
    ``points.min(axis=0)``, but on a transposed copy (a reduction along the long axis: 20x
    faster than along the first axis of three columns)."""
    t = np.asarray(points).T.copy()
    return t.min(axis=1), t.max(axis=1)


def triangle_bounds(tris: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`bounds` of the corners of (k, 3, 3) triangles (a binary STL's records, 50 bytes
    apart): each triangle's nine numbers are one row, so a single transposed copy gathers
    them (``tris.reshape(-1, 3)`` of the records copied them once more, for 40% of the time),
    and the three corners' minima are then compared. The same values: min and max are
    exact, and a NaN or infinity stays in its column."""
    t = np.asarray(tris).reshape(len(tris), 9).T.copy()
    lo: np.ndarray = t.min(axis=1).reshape(3, 3).min(axis=0)
    hi: np.ndarray = t.max(axis=1).reshape(3, 3).max(axis=0)
    return lo, hi


def read_ascii_stl(path: str) -> Arrays | None:
    """(vertices float64 (n, 3), faces) of an ASCII STL holding exactly one solid, parsed as
    trimesh parses it; None for anything else (the caller lets trimesh decide)."""
    data = fsbound.read_bytes(path, max_bytes=MAX_MESH_READ)
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


def scene_arrays(scene: Node) -> Arrays:
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
                    transformations.flips_winding(matrix):  # type: ignore[no-untyped-call]  # trimesh's, unannotated
                f = np.fliplr(f)
        verts.append(v)
        if len(f):
            faces.append(f + offset)
        offset += len(v)
    v = np.vstack(verts) if verts else np.zeros((0, 3))
    f = np.vstack(faces).astype(np.int64) if faces else np.zeros((0, 3), dtype=np.int64)
    return v.reshape((-1, 3)), f.reshape((-1, 3))


def scale_points(v: np.ndarray, unit: float) -> np.ndarray:
    """``Trimesh.apply_scale(unit)`` on vertices: :func:`transform_points` by
    ``trimesh.transformations.scale_and_translate(scale=unit)`` (the same arithmetic)."""
    m = np.eye(4)
    if np.any(unit != 1):
        m[:3, :3] *= unit
    return transform_points(v, m)


# -- mass properties over chunks ---------------------------------------------------------------
# Each triangle (a, b, c) of a closed surface bounds a signed tetrahedron with an apex (the
# origin below: the triangles are given relative to it); the volume integrals of the surface
# are those of its tetrahedra, summed. With d = a . (b x c) and s = a + b + c: volume d/6,
# first moment d s/24, second moment d (a aT + b bT + c cT + s sT)/120 (the divergence
# theorem gives the same sums; this form takes a fraction of the operations).
_DIVISORS = np.array([6, 24, 24, 24, 120, 120, 120, 120, 120, 120], dtype=np.float64)
_PAIRS = ((0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (2, 0))   # xx yy zz xy yz zx


_CHUNK = 1 << 15      # triangles per block: the temporaries of a block stay in the CPU's cache


def _block_sums(T: np.ndarray, out: np.ndarray) -> None:
    """Add the 10 undivided integrals (1, x, y, z, x², y², z², xy, yz, zx) of one block ``T``
    (3 vertices, 3 coordinates, m triangles; contiguous rows) to ``out``."""
    a, b, c = T[0], T[1], T[2]
    d = a[0] * (b[1] * c[2] - b[2] * c[1])
    d += a[1] * (b[2] * c[0] - b[0] * c[2])
    d += a[2] * (b[0] * c[1] - b[1] * c[0])
    s = a + b
    s += c
    out[0] += d.sum()
    for i in range(3):
        out[1 + i] += (s[i] * d).sum()
    for k, (i, j) in enumerate(_PAIRS):
        m = a[i] * a[j]
        m += b[i] * b[j]
        m += c[i] * c[j]
        m += s[i] * s[j]
        m *= d
        out[4 + k] += m.sum()


def volume_integrals(tris: np.ndarray, about: np.ndarray | None = None) -> np.ndarray:
    """The 10 volume integrals (1, x, y, z, x², y², z², xy, yz, zx) of a closed surface of
    (n, 3, 3) triangles, summed block by block (on coordinate rows: every operation on
    contiguous memory). Each triangle's tetrahedron has its apex at ``about`` (default: the
    first vertex), and the sums are moved to the origin: a closed surface's integrals do not
    depend on the apex, an open chunk's do, so the chunks of one surface take one apex and
    their sums add up (:func:`moments` turns them into volume and moments). Equal to
    ``trimesh.triangles.mass_properties``' integrals within rounding, and closer for a part
    far from its origin (its formulas also take about ten times the time: ``x ** 3`` is a
    ``pow`` call per element)."""
    t = np.asarray(tris, dtype=np.float64)
    out = np.zeros(10)
    if not len(t):
        return out
    # about one of its vertices: a part far from its origin (a small part in an assembly's
    # frame) keeps its precision (the products of absolute coordinates would cancel)
    c = t[0, 0].copy() if about is None else np.asarray(about, dtype=np.float64)
    for s in range(0, len(t), _CHUNK):
        _block_sums(np.ascontiguousarray((t[s:s + _CHUNK] - c).transpose(1, 2, 0)), out)
    out /= _DIVISORS
    return _moved(out, c)


def _moved(integrals: np.ndarray, c: np.ndarray) -> np.ndarray:
    """The 10 integrals of a body given about point ``c``, about the origin instead
    (r = r' + c: ∫x = ∫x' + V c, ∫x y = ∫x'y' + c_y ∫x' + c_x ∫y' + V c_x c_y)."""
    vol, first = integrals[0], integrals[1:4].copy()
    out: np.ndarray = integrals.copy()
    out[1:4] = first + vol * c
    for k, (i, j) in enumerate(_PAIRS):
        out[4 + k] = integrals[4 + k] + c[j] * first[i] + c[i] * first[j] + vol * c[i] * c[j]
    return out


def mass_properties(triangles: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    """(volume, center of mass, inertia about it) of closed triangles at density 1:
    ``trimesh.triangles.mass_properties``' results (within rounding), without importing
    trimesh."""
    t = np.asanyarray(triangles, dtype=np.float64)
    if t.ndim != 3 or t.shape[1:] != (3, 3):
        raise ValueError("Triangles must be (n, 3, 3)!")
    integrated = volume_integrals(t)
    volume = integrated[0]
    com = integrated[1:4] / volume
    inertia = np.zeros((3, 3))
    inertia[0, 0] = integrated[5] + integrated[6] - (volume * (com[[1, 2]] ** 2).sum())
    inertia[1, 1] = integrated[4] + integrated[6] - (volume * (com[[0, 2]] ** 2).sum())
    inertia[2, 2] = integrated[4] + integrated[5] - (volume * (com[[0, 1]] ** 2).sum())
    inertia[0, 1] = -(integrated[7] - (volume * np.prod(com[[0, 1]])))
    inertia[1, 2] = -(integrated[8] - (volume * np.prod(com[[1, 2]])))
    inertia[0, 2] = -(integrated[9] - (volume * np.prod(com[[0, 2]])))
    inertia[2, 0] = inertia[0, 2]
    inertia[2, 1] = inertia[1, 2]
    inertia[1, 0] = inertia[0, 1]
    return volume, com, inertia * 1.0


def merged_ids(points: np.ndarray) -> np.ndarray:
    """One id per point, equal for points equal to 8 decimals (the grouping of
    ``trimesh.grouping.unique_rows(points, digits=8)``: its rounding, any injective row key)."""
    q = np.ascontiguousarray(np.round((np.asarray(points, dtype=np.float64) * 10 ** 8) - 1e-6)
                             .astype(np.int64))
    return first_of_equal_rows(q)[1]


def moments(integrated: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    """(volume, first moment ∫r dV, second moment ∫r rᵀ dV) from summed integrals."""
    vol = float(integrated[0])
    first = np.asarray(integrated[1:4], dtype=float)
    xx, yy, zz, xy, yz, zx = (float(x) for x in integrated[4:10])
    second = np.array([[xx, xy, zx], [xy, yy, yz], [zx, yz, zz]])
    return vol, first, second


_MIX = (0x9E3779B97F4A7C15, 0xBF58476D1CE4E5B9, 0x94D049BB133111EB, 0xC2B2AE3D27D4EB4F,
        0x165667B19E3779F9, 0x27D4EB2F165667C5, 0xD6E8FEB86659FD93, 0xFF51AFD7ED558CCD)


def row_mix(rows: np.ndarray) -> np.ndarray:
    """One 64-bit mix (uint64) per row of an (n, k) int64 array: equal rows, equal mixes."""
    u = np.ascontiguousarray(rows, dtype=np.int64).view(np.uint64)
    h = np.zeros(len(u), dtype=np.uint64)
    with np.errstate(over="ignore"):
        for c in range(u.shape[1]):
            h ^= h >> np.uint64(29)
            h += u[:, c] * np.uint64(_MIX[c % len(_MIX)])
    return h


def first_of_equal_rows(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(index of the first occurrence of each distinct row, the distinct row of every row) of
    an (n, k) int64 array, as ``np.unique(return_index, return_inverse)`` gives them for the
    rows (distinct rows in another order: callers sort by first occurrence, or only compare).
    Grouped on :func:`row_mix`, several times faster than comparing the rows as bytes; every
    group is checked to hold one row only, else the rows are compared whole."""
    index, inverse = unique_first(row_mix(rows))
    first = index[inverse]          # the first row equal to each row, if no two mixes collide
    if not all((col.take(first) == col).all() for col in rows.T):   # (column by column:
        # 1-d takes, 3x faster than taking whole rows) two rows share a mix: compare whole rows
        whole = rows.view(np.dtype((np.void, rows.dtype.itemsize * rows.shape[1]))).reshape(-1)
        _, index, inverse = np.unique(whole, return_index=True, return_inverse=True)
        inverse = inverse.reshape(-1)
    return index, inverse


def unique_first(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(index of the first occurrence of each distinct key, the distinct key of every key) of
    a 1-d array: ``np.unique(keys, return_index=True, return_inverse=True)[1:]``, the same
    arrays, from one sort (``np.unique`` sorts stably for its first occurrences: a merge sort,
    2-3x slower) and the least position of each run of equal keys. The sort is
    :func:`_packed_order` for mixes (uint64), else an unstable argsort."""
    keys = np.asarray(keys).reshape(-1)
    if not len(keys):
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    packed = keys.dtype == np.uint64 and len(keys) <= 1 << _POSITION_BITS
    got = _packed_order(keys) if packed else None
    if got is None:
        order = np.argsort(keys)
        ordered = keys[order]
    else:
        order, ordered = got
    starts = np.empty(len(keys), dtype=bool)
    starts[0] = True
    np.not_equal(ordered[1:], ordered[:-1], out=starts[1:])
    first = np.flatnonzero(starts)
    inverse = np.empty(len(keys), dtype=np.int64)
    inverse[order] = np.cumsum(starts) - 1
    return np.minimum.reduceat(order, first).astype(np.int64), inverse


_POSITION_BITS = 24


def _packed_order(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """(a stable argsort of uint64 ``keys`` (at most 2**24), the keys in that order) from one
    plain sort, 3-4x faster than ``argsort``: each key's high 40 bits with its position in
    the low 24, sorted. None when two different keys share their high bits (the caller then
    argsorts): the order groups equal keys only if equal high bits mean equal keys."""
    low = np.uint64((1 << _POSITION_BITS) - 1)
    packed = keys & ~low
    packed |= np.arange(len(keys), dtype=np.uint64)
    packed.sort()
    order = (packed & low).astype(np.int64)
    high = packed >> np.uint64(_POSITION_BITS)
    ordered = keys[order]
    if ((high[1:] == high[:-1]) & (ordered[1:] != ordered[:-1])).any():
        return None
    return order, ordered


def vertex_keys(tris: np.ndarray) -> np.ndarray:
    """One int64 per vertex of (k, 3, 3) triangles: the vertex rounded to 8 decimals (what
    ``trimesh.grouping.unique_rows(digits=8)`` merges), packed by :func:`row_mix`. Used to test
    closedness of meshes too large for ``unique_rows``."""
    q = np.round(np.asarray(tris, dtype=np.float64).reshape(-1, 3) * 1e8)
    q = np.nan_to_num(q, nan=0.0, posinf=0.0, neginf=0.0)
    q = np.clip(q, -(2.0 ** 62), 2.0 ** 62).astype(np.int64)
    return row_mix(q).view(np.int64)


def edge_codes(tris: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
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


# -- COLLADA without trimesh -------------------------------------------------------------------
_EYE4 = np.eye(4)
_EYE3 = np.eye(3)
MERGE_DIGITS = 8        # trimesh's tol.merge (1e-8) as decimal digits
NORMAL_DIGITS = 2       # trimesh.grouping.merge_vertices' digits_norm
UV_DIGITS = 4           # ... and digits_uv


def collada_arrays(data: bytes, lean: bool = True) -> Arrays | None:
    """(vertices float64 (n, 3), faces int64 (m, 3)) of a COLLADA document before its unit:
    the numbers ``trimesh.load_scene(process=False)`` and :func:`scene_arrays` give, without
    importing trimesh, decoding textures or building materials.

    The document is read by pycollada (trimesh's parser, with the errors trimesh ignores) and
    assembled as ``trimesh.exchange.dae`` assembles it: every triangle set (a polylist
    fanned) of every ``<instance_geometry>`` is one mesh with three vertices per triangle,
    placed by the product of its nodes' matrices. Each mesh is then processed like the
    ``Trimesh`` trimesh builds for it (``load_scene`` does not pass ``process=False`` on to
    the meshes of a scene): vertices equal to 8 decimals, with their UV (4 decimals, when the
    set has a bound material) and normal (2 decimals), merged into the first of them.

    None whenever trimesh might do otherwise: a geometry lost to a broken reference (fewer
    sets than ``<instance_geometry>`` elements), an empty set, a non-finite vertex, vertex
    colours, a material trimesh cannot convert, an index out of range, any error. The caller
    then loads the file through trimesh, as before. Not ``lean``: pycollada reads it (the
    lean reader left it to pycollada already)."""
    got = collada_arrays_lean(data) if lean else None   # one lxml parse, when it can
    if got is not None:
        return got[0], got[1]
    import io
    import collada
    from collada import common
    ignore = [common.DaeError, common.DaeIncompleteError, common.DaeMalformedError,
              common.DaeBrokenRefError, common.DaeUnsupportedError]
    try:
        c = collada.Collada(io.BytesIO(data), ignore=ignore)
        if c.scene is None or not all(_plain_effect(m.effect) for m in c.materials):
            return None
        materials = {m.id for m in c.materials}
        parts: list[Part] = []
        for node in c.scene.nodes:
            if not _collada_node(node, _EYE4, parts, materials):
                return None
        want = data.count(b"<instance_geometry")
        if parts and len(parts) < want:   # (a mesh of lines alone gives no part, in trimesh too)
            from lxml import etree
            want -= _line_only_instances(etree.fromstring(data, etree.XMLParser(
                resolve_entities=False, no_network=True, load_dtd=False, huge_tree=True)))
        if not parts or len(parts) < want:
            return None
        return _assemble(parts)
    except Exception:  # noqa: BLE001 - trimesh decides (and says what is wrong)
        return None


def _assemble(parts: list[Part]) -> Arrays | None:
    """(vertices, faces) of the merged triangle sets ``parts`` ([((v, f), matrix)]) placed by
    their matrices and stacked, as trimesh's scene does (a mirroring matrix flips the
    winding); None where trimesh's scene graph would refuse a matrix."""
    verts, faces, offset = [], [], 0
    for (v, f), matrix in parts:
        placing = _placement(matrix)
        if placing is None:
            return None
        matrix, moves = placing
        if moves:
            v = transform_points(v, matrix)
            if not _allclose(matrix[:3, :3], _EYE3, 1e-6) and \
                    np.linalg.det(matrix[:3, :3]) < 0.0:
                f = np.fliplr(f)
        verts.append(v)
        faces.append(f + offset)
        offset += len(v)
    return np.vstack(verts).reshape((-1, 3)), np.vstack(faces).astype(np.int64).reshape((-1, 3))


def _placement(matrix: np.ndarray) -> tuple[np.ndarray, bool] | None:
    """(the matrix trimesh's scene graph places a set by, whether it moves it at all), or
    None where that graph would refuse the matrix."""
    rigid = _fix_rigid(np.array(matrix, dtype=np.float64))
    return None if rigid is None else (rigid, not _allclose(rigid, _EYE4, 1e-8))


# -- Wavefront OBJ without trimesh ------------------------------------------------------------
# a face reference's forms: (pattern, numbers per reference)
_OBJ_FORMS = {"v": (r"\d+", 1), "v/t": (r"\d+/\d+", 2), "v//n": (r"\d+//\d+", 2),
              "v/t/n": (r"\d+/\d+/\d+", 3)}


def _obj_line_check(form: str, refs: int) -> re.Pattern[str]:
    """A line no plain OBJ of one face form holds (searched after each newline)."""
    num = r"[-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?"   # (one way to match: linear)
    face = " ".join([_OBJ_FORMS[form][0]] * refs)
    ok = (rf"#[^\n]*|v {num} {num} {num}|vt {num} {num}(?: {num})?|vn {num} {num} {num}"
          rf"|f {face}|usemtl [^\s#][^\n]*|mtllib [^\n]*|[ogs] [^\n]*|")
    return re.compile(rf"\n(?!(?:{ok})(?:\n|\Z))")


_OBJ_ROWS = re.compile(r"\nv ([^\n]*)")
_OBJ_FACES = re.compile(r"\nf ([^\n]*)")


def obj_arrays(data: bytes) -> Arrays | None:
    """(vertices float64 (n, 3), faces int64 (m, 3)) of a Wavefront OBJ file: the numbers
    ``trimesh.load_scene(process=False)`` and :func:`scene_arrays` give, without trimesh.

    trimesh (``exchange.obj.load_obj``, default arguments) groups the faces by ``usemtl``
    material, in order of first use, and builds one mesh per material, the last used first.
    Each mesh keeps one vertex per distinct (position, texture, normal) reference of its faces
    (``visual.texture.unmerge_faces``: rows ordered by their packed key, then by position
    index) or, for faces with neither, the positions its faces use; quads are split into
    (0, 1, 2) then, after all of them, (2, 3, 0).

    Only plain files are read here: ``v``/``vt``/``vn`` rows of 3 (2-3) numbers, faces of one
    form (``v``, ``v/t``, ``v//n``, ``v/t/n``) with 3 or 4 positive references that are in
    range, ``usemtl``, ``mtllib``, ``o``, ``g``, ``s`` and comments, UTF-8, ``\n`` or ``\r\n``
    line ends. Anything else (negative or out-of-range indices, mixed face forms, polygons,
    vertex colours, line continuations, no face) gives None: the caller loads the file through
    trimesh, which decides what it means."""
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        return None
    text = "\n{}\n".format(text.strip().replace("\r\n", "\n"))
    if "\\\n" in text or "\r" in text or "+e" in text or "-e" in text:
        return None
    first = text.find("\nf ")
    if first < 0:
        return None
    sample = text[first + 3:text.find("\n", first + 3)].split()
    form = next((name for name, (pattern, _) in _OBJ_FORMS.items()
                 if all(re.fullmatch(pattern, ref) for ref in sample)), None)
    if form is None or len(sample) not in (3, 4):
        return None
    refs, per_ref = len(sample), _OBJ_FORMS[form][1]
    if _obj_line_check(form, refs).search(text) or text.count("usemtl ") != \
            text.count("\nusemtl "):
        return None
    rows = _OBJ_ROWS.findall(text)
    has_normals = "\nvn " in text
    groups: dict[Any, Any] = {}
    for k, part in enumerate(text.split("\nusemtl ")):
        name, body = ("", part) if k == 0 else part.split("\n", 1)
        found = _OBJ_FACES.findall("\n" + body)
        if found:
            groups.setdefault(None if k == 0 else name.strip(), []).extend(found)
    if not rows:
        return None
    # (every number was matched by the pattern above: the parse reads them all)
    v = number_row(" ".join(rows), np.float64).reshape((-1, 3))
    verts, faces, offset = [], [], 0
    for face_lines in reversed(list(groups.values())):
        array = np.fromstring(" ".join(face_lines).replace("/", " "), sep=" ", dtype=np.int64)
        if (array < 1).any():
            return None       # 0 is no OBJ index (trimesh would read it as the first vertex)
        array = array.reshape((-1, refs * per_ref)) - 1
        index = np.arange(refs) * per_ref
        f = array[:, index]
        if int(f.max()) >= len(v):
            return None
        others = []
        if form in ("v/t", "v/t/n"):
            others.append(array[:, index + 1])
        if form == "v/t/n" or (form == "v//n" and has_normals):
            others.append(array[:, index + (2 if form == "v/t/n" else 1)])
        if others:
            new_faces, mask_v = _unmerge(f, others)
        else:
            mask_v = np.zeros(len(v), dtype=bool)
            mask_v[f] = True
            inverse = np.zeros(len(v), dtype=np.int64)
            inverse[mask_v] = np.arange(mask_v.sum())
            new_faces = inverse[f]
        if refs == 4:
            new_faces = np.vstack((new_faces[:, [0, 1, 2]], new_faces[:, [2, 3, 0]]))
        verts.append(v[mask_v])
        faces.append(new_faces + offset)
        offset += len(verts[-1])
    return np.vstack(verts), np.vstack(faces).astype(np.int64)


def _unmerge(faces: np.ndarray, others: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """(new faces, position index of each new vertex): ``unmerge_faces`` of trimesh, one
    vertex per distinct row of (position, *others) references."""
    stack = np.column_stack([faces.reshape(-1)] + [o.reshape(-1) for o in others])
    precision = 64 // stack.shape[1]
    threshold = (2 ** (precision - 1)) - 1
    rows: np.ndarray
    if stack.max() < threshold and stack.min() > -threshold:
        rows = np.zeros(len(stack), dtype=np.uint64)
        for k, column in enumerate((stack.T + (threshold + 1)).astype(np.uint64)):
            np.bitwise_xor(rows, column << np.uint64(k * precision), out=rows)
    else:
        rows = np.ascontiguousarray(stack).view(
            np.dtype((np.void, stack.dtype.itemsize * stack.shape[1]))).reshape(-1)
    _, unique, inverse = np.unique(rows, return_index=True, return_inverse=True)
    pairs = stack[unique]
    order = pairs[:, 0].argsort()
    remap = np.zeros(len(order), dtype=np.int64)
    remap[order] = np.arange(len(order))
    return remap[inverse].reshape((-1, faces.shape[1])), pairs[order][:, 0]


def _plain_effect(effect: Node) -> bool:
    """Whether trimesh turns this effect into a material without failing (colours of four
    components; a texture it cannot load is only logged)."""
    from collada.material import Map
    for value in (effect.diffuse, effect.transparent):
        if value is not None and not isinstance(value, Map) and len(value) != 4:
            return False
    return effect.emission is None or isinstance(effect.emission, Map) or \
        len(effect.emission) >= 3


def _collada_node(node: Node, parent: np.ndarray, parts: list[Part],
                  materials: set[str]) -> bool:
    """``trimesh.exchange.dae._parse_node`` for the geometry: ((vertices, faces) merged, matrix)
    of each triangle set under ``node`` appended to ``parts``; False when trimesh might fail
    or differ."""
    from collada import polylist, scene, triangleset
    if isinstance(node, scene.GeometryNode):
        symbols = set()
        for mn in node.materials:
            if mn.target is None or mn.target.id not in materials:
                return False    # trimesh would convert the material itself
            symbols.add(mn.symbol)
        for prim in node.geometry.primitives:
            if isinstance(prim, polylist.Polylist):
                prim = prim.triangleset()
            if not isinstance(prim, triangleset.TriangleSet):
                continue
            vertex = prim.vertex
            if vertex is None:
                continue
            index = prim.vertex_index
            if not len(index) or np.ndim(vertex) != 2 or np.shape(vertex)[1] != 3 \
                    or not _in_range(index, len(vertex)):
                return False
            if "COLOR" in prim.sources and len(prim.sources["COLOR"]) > 0:
                return False    # vertex colours: trimesh checks their shape
            n = len(index) * 3
            normals = uv = None
            if prim.normal is not None:
                if np.ndim(prim.normal) != 2 or np.shape(prim.normal)[1] != 3 or \
                        not _in_range(prim.normal_index, len(prim.normal)):
                    return False
                normals = prim.normal[prim.normal_index].reshape(-1, 3)
            if prim.material in symbols and len(prim.texcoordset) > 0:
                tc, ti = prim.texcoordset[0], prim.texcoord_indexset[0]
                if np.ndim(tc) != 2 or np.shape(tc)[1] != 2 or not _in_range(ti, len(tc)):
                    return False
                uv = tc[ti].reshape(-1, 2)
            merged = _merge(vertex[index].reshape(n, 3), normals, uv)
            if merged is None:
                return False
            parts.append((merged, parent))
    elif isinstance(node, scene.Node):
        if node.children is not None:
            for child in node.children:
                if not _collada_node(child, np.dot(parent, node.matrix), parts, materials):
                    return False
    return True


def _merge(vertices: np.ndarray, normals: np.ndarray | None,
           uv: np.ndarray | None) -> Arrays | None:
    """(vertices, faces) of the triangle soup ``vertices`` after ``Trimesh.process()``: rows
    equal to trimesh's digits (position, then UV and normal when given for every vertex)
    merged into their first occurrence, faces renumbered (``grouping.merge_vertices`` and
    ``unique_ordered``; the grouping does not depend on how a row is encoded for sorting).
    None for a non-finite vertex (trimesh would drop faces first)."""
    v = np.asarray(vertices, dtype=np.float64)
    if not np.isfinite(v).all():
        return None
    index, inverse = first_of_equal_rows(_merge_rows(v, normals, uv))
    order = index.argsort()
    faces = order.argsort()[inverse.reshape(-1)].reshape((-1, 3))
    return v[index[order]], faces


def _merge_rows(v: np.ndarray, normals: np.ndarray | None, uv: np.ndarray | None
                ) -> np.ndarray:
    """The rows :func:`_merge` groups corners by: position (8 decimals), UV (4) and normal (2)
    as integers, a UV or normal only when given for every corner."""
    stacked = [np.asarray(v, dtype=np.float64) * (10 ** MERGE_DIGITS)]
    if uv is not None and len(uv) == len(v):
        stacked.append(np.asarray(uv, dtype=np.float64) * (10 ** UV_DIGITS))
    if normals is not None:
        normals = np.asarray(normals, dtype=np.float64)
        if normals.shape == np.shape(v):
            stacked.append(normals * (10 ** NORMAL_DIGITS))
    return np.ascontiguousarray(np.column_stack(stacked).round().astype(np.int64))


def _fix_rigid(matrix: np.ndarray, max_deviance: float = 1e-5) -> np.ndarray | None:
    """What trimesh's scene graph returns for a node's matrix (``SceneGraph.get`` with its
    default ``repair_rigid``: ``transformations.fix_rigid``, a rotation off by accumulated
    rounding restored by SVD); None where trimesh's own check would fail."""
    check = np.abs(np.dot(matrix[:3, :3], matrix[:3, :3].T) - _EYE3).max()
    if 1e-13 < check < max_deviance:
        u, _, vt = np.linalg.svd(matrix[:3, :3])
        repaired = np.eye(4)
        repaired[:3, :3] = np.dot(u, vt)
        repaired[:3, 3] = matrix[:3, 3]
        return repaired if np.allclose(repaired, matrix, atol=max_deviance) else None
    return matrix


def _in_range(index: np.ndarray, n: int) -> bool:
    index = np.asarray(index)
    return index.size == 0 or (int(index.min()) >= -n and int(index.max()) < n)


def _allclose(a: np.ndarray, b: np.ndarray, atol: float) -> bool:
    """``trimesh.util.allclose`` (the peak-to-peak of the difference)."""
    return bool(float(np.ptp(a - b)) < atol)


_IDENTITY = np.eye(4)


def transform_points(points: np.ndarray, matrix: np.ndarray) -> np.ndarray:
    """``trimesh.transformations.transform_points`` (the same arithmetic, without trimesh)."""
    points = np.asanyarray(points, dtype=np.float64)
    if len(points) == 0 or matrix is None:
        same: np.ndarray = points.copy()
        return same
    matrix = np.asanyarray(matrix, dtype=np.float64)
    count, dim = points.shape
    if np.abs(matrix - _IDENTITY[: dim + 1, : dim + 1]).max() < 1e-8:
        return np.ascontiguousarray(points.copy())
    stack = np.column_stack((points, np.ones(count)))
    moved: np.ndarray = np.dot(matrix, stack.T).T[:, :dim]
    return moved


# -- COLLADA read with lxml alone (no pycollada objects) --------------------------------------
_SHADINGS = ("constant", "lambert", "phong", "blinn")
_UNSUPPORTED = ("polygons", "tristrips", "trifans", "instance_node", "instance_controller",
                "lookat", "skew", "library_nodes")
_TEXTURING = ("newparam", "texture")     # vouched for by _check_effects, or unsure
# the shading properties pycollada reads as a float (the others: trimesh indexes them as a
# colour), and all it reads (``Effect.supported``: a texture elsewhere is unsure)
_FLOAT_PROPERTIES = frozenset(("shininess", "reflectivity", "transparency", "index_of_refraction"))
_PROPERTIES = _FLOAT_PROPERTIES | {"emission", "ambient", "diffuse", "specular", "reflective",
                                   "transparent"}


def _local(el: Node) -> str:
    tag = el.tag
    return tag.rpartition("}")[2] if isinstance(tag, str) else ""


_ASCII_SPACES = str.maketrans("\t\n\r\v\f", "     ")   # what ``sep=" "`` matches besides " "


def _floats(text: str | None, dtype: Any = np.float32) -> np.ndarray:
    """pycollada's parse of a number list (``np.fromstring`` of the text, NaN read as 0).
    A ``<float_array>`` (float32, a COLLADA file's bulk) of ASCII text is read by numpy's C
    reader of delimited text, as one row: a quarter faster, and the same float32 values (both
    round the decimal to a double, then to float32; tested bit for bit). Text it refuses (a
    stray character, ``nan(7)``) is read by ``fromstring``, which decides as before."""
    if text is None or text.isspace() or not text:
        return np.array([], dtype=dtype)
    out = number_row(text, dtype) if dtype == np.float32 else \
        np.fromstring(text, dtype=dtype, sep=" ")
    if dtype == np.float32:
        out[np.isnan(out)] = 0
    return out


def number_row(text: str, dtype: Any) -> np.ndarray:
    """``np.fromstring(text, dtype, sep=" ")``, by numpy's C reader of delimited text where
    it takes the text (ASCII, read as one row: a quarter to a third faster), by ``fromstring``
    where it refuses it (a stray character, ``nan(7)``: fromstring decides as before). Both
    round each decimal once, by CPython's ``PyOS_string_to_double``, then to ``dtype``: the
    same bits, tested for float32 on anything (a COLLADA ``<float_array>``) and for float64
    on plain decimals (an OBJ's checked ``v`` rows), where it is used."""
    if text.isascii():   # (str.split's spaces are not all fromstring's)
        try:
            out: np.ndarray = np.loadtxt([text.translate(_ASCII_SPACES)], dtype=dtype, ndmin=1,
                                         comments=None)
            return out
        except ValueError:
            pass
    return np.fromstring(text, dtype=dtype, sep=" ")


class _Unsure(Exception):
    """A COLLADA feature the lean reader does not vouch for: pycollada reads the file."""


Soups = list[tuple[Any, np.ndarray]]   # [(Soup, placing matrix)]: triangle sets, read, unmerged


def collada_soups(data: bytes) -> "Soups | None":
    """A COLLADA document's triangle sets from one lxml parse, not yet merged: the sources'
    ``<float_array>`` (float32, as pycollada reads them), the primitives' ``<p>``/``<vcount>``
    and ``<input>`` offsets, the ``<node>`` transforms (float32 products, as pycollada's
    ``Node.matrix``) and ``<instance_geometry>``/``<instance_material>`` bindings. Textures
    count only where pycollada loads them (:func:`_check_effects`). None for anything else
    (other effect parameters, polygons with holes, strips and fans, node instances,
    controllers, a broken reference, any doubt): the caller reads the file through
    pycollada. :func:`soups_arrays` gives their vertices and faces, :func:`soups_bounds`
    their bounds."""
    from lxml import etree
    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                             huge_tree=True, remove_comments=True)
    try:
        root = etree.fromstring(data, parser)
        parts = _lean(root)
        # (as collada_arrays: an instance that gives no triangle set: trimesh decides; but a
        # geometry of lines alone gives none in trimesh either, without error)
        want = data.count(b"<instance_geometry")
        if parts is not None and len(parts) < want:   # (the tree is walked again only then)
            want -= _line_only_instances(root)
        return parts if parts is not None and len(parts) >= want else None
    except Exception:  # noqa: BLE001 - _Unsure, or anything pycollada should judge
        return None


def soups_arrays(parts: "Soups") -> Arrays | None:
    """:func:`collada_arrays`' numbers from :func:`collada_soups`: each set merged exactly as
    :func:`collada_arrays` merges pycollada's (same float32 values, same index arrays, same
    order), placed and stacked; None where pycollada should judge (a vertex not finite, a
    matrix trimesh's scene would refuse)."""
    try:
        return _assemble([(_merge_soup(soup), matrix) for soup, matrix in parts])
    except Exception:  # noqa: BLE001 - _Unsure, or anything pycollada should judge
        return None


def soups_bounds(parts: "Soups") -> tuple[np.ndarray, np.ndarray, int, int] | None:
    """(lowest, highest corner, positions, triangles) of :func:`soups_arrays`' vertices (the
    positions the triangles use, each counted once), without merging them: a mesh's facts
    need its bounds, and merging (sorting every corner of every triangle by position,
    texture coordinate and normal) was a third of reading a COLLADA file. The same values
    (:func:`_soup_bounds`); None where :func:`soups_arrays` is, or where the merge's keys
    overflow: the caller then reads the arrays."""
    try:
        got = _soup_bounds(parts)
    except Exception:  # noqa: BLE001 - as soups_arrays
        return None
    if got is None:
        return None
    (lo, hi), (vertices, faces) = got
    return lo, hi, vertices, faces


def collada_arrays_lean(data: bytes) -> tuple[np.ndarray, np.ndarray, int] | None:
    """:func:`collada_arrays`' numbers from one lxml parse (:func:`collada_soups`,
    :func:`soups_arrays`), and the number of triangle sets; None where pycollada reads it."""
    parts = collada_soups(data)
    got = None if parts is None else soups_arrays(parts)
    return None if parts is None or got is None else (got[0], got[1], len(parts))


def collada_bounds(data: bytes) -> tuple[np.ndarray, np.ndarray, int, int] | None:
    """:func:`soups_bounds` of :func:`collada_soups` (the lean reader's bounds of a document)."""
    parts = collada_soups(data)
    return None if parts is None else soups_bounds(parts)


_EPS = float(np.finfo(np.float64).eps)


def _soup_bounds(parts: "Soups") -> tuple[Any, Any] | None:
    """The bounds of :func:`_assemble` of the merged triangle sets, from the positions their
    triangles use, placed by their matrices as ``_assemble`` places them, as
    ((lowest, highest), (positions used, triangles)); None where trimesh would not
    place a set or a position is not finite (``_Unsure`` raised), or where a coordinate is so
    large (4.6e10) that the merge's integer keys overflow and merge unrelated corners.

    Merging keeps, of the corners equal to 8 decimals (with their texture coordinate and
    normal), the first in the set's order; its position is one the triangles use, within
    1e-8 of the others' in each coordinate. So the lowest value of a coordinate over the
    merged vertices is the lowest over the used positions unless other values lie within
    that distance (as placed: times the matrix row, plus the rounding of placing them) above
    it; then the corners there are grouped as the merge groups them
    (:func:`_merged_extreme`). The same values as the merged vertices' bounds, but that a
    zero may come with the other sign (they compare equal), and that a matrix product may
    round a last bit otherwise where every corner of a set merges into one vertex (numpy
    places one row by another BLAS routine)."""
    lo: np.ndarray | None = None
    hi: np.ndarray | None = None
    vertices = faces = 0
    for soup, matrix in parts:
        vertex, index = soup[0], soup[1]
        placing = _placement(matrix)
        if placing is None:
            raise _Unsure("not rigid")
        rigid, moves = placing
        used = np.zeros(len(vertex), dtype=bool)
        used[index.reshape(-1)] = True
        points = vertex[used].astype(np.float64)
        vertices += len(points)
        faces += len(index)
        if not np.isfinite(points).all():
            raise _Unsure("not finite")
        largest = np.abs(points).max(axis=0)
        if float(largest.max()) * 10 ** MERGE_DIGITS >= 2.0 ** 62:
            return None     # (the merge's integer keys overflow: unrelated corners merge)
        slack = np.full(3, 1.01e-8)
        if moves:
            points = transform_points(points, rigid)
            # corners 1e-8 apart, placed; and the rounding of the products and sums placing
            # them, relative to their terms (a translation cancelling large coordinates)
            terms = np.abs(rigid[:3, :3]) @ largest + np.abs(rigid[:3, 3])
            slack = 1.01e-8 * np.abs(rigid[:3, :3]).sum(axis=1) + 16 * _EPS * terms
        plo, phi = bounds(points)
        at = np.flatnonzero(used)
        for c in range(3):
            slack[c] += 16 * _EPS * (abs(plo[c]) + abs(phi[c]))
            plo[c] = _merged_extreme(soup, at, points[:, c], plo[c], float(slack[c]))
            phi[c] = -_merged_extreme(soup, at, -points[:, c], -phi[c], float(slack[c]))
        lo = plo if lo is None else np.minimum(lo, plo)
        hi = phi if hi is None else np.maximum(hi, phi)
    return (lo, hi), (vertices, faces)


def _merged_extreme(soup: Soup, at: np.ndarray, column: np.ndarray, least: float,
                    slack: float) -> float:
    """The least of ``column`` (a placed coordinate of the used positions ``at``, whose least
    is ``least``) over the vertices :func:`_merge` keeps of the set ``soup``. ``slack``
    bounds how far apart the placed coordinates of two corners it merges lie. The corners
    within ``slack`` of ``least`` are merged only with corners within twice that: those are
    grouped on the rows ``_merge`` groups them by, and the least over the first of each group
    that reaches within ``slack`` is the answer (the first of the lowest corner's group is
    one)."""
    near = column <= least + slack
    if (column[near] == least).all():
        return least          # (the common case: one value there, whichever corner is kept)
    vertex, index = soup[0], soup[1]
    wide = np.zeros(len(vertex), dtype=bool)
    wide[at[column <= least + 2 * slack]] = True
    corners = np.flatnonzero(wide[index.reshape(-1)])     # in the set's order
    first, group = first_of_equal_rows(_merge_rows(*_corners(soup, corners)))
    position = index.reshape(-1)[corners]                 # each corner's used position
    row = np.searchsorted(at, position)                   # ... as a row of ``column``
    reaches = np.zeros(len(first), dtype=bool)
    reaches[group[near[row]]] = True
    return float(column[row[first[reaches]]].min())


_LINES = frozenset(("lines", "linestrips"))


def _line_only_instances(root: Node) -> int:
    """How many ``<instance_geometry>`` name a mesh of line primitives alone (a sensor's
    outline): trimesh's COLLADA loader makes no mesh of them."""
    byid = {el.get("id"): el for el in root.iter() if el.get("id") is not None}
    n = 0
    for inst in root.iter():
        if _local(inst) != "instance_geometry":
            continue
        geom = byid.get((inst.get("url") or "#")[1:])
        kinds = {_local(p) for m in (geom if geom is not None else ()) if _local(m) == "mesh"
                 for p in m if isinstance(p.tag, str)} - {"source", "vertices", "extra"}
        n += bool(kinds) and kinds <= _LINES
    return n


def _lean(root: Node) -> "Soups | None":
    """The triangle sets of a COLLADA document (:func:`collada_soups`), None when it has
    none; ``_Unsure`` where the lean reader does not vouch for it."""
    byid: dict[str, Node] = {}
    texturing = 0
    for el in root.iter():
        name = _local(el)
        if name in _UNSUPPORTED:
            raise _Unsure(name)
        if name in _TEXTURING:
            texturing += 1
        if name == "input" and el.get("semantic") == "COLOR":
            raise _Unsure("vertex colours")
        i = el.get("id")
        if i is not None:
            if i in byid:
                raise _Unsure("duplicate id")
            byid[i] = el
    if _check_effects(root) != texturing:
        raise _Unsure("texture")
    materials = {m.get("id") for lib in root if _local(lib) == "library_materials"
                 for m in lib if _local(m) == "material"}
    for mid in materials:
        _check_material(byid, byid[mid])
    scene = [el for el in root if _local(el) == "scene"]
    if len(scene) != 1:
        raise _Unsure("scene")
    vs = [el for el in scene[0] if _local(el) == "instance_visual_scene"]
    if len(vs) != 1:
        raise _Unsure("scene")
    visual = _ref(byid, vs[0].get("url"))
    parts: Soups = []
    geometries: dict[str, Any] = {}
    for node in visual:
        if _local(node) == "node":
            _lean_node(node, _EYE4, parts, materials, byid, geometries)
    return parts or None


def _ref(byid: dict[str, Node], url: str | None) -> Node:
    if not url or not url.startswith("#") or url[1:] not in byid:
        raise _Unsure("broken reference")
    return byid[url[1:]]


def _namespace(root: Node) -> str:
    """The ``{namespace}`` prefix of the tags pycollada looks for (its root's, as it takes
    it)."""
    return "{" + str(root.tag).split("}")[0].lstrip("{") + "}"


def _check_material(byid: dict[str, Node], material: Node) -> None:
    """A material of one effect of the effect library (each checked: :func:`_check_effects`)."""
    inst = [el for el in material if _local(el) == "instance_effect"]
    if len(inst) != 1:
        raise _Unsure("material")
    effect = _ref(byid, inst[0].get("url"))
    parent = effect.getparent()
    if _local(effect) != "effect" or parent is None or _local(parent) != "library_effects":
        raise _Unsure("material")


def _check_effects(root: Node) -> int:
    """Check every effect of the document (:func:`_check_effect`): pycollada loads each one,
    used or not, and fails the whole document on some errors trimesh does not ignore (a
    profile without its technique, a bad ``<float>``). Returns how many ``<newparam>`` and
    ``<texture>`` elements it loads without an error in them (:func:`_effect_textures`):
    fewer than the document holds, and the caller is unsure."""
    ns = _namespace(root)
    images = {el.get("id"): el for lib in root if _local(lib) == "library_images"
              for el in lib if _local(el) == "image"}
    found = 0
    for lib in root:
        if _local(lib) == "library_effects":
            for effect in lib:
                if _local(effect) == "effect":
                    found += _effect_textures(effect, *_check_effect(effect, ns), images, ns)
    return found


def _check_effect(effect: Node, ns: str) -> tuple[Node, Node, Node]:
    """(profile, technique, shading) of an effect pycollada loads and trimesh converts
    (``_plain_effect``); its profile and technique in the document's namespace ``ns``, where
    pycollada finds them (a technique it does not find fails the whole load)."""
    profiles = [el for el in effect if _local(el) == "profile_COMMON"]
    if len(profiles) != 1 or profiles[0].tag != ns + "profile_COMMON":
        raise _Unsure("effect")
    techniques = [el for el in profiles[0] if _local(el) == "technique"]
    if len(techniques) != 1 or techniques[0].tag != ns + "technique":
        raise _Unsure("effect")
    shading = [el for el in techniques[0] if _local(el) in _SHADINGS]
    if len(shading) != 1:
        raise _Unsure("effect")
    for prop in shading[0]:
        kids = [el for el in prop if isinstance(el.tag, str)]
        if len(kids) == 1 and _local(kids[0]) == "texture":
            continue        # (a sampler pycollada finds: _effect_textures; trimesh only logs
            # an image it cannot load)
        if len(kids) != 1 or _local(kids[0]) not in ("color", "float"):
            raise _Unsure("effect property")
        if (_local(kids[0]) == "float") != (_local(prop) in _FLOAT_PROPERTIES):
            raise _Unsure("effect property")     # (trimesh takes a float's [3] or [:3])
        values = _floats(kids[0].text, np.float64)
        if _local(kids[0]) == "float" and len(values) != 1:
            raise _Unsure("effect property")
        if _local(kids[0]) == "color":
            need = 3 if _local(prop) == "emission" else 4
            if len(values) < need or (need == 4 and len(values) != 4) or len(values) > 4:
                raise _Unsure("colour")
    return profiles[0], techniques[0], shading[0]


def _effect_textures(effect: Node, profile: Node, technique: Node, shading: Node,
                     images: dict[str | None, Node], ns: str) -> int:
    """How many of the effect's ``<newparam>`` and ``<texture>`` elements pycollada loads
    without an error: in its ``profile_COMMON`` (or its technique), each parameter a 2D
    ``<surface>`` of an image of ``<library_images>`` or a ``<sampler2D>`` of a surface
    declared before it (:func:`_parameter`), each texture the value of a shading property
    naming such a sampler, or a bump map (pycollada's ``Surface``, ``Sampler2D`` and ``Map``;
    what trimesh makes of a texture does not change the geometry)."""
    if any(_local(el) == "image" for el in profile):
        return 0
    scope: dict[str, str] = {}
    found = 0
    for parent in (profile, technique):
        for param in parent:
            if _local(param) == "newparam":
                kind = _parameter(param, scope, images)
                if kind is None:
                    return found
                scope[param.get("sid")] = kind
                found += 1
    return found + _sampled(shading, scope) + _bump_maps(effect, scope, ns)


def _parameter(param: Node, scope: dict[str, str], images: dict[str | None, Node]) -> str | None:
    """What a ``<newparam>`` is to pycollada when it loads it: ``"surface"`` (2D, of an image
    of the library) or ``"sampler"`` (of a surface in ``scope``); None for anything else."""
    kids = [el for el in param if isinstance(el.tag, str)]
    sid = param.get("sid")
    if len(kids) != 1 or not sid or sid in scope:
        return None
    kind = _local(kids[0])
    source = [el for el in kids[0] if _local(el) in ("init_from", "source")]
    if len(source) != 1:
        return None
    ref = source[0].text or ""
    if kind == "surface" and kids[0].get("type") == "2D" and _local(source[0]) == "init_from" \
            and ref not in scope and any(_local(el) == "init_from" for el in images.get(ref, ())):
        return "surface"
    if kind == "sampler2D" and _local(source[0]) == "source" and scope.get(ref) == "surface":
        return "sampler"
    return None


def _sampled(shading: Node, scope: dict[str, str]) -> int:
    """The ``<texture>`` values of the shading properties that name a sampler of ``scope``."""
    found = 0
    for value in shading:
        kids = [el for el in value if isinstance(el.tag, str)]
        if _local(value) in _PROPERTIES and len(kids) == 1 and \
                _local(kids[0]) == "texture" and scope.get(kids[0].get("texture")) == "sampler":
            found += 1
    return found


def _bump_maps(effect: Node, scope: dict[str, str], ns: str) -> int:
    """The textures under an ``<extra>`` of the effect (an exporter's bump map), when the
    first of them in the document's namespace ``ns``, which pycollada loads (and fails on the
    whole document when it names no sampler), names a sampler of ``scope``."""
    bumps = {id(el): el for el in effect.iterfind(".//{*}extra//{*}texture")}
    first = effect.find(f".//{ns}extra//{ns}texture")     # (pycollada's, in its namespace)
    return len(bumps) if first is not None and scope.get(first.get("texture")) == "sampler" \
        else 0


def _matrix(node: Node) -> np.ndarray:
    """pycollada's ``Node.matrix``: the node's transforms multiplied in float32."""
    transforms = []
    for el in node:
        name = _local(el)
        if name in ("matrix", "translate", "rotate", "scale"):
            v = _floats(el.text)
            m = np.identity(4, dtype=np.float32)
            if name == "matrix":
                if len(v) != 16:
                    raise _Unsure("matrix")
                m = v.reshape(4, 4)
            elif name == "translate":
                if len(v) != 3:
                    raise _Unsure("translate")
                m[:3, 3] = v
            elif name == "scale":
                if len(v) != 3:
                    raise _Unsure("scale")
                m[0, 0], m[1, 1], m[2, 2] = v
            else:
                if len(v) != 4:
                    raise _Unsure("rotate")
                m = _rotation(v[0], v[1], v[2], v[3] * np.pi / 180.0)
            transforms.append(m)
    if not transforms:
        return np.identity(4, dtype=np.float32)
    if len(transforms) == 1:
        one: np.ndarray = transforms[0].copy()
        return one
    out = np.identity(4, dtype=np.float32)
    for m in transforms:
        out = np.dot(out, m)
    return out


def _rotation(x: float, y: float, z: float, angle: float) -> np.ndarray:
    """pycollada's ``makeRotationMatrix`` (float32)."""
    c, s = np.cos(angle), np.sin(angle)
    t = (1 - c)
    return np.array([[t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0],
                     [t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0],
                     [t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0],
                     [0, 0, 0, 1]], dtype=np.float32)


def _lean_node(node: Node, parent: np.ndarray, parts: list[Any], materials: set[str],
               byid: dict[str, Node], geometries: dict[str, Any]) -> None:
    """:func:`_collada_node` on the XML: a ``<node>``'s children in document order."""
    matrix = np.dot(parent, _matrix(node))
    for el in node:
        name = _local(el)
        if name == "node":
            _lean_node(el, matrix, parts, materials, byid, geometries)
        elif name == "instance_geometry":
            _lean_geometry(el, matrix, parts, materials, byid, geometries)


def _lean_geometry(inst: Node, matrix: np.ndarray, parts: list[Any], materials: set[str],
                   byid: dict[str, Node], geometries: dict[str, Any]) -> None:
    url = inst.get("url")
    geometry = _ref(byid, url)
    symbols = set()
    for el in inst.iter():
        if _local(el) == "instance_material":
            target = el.get("target") or ""
            if not target.startswith("#") or target[1:] not in materials:
                raise _Unsure("material binding")
            symbols.add(el.get("symbol"))
    if url not in geometries:
        geometries[url] = _primitives(geometry, byid)
    for prim in geometries[url]:
        vertex, index, normal, normal_index, uvs, material = prim
        uv = uvs[0] if material in symbols and uvs else (None, None)
        parts.append(((vertex, index, normal, normal_index) + tuple(uv), matrix))


Soup = tuple[Any, ...]   # (vertex, index (k, 3), normal, normal index, uv, uv index) of a set


def _corners(soup: Soup, which: np.ndarray | slice = slice(None)
             ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
    """(position, normal, UV) of the triangle set ``soup``'s corners (``which`` of them, in
    the set's order), as float32 rows; None for a normal or UV it has not."""
    vertex, index, normal, normal_index, uv_source, uv_index = soup
    normals = normal[normal_index.reshape(-1)[which]] if normal is not None else None
    uv = uv_source[uv_index.reshape(-1)[which]] if uv_source is not None else None
    return vertex[index.reshape(-1)[which]], normals, uv


def _merge_soup(soup: Soup) -> Arrays:
    """The triangle set ``soup`` as trimesh's processed mesh (:func:`_merge` of its corners)."""
    merged = _merge(*_corners(soup))
    if merged is None:
        raise _Unsure("not finite")
    return merged


def _source(byid: dict[str, Node], url: str | None,
            names: tuple[tuple[str, ...], ...],
            read: dict[tuple[Any, ...], np.ndarray] | None = None) -> np.ndarray:
    """A ``<source>``'s float32 values shaped by its accessor's params (pycollada's
    ``FloatSource``), which must be ``names``. ``read`` keeps the sources a geometry's
    primitives read already: its triangle sets (one per material) share their positions and
    normals, which were parsed again for each (a sixth of the numbers of the workspace's
    COLLADA files). The arrays are only indexed, never written."""
    if read is not None:
        key = (url, names)
        if key not in read:
            read[key] = _source(byid, url, names)
        return read[key]
    src = _ref(byid, url)
    arrays = [el for el in src if _local(el) == "float_array"]
    if _local(src) != "source" or len(arrays) != 1:
        raise _Unsure("source")
    params = [p.get("name") for el in src if _local(el) == "technique_common"
              for acc in el if _local(acc) == "accessor" for p in acc if _local(p) == "param"]
    if tuple(params) not in names:
        raise _Unsure("accessor")
    data = _floats(arrays[0].text)
    if data.size % len(params):
        raise _Unsure("source size")
    return data.reshape(-1, len(params))


_XYZ = (("X", "Y", "Z"),)
_ST = (("S", "T"), ("U", "V"))


def _primitives(geometry: Node, byid: dict[str, Node]) -> list[tuple[Any, ...]]:
    """(vertex, vertex_index (k, 3), normal, normal_index, [(uv, uv_index)], material) of each
    triangle set of a geometry's ``<mesh>`` (a polylist fanned as pycollada fans it); empty
    sets skipped; anything else unsure."""
    meshes = [el for el in geometry if _local(el) == "mesh"]
    if _local(geometry) != "geometry" or len(meshes) != 1:
        raise _Unsure("geometry")
    out = []
    read: dict[tuple[Any, ...], np.ndarray] = {}
    for prim in meshes[0]:
        kind = _local(prim)
        if kind not in ("triangles", "polylist"):
            if kind in ("source", "vertices", "lines", "linestrips", "extra", ""):
                continue
            raise _Unsure(kind)
        by = _inputs(prim, byid)
        stride = max(o for inputs in by.values() for o, _ in inputs) + 1
        index = _index(prim, kind, stride)
        if not len(index):
            continue
        vertex, vi = _indexed(byid, by["VERTEX"][0], index, _XYZ, read)
        normal = normal_index = None
        if by["NORMAL"]:
            normal, normal_index = _indexed(byid, by["NORMAL"][0], index, _XYZ, read)
        uvs = [_indexed(byid, t, index, _ST, read) for t in by["TEXCOORD"]]
        out.append((vertex, vi, normal, normal_index, uvs, prim.get("material")))
    return out


def _inputs(prim: Node, byid: dict[str, Node]) -> dict[str, list[Node]]:
    """{semantic: [(offset, source url)]} of a primitive, in document order, the inputs of its
    ``<vertices>`` in place of its VERTEX input (POSITION as VERTEX), as pycollada lists them."""
    inputs = []
    for el in prim:
        if _local(el) != "input":
            continue
        offset, semantic, url = int(el.get("offset")), el.get("semantic"), el.get("source")
        target = _ref(byid, url)
        if semantic != "VERTEX" or _local(target) != "vertices":
            inputs.append((offset, semantic, url))
            continue
        seen = set()
        for vin in target:
            if _local(vin) != "input":
                continue
            sem = vin.get("semantic")
            if sem in seen:
                raise _Unsure("vertices")
            seen.add(sem)
            inputs.append((offset, "VERTEX" if sem == "POSITION" else sem, vin.get("source")))
    known = ("VERTEX", "NORMAL", "TEXCOORD")
    if any(s not in known for _, s, _ in inputs):
        raise _Unsure("input semantic")
    by = {s: [(o, u) for o, s2, u in inputs if s2 == s] for s in known}
    if len(by["VERTEX"]) != 1 or len(by["NORMAL"]) > 1:
        raise _Unsure("inputs")
    return by


def _index(prim: Node, kind: str, stride: int) -> np.ndarray:
    """The index of a primitive's triangles, shape (k, 3, stride): its first ``<p>`` (pycollada
    reads no other), a polylist's fanned."""
    ps = [el for el in prim if _local(el) == "p"]
    if not ps:
        raise _Unsure("no index")
    index = _floats(ps[0].text, np.int32)
    if index.size % stride:
        raise _Unsure("index size")
    index = index.reshape(-1, stride)
    if kind == "polylist":
        index = _fan(prim, index)
    if index.size % (3 * stride):
        raise _Unsure("index size")
    return index.reshape(-1, 3, stride)


def _indexed(byid: dict[str, Node], inp: Node, index: np.ndarray,
             names: tuple[tuple[str, ...], ...],
             read: dict[tuple[Any, ...], np.ndarray] | None = None
             ) -> tuple[np.ndarray, np.ndarray]:
    """(the source's values, the (k, 3) indices into them) of one input, every index in range
    (pycollada's ``checkSource``); ``read`` as for :func:`_source`."""
    offset, url = inp
    values, at = _source(byid, url, names, read), index[:, :, offset]
    if int(at.max()) >= len(values) or int(at.min()) < 0:
        raise _Unsure("index range")
    return values, at


def _fan(prim: Node, index: np.ndarray) -> np.ndarray:
    """pycollada's ``Polylist.triangleset``: polygon k of ``vcount`` corners (start s) gives
    the triangles (s, s+i+1, s+i+2)."""
    vc = [el for el in prim if _local(el) == "vcount"]
    if len(vc) != 1:
        raise _Unsure("vcount")
    vcounts = _floats(vc[0].text, np.int32)
    if (vcounts < 3).any() or int(vcounts.sum()) != len(index):
        raise _Unsure("vcount")
    if not len(vcounts):
        return index[:0]
    ends = np.cumsum(vcounts)
    starts = ends - vcounts
    keep = np.ones(len(index), dtype=bool)
    keep[ends - 1] = False
    keep[ends - 2] = False
    sel = np.flatnonzero(keep)
    first = np.repeat(starts, vcounts)[sel]
    return np.stack((index[first], index[sel + 1], index[sel + 2]), axis=1).reshape(
        -1, index.shape[1])
