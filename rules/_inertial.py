"""Helpers for the inertial rules (not a rule): declared mass and inertia, and the rigid bodies
that physics engines actually simulate.

KDL, Pinocchio and Gazebo merge every link attached by a ``fixed`` joint into its parent, so
the unit that moves is a *body*: a link that is the child of a non-fixed joint (or the root),
together with everything fixed to it. A massless sensor frame fixed to a heavy link is valid;
a body that moves and has no mass at all is not.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, cast

from urdf_lint.engine.api import number

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.engine.api import Model

INERTIA = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
# sdformat's URDF conversion drops a link of at most this mass (measured with sdformat 12.3)
SDF_DROPPED = 1e-6


def mass(lk: Any) -> float | None:
    """The declared mass (float) of a link, or None when absent or not a number."""
    m = lk.find("inertial/mass")
    return number(m.get("value")) if m is not None else None


def tensor(lk: Any) -> dict[str, float] | None:
    """{ixx..izz} of a link's declared inertia (missing values are 0), or None when absent or
    any value is not a number (UL206 reports those)."""
    i = lk.find("inertial/inertia")
    if i is None:
        return None
    v = {a: number(i.get(a, "0")) for a in INERTIA}
    return None if any(x is None for x in v.values()) else cast("dict[str, float]", v)


def is_zero(t: dict[str, float] | None) -> bool:
    return t is not None and all(x == 0 for x in t.values())


class Bodies:
    """The fixed-merged bodies of a model."""

    def __init__(self, model: Model) -> None:
        self.model = model
        self.parent_joint: dict[str, Any] = {}    # child link name -> first joint naming it as child
        self.children: dict[str, list[tuple[Any, str]]] = {}   # parent link name -> [(joint, child name)]
        for j in model.top_joints():
            p, c = j.find("parent"), j.find("child")
            if p is None or c is None or not p.get("link") or not c.get("link"):
                continue
            self.parent_joint.setdefault(c.get("link"), j)
            self.children.setdefault(p.get("link"), []).append((j, c.get("link")))
        self._merged: dict[str, float] = {}   # merged_mass, per link

    def root_of(self, name: str) -> tuple[str, Any]:
        """(body root link name, the non-fixed joint that moves it or None), following fixed
        joints up from ``name``."""
        seen: set[str] = set()
        while name not in seen:
            seen.add(name)
            j = self.parent_joint.get(name)
            if j is None:
                return name, None
            if j.get("type") != "fixed":
                return name, j
            name = j.find("parent").get("link")
        return name, None  # a loop (UL102 reports it)

    def members(self, root: str) -> list[str]:
        """Link names of the body rooted at ``root`` (the root and everything fixed below it)."""
        out: list[str] = []
        todo = [root]
        while todo:
            n = todo.pop()
            if n in out:
                continue
            out.append(n)
            todo.extend(c for j, c in self.children.get(n, ()) if j.get("type") == "fixed")
        return out

    def subtree_mass(self, root: str) -> float:
        """Total declared mass of ``root`` and every link below it, through any joint."""
        total, todo = 0.0, [root]
        seen: set[str] = set()
        while todo:
            n = todo.pop()
            if n in seen:
                continue
            seen.add(n)
            lk = self.model.links.get(n)
            total += max(mass(lk) or 0.0, 0.0) if lk is not None else 0.0
            todo.extend(c for _j, c in self.children.get(n, ()))
        return total

    def merged_mass(self, name: str) -> float:
        """The mass Gazebo's URDF conversion (sdformat) gives the link: its own plus that of
        the links fixed below it which it merges in, from the leaves up; a link of at most
        :data:`SDF_DROPPED` kg is dropped instead, with everything below it."""
        memo = self._merged

        def walk(n: str, seen: frozenset[str]) -> float:
            if n not in memo:
                lk = self.model.links.get(n)
                total = max(mass(lk) or 0.0, 0.0) if lk is not None else 0.0
                for j, c in self.children.get(n, ()):
                    if j.get("type") == "fixed" and c not in seen:
                        m = walk(c, seen | {n})
                        total += m if m > SDF_DROPPED else 0.0
                memo[n] = total
            return memo[n]
        return walk(name, frozenset())

    def moving_body(self, name: str) -> tuple[str, Any, list[Any]] | None:
        """(root, joint, member link elements) when the link belongs to a body that a non-fixed
        joint moves, else None."""
        root, j = self.root_of(name)
        if j is None:
            return None
        links = [self.model.links[n] for n in self.members(root) if n in self.model.links]
        return root, j, links
