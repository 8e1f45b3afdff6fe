"""Helpers for the material rules (not a rule)."""
from urdf_lint.engine.api import numbers
from urdf_lint.rules._schema import urdf_iter


def rgba(material):
    c = material.find("color")
    if c is None:
        return None
    v = numbers(c.get("rgba"), 4)
    return tuple(round(x, 6) for x in v) if v else None


def all_materials(model):
    """(element, name, rgba, is_top_level) for every <material> in the model."""
    out = []
    for m in urdf_iter(model, "material"):
        p = m.getparent()
        if p is model.root or (p is not None and p.tag == "visual"):
            out.append((m, m.get("name"), rgba(m), p is model.root))
    return out
