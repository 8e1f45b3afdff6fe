"""Links and joints in the expanded models: which element a name refers to, the element at a
start tag in every model that expands it, and what hover says of one (its frame at zero)."""
from __future__ import annotations

import math
from typing import Any, Iterator

from urdf_lint.lsp.cursor import At
from urdf_lint.lsp.services import ModelView, Services

# where a name of another element is written: (tag, attribute) -> "link" | "joint" | "any"
NAME_REFS = {("parent", "link"): "link", ("child", "link"): "link", ("mimic", "joint"): "joint",
             ("gazebo", "reference"): "any", ("joint", "name"): "joint",
             ("link", "name"): "link"}
REF_CONTEXT = {"transmission", "ros2_control"}   # a <joint name=...> there names a joint


def targets(sv: Services, path: str, at: At) -> Iterator[tuple[ModelView, Any]]:
    """(model view, element at the cursor's start tag) for every model that expands it."""
    if not at.tag_line:
        return
    for v in sv.views():
        for el in v.at.get((path, at.tag_line, at.tag_col or 0), ()):
            yield v, el


def named(v: ModelView, kind: str, name: str) -> Any:
    kinds = ("link", "joint") if kind == "any" else (kind,)
    for k in kinds:
        el = v.named.get((k, name))
        if el is not None:
            return el
    return None


def ref_kind(el: Any, attr: str) -> str | None:
    kind = NAME_REFS.get((el.tag, attr))
    if el.tag == "joint" and attr == "name":
        parent = el.getparent()
        return "joint" if parent is not None and parent.tag in REF_CONTEXT else None
    if el.tag == "link" and attr == "name":
        return None
    return kind


def describe(el: Any) -> str:
    if el.tag == "joint":
        parts = [f"`{el.get('name')}` {el.get('type')}"]
        p, c = el.find("parent"), el.find("child")
        parts.append(f"parent `{p.get('link') if p is not None else '?'}`, "
                     f"child `{c.get('link') if c is not None else '?'}`")
        lim = el.find("limit")
        if lim is not None:
            parts.append("limits " + ", ".join(f"{k} {lim.get(k)}" for k in
                                                ("lower", "upper", "effort", "velocity")
                                                if lim.get(k) is not None))
        return "; ".join(parts)
    m = el.find("inertial/mass")
    return f"`{el.get('name')}`" + (f"; mass {m.get('value')}" if m is not None else "")


def _frame(el: Any) -> Any:
    """The 4x4 transform of an element's <origin> (URDF: R = Rz(yaw) Ry(pitch) Rx(roll))."""
    import numpy as np
    o = el.find("origin")

    def nums(attr: str) -> list[float]:
        try:
            got = [float(x) for x in (o.get(attr) or "0 0 0").split()] if o is not None \
                else [0.0] * 3
        except ValueError:
            got = [0.0] * 3
        return (got + [0.0] * 3)[:3]
    (x, y, z), (r, p, w) = nums("xyz"), nums("rpy")
    cr, sr, cp, sp, cw, sw = (math.cos(r), math.sin(r), math.cos(p), math.sin(p),
                              math.cos(w), math.sin(w))
    m = np.eye(4)
    m[:3, :3] = [[cw * cp, cw * sp * sr - sw * cr, cw * sp * cr + sw * sr],
                 [sw * cp, sw * sp * sr + cw * cr, sw * sp * cr - cw * sr],
                 [-sp, cp * sr, cp * cr]]
    m[:3, 3] = [x, y, z]
    return m


def world_pose(v: ModelView, el: Any) -> tuple[list[float], list[float]] | None:
    """(xyz, rpy) of a link's or joint's frame at the zero configuration, or None (a loop)."""
    import numpy as np
    by_child = {}
    for j in v.root.findall("joint"):
        c = j.find("child")
        if c is not None:
            by_child[c.get("link")] = j
    chain = [el] if el.tag == "joint" else []
    link = el.find("parent").get("link") if el.tag == "joint" and el.find("parent") is not None \
        else el.get("name")
    seen = set()
    while link in by_child:
        if link in seen:
            return None
        seen.add(link)
        j = by_child[link]
        chain.append(j)
        p = j.find("parent")
        link = p.get("link") if p is not None else None
    m = np.eye(4)
    for j in reversed(chain):
        m = m @ _frame(j)
    rpy = (math.atan2(m[2, 1], m[2, 2]), math.asin(max(-1.0, min(1.0, -m[2, 0]))),
           math.atan2(m[1, 0], m[0, 0]))
    return [round(float(x), 4) + 0.0 for x in m[:3, 3]], [round(r, 4) + 0.0 for r in rpy]


def pose_text(v: ModelView, el: Any) -> str:
    got = world_pose(v, el)
    if got is None:
        return ""
    xyz, rpy = got
    return f"; world pose at zero: xyz {' '.join(map(str, xyz))}, rpy {' '.join(map(str, rpy))}"
