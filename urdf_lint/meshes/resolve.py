"""Mesh references: resolution through the package resolver, confinement, and mesh facts.

Resolution and existence checks are pure path work (no trimesh). Loading a mesh (for the
rules that need its geometry, and for rendering) imports trimesh lazily, and its facts are
cached by file content, so a mesh is read once per change, not once per model or run.
"""
from __future__ import annotations

import contextlib
import math
import os
import re
import stat
import time
from collections import OrderedDict
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Iterable, Iterator

if TYPE_CHECKING:  # pragma: no cover - numpy and trimesh are imported on first use
    import numpy as np
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.engine.model import Model

from urdf_lint.core import fsbound, overlay
from urdf_lint.core.hashing import content_digest, known, memo_read
from urdf_lint.discovery.packages import PackageNotFound
from urdf_lint.meshes.status import MeshStatus as MeshStatus
from urdf_lint.meshes.store import MeshStore

Facts = dict[str, Any]          # a mesh's measured facts (a JSON record)
Mesh = Any                      # a trimesh.Trimesh (trimesh ships no type information here)
# vertices (n, 3), faces (m, 3) and the broken references of a mesh
Arrays = tuple["np.ndarray", "np.ndarray", list[str]]


@dataclass
class MeshRef:
    """A mesh reference of the model: its URI, the resolved file, and whether it loads."""
    uri: str
    path: str | None          # resolved absolute path (None when it cannot be resolved)
    status: MeshStatus
    message: str = ""
    package: str = ""         # the unknown package (UNKNOWN_PACKAGE)
    cause: str = ""           # why it is unknown (the searched places), for the root cause
    # the folder relative paths were assumed to start from (the generated URDF's), when this
    # one is not there and was found from the entry's folder instead (Model.mesh_base_fallback)
    assumed: str = ""

    @property
    def problem(self) -> MeshStatus | None:
        """None when the reference resolved (``status is MeshStatus.OK``), else its status.
        Kept for rules written before :class:`MeshStatus`; new code reads ``status``."""
        return None if self.status is MeshStatus.OK else self.status


def _case_true_path(path: Path, top: Path | None = None) -> tuple[bool, str | None]:
    """(exists with exact case, the real spelling if it only exists with another case).

    Only folders below ``top`` (the root holding ``path``) are listed: names of folders
    outside the roots are never read."""
    if top is not None:
        try:
            rest = path.relative_to(top).parts
        except ValueError:
            top = None
    if top is None:
        cur, rest = Path(path.parts[0]), path.parts[1:]
    else:
        cur = top
    exact = True
    for part in rest:
        names = _listing(cur)
        if names is None:
            return False, None
        if part in names:
            cur = cur / part
            continue
        low = [n for n in names if n.lower() == part.lower()]
        if not low:
            return False, None
        exact = False
        cur = cur / low[0]
    return exact, (None if exact else str(cur))


_listings: dict[str, "_Names"] = {}     # folder -> (mtime_ns, names in listdir order, set of names)
MAX_LISTINGS = 20_000
RACY_NS = 2_000_000_000  # a folder changed this recently may change again within its mtime tick


def _listing(folder: Path) -> "_Names | None":
    """The names in a folder, listed once per version of it in this process (a folder's
    mtime changes when an entry is added, removed or renamed; one modified in the last two
    seconds is listed again, like git's racily clean entries)."""
    key = str(folder)
    try:
        mtime = os.stat(key).st_mtime_ns
    except OSError:
        return None
    got = _listings.get(key)
    if got is not None and got.mtime == mtime and time.time_ns() - mtime > RACY_NS:
        return got
    try:
        names = _Names(mtime, fsbound.list_dir(key))
    except OSError:
        return None
    if len(_listings) >= MAX_LISTINGS:
        _listings.clear()
    _listings[key] = names
    return names


class _Names(list[str]):
    """A folder's names in ``os.listdir`` order, with a set for membership tests."""

    def __init__(self, mtime: int, names: Iterable[str]) -> None:
        super().__init__(names)
        self.mtime = mtime
        self._set = frozenset(self)

    def __contains__(self, name: object) -> bool:
        return name in self._set


def resolve(model: "Model", uri: str) -> MeshRef:
    ref = _resolve(model, uri, model.base_dir)
    other = getattr(model, "mesh_base_fallback", None)
    if ref.status is MeshStatus.NOT_FOUND and other and other != model.base_dir \
            and _relative(uri):
        # the generated URDF's folder was assumed, not configured: the models of the same
        # macros without one start from their entry's folder; so does this one, when that
        # holds the file (a fact UL411 reports, naming the ``mesh-base`` key that decides)
        there = _resolve(model, uri, other)
        if there.status is MeshStatus.OK:
            return replace(there, assumed=model.base_dir)
    if ref.status is MeshStatus.NOT_FOUND and _relative(uri) and ref.path:
        hint = _found_above(model, uri, model.base_dir)
        if hint:
            return replace(ref, message=ref.message + hint)
    return ref


def _found_above(model: Any, uri: str, base_dir: str) -> str:
    """Where a relative mesh missing from ``base_dir`` is when read from a folder above it
    (inside the same root): unitree's hand URDFs write ``meshes/x.STL`` one folder below the
    package's ``meshes``. A hint, never a resolution: the loader decides where relative paths
    start."""
    from urdf_lint.core.locations import display_path
    top = model.resolver.root_of(base_dir)
    d = base_dir
    while top is not None and os.path.dirname(d) != d and len(d) > len(top):
        d = os.path.dirname(d)
        p = os.path.join(d, uri)
        if model.resolver.is_inside(p) and os.path.isfile(p):
            return (f"; a file of that name is at {display_path(p)}: if the program that "
                    f"loads this robot reads relative paths from {display_path(d)}, set "
                    "mesh-base")
    return ""


