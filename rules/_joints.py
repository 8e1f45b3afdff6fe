"""Helpers for the joint-limit rules (not a rule)."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, Iterable, Iterator

from urdf_lint.engine.api import Request, number, reference_fixes

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.engine.api import Model


def limits(j: Any) -> tuple[Any, float | None, float | None, float | None, float | None]:
    """(limit element or None, lower, upper, effort, velocity) with URDF defaults (0) applied."""
    lim = j.find("limit")
    if lim is None:
        return None, None, None, None, None
    return (lim, number(lim.get("lower", "0")), number(lim.get("upper", "0")),
            number(lim.get("effort")), number(lim.get("velocity")))


def moving(j: Any) -> bool:
    return j.get("type") in ("revolute", "prismatic")


def ranged(model: Model) -> Iterator[tuple[Any, Any, float, float]]:
    """(joint, limit, lower, upper) of revolute/prismatic joints with numeric limits."""
    for j in model.top_joints():
        if moving(j):
            lim, lo, hi, _, _ = limits(j)
            if lim is not None and lo is not None and hi is not None:
                yield j, lim, lo, hi


def unknown_joint_refs(model: Model, pairs: Iterable[tuple[Any, Any]]
                       ) -> list[tuple[Any, Any, str, Request | None]]:
    """(block, joint element, name, fix request or None) for each ``(block, <joint name>)`` of
    ``pairs`` naming a joint the model does not have (transmission, ros2_control)."""
    found: list[tuple[Any, Any, str]] = []
    taken: set[str] = set()
    for blk, j in pairs:
        n = j.get("name")
        if n and n not in model.joints:
            found.append((blk, j, n))
        elif n:
            taken.add(n)
    fixes = reference_fixes([(j, "name", n) for _, j, n in found], model.joints, taken)
    return [(blk, j, n, fixes.get((j, "name"))) for blk, j, n in found]
