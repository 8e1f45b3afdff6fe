"""What urdf-lint measures of a mesh file, typed: :class:`MeshFacts` (loads? vertices, faces,
bounds, broken internal references) and :class:`MassFacts` (its volume properties at unit
density). They are measured and cached by content as plain records (JSON on disk,
:mod:`urdf_lint.meshes.resolve`); the rules read these types, through ``ctx.mesh_facts`` and
``ctx.mass_facts`` (:class:`urdf_lint.engine.lint.Context`)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

Bounds = tuple[tuple[float, float, float], tuple[float, float, float]]   # (lowest, highest)


def _bounds(b: Any) -> Bounds | None:
    if not b:
        return None
    lo, hi = b
    return (tuple(map(float, lo)), tuple(map(float, hi)))   # type: ignore[return-value]


@dataclass(frozen=True)
class MeshFacts:
    """A mesh file's facts: ``ok`` (it loads; else ``error`` says why), its vertex and face
    counts, whether every vertex is finite, its bounds in the file's frame (None when empty or
    not finite) and the broken internal references of a COLLADA file whose geometry loads.
    The vertex count says whether there are any: a COLLADA file read without merging its
    corners counts the positions its triangles use (``meshes.resolve._collada_facts``)."""
    ok: bool
    error: str = ""
    vertices: int = 0
    faces: int = 0
    finite: bool = True
    bounds: Bounds | None = None
    broken_refs: tuple[str, ...] = ()

    @classmethod
    def from_record(cls, d: dict[str, Any]) -> "MeshFacts":
        """From the record the measurement stores (:func:`urdf_lint.meshes.resolve.mesh_facts`)."""
        return cls(bool(d.get("ok")), str(d.get("error") or ""), int(d.get("vertices") or 0),
                   int(d.get("faces") or 0), bool(d.get("finite", True)), _bounds(d.get("bounds")),
                   tuple(d.get("broken_refs") or ()))


@dataclass(frozen=True)
class MassFacts:
    """A mesh filled with unit density: ``volume``, ``first`` (∫r dV), ``second`` (∫r rᵀ dV,
    3x3, in the mesh frame), ``bounds``, and ``hull`` (the mesh is not closed: its convex hull
    was measured). ``ok`` False: no volume to judge (it does not load, is flat or too large)."""
    ok: bool
    volume: float = 0.0
    first: tuple[float, ...] = ()
    second: tuple[tuple[float, ...], ...] = ()
    bounds: Bounds | None = None
    hull: bool = False

    @classmethod
    def from_record(cls, d: dict[str, Any]) -> "MassFacts":
        """From the record the measurement stores (:func:`urdf_lint.meshes.resolve.mass_facts`)."""
        if not d.get("ok"):
            return cls(False)
        return cls(True, float(d["volume"]), tuple(map(float, d["first"])),
                   tuple(tuple(map(float, row)) for row in d["second"]), _bounds(d.get("bounds")),
                   bool(d.get("hull")))