def _relative(uri: str) -> bool:
    """A path written relative to the URDF (not ``package://``, ``file://`` nor absolute)."""
    return "://" not in uri and not os.path.isabs(uri)


def _resolve(model: "Model", uri: str, base_dir: str) -> MeshRef:
    resolver = model.resolver
    try:
        p = resolver.resolve_uri(uri, base_dir)
    except PackageNotFound as e:
        return MeshRef(uri, None, MeshStatus.UNKNOWN_PACKAGE, f"mesh '{uri}': {e}", e.name,
                       str(e))
    p = Path(os.path.abspath(p))
    top = _root_of(resolver, p)
    if top is None and resolver.is_inside(p):  # written outside, resolves inside (a symlink)
        p = Path(os.path.realpath(p))
        top = _root_of(resolver, p)
    if top is None:
        if not os.path.lexists(p):
            return MeshRef(uri, str(p), MeshStatus.NOT_FOUND,
                           f"mesh file not found: '{uri}' (looked for {p})")
        return MeshRef(uri, None, MeshStatus.OUTSIDE_ROOTS,
                       f"mesh '{uri}' resolves to {os.path.realpath(p)}, outside "
                       "the package roots; it is not read")
    exact, real = _case_true_path(p, top)
    if not exact and real is None:
        return MeshRef(uri, str(p), MeshStatus.NOT_FOUND,
                       f"mesh file not found: '{uri}' (looked for {p})")
    if not exact:
        return MeshRef(uri, real, MeshStatus.CASE_MISMATCH,
                       f"mesh '{uri}' only exists as '{os.path.basename(real or '')}' "
                       f"(case differs: works on macOS/Windows, fails on Linux)")
    if not resolver.is_inside(p):
        return MeshRef(uri, None, MeshStatus.OUTSIDE_ROOTS,
                       f"mesh '{uri}' resolves to {os.path.realpath(p)}, outside "
                       "the package roots; it is not read")
    try:
        st = os.stat(p)
    except OSError as e:  # a symlink loop, a dangling link, no permission
        return MeshRef(uri, str(p), MeshStatus.NOT_FOUND, f"mesh '{uri}' cannot be read: "
                       f"{e.strerror or e} ({p})")
    if not stat.S_ISREG(st.st_mode):
        what = "a directory" if stat.S_ISDIR(st.st_mode) else "not a regular file"
        return MeshRef(uri, str(p), MeshStatus.NOT_FOUND,
                       f"mesh '{uri}' is {what}, not a mesh file ({p})")
    return MeshRef(uri, str(p), MeshStatus.OK)


def _root_of(resolver: "PackageResolver", p: Path) -> Path | None:
    """The deepest root that holds ``p`` as written (before symlinks), or None."""
    best = resolver.root_of(p)
    return None if best is None else Path(best)


_DAE_IMAGE = re.compile(rb"<init_from>\s*([^<]+?)\s*</init_from>")
_MTL_MAP = re.compile(r"^\s*(?:map_\w+|bump|disp|decal|refl)\s+(?:-\S+\s+\S+\s+)*(\S.*?)\s*$", re.M)


_textures: dict[Any, list[str]] = {}
MAX_MESH_BYTES = 1 << 30
_scan_memory: dict[str, Facts] = {}
TEXTURE_SCAN_VERSION = 1


def _readable(path: str, store: MeshStore) -> bool:
    from urdf_lint.discovery.packages import regular_file
    return regular_file(path, MAX_MESH_BYTES) and (store.inside is None or store.inside(path))


def texture_refs(path: str, store: MeshStore | None = None) -> list[str]:
    """Image files a DAE or OBJ(+MTL) mesh refers to, as absolute paths (memoized per version;
    references outside ``store.inside`` are not read)."""
    if not path.lower().endswith((".dae", ".obj")):
        return []      # (asked for every mesh of every link: no stat for formats without any)
    try:
        key = _version(path)
    except OSError:
        return []
    if key not in _textures:
        _textures[key] = _texture_refs(path, store or MeshStore())
    return list(_textures[key])


def _texture_refs(path: str, store: MeshStore) -> list[str]:
    out: list[str] = []
    base = os.path.dirname(path)
    low = path.lower()
    if not low.endswith((".dae", ".obj")) or not _readable(path, store):
        return out
    try:
        # what the mesh itself names depends on its bytes only: scanned once per content,
        # cached on disk with the mesh facts (a DAE is not read again on the next run)
        scan = _cached(_scan_memory, f"tex{TEXTURE_SCAN_VERSION}", path, store,
                       _scan_texture_names)
    except OSError:
        return out
    if low.endswith(".dae"):
        return [os.path.normpath(os.path.join(base, ref)) for ref in scan.get("refs", [])]
    try:
        for name in scan.get("refs", []):
            mtl = os.path.normpath(os.path.join(base, name))
            out.append(mtl)
            if _readable(mtl, store):   # the MTL is read each time: it may lie outside the roots
                text = fsbound.read_text(mtl, max_bytes=MAX_MESH_BYTES, errors="replace")
                for ref in _MTL_MAP.finditer(text):
                    out.append(os.path.normpath(os.path.join(os.path.dirname(mtl),
                                                             ref.group(1))))
    except OSError:
        pass
    return out


