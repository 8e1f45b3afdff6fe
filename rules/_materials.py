"""Helpers for the material rules (not a rule)."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

from urdf_lint.engine.api import numbers
from urdf_lint.rules._schema import urdf_iter

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.engine.api import Model


def rgba(material: Any) -> tuple[float, ...] | None:
    c = material.find("color")
    if c is None:
        return None
    v = numbers(c.get("rgba"), 4)
    return tuple(round(x, 6) for x in v) if v else None


def all_materials(model: Model) -> list[tuple[Any, str | None, tuple[float, ...] | None, bool]]:
    """(element, name, rgba, is_top_level) for every <material> in the model."""
    out: list[tuple[Any, str | None, tuple[float, ...] | None, bool]] = []
    for m in urdf_iter(model, "material"):
        p = m.getparent()
        if p is model.root or (p is not None and p.tag == "visual"):
            out.append((m, m.get("name"), rgba(m), p is model.root))
    return out
