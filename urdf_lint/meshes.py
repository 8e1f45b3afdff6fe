"""Mesh references: resolution through the package resolver, confinement, and mesh facts.

Resolution and existence checks are pure path work (no trimesh). Loading a mesh (for the
rules that need its geometry, and for rendering) imports trimesh lazily, and its facts are
cached by file content, so a mesh is read once per change, not once per model or run.
"""
from __future__ import annotations

import enum
import json
import math
import os
import re
from collections import OrderedDict
from dataclasses import dataclass
from pathlib import Path

from .hashing import file_digest
from .packages import PackageNotFound


class MeshStatus(enum.Enum):
    """How a mesh or texture reference resolved (the UL4xx rules map these to codes)."""
    OK = "ok"                          # an existing file inside the package roots
    UNKNOWN_PACKAGE = "unknown-package"
    NOT_FOUND = "not-found"
    CASE_MISMATCH = "case-mismatch"    # exists only with different letter case
    OUTSIDE_ROOTS = "outside-roots"    # resolves outside the package roots: never read


@dataclass
class MeshRef:
    uri: str
    path: str | None          # resolved absolute path (None when it cannot be resolved)
    status: MeshStatus
    message: str = ""

    @property
    def problem(self) -> MeshStatus | None:
        """None when the reference resolved (``status is MeshStatus.OK``), else its status.
        Kept for rules written before :class:`MeshStatus`; new code reads ``status``."""
        return None if self.status is MeshStatus.OK else self.status


def _case_true_path(path: Path) -> tuple[bool, str | None]:
    """(exists with exact case, the real spelling if it only exists with another case)."""
    parts = path.parts
    cur = Path(parts[0])
    exact = True
    for part in parts[1:]:
        try:
            names = os.listdir(cur)
        except OSError:
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


def resolve(model, uri: str) -> MeshRef:
    resolver = model.resolver
    try:
        p = resolver.resolve_uri(uri, model.base_dir)
    except PackageNotFound as e:
        return MeshRef(uri, None, MeshStatus.UNKNOWN_PACKAGE, f"mesh '{uri}': {e}")
    p = Path(os.path.abspath(p))
    exact, real = _case_true_path(p)
    if not exact and real is None:
        return MeshRef(uri, str(p), MeshStatus.NOT_FOUND, f"mesh file not found: '{uri}' (looked for {p})")
    if not exact:
        return MeshRef(uri, real, MeshStatus.CASE_MISMATCH, f"mesh '{uri}' only exists as '{os.path.basename(real)}' "
                       f"(case differs: works on macOS/Windows, fails on Linux)")
    if not resolver.is_inside(p):
        return MeshRef(uri, None, MeshStatus.OUTSIDE_ROOTS, f"mesh '{uri}' resolves to {os.path.realpath(p)}, outside "
                       "the package roots; it is not read")
    return MeshRef(uri, str(p), MeshStatus.OK)


_DAE_IMAGE = re.compile(rb"<init_from>\s*([^<]+?)\s*</init_from>")
_MTL_MAP = re.compile(r"^\s*(?:map_\w+|bump|disp|decal|refl)\s+(?:-\S+\s+\S+\s+)*(\S.*?)\s*$", re.M)


_textures: dict = {}


def texture_refs(path: str) -> list[str]:
    """Image files a DAE or OBJ(+MTL) mesh refers to, as absolute paths (memoized per version)."""
    try:
        key = _version(path)
    except OSError:
        return []
    if key not in _textures:
        _textures[key] = _texture_refs(path)
    return list(_textures[key])


def _texture_refs(path: str) -> list[str]:
    out = []
    base = os.path.dirname(path)
    low = path.lower()
    try:
        if low.endswith(".dae"):
            with open(path, "rb") as f:
                data = f.read()
            for m in _DAE_IMAGE.finditer(data):
                ref = m.group(1).decode("utf-8", "replace").strip()
                if ref.startswith("file://"):
                    ref = ref[7:]
                if re.search(r"\.(png|jpe?g|tga|bmp|tiff?|gif|dds)$", ref, re.I):
                    out.append(os.path.normpath(os.path.join(base, ref)))
        elif low.endswith(".obj"):
            with open(path, "r", errors="replace") as f:
                for line in f:
                    if line.startswith("mtllib"):
                        mtl = os.path.normpath(os.path.join(base, line.split(None, 1)[1].strip()))
                        out.append(mtl)
                        if os.path.isfile(mtl):
                            with open(mtl, "r", errors="replace") as mf:
                                for m in _MTL_MAP.finditer(mf.read()):
                                    out.append(os.path.normpath(os.path.join(os.path.dirname(mtl),
                                                                             m.group(1))))
    except OSError:
        pass
    return out