def _scan_texture_names(path: str) -> Facts:
    """{ok, refs}: the image references of a DAE (``<init_from>``, relative as written) or
    the ``mtllib`` names of an OBJ."""
    refs: list[str] = []
    if path.lower().endswith(".dae"):
        data = _file_bytes(path)
        # the matches of _DAE_IMAGE.finditer, found by bytes.find (a match can only start
        # at "<init_from>"; the regex engine tried every byte of a 3 MB mesh)
        at = data.find(_INIT_FROM)
        while at >= 0:
            m = _DAE_IMAGE.match(data, at)
            if m is None:
                at = data.find(_INIT_FROM, at + 1)
                continue
            ref = m.group(1).decode("utf-8", "replace").strip()
            if ref.startswith("file://"):
                ref = ref[7:]
            if _IMAGE_NAME.search(ref):
                refs.append(ref)
            at = data.find(_INIT_FROM, m.end())
    else:
        text = fsbound.read_text(path, max_bytes=MAX_MESH_BYTES, errors="replace")
        if "mtllib" not in text:     # (a 1 MB OBJ without one: no line looked at)
            return {"ok": True, "refs": refs}
        # the lines open() in text mode gives (universal newlines: \r\n and \r become \n),
        # those starting with "mtllib" (the rest of the line: the name, or what a line like
        # "mtllibx y" gives, as before)
        for line in _MTLLIB_LINE.findall(text.replace("\r\n", "\n").replace("\r", "\n")):
            parts = line.split(None, 1)
            if len(parts) == 2:
                refs.append(parts[1].strip())
    return {"ok": True, "refs": refs}


_INIT_FROM = b"<init_from>"
_IMAGE_NAME = re.compile(r"\.(png|jpe?g|tga|bmp|tiff?|gif|dds)$", re.I)
_MTLLIB_LINE = re.compile(r"^mtllib[^\n]*", re.M)


# -- mesh facts (geometry) -------------------------------------------------------------------
_memory: dict[str, Facts] = {}
FACTS_VERSION = 4  # bump when the loader changes what it measures


def _version(path: str) -> tuple[str, int, int]:
    st = os.stat(path)
    from urdf_lint.core.tree import real_path
    return (real_path(path), st.st_size, st.st_mtime_ns)


def _digest(path: str) -> str:
    """Content hash of a file, computed once per file version in this process (shared with
    the worker's record of what a model read, :func:`hashing.memo_digest`). A mesh up to
    ``READ_WHOLE_BYTES`` hashed for the first time is read once: its bytes are kept for the
    readers and scans that follow (:func:`_file_bytes`). An unsaved editor buffer standing
    for the mesh (``urdf-lint server``, :mod:`urdf_lint.core.overlay`) is what the readers
    get: its digest is the buffer's, so its facts are memoized under that content, and the
    parent, which hashes the file itself, never stores them as the file's."""
    data: bytes | None = overlay.get(path) if overlay.active() else None
    if data is not None:
        digest = content_digest(data)
    else:
        got = memo_read(path, READ_WHOLE_BYTES)
        if got is None:
            raise OSError(f"cannot read {path}")
        digest, data = got
    if data is not None:
        _kept_bytes[digest] = data
        _kept_bytes.move_to_end(digest)
        total = sum(map(len, _kept_bytes.values()))
        while total > MAX_KEPT_BYTES and len(_kept_bytes) > 1:
            total -= len(_kept_bytes.popitem(last=False)[1])
    return digest


READ_WHOLE_BYTES = 32 << 20       # meshes up to this size: hashed and parsed from one read
MAX_KEPT_BYTES = 64 << 20         # the bytes kept between the hash, the facts and the scans
_kept_bytes: "OrderedDict[str, bytes]" = OrderedDict()


def _file_bytes(path: str) -> bytes:
    """The bytes of a mesh file: those read for its hash when still kept, else read now."""
    data = _kept_bytes.get(_digest(path))
    if data is not None:
        return data
    return fsbound.read_bytes(path, max_bytes=MAX_MESH_BYTES)


# the libraries that read a model or its meshes: what they log about a model (yourdfpy's
# "Joint 'spinner' is supposed to mimic 'spinner'", 53 times on the broken demo) is the rules'
# job, reported as located findings; it never reaches the user's terminal
LIBRARY_LOGGERS = ("trimesh", "collada", "PIL", "yourdfpy")


def quiet_libraries() -> None:
    import logging
    for name in LIBRARY_LOGGERS:
        lg = logging.getLogger(name)
        lg.setLevel(logging.CRITICAL + 1)
        lg.propagate = False




