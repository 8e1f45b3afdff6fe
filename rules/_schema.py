"""The URDF element/attribute schema shared by UL209 and UL210, and the names a xacro source
writes (not a rule: starts with _)."""
from __future__ import annotations

import re
from typing import TYPE_CHECKING, Any, Iterator

from urdf_lint.engine.api import names_in_scope, read_source

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.engine.api import Model

CHILDREN = {
    "robot": {"link", "joint", "material", "transmission", "gazebo", "ros2_control", "mujoco",
              "sensor", "plugin"},
    "link": {"inertial", "visual", "collision", "self_collision_checking"},
    "inertial": {"origin", "mass", "inertia"},
    "visual": {"origin", "geometry", "material"},
    "collision": {"origin", "geometry", "verbose"},
    "geometry": {"box", "cylinder", "sphere", "mesh", "capsule"},
    "material": {"color", "texture"},
    "joint": {"origin", "parent", "child", "axis", "calibration", "dynamics", "limit", "mimic",
              "safety_controller"},
}
# elements whose content belongs to other tools (Gazebo, ros2_control, MuJoCo ...)
FREE_FORM = {"transmission", "gazebo", "ros2_control", "mujoco", "sensor", "plugin"}
ATTRIBUTES = {
    "robot": {"name", "version"},
    "link": {"name", "type"},
    "joint": {"name", "type"},
    "origin": {"xyz", "rpy", "quat_xyzw"},                  # quat_xyzw: URDF 1.1
    "mass": {"value"},
    "inertia": {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"},
    "visual": {"name"},
    "collision": {"name"},
    "verbose": {"value"},
    "box": {"size"},
    "cylinder": {"radius", "length"},
    "capsule": {"radius", "length"},
    "sphere": {"radius"},
    "mesh": {"filename", "scale"},
    "material": {"name"},
    "color": {"rgba"},
    "texture": {"filename"},
    "parent": {"link"},
    "child": {"link"},
    "axis": {"xyz"},
    "calibration": {"rising", "falling", "reference_position"},
    "dynamics": {"damping", "friction"},
    "limit": {"lower", "upper", "effort", "velocity",
              "acceleration", "deceleration", "jerk"},                  # the last three: URDF 1.2
    "mimic": {"joint", "multiplier", "offset"},
    "safety_controller": {"soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"},
}




# xacro directives: written without their prefix, xacro copies them into the URDF as they are
XACRO_WORDS = {"macro", "property", "arg", "include", "insert_block", "if", "unless", "call",
               "element", "attribute", "eval-comments"}
# children URDF reads once (the first): a second one is ignored
SINGLE = {
    "link": {"inertial"},
    "inertial": {"origin", "mass", "inertia"},
    "visual": {"origin", "geometry", "material"},
    "collision": {"origin", "geometry"},
    "joint": {"origin", "parent", "child", "axis", "calibration", "dynamics", "limit", "mimic",
              "safety_controller"},
}
_MACRO_DEF: re.Pattern[bytes] | None = None


def macro_names(model: Model) -> set[str]:
    """The names of the xacro macros defined in the files the model was expanded from (read
    again here, as xacro read them; an empty set for a plain URDF)."""
    cached: set[str] | None = getattr(model, "_macro_names", None)
    if cached is not None:
        return cached
    global _MACRO_DEF
    import re
    _MACRO_DEF = _MACRO_DEF or re.compile(rb"<[A-Za-z_][\w.-]*:macro\s[^>]*?name\s*=\s*[\"']([^\"'$]+)")
    names: set[str] = set()
    for f in [model.entry, *model.deps]:
        if not str(f).endswith(".xacro"):
            continue
        data = read_source(f)   # a regular file of bounded size, through the boundary
        if data:
            names.update(n.decode("utf-8", "replace") for n in _MACRO_DEF.findall(data))
    try:
        model._macro_names = names   # type: ignore[attr-defined]  # a memo on the model
    except AttributeError:
        pass
    return names


def _checked(model: Model) -> tuple[list[Any], dict[str, list[Any]]]:
    """(the elements of the URDF schema: not namespaced (``drake:...``), not inside a free-form
    extension element (``FREE_FORM``); in document order, and the same by tag),
    found in one walk of the model's tree, once per model: every rule that walks the URDF
    part of the document shares it (no rule changes the tree)."""
    memo: tuple[list[Any], dict[str, list[Any]]] | None = getattr(model, "_urdf_elements", None)
    if memo is not None:
        return memo
    elements: list[Any] = []
    by_tag: dict[str, list[Any]] = {}
    within: dict[Any, bool] = {}     # element -> its children are inside an extension block
    for el in model.root.iter():
        tag = el.tag
        if not isinstance(tag, str):
            continue
        parent = el.getparent()
        inside = parent is not None and within[parent]
        within[el] = inside or tag in FREE_FORM
        if not (inside or tag.startswith("{") or ":" in tag):
            elements.append(el)
            by_tag.setdefault(tag, []).append(el)
    try:
        model._urdf_elements = (elements, by_tag)   # type: ignore[attr-defined]  # a memo on the model
    except AttributeError:
        pass
    return elements, by_tag


def checked_elements(model: Model) -> Iterator[Any]:
    """Elements of the URDF schema (not namespaced, not inside extension blocks)."""
    return iter(_checked(model)[0])


def urdf_iter(model: Model, tag: str) -> Iterator[Any]:
    """The ``<tag>`` elements of the URDF part of the document: what ``model.root.iter(tag)``
    gives, minus anything inside ``<gazebo>`` (SDF), ``<ros2_control>``, ``<transmission>`` and
    the other extension blocks, and minus namespaced elements. Every rule about URDF elements
    walks the document through this (or ``checked_elements``)."""
    return iter(_checked(model)[1].get(tag, ()))


# a literal {name} anywhere in the value, also after a word character (arm_{side}_link); not
# ${name} and not an expression's {} (after "}")
BRACED = re.compile(r"(?<![$}]){([A-Za-z_]\w*)}")


def literal_names(model: Model, value: str, known: set[str] | None = None) -> list[str]:
    """The property / parameter names written as a literal ``{name}`` in ``value``."""
    hits = BRACED.findall(value) if value and "{" in value else []
    if not hits:
        return []
    known = names_in_scope(model) if known is None else known
    return [h for h in hits if h in known]
