"""The one module a rule imports from urdf-lint: what a check yields (:class:`Report`, a
:class:`Cause`), the fix requests it may attach (``set_attrs``, ``rename_tag``, ...), the mesh
types it may need (``MeshStatus``, ``MeshFacts``, ``MassFacts``; the look-ups themselves are
the context's: ``ctx.mesh_ref``, ``ctx.mesh_facts``, ``ctx.mass_facts``, ``ctx.texture_refs``)
and small helpers (number parsing, "did you mean"). A rule imports nothing else of urdf_lint
except its own private helper modules (``rules/_*.py``); ``tests/test_rule_api.py`` checks it.

Every name here is a real one, which mypy and editors see: the fix kinds' request functions
are imported from their kinds' modules (the block written by ``scripts/gen_docs.py`` from each
kind's ``REQUESTS``; ``tests/test_rule_api.py`` fails while it is stale), ``MeshStatus`` from
its own small module, so that ``urdf-lint expand`` still imports no mesh resolver. A kind
added at run time (a folder appended to :mod:`urdf_lint.fix.kinds`) is found on first use.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Iterable

from urdf_lint.core.findings import Cause
from urdf_lint.core.locations import Origin, display_path
from urdf_lint.core.suggest import did_you_mean
from urdf_lint.fix.fixes import Request, names_in_scope
from urdf_lint.meshes.facts import MassFacts, MeshFacts
from urdf_lint.meshes.status import MeshStatus


__all__ = ["Cause", "MassFacts", "MeshFacts", "MeshStatus", "Origin", "Report", "Request",
           "binary_stl_triangles", "did_you_mean", "display_path", "fmt", "mesh_mass_properties",
           "names_in_scope", "number", "numbers", "read_head", "read_source", "reference_fixes",
           "single_candidate", "top"]

# generated: requests
from urdf_lint.fix.kinds.add_dollar import add_dollar as add_dollar
from urdf_lint.fix.kinds.drop_attrs import drop_attrs as drop_attrs
from urdf_lint.fix.kinds.named_material import named_material as named_material
from urdf_lint.fix.kinds.new_root import new_root as new_root
from urdf_lint.fix.kinds.rename_at import rename_at as rename_at
from urdf_lint.fix.kinds.rename_attr import rename_attr as rename_attr
from urdf_lint.fix.kinds.rename_tag import rename_tag as rename_tag
from urdf_lint.fix.kinds.set import set_attrs as set_attrs
__all__ += ["add_dollar", "drop_attrs", "named_material", "new_root", "rename_at",
            "rename_attr", "rename_tag", "set_attrs"]
# end: requests


@dataclass(frozen=True)
class Report:
    """One problem a rule's ``check`` found: where (``element``, an element of the model; a
    run-scope rule gives an :class:`urdf_lint.core.locations.Origin`, and so may a model rule
    for a place in a source that no element has) and what (``message``).
    ``severity`` raises or lowers the rule's severity for this one problem; ``fix`` is a fix
    request (``set_attrs`` and the other requests here); ``targets`` a severity per consumer
    target for this one problem (:mod:`urdf_lint.core.targets`); ``cause`` the root cause it
    is an instance of (:class:`Cause`); ``related`` the robot's element a finding placed in a
    configuration file (an ``Origin`` in an SRDF or a controller YAML) is about: its xacro line
    is shown as the related location."""
    element: Any
    message: str
    severity: str | None = None
    fix: Request | None = None
    targets: dict[str, str] | None = None
    cause: Cause | None = None
    related: Any = None


if TYPE_CHECKING:   # what a rule's ``check`` is typed with (rules import them the same way)
    from collections.abc import Iterator

    from urdf_lint.engine.configs import ConfigDoc as ConfigDoc, YNode as YNode   # ctx.configs
    from urdf_lint.engine.lint import Context as Context
    from urdf_lint.engine.model import Model as Model
    Checked = Iterator[Report]   # def check(model: Model, ctx: Context) -> Checked


if not TYPE_CHECKING:      # hidden from mypy: a name not defined above is a mistake there
    def __getattr__(name: str) -> Any:
        """The request function of a fix kind added at run time (``REQUESTS`` of a module in
        a folder appended to :mod:`urdf_lint.fix.kinds`); the built-in ones are imported
        above."""
        from urdf_lint.fix.kinds import requests
        value = requests().get(name)
        if value is None:
            raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
        globals()[name] = value
        return value


def mesh_mass_properties(mesh: Any) -> MassFacts:
    """The volume properties of a loaded mesh (a ``trimesh.Trimesh``) filled with unit
    density, as the mesh facts give them for a file (``ctx.mass_facts``)."""
    from urdf_lint.meshes.resolve import trimesh_mass_properties
    return MassFacts.from_record(trimesh_mass_properties(mesh))


def read_source(path: str, max_bytes: int | None = None) -> bytes | None:
    """The bytes of a source file the model read, through the file-system boundary (a regular
    file of bounded size), or None when it cannot or may not be read."""
    from urdf_lint.core import fsbound
    return fsbound.read_regular(path, fsbound.MAX_SOURCE_BYTES if max_bytes is None else max_bytes)


def read_head(path: str, n: int) -> bytes | None:
    """The first ``n`` bytes of a file the model read (a mesh's magic bytes), through the
    file-system boundary, or None when it cannot or may not be read."""
    from urdf_lint.core import fsbound
    try:
        return fsbound.read_head(path, n)
    except OSError:                       # BoundaryError too
        return None


def binary_stl_triangles(path: str) -> int | None:
    """The triangle count a binary STL declares when its size agrees with it, else None (an
    ASCII STL, or not an STL)."""
    from urdf_lint.meshes.readers import binary_stl_triangles as count
    n: int | None = count(path)
    return n


def number(s: str | None) -> float | None:
    """A finite float from an attribute value, or None."""
    if s is None:
        return None
    try:
        v = float(s.strip())
    except (ValueError, AttributeError):
        return None
    return v if math.isfinite(v) else None


def numbers(s: str | None, n: int | None = None) -> list[float] | None:
    """A list of finite floats from a whitespace-separated value (None if any is bad)."""
    if s is None:
        return None
    parts = s.split()
    if n is not None and len(parts) != n:
        return None
    out = []
    for p in parts:
        v = number(p)
        if v is None:
            return None
        out.append(v)
    return out


CLEAR_MARGIN = 0.15


def single_candidate(word: str, candidates: Iterable[str], cutoff: float = 0.6) -> str | None:
    """The one close match of ``word`` among ``candidates`` (None when there are none or
    several): what a "did you mean" fix may apply. With a ``cutoff`` above 0.6 (references),
    a second candidate a "did you mean" would consider (similarity 0.6) within
    ``CLEAR_MARGIN`` of the first makes two: 'left_finger'
    (0.79 to left_finger_joint, 0.67 to left_inner_joint) is not fixed, 'bse_link' (0.94 to
    base_link, 0.63 to arm_link) is."""
    import difflib   # (only for a name that is not found)
    m = difflib.get_close_matches(word, list(candidates), n=2, cutoff=min(cutoff, 0.6))
    if not m:
        return None
    r = [difflib.SequenceMatcher(None, word, c).ratio() for c in m]
    if r[0] < cutoff or (len(m) == 2 and (cutoff <= 0.6 or r[1] > r[0] - CLEAR_MARGIN)):
        return None
    return m[0]


def reference_fixes(broken: Iterable[tuple[Any, str, str]], candidates: Iterable[str],
                    taken: Iterable[str] = ()) -> dict[tuple[Any, str], Request]:
    """{(element, attr): fix request} for broken references ``broken`` (``(element, attr,
    name)``) that have one close candidate (similarity 0.75) which no other reference of the
    same kind already names and no other broken reference would take too."""
    guess = {(el, a): single_candidate(n, candidates, 0.75) for el, a, n in broken}
    counts: dict[str | None, int] = {}
    for g in guess.values():
        counts[g] = counts.get(g, 0) + 1
    return {k: set_attrs({k[1]: g}, f"point the reference at '{g}'")
            for k, g in guess.items() if g and counts[g] == 1 and g not in set(taken)}


def fmt(v: float) -> str:
    """Short, readable number."""
    return f"{v:g}"


def top(model: Any, tag: str) -> list[Any]:
    return [e for e in model.root if e.tag == tag]