def load_mesh(path: str) -> Mesh:
    """A trimesh.Trimesh (scene concatenated) or raises.

    A COLLADA file whose geometry is lost to a broken internal reference (a ``<surface>``,
    effect or material that points at nothing makes pycollada drop the whole
    ``<instance_geometry>``) is loaded again without its materials, so a valid mesh is never
    reported empty; the broken references are kept in ``metadata["broken_refs"]``."""
    quiet_libraries()
    import trimesh  # lazy: only rules that need geometry, and the renderer, pay for it
    is_dae = path.lower().endswith(".dae")
    if not is_dae:
        m = trimesh.load(path, force="mesh", process=False)
    else:
        m, failure, lost = None, None, True
        try:
            scene = trimesh.load_scene(path, process=False)   # what force="mesh" does
            m = scene.to_mesh()
            # every <instance_geometry> that loads gives at least one geometry node
            lost = len(scene.graph.nodes_geometry) < \
                _file_bytes(path).count(b"<instance_geometry")
        except Exception as e:  # noqa: BLE001 - retried without materials below
            failure = e
        broken = dae_broken_refs(path) if lost or m is None or len(m.vertices) == 0 else []
        if broken:
            try:
                full = _load_dae_without_materials(path)
                if m is None or len(full.vertices) > len(m.vertices):
                    m = full
            except Exception:  # noqa: BLE001 - report the original problem
                pass
            if m is not None:
                m.metadata["broken_refs"] = broken
        if m is None:
            raise failure if failure is not None else ValueError("the mesh has no geometry")
    assert m is not None
    unit = dae_unit(path) if is_dae else 1.0
    if unit != 1.0:
        # RViz/Gazebo (assimp) honour <unit meter=...>; trimesh does not
        m.apply_scale(unit)  # type: ignore[no-untyped-call]  # trimesh's, unannotated
    return m


def dae_broken_refs(path: str) -> list[str]:
    """The broken internal references pycollada finds in a COLLADA file (messages)."""
    import collada
    ignore = [collada.common.DaeBrokenRefError, collada.common.DaeUnsupportedError,
              collada.common.DaeIncompleteError, collada.common.DaeMalformedError,
              collada.common.DaeError]
    try:
        c = collada.Collada(path, ignore=ignore)
    except Exception:  # noqa: BLE001 - not a broken reference: the caller reports the failure
        return []
    out = []
    for e in c.errors:
        if isinstance(e, collada.common.DaeBrokenRefError):
            msg = error_text(e)
            if msg not in out:
                out.append(msg)
    return out


def _load_dae_without_materials(path: str) -> Mesh:
    """The geometry of a COLLADA file with every material binding, effect and image removed
    (what a broken material reference cannot take down)."""
    import io
    import trimesh
    from lxml import etree
    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                             huge_tree=True)
    root = fsbound.parse_xml(path, parser, max_bytes=MAX_MESH_BYTES)
    drop = {"bind_material", "library_effects", "library_materials", "library_images"}
    for el in [e for e in root.iter() if isinstance(e.tag, str)
               and etree.QName(e).localname in drop]:
        el.getparent().remove(el)
    for el in root.iter():
        if isinstance(el.tag, str) and etree.QName(el).localname in (
                "triangles", "polylist", "polygons", "lines", "tristrips", "trifans"):
            el.attrib.pop("material", None)
    data = etree.tostring(root)
    return trimesh.load(io.BytesIO(data), file_type="dae", force="mesh", process=False)


def error_text(e: BaseException) -> str:
    """``Type: message`` once (pycollada's messages already start with their type)."""
    msg = str(e).strip()
    name = type(e).__name__
    return msg if msg.startswith(name) else f"{name}: {msg}" if msg else name


_DAE_UNIT = re.compile(rb"<unit\b[^>]*\bmeter\s*=\s*[\"']([0-9.eE+-]+)[\"']")


def dae_unit(path: str) -> float:
    """The metres-per-unit a COLLADA file declares in its <asset> (1.0 when absent)."""
    try:
        return _unit_of(fsbound.read_head(path, 8192))
    except OSError:
        return 1.0


def _unit_of(data: bytes) -> float:
    """:func:`dae_unit` of a COLLADA document's bytes (its first 8 KiB)."""
    m = _DAE_UNIT.search(data[:8192])
    try:
        v = float(m.group(1)) if m else 1.0
    except ValueError:
        return 1.0
    return v if math.isfinite(v) and v > 0 else 1.0


_loaded: "OrderedDict[str, Any]" = OrderedDict()
MAX_LOADED_VERTICES = 4_000_000   # bound the in-memory mesh cache of a long-lived worker


def get_mesh(path: str) -> Mesh:
    """The loaded mesh, shared in memory between the rules and the renderer (by content).
    Least recently used meshes are dropped beyond MAX_LOADED_VERTICES."""
    digest = _digest(path)
    if digest in _loaded:
        _loaded.move_to_end(digest)
        return _loaded[digest]
    mesh = load_mesh(path)
    _loaded[digest] = mesh
    total = sum(len(m.vertices) for m in _loaded.values())
    while total > MAX_LOADED_VERTICES and len(_loaded) > 1:
        _, old = _loaded.popitem(last=False)
        total -= len(old.vertices)
    return mesh


def mesh_facts(path: str, cache_dir: str | None = None,
               store: MeshStore | None = None) -> Facts:
    """{ok, error, vertices, faces, finite, bounds, broken_refs} for a mesh file, cached by
    content. Measured on the mesh's arrays (:mod:`urdf_lint.meshes.readers`), never on a processed
    trimesh: a binary STL is streamed in chunks, so its size alone is never an error. The run's
    ``store`` (else one caching in ``cache_dir``) says where it is cached."""
    over = _over_limit(path)
    if over is not None:
        return over
    store = store or MeshStore(cache_dir=cache_dir)
    return _cached(_memory, f"v{FACTS_VERSION}", path, store,
                   lambda p: _measure(p, store.keep_loaded))


def _over_limit(path: str) -> Facts | None:
    """The finding for a mesh file larger than urdf-lint reads (a stat decides it, so it is
    the same on every run without being stored)."""
    try:
        size = os.stat(path).st_size
    except OSError:
        return None
    if size <= MAX_MESH_BYTES:
        return None
    return {"ok": False, "error": f"the file is {size / 2**20:.0f} MiB, over the "
            f"{MAX_MESH_BYTES / 2**20:g} MiB limit of mesh files urdf-lint reads",
            "vertices": 0, "faces": 0, "finite": True, "bounds": None}