# -- mesh facts (geometry) -------------------------------------------------------------------
_memory: dict = {}
FACTS_VERSION = 2  # bump when the loader changes what it measures


_digests: dict = {}


def _version(path: str):
    st = os.stat(path)
    return (os.path.realpath(path), st.st_size, st.st_mtime_ns)


def _digest(path: str) -> str:
    """Content hash of a file, computed once per file version in this process."""
    key = _version(path)
    if key not in _digests:
        _digests[key] = _hash_file(path)
    return _digests[key]


def _hash_file(path: str) -> str:
    digest = file_digest(path)
    if digest is None:
        raise OSError(f"cannot read {path}")
    return digest


def _quiet_loggers():
    import logging
    for name in ("trimesh", "collada", "PIL"):
        lg = logging.getLogger(name)
        lg.setLevel(logging.CRITICAL + 1)
        lg.propagate = False


def load_mesh(path: str):
    """A trimesh.Trimesh (scene concatenated) or raises."""
    _quiet_loggers()
    import trimesh  # lazy: only rules that need geometry, and the renderer, pay for it
    m = trimesh.load(path, force="mesh", process=False)
    unit = dae_unit(path) if path.lower().endswith(".dae") else 1.0
    if unit != 1.0:
        m.apply_scale(unit)  # RViz/Gazebo (assimp) honour <unit meter=...>; trimesh does not
    return m


_DAE_UNIT = re.compile(rb"<unit\b[^>]*\bmeter\s*=\s*[\"']([0-9.eE+-]+)[\"']")


def dae_unit(path: str) -> float:
    """The metres-per-unit a COLLADA file declares in its <asset> (1.0 when absent)."""
    try:
        with open(path, "rb") as f:
            head = f.read(8192)
        m = _DAE_UNIT.search(head)
        v = float(m.group(1)) if m else 1.0
        return v if math.isfinite(v) and v > 0 else 1.0
    except (OSError, ValueError):
        return 1.0


_loaded: "OrderedDict[str, object]" = OrderedDict()
MAX_LOADED_VERTICES = 4_000_000   # bound the in-memory mesh cache of a long-lived worker


def get_mesh(path: str):
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


def mesh_facts(path: str, cache_dir: str | None = None) -> dict:
    """{ok, error, vertices, faces, finite, bounds} for a mesh file, cached by content."""
    digest = _digest(path)
    if digest in _memory:
        return _memory[digest]
    cache_file = None
    if cache_dir:
        cache_file = Path(cache_dir, "meshes", f"v{FACTS_VERSION}-{digest}.json")
        try:
            facts = json.loads(cache_file.read_text())
            if isinstance(facts, dict) and "ok" in facts:
                _memory[digest] = facts
                return facts
        except (OSError, ValueError):
            pass
    try:
        m = get_mesh(path)
        import numpy as np
        v = np.asarray(m.vertices, dtype=float)
        finite = bool(np.isfinite(v).all()) if len(v) else True
        bounds = [list(map(float, v.min(axis=0))), list(map(float, v.max(axis=0)))] \
            if len(v) and finite else None
        facts = {"ok": True, "error": "", "vertices": int(len(v)), "faces": int(len(m.faces)),
                 "finite": finite, "bounds": bounds}
    except (PermissionError, MemoryError) as e:
        # the environment refused (sandbox, memory limit): a finding now, never cached
        return {"ok": False, "error": f"{type(e).__name__}: {e}"[:300], "vertices": 0,
                "faces": 0, "finite": True, "bounds": None}
    except Exception as e:  # noqa: BLE001 - any loader failure is a finding
        facts = {"ok": False, "error": f"{type(e).__name__}: {e}"[:300], "vertices": 0,
                 "faces": 0, "finite": True, "bounds": None}
    _memory[digest] = facts
    if cache_file is not None:
        try:
            from .cachedir import ensure
            ensure(str(Path(cache_dir)))   # the markers, whoever creates the folder first
            cache_file.parent.mkdir(parents=True, exist_ok=True)
            tmp = cache_file.with_suffix(".tmp%d" % os.getpid())
            tmp.write_text(json.dumps(facts))
            os.replace(tmp, cache_file)
        except OSError:
            pass
    return facts


def parse_scale(s):
    if s is None:
        return [1.0, 1.0, 1.0]
    parts = s.split()
    try:
        vals = [float(p) for p in parts]
    except ValueError:
        return None
    if len(vals) != 3 or not all(math.isfinite(v) for v in vals):
        return None
    return vals