def _measure(path: str, keep_loaded: bool = False) -> Facts:
    try:
        from urdf_lint.meshes import readers as meshio
        n = meshio.binary_stl_triangles(path) if path.lower().endswith(".stl") else None
        if n is not None:
            return _stl_facts(path, n)
        if path.lower().endswith(".dae"):
            facts = _collada_facts(path)
            if facts is not None:
                return facts
        v, f, broken = _arrays(path, keep_loaded)
        import numpy as np
        finite, bounds = True, None
        if len(v):
            lo, hi = meshio.bounds(v)
            finite = bool(np.isfinite(lo).all() and np.isfinite(hi).all())
            bounds = [list(map(float, lo)), list(map(float, hi))] if finite else None
        return {"ok": True, "error": "", "vertices": int(len(v)), "faces": int(len(f)),
                "finite": finite, "bounds": bounds, "broken_refs": list(broken)}
    except (PermissionError, MemoryError) as e:
        # the environment refused (sandbox, memory limit): a finding now, never cached
        msg = error_text(e)[:300]
        if isinstance(e, MemoryError):
            msg = ("ran out of memory while loading it (the worker's memory limit, "
                   f"memory-mb): {msg}")[:300]
        raise _Uncached({"ok": False, "error": msg, "vertices": 0,
                         "faces": 0, "finite": True, "bounds": None}) from e
    except Exception as e:  # noqa: BLE001 - any loader failure is a finding
        return {"ok": False, "error": error_text(e)[:300], "vertices": 0,
                "faces": 0, "finite": True, "bounds": None}


def _stl_facts(path: str, n: int) -> Facts:
    """The facts of a binary STL of ``n`` triangles, streamed chunk by chunk."""
    import numpy as np
    from urdf_lint.meshes import readers as meshio
    finite, lo, hi = True, None, None
    for tris in meshio.iter_binary_stl(path, STL_CHUNK, _kept_bytes.get(_digest(path))):
        # a NaN makes its column's minimum NaN, an infinity a minimum or maximum infinite
        clo, chi = meshio.triangle_bounds(tris)
        if not (np.isfinite(clo).all() and np.isfinite(chi).all()):
            finite = False
            break
        lo = clo if lo is None else np.minimum(lo, clo)
        hi = chi if hi is None else np.maximum(hi, chi)
    bounds = [list(map(float, lo)), list(map(float, hi))] \
        if n and finite and lo is not None and hi is not None else None
    return {"ok": True, "error": "", "vertices": 3 * n, "faces": n, "finite": finite,
            "bounds": bounds, "broken_refs": []}


def _collada_facts(path: str) -> Facts | None:
    """The facts of a COLLADA file the lean reader reads, from the bounds of its triangles'
    positions (:func:`meshio.soups_bounds`: no merging of vertices, a third of reading the
    arrays), the unit applied as ``_scene_arrays`` applies it (a positive scale: the bounds
    of the scaled vertices are the scaled bounds). ``vertices`` counts the positions the
    triangles use (trimesh's mesh merges equal corners; the rules ask only whether there are
    any). In every run, a render's too, so that the facts of a file depend on its bytes
    alone. What was read is kept for the file's arrays (:func:`_scene_arrays`: a collision
    mesh's mass properties), so it is parsed once. None when the arrays are read instead."""
    import numpy as np
    from urdf_lint.meshes import readers as meshio
    data = _file_bytes(path)
    soups = meshio.collada_soups(data)
    _keep_lean(_digest(path), soups)
    got = None if soups is None else meshio.soups_bounds(soups)
    if got is None:
        return None
    lo, hi, vertices, faces = got
    unit = _unit_of(data)
    if unit != 1.0:
        lo, hi = meshio.scale_points(np.array([lo, hi]), unit)
    if not (np.isfinite(lo).all() and np.isfinite(hi).all()):
        return None
    return {"ok": True, "error": "", "vertices": int(vertices), "faces": int(faces),
            "finite": True, "bounds": [list(map(float, lo)), list(map(float, hi))],
            "broken_refs": []}


# digest -> the triangle sets the lean reader read of a COLLADA file for its facts, or None
# where it left the file to pycollada; taken by the file's arrays, at most MAX_KEPT_BYTES kept
_lean_read: "OrderedDict[str, Any]" = OrderedDict()


def _keep_lean(digest: str, soups: Any) -> None:
    _lean_read[digest] = soups
    _lean_read.move_to_end(digest)

    def size(parts: Any) -> int:
        return sum(a.nbytes for soup, _ in parts or () for a in soup if a is not None)
    total = sum(size(p) for p in _lean_read.values())
    while total > MAX_KEPT_BYTES and len(_lean_read) > 1:
        total -= size(_lean_read.popitem(last=False)[1])


STL_CHUNK: int | None = None      # triangles per chunk (None: meshio.STL_CHUNK_TRIANGLES)
_arrays_memo: "OrderedDict[str, Arrays]" = OrderedDict()
MAX_MEMO_VERTICES = 1_000_000     # the arrays kept between the facts and the mass rules


def _arrays(path: str, keep_loaded: bool = False) -> Arrays:
    """(vertices float64 (n, 3), faces int64 (m, 3), broken_refs) of a mesh: what
    ``load_mesh`` gives (scene instances placed and stacked, the COLLADA unit applied), from
    the loaders' raw arrays. A render run (``keep_loaded``: it draws the meshes the rules
    measure) loads the mesh and keeps it; a mesh loaded already is used."""
    digest = _digest(path)
    if digest in _arrays_memo:
        _arrays_memo.move_to_end(digest)
        return _arrays_memo[digest]
    import numpy as np
    if digest in _loaded or keep_loaded:
        m = get_mesh(path)
        out = (np.asarray(m.vertices, dtype=np.float64), np.asarray(m.faces, dtype=np.int64),
               list(m.metadata.get("broken_refs", ())))
    else:
        out = _read_arrays(path)
    if len(out[0]) <= MAX_MEMO_VERTICES:
        _arrays_memo[digest] = out
        total = sum(len(a[0]) for a in _arrays_memo.values())
        while total > MAX_MEMO_VERTICES and len(_arrays_memo) > 1:
            _, old = _arrays_memo.popitem(last=False)
            total -= len(old[0])
    return out


def _read_arrays(path: str) -> Arrays:
    import numpy as np
    from urdf_lint.meshes import readers as meshio
    low = path.lower()
    if low.endswith(".stl"):
        n = meshio.binary_stl_triangles(path)
        if n is not None:
            tris = np.concatenate(list(meshio.iter_binary_stl(
                path, data=_kept_bytes.get(_digest(path))))) if n else \
                np.zeros((0, 3, 3), dtype=np.float32)
            v = tris.reshape(-1, 3).astype(np.float64)
            return v, np.arange(len(v), dtype=np.int64).reshape(-1, 3), []
        got = meshio.read_ascii_stl(path)
        if got is not None:
            return got[0], got[1], []
    elif low.endswith(".obj"):
        got = meshio.obj_arrays(_file_bytes(path))   # the same numbers without trimesh
        if got is not None:
            return got[0], got[1], []
        scene = _scene_arrays(path, False)
        assert scene is not None    # (None only for a COLLADA file)
        return scene
    elif low.endswith(".dae"):
        scene = _scene_arrays(path, True)
        if scene is not None:
            return scene
    m = load_mesh(path)     # anything unusual: trimesh decides, as before
    return (np.asarray(m.vertices, dtype=np.float64), np.asarray(m.faces, dtype=np.int64),
            list(m.metadata.get("broken_refs", ())))


def _scene_arrays(path: str, is_dae: bool, lean: bool = True) -> Arrays | None:
    """The arrays of ``load_mesh`` for a COLLADA or OBJ file through ``load_scene``, or None
    when the COLLADA geometry is lost to a broken reference (``load_mesh`` handles that).
    A COLLADA file is read by :func:`meshio.collada_arrays` when it can (``lean``; the same
    numbers, without trimesh)."""
    from urdf_lint.meshes import readers as meshio
    if is_dae and lean:
        data = _file_bytes(path)
        # the same numbers without trimesh, when it can: from what the facts read, or by
        # pycollada alone where the lean reader left the file to it already
        digest = _digest(path)
        if digest in _lean_read:
            soups = _lean_read.pop(digest)
            got = meshio.soups_arrays(soups) if soups is not None else None
            if got is None:
                got = meshio.collada_arrays(data, lean=False)
        else:
            got = meshio.collada_arrays(data)
        if got is not None:
            unit = _unit_of(data)
            v = meshio.scale_points(got[0], unit) if unit != 1.0 else got[0]
            return v, got[1], []
    quiet_libraries()
    import trimesh
    if not is_dae:
        return (*meshio.scene_arrays(trimesh.load_scene(path, process=False)), [])
    try:
        scene = trimesh.load_scene(path, process=False)
    except Exception:  # noqa: BLE001 - load_mesh retries without materials, or reports it
        return None
    lost = len(scene.graph.nodes_geometry) < _file_bytes(path).count(b"<instance_geometry")
    v, f = meshio.scene_arrays(scene)
    if lost or len(v) == 0:
        return None
    unit = dae_unit(path)
    if unit != 1.0:
        v = meshio.scale_points(v, unit)
    return v, f, []




class _Uncached(Exception):
    """A result that depends on the environment, not on the file: returned, never cached."""

    def __init__(self, facts: Facts) -> None:
        super().__init__()
        self.facts = facts


def remember(shared: Iterable[tuple[str, Any]]) -> None:
    """Take in what the run's other workers measured (``LintJob.shared``: (``{prefix}-{digest}``,
    record) under the digest the parent computed): looked up by content like what this
    worker measured itself. With them come the parent's digests of those files
    (``at-{digest}-{path}``, [path, dev, ino, size, mtime_ns]): while a file's stat still
    matches, this worker looks its facts up without reading and hashing it."""
    memories = {f"v{FACTS_VERSION}": _memory, f"mass{MASS_FACTS_VERSION}": _mass_memory,
                f"tex{TEXTURE_SCAN_VERSION}": _scan_memory}
    for name, record in shared:
        prefix, _, digest = str(name).partition("-")
        if prefix == "at":   # the parent's digest of a file at a version (hashing.memo_entry)
            known(record, digest[:32])
            continue
        memory = memories.get(prefix)
        if memory is not None and digest and isinstance(record, dict) and "ok" in record:
            memory.setdefault(digest, record)


def _cached(memory: dict[str, Facts], prefix: str, path: str, store: MeshStore,
            compute: Callable[[str], Facts]) -> Facts:
    """``compute(path)``, memoized in ``memory`` and in the run's facts store (the user's
    :class:`urdf_lint.meshes.store.FactsStore`, read only here), keyed by the file's content.
    What is measured is noted in ``store.measured`` for the parent to store (a result that
    depends on the environment is neither kept nor noted: it is counted in
    ``store.env_failures``)."""
    digest = _digest(path)
    if digest in memory:
        return memory[digest]
    name = f"{prefix}-{digest}"
    facts_store = store.facts()
    if facts_store is not None:
        got = facts_store.get(name)     # signed by this user's urdf-lint, else measured again
        if got is not None:
            memory[digest] = got
            return got
    try:
        facts = compute(path)
    except _Uncached as e:
        store.env_failures += 1     # the model's result must not be cached either
        return e.facts
    memory[digest] = facts
    # for the parent: stored (cache_dir), and handed to the run's other workers
    store.measured.append([name, path, digest, facts])
    return facts


# -- mass properties (for the physical plausibility rules) ----------------------------------
_mass_memory: dict[str, Facts] = {}
MASS_FACTS_VERSION = 2


def mass_facts(path: str, cache_dir: str | None = None,
               store: MeshStore | None = None) -> Facts:
    """Volume properties of a mesh filled with unit density, cached by content (like
    ``mesh_facts``): {ok, volume, first (∫r dV), second (∫r rᵀ dV, 3x3, mesh frame),
    bounds, hull}. ``hull`` is True when the mesh is not watertight and its convex hull was
    used instead (an open surface has no volume)."""
    store = store or MeshStore(cache_dir=cache_dir)
    return _cached(_mass_memory, f"mass{MASS_FACTS_VERSION}", path, store,
                   lambda p: _measure_mass(p, store.keep_loaded))


def _measure_mass(path: str, keep_loaded: bool = False) -> Facts:
    try:
        from urdf_lint.meshes import readers as meshio
        n = meshio.binary_stl_triangles(path) if path.lower().endswith(".stl") else None
        if n is not None and n > (STL_CHUNK or meshio.STL_CHUNK_TRIANGLES):
            return _stl_mass_chunked(path, n)
        v, f, _ = _arrays(path, keep_loaded)
        return _mass_arrays(v, f)
    except (PermissionError, MemoryError) as e:
        raise _Uncached({"ok": False}) from e
    except Exception:  # noqa: BLE001 - UL404 reports meshes that do not load
        return {"ok": False}


def trimesh_mass_properties(mesh: Mesh) -> Facts:
    import numpy as np
    return _mass_arrays(np.asarray(mesh.vertices, dtype=float),
                        np.asarray(mesh.faces, dtype=np.int64))


def _mass_arrays(v: "np.ndarray", f: "np.ndarray") -> Facts:
    import numpy as np
    from urdf_lint.meshes.readers import bounds, mass_properties
    if len(v) == 0 or len(f) == 0 or not np.isfinite(v).all():
        return {"ok": False}
    lo, hi = bounds(v)
    hull = not _closed(v, f)
    if hull:
        try:
            h = _convex_hull(v)
        except Exception:  # noqa: BLE001 - flat or degenerate: no volume to judge
            return {"ok": False}
        tris = np.asarray(h.vertices)[np.asarray(h.faces)]
    else:
        tris = v[f]
    with np.errstate(divide="ignore", invalid="ignore"):   # (no volume: judged below)
        volume, com, inertia = mass_properties(tris)
    vol = float(volume)
    if not math.isfinite(vol) or abs(vol) < 1e-15:
        return {"ok": False}
    sign = 1.0 if vol > 0 else -1.0      # inside-out winding: every moment flips sign
    vol *= sign
    com = np.asarray(com, dtype=float)
    inertia = sign * np.asarray(inertia, dtype=float)   # about com, density 1
    s_com = np.trace(inertia) / 2.0 * np.eye(3) - inertia
    second = s_com + vol * np.outer(com, com)
    return {"ok": True, "volume": vol, "first": (vol * com).tolist(), "second": second.tolist(),
            "bounds": [lo.tolist(), hi.tolist()], "hull": bool(hull)}


def _closed(v: "np.ndarray", f: "np.ndarray") -> bool:
    """Whether the triangles bound a volume: with coincident vertices merged, every directed
    edge occurs once and its reverse occurs too (watertight, consistently wound). Cheaper than
    building a processed trimesh.Trimesh for it."""
    from urdf_lint.meshes.readers import merged_ids
    return _closed_faces(merged_ids(v)[f])     # vertices merged as trimesh's unique_rows does


def _closed_faces(ff: "np.ndarray") -> bool:
    """``_closed`` on faces already indexing merged vertices."""
    import numpy as np
    ff = ff[(ff[:, 0] != ff[:, 1]) & (ff[:, 1] != ff[:, 2]) & (ff[:, 0] != ff[:, 2])]
    if len(ff) < 4:
        return False
    e = np.stack([ff[:, [0, 1]], ff[:, [1, 2]], ff[:, [2, 0]]], axis=1).reshape(-1, 2)
    n = int(ff.max()) + 1
    code = np.sort(e[:, 0] * n + e[:, 1])
    if (code[1:] == code[:-1]).any():
        return False
    # every edge once, so the reverses are distinct too: each is an edge exactly when the two
    # sets are equal (two sorts: faster than a search of each reverse among the edges)
    return bool(np.array_equal(code, np.sort(e[:, 1] * n + e[:, 0])))


MAX_MASS_TRIANGLES = 6_000_000   # above: no mass facts (~15 s, ~1 GB at 5M; the inertia rules skip it)


def _stl_mass_chunked(path: str, n: int) -> Facts:
    """Mass properties of a binary STL too large to hold as one float64 array: the volume
    integrals are summed chunk by chunk, closedness is tested on one int64 code per directed
    edge (from its ends rounded like ``unique_rows``), and an open surface (a second pass)
    uses the hull of the chunks' hulls."""
    import numpy as np
    from urdf_lint.meshes import readers as meshio
    if n > MAX_MASS_TRIANGLES:
        return {"ok": False, "error": f"{n} triangles: over the {MAX_MASS_TRIANGLES} "
                "urdf-lint measures volumes of"}
    integ = np.zeros(10)
    codes, revs = [], []
    lo = hi = apex = None
    for tris in meshio.iter_binary_stl(path, STL_CHUNK):
        t = tris.astype(np.float64)
        if not np.isfinite(t).all():
            return {"ok": False}
        if apex is None and len(t):
            apex = t[0, 0].copy()      # one apex for every chunk: their sums add up
        integ += meshio.volume_integrals(t, apex)
        code, rev = meshio.edge_codes(t)
        codes.append(code)
        revs.append(rev)
        clo, chi = meshio.bounds(t.reshape(-1, 3))
        lo = clo if lo is None else np.minimum(lo, clo)
        hi = chi if hi is None else np.maximum(hi, chi)
    if lo is None:
        return {"ok": False}
    hull = not _closed_codes(codes, revs)
    del codes, revs
    if hull:
        try:
            parts = []
            for tris in meshio.iter_binary_stl(path, STL_CHUNK):
                pts = tris.reshape(-1, 3).astype(np.float64)
                try:
                    parts.append(np.asarray(_convex_hull(pts).vertices))
                except Exception:  # noqa: BLE001 - a flat chunk: keep its points
                    parts.append(pts)
            h = _convex_hull(np.concatenate(parts))
        except Exception:  # noqa: BLE001 - flat or degenerate: no volume to judge
            return {"ok": False}
        integ = meshio.volume_integrals(np.asarray(h.vertices)[np.asarray(h.faces)])
    vol, first, second = meshio.moments(integ)
    if not math.isfinite(vol) or abs(vol) < 1e-15:
        return {"ok": False}
    sign = 1.0 if vol > 0 else -1.0
    return {"ok": True, "volume": sign * vol, "first": (sign * first).tolist(),
            "second": (sign * second).tolist(),
            "bounds": [lo.tolist(), hi.tolist()] if lo is not None and hi is not None else None,
            "hull": bool(hull)}


def _closed_codes(codes: list["np.ndarray"], revs: list["np.ndarray"]) -> bool:
    """``_closed`` for millions of faces, on the chunks' directed edge codes
    (:func:`meshio.edge_codes`): every code once, and sorted they equal their reverses sorted
    (no merge of vertices, no random-access search over the whole array)."""
    import numpy as np
    code = np.concatenate(codes)
    if len(code) < 12:
        return False
    code.sort()
    if (code[1:] == code[:-1]).any():
        return False
    rev = np.concatenate(revs)
    rev.sort()
    return bool(np.array_equal(code, rev))


_sched_getcpu: Any = None


def _current_cpu() -> int | None:
    """The CPU this thread runs on (glibc's ``sched_getcpu``; None where there is none)."""
    global _sched_getcpu
    if _sched_getcpu is None:
        try:
            import ctypes
            _sched_getcpu = ctypes.CDLL(None).sched_getcpu
        except (OSError, AttributeError):
            _sched_getcpu = False
    if not _sched_getcpu:
        return None
    cpu = int(_sched_getcpu())
    return cpu if cpu >= 0 else None


@contextlib.contextmanager
def _one_cpu() -> Iterator[None]:
    """This thread on the CPU it runs on, within. manifold3d runs a hull on TBB, whose
    thread pool takes the size of the process's CPU set when it starts: started within, it
    has no thread to hand work to. A hull here takes milliseconds, and the run's other
    workers hold the other cores: measured on the corpus's 13 open meshes, threads made it
    no faster and cost 75% more CPU (0.077 s against 0.044 s)."""
    get = getattr(os, "sched_getaffinity", None)
    put = getattr(os, "sched_setaffinity", None)
    try:
        cpus = get(0) if get is not None and put is not None else None
        here = _current_cpu()
        if cpus is not None and len(cpus) > 1 and here in cpus:
            put(0, {here})           # type: ignore[misc]
        else:
            cpus = None
    except OSError:
        cpus = None
    try:
        yield
    finally:
        if cpus is not None:
            try:
                put(0, cpus)         # type: ignore[misc]
            except OSError:
                pass


def _convex_hull(points: "np.ndarray") -> Any:   # .vertices, .faces
    """The convex hull of points (``.vertices``, ``.faces``), with manifold3d (a 4 MB wheel
    that imports in milliseconds; trimesh's own hull needs scipy, 100+ MB and ~0.7 s to
    import)."""
    import types
    import manifold3d
    import numpy as np
    with _one_cpu():
        m = manifold3d.Manifold.hull_points(
            np.ascontiguousarray(points, dtype=np.float64)).to_mesh()
    verts = np.asarray(m.vert_properties, dtype=float)[:, :3]
    faces = np.asarray(m.tri_verts, dtype=np.int64)
    if len(faces) < 4:
        raise ValueError("degenerate hull")
    return types.SimpleNamespace(vertices=verts, faces=faces)
