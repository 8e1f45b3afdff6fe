"""The semantic difference between two revisions of one robot model.

:func:`robot_facts` reduces a :class:`~urdf_lint.engine.model.Model` to the physical facts a reviewer
cares about (per link: inertial, visual and collision geometry with mesh content hashes,
materials; per joint: type, parent/child, origin, axis, limits, mimic, dynamics, safety
controller), each with the source location that wrote it. :func:`diff_facts` compares two such
fact sets: links and joints matched by name, then by structure (a rename), field-level changes
with float tolerance, and the world pose of every link at the zero configuration with the
largest displacement. Pure data in, pure data out: no git, no expansion, no I/O beyond hashing
mesh files that already resolved inside the package roots.
"""
from __future__ import annotations

import hashlib
import math
import os
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable

from urdf_lint.core.locations import Origin

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.engine.model import Model

Element = Any   # an lxml element (lxml ships no type information here)
Vec = tuple[float, ...]
Rot = tuple[Vec, ...]
Pose = tuple[Rot, Vec]             # (rotation, translation)
Key = tuple[str, str]              # (kind, name)
FindingKey = tuple[str, str, str]  # (code, file relative to its revision, message)
Locate = Callable[[Element], "Origin | None"]
ValueSource = Callable[["_Fact | None", str], tuple[Any, ...]]

_TOL = 1e-9          # relative/absolute float tolerance for "unchanged"
_MOVE_TOL = 1e-6     # metres / radians below which a link has not moved


@dataclass(frozen=True)
class Change:
    """One difference. ``kind`` is link, joint, material or robot; ``change`` is added, removed,
    renamed or changed; ``field`` names what changed (``limit.upper``, ``inertial.mass``, ...)."""
    kind: str
    name: str
    change: str
    field: str = ""
    before: object = None
    after: object = None
    head: Origin | None = None     # where HEAD writes it (None when removed)
    base: Origin | None = None     # where BASE wrote it (None when added)
    value_from: tuple[Any, ...] = ()   # (file, line, col) HEAD's value comes from (a YAML scalar,
                                   # a property elsewhere), () when written at ``head``

    def to_dict(self, rel: Callable[[str], str] | None = None) -> dict[str, Any]:
        rel = rel or (lambda p: p)
        def loc(o: Origin | None) -> dict[str, Any] | None:
            return None if o is None else {"file": rel(o.file), "line": o.line, "col": o.col,
                                           "chain": [[rel(c[0]), c[1], c[2]] for c in o.chain]}
        return {"kind": self.kind, "name": self.name, "change": self.change, "field": self.field,
                "before": _jsonable(self.before), "after": _jsonable(self.after),
                "head": loc(self.head), "base": loc(self.base),
                **({"value_from": [rel(self.value_from[0]), *self.value_from[1:]]}
                   if self.value_from else {})}


@dataclass
class ModelDiff:
    """What changed in one model between two revisions: changes, moved links, and the
    findings introduced and fixed."""
    model: str                     # display label of the model
    status: str                    # changed | unchanged | added | removed | failed
    changes: list[Change] = field(default_factory=list)
    # (link, metres, radians), largest first
    moved: list[tuple[str, float, float]] = field(default_factory=list)
    # (finding key, severity); a key is (code, file relative to its revision, message)
    findings_introduced: list[tuple[FindingKey, str]] = field(default_factory=list)
    findings_fixed: list[tuple[FindingKey, str]] = field(default_factory=list)
    # finding key -> (line, col) in its revision
    finding_lines: dict[FindingKey, tuple[int, int]] = field(default_factory=dict)
    # finding key -> (file, line, col) of the robot element an SRDF or YAML finding is about,
    # in its revision
    finding_related: dict[FindingKey, tuple[str, int, int]] = field(default_factory=dict)
    # finding key -> (file, line, col) its value comes from (a YAML scalar, a property
    # elsewhere), in its revision: HEAD's for an introduced finding, BASE's for a fixed one
    finding_value_from: dict[FindingKey, tuple[str, int, int]] = field(default_factory=dict)
    error: str = ""
    snapshot: dict[str, Any] = field(default_factory=dict)   # diff --render: png/diff/rrd paths
    picture: str = ""              # the file name stem of its pictures (locations.picture_name)


def _jsonable(v: Any) -> Any:
    if isinstance(v, tuple):
        return [_jsonable(x) for x in v]
    if isinstance(v, float) and not math.isfinite(v):
        return str(v)
    return v


# -- facts ------------------------------------------------------------------------------------
def _num(s: Any) -> Any:
    try:
        return float(s)
    except (TypeError, ValueError):
        return s


def _vec(s: str | None, n: int = 3) -> Vec | str | None:
    if s is None:
        return None
    parts = s.split()
    try:
        v = tuple(float(p) for p in parts)
    except ValueError:
        return s
    return v if len(v) == n else s


def _origin(el: Element) -> dict[str, Any]:
    o = el.find("origin") if el is not None else None
    xyz = _vec(o.get("xyz")) if o is not None and o.get("xyz") is not None else (0.0, 0.0, 0.0)
    rpy = _vec(o.get("rpy")) if o is not None and o.get("rpy") is not None else (0.0, 0.0, 0.0)
    return {"xyz": xyz, "rpy": rpy}


def _el(el: Element, fallback: Element) -> Element:
    """lxml elements are falsy without children: never use ``or`` on them."""
    return el if el is not None else fallback


class _Fact:
    """A value with the element that wrote it (for the location)."""
    __slots__ = ("value", "el")

    def __init__(self, value: Any, el: Element) -> None:
        self.value, self.el = value, el


FactMap = dict[str, _Fact]                           # field -> its value and element
Facts = dict[Key, tuple[Element, FactMap]]           # (kind, name) -> (element, its facts)


def _mesh_digest(model: "Model", uri: str, cache: dict[tuple[str, str], str | None]
                 ) -> str | None:
    if model.resolver is None:
        return None
    from urdf_lint.meshes import resolve as meshes
    key = (model.base_dir, uri)
    if key not in cache:
        digest = None
        try:
            ref = meshes.resolve(model, uri)
            if ref.path and ref.problem is None and os.path.isfile(ref.path):
                from urdf_lint.core import fsbound
                from urdf_lint.meshes.resolve import MAX_MESH_BYTES
                digest = hashlib.sha256(fsbound.read_bytes(
                    ref.path, model.resolver.roots, MAX_MESH_BYTES)).hexdigest()[:12]
        except Exception:  # noqa: BLE001 - an unreadable mesh has no digest; rules report it
            digest = None
        cache[key] = digest
    return cache[key]


def _geometry(model: "Model", g: Element, cache: dict[tuple[str, str], str | None]
              ) -> dict[str, Any]:
    if g is None:
        return {}
    shape = next((c for c in g if isinstance(c.tag, str)), None)
    if shape is None:
        return {}
    out: dict[str, Any] = {"type": shape.tag}
    for a in ("size", "scale"):
        if shape.get(a) is not None:
            out[a] = _vec(shape.get(a))
    for a in ("radius", "length"):
        if shape.get(a) is not None:
            out[a] = _num(shape.get(a))
    if shape.tag == "mesh" and shape.get("filename"):
        out["filename"] = shape.get("filename")
        digest = _mesh_digest(model, shape.get("filename"), cache)
        if digest:
            out["content"] = digest
    return out


def robot_facts(model: "Model") -> "Facts":
    """{(kind, name): {field: _Fact}} plus the element of each link/joint (for locations)."""
    facts: Facts = {}
    cache: dict[tuple[str, str], str | None] = {}
    for lk in model.top_links():
        facts[("link", lk.get("name"))] = (lk, _link_facts(model, lk, cache))
    for j in model.top_joints():
        facts[("joint", j.get("name"))] = (j, _joint_facts(j))
    for name, el in model.materials.items():
        facts[("material", name)] = (el, _material_facts(el))
    return facts


def _link_facts(model: "Model", lk: Element, cache: dict[tuple[str, str], str | None]
                ) -> "FactMap":
    f: FactMap = {}
    inertial = lk.find("inertial")
    if inertial is not None:
        _inertial_facts(inertial, f)
    for part in ("visual", "collision"):
        for n, el in enumerate(lk.findall(part)):
            _part_facts(model, part, f"{part}[{n}]", el, cache, f)
    return f


def _inertial_facts(inertial: Element, f: "FactMap") -> None:
    m = inertial.find("mass")
    f["inertial.mass"] = _Fact(_num(m.get("value")) if m is not None else None, _el(m, inertial))
    o = _origin(inertial)
    f["inertial.origin.xyz"] = _Fact(o["xyz"], _el(inertial.find("origin"), inertial))
    f["inertial.origin.rpy"] = _Fact(o["rpy"], _el(inertial.find("origin"), inertial))
    i = inertial.find("inertia")
    if i is not None:
        f["inertial.inertia"] = _Fact(tuple(_num(i.get(k)) for k in
                                            ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")), i)


def _part_facts(model: "Model", part: str, key: str, el: Element,
                cache: dict[tuple[str, str], str | None], f: "FactMap") -> None:
    """The facts of one ``<visual>`` or ``<collision>`` (``key``: ``visual[0]``...)."""
    geometry = el.find("geometry")
    shape = next((c for c in geometry if isinstance(c.tag, str)), geometry) \
        if geometry is not None else el
    for k, v in _geometry(model, geometry, cache).items():
        f[f"{key}.{k}"] = _Fact(v, shape)
    o = _origin(el)
    f[f"{key}.origin.xyz"] = _Fact(o["xyz"], _el(el.find("origin"), el))
    f[f"{key}.origin.rpy"] = _Fact(o["rpy"], _el(el.find("origin"), el))
    mat = el.find("material")
    if part == "visual" and mat is not None:
        f[f"{key}.material"] = _Fact(mat.get("name"), mat)
        c = mat.find("color")
        if c is not None:
            f[f"{key}.material.rgba"] = _Fact(_vec(c.get("rgba"), 4), c)


_JOINT_ATTRS = (("limit", ("lower", "upper", "effort", "velocity")),
                ("mimic", ("joint", "multiplier", "offset")),
                ("dynamics", ("damping", "friction")),
                ("safety_controller", ("soft_lower_limit", "soft_upper_limit",
                                       "k_position", "k_velocity")))


def _joint_facts(j: Element) -> "FactMap":
    f: FactMap = {"type": _Fact(j.get("type"), j)}
    for k in ("parent", "child"):
        e = j.find(k)
        f[k] = _Fact(e.get("link") if e is not None else None, e if e is not None else j)
    o = _origin(j)
    f["origin.xyz"] = _Fact(o["xyz"], _el(j.find("origin"), j))
    f["origin.rpy"] = _Fact(o["rpy"], _el(j.find("origin"), j))
    ax = j.find("axis")
    if ax is not None or j.get("type") in ("revolute", "continuous", "prismatic", "planar"):
        f["axis"] = _Fact(_vec(ax.get("xyz")) if ax is not None and ax.get("xyz") else
                          (1.0, 0.0, 0.0), ax if ax is not None else j)
    for tag, attrs in _JOINT_ATTRS:
        e = j.find(tag)
        if e is None:
            continue
        for a in attrs:
            if e.get(a) is not None:
                f[f"{tag}.{a}"] = _Fact(_num(e.get(a)) if a != "joint" else e.get(a), e)
    return f


def _material_facts(el: Element) -> "FactMap":
    f: FactMap = {}
    c = el.find("color")
    if c is not None:
        f["rgba"] = _Fact(_vec(c.get("rgba"), 4), c)
    t = el.find("texture")
    if t is not None:
        f["texture"] = _Fact(t.get("filename"), t)
    return f


# -- kinematics at the zero configuration ------------------------------------------------------
def _rot(rpy: Vec) -> Rot:
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return ((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
            (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
            (-sp, cp * sr, cp * cr))


def _mul(a: Pose, b: Pose) -> Pose:
    (ra, ta), (rb, tb) = a, b
    r = tuple(tuple(sum(ra[i][k] * rb[k][j] for k in range(3)) for j in range(3)) for i in range(3))
    t = tuple(sum(ra[i][k] * tb[k] for k in range(3)) + ta[i] for i in range(3))
    return r, t


def world_poses(facts: "Facts") -> dict[str, Pose]:
    """link -> (rotation, translation) at the zero configuration, from every tree root."""
    children: dict[str, list[tuple[str, Pose]]] = {}
    is_child = set()
    for (kind, _), (_, f) in facts.items():
        if kind != "joint":
            continue
        xyz, rpy = f["origin.xyz"].value, f["origin.rpy"].value
        if not (isinstance(xyz, tuple) and isinstance(rpy, tuple)):
            continue
        parent, child = f["parent"].value, f["child"].value
        children.setdefault(parent, []).append((child, (_rot(rpy), xyz)))
        is_child.add(child)
    ident: Pose = (((1.0, 0, 0), (0, 1.0, 0), (0, 0, 1.0)), (0.0, 0.0, 0.0))
    poses: dict[str, Pose] = {}
    roots = [n for (k, n) in facts if k == "link" and n not in is_child]
    stack = [(r, ident) for r in roots]
    while stack:
        link, pose = stack.pop()
        if link in poses:
            continue  # a loop or a second parent: first path wins (rules report the defect)
        poses[link] = pose
        for child, t in children.get(link, ()):
            stack.append((child, _mul(pose, t)))
    return poses


def _angle_between(ra: Rot, rb: Rot) -> float:
    # angle of ra^T rb
    tr = sum(ra[k][i] * rb[k][i] for i in range(3) for k in range(3))
    return math.acos(max(-1.0, min(1.0, (tr - 1.0) / 2.0)))


# -- comparison --------------------------------------------------------------------------------
def _same(a: object, b: object) -> bool:
    if isinstance(a, tuple) and isinstance(b, tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, float) and isinstance(b, float):
        return a == b or abs(a - b) <= _TOL * max(1.0, abs(a), abs(b))
    return a == b


def _signature(f: "FactMap", rename: dict[str, str]) -> tuple[tuple[str, Any], ...]:
    items = []
    for k, v in sorted(f.items()):
        val = v.value
        if k in ("parent", "child", "mimic.joint"):
            val = rename.get(val, val)
        items.append((k, _round(val)))
    return tuple(items)


def _round(v: Any) -> Any:
    if isinstance(v, float):
        return round(v, 9)
    if isinstance(v, tuple):
        return tuple(_round(x) for x in v)
    return v


def diff_facts(base: "Facts", head: "Facts", base_model: "Model | None",
               head_model: "Model | None") -> tuple[list[Change], list[tuple[str, float, float]]]:
    """(changes, moved links) between two fact sets of one robot."""
    hloc: Locate = head_model.origin if head_model is not None else (lambda el: None)
    bloc: Locate = base_model.origin if base_model is not None else (lambda el: None)
    renames = _match_renames(base, head)
    changes = _presence_changes(base, head, renames, hloc, bloc)
    changes += _field_changes(base, head, renames, hloc, bloc, _value_source(head_model))
    return changes, _moved_links(base, head, renames)


def _link_map(renames: dict[Key, str]) -> dict[str, str]:
    return {o: n for (k, o), n in renames.items() if k == "link"}


def _match_renames(base: "Facts", head: "Facts") -> dict[Key, str]:
    """``(kind, old name) -> new name`` for each element removed at BASE whose facts match
    one added at HEAD (links first, so joints and materials match through renamed links)."""
    renames: dict[Key, str] = {}   # (kind, old) -> new
    for kind in ("link", "joint", "material"):
        removed = [n for (k, n) in base if k == kind and (k, n) not in head]
        added = [n for (k, n) in head if k == kind and (k, n) not in base]
        link_map = _link_map(renames)
        by_sig: dict[tuple[tuple[str, Any], ...], list[str]] = {}
        for n in added:
            by_sig.setdefault(_signature(head[(kind, n)][1], {}), []).append(n)
        for o in removed:
            sig = _signature(base[(kind, o)][1], link_map)
            cands = by_sig.get(sig)
            if cands:
                renames[(kind, o)] = cands.pop(0)
        if kind == "joint":
            _match_joints_by_links(base, head, removed, added, link_map, renames)
    return renames


def _match_joints_by_links(base: "Facts", head: "Facts", removed: list[str], added: list[str],
                           link_map: dict[str, str], renames: dict[Key, str]) -> None:
    """Joints also match by structure: the same parent and child links."""
    left = [o for o in removed if ("joint", o) not in renames]
    taken = set(renames.values())
    for o in left:
        bf = base[("joint", o)][1]
        pc = (link_map.get(bf["parent"].value, bf["parent"].value),
              link_map.get(bf["child"].value, bf["child"].value))
        for n in added:
            hf = head[("joint", n)][1]
            if n not in taken and (hf["parent"].value, hf["child"].value) == pc:
                renames[("joint", o)] = n
                taken.add(n)
                break


def _presence_changes(base: "Facts", head: "Facts", renames: dict[Key, str], hloc: Locate,
                      bloc: Locate) -> list[Change]:
    """The elements added, renamed and removed."""
    changes: list[Change] = []
    new_names = {(k, n) for (k, _), n in renames.items()}
    for (kind, name), (el, _f) in sorted(head.items()):
        if (kind, name) not in base and (kind, name) not in new_names:
            changes.append(Change(kind, name, "added", head=hloc(el)))
    for (kind, name), (el, _f) in sorted(base.items()):
        if (kind, name) in head:
            continue
        if (kind, name) in renames:
            new = renames[(kind, name)]
            changes.append(Change(kind, new, "renamed", "name", name, new,
                                  head=hloc(head[(kind, new)][0]), base=bloc(el)))
        else:
            changes.append(Change(kind, name, "removed", base=bloc(el)))
    return changes


def _field_changes(base: "Facts", head: "Facts", renames: dict[Key, str], hloc: Locate,
                   bloc: Locate, value_from: ValueSource) -> list[Change]:
    """The fields whose value differs, for each element on both sides (renamed included)."""
    changes: list[Change] = []
    pairs = [((k, n), (k, n)) for (k, n) in head if (k, n) in base]
    pairs += [(old, (old[0], new)) for old, new in renames.items()]
    for bkey, hkey in sorted(pairs, key=lambda p: p[1]):
        (bel, bf), (hel, hf) = base[bkey], head[hkey]
        for k in sorted(set(bf) | set(hf)):
            b, h = bf.get(k), hf.get(k)
            bv, hv = (b.value if b else None), (h.value if h else None)
            if _same(bv, hv):
                continue
            changes.append(Change(hkey[0], hkey[1], "changed", k, bv, hv,
                                  head=hloc(h.el) if h else hloc(hel),
                                  base=bloc(b.el) if b else bloc(bel),
                                  value_from=value_from(h, k)))
    return changes


def _moved_links(base: "Facts", head: "Facts", renames: dict[Key, str]
                 ) -> list[tuple[str, float, float]]:
    """(link, distance, angle) of each link whose pose at the zero configuration moved,
    the farthest first."""
    bp, hp = world_poses(base), world_poses(head)
    link_map = _link_map(renames)
    moved: list[tuple[str, float, float]] = []
    for old, (rb, tb) in bp.items():
        new = link_map.get(old, old)
        if new not in hp:
            continue
        rh, th = hp[new]
        dist = math.dist(tb, th)
        ang = _angle_between(rb, rh)
        if dist > _MOVE_TOL or ang > _MOVE_TOL:
            moved.append((new, dist, ang))
    moved.sort(key=lambda m: (-m[1], -m[2], m[0]))
    return moved


def _value_source(model: "Model | None") -> ValueSource:
    """``(fact, field) -> (file, line, col) | ()``: where HEAD's value of ``field`` comes from
    when not from the element's own line (the YAML line a person edits, a property elsewhere):
    :meth:`urdf_lint.fix.fixes.Fixer.value_from` on the attribute the field names
    (``limit.upper`` -> ``upper``)."""
    if model is None or not hasattr(model, "origins"):
        return lambda fact, field: ()
    from urdf_lint.fix.fixes import Fixer
    fixer = Fixer(model)

    def source(fact: _Fact | None, field: str) -> tuple[Any, ...]:
        attr = field.rsplit(".", 1)[-1]
        if fact is None or fact.el is None or fact.el.get(attr) is None:
            return ()
        return fixer.value_from(fact.el, (attr,))
    return source


def diff_models(base_model: "Model | None", head_model: "Model | None"
                ) -> tuple[list[Change], list[tuple[str, float, float]]]:
    base: Facts = robot_facts(base_model) if base_model is not None else {}
    head: Facts = robot_facts(head_model) if head_model is not None else {}
    changes, moved = diff_facts(base, head, base_model, head_model)
    if base_model is not None and head_model is not None and base_model.name != head_model.name:
        changes.insert(0, Change("robot", head_model.name, "changed", "name", base_model.name,
                                 head_model.name, head=head_model.origin(head_model.root),
                                 base=base_model.origin(base_model.root)))
    return changes, moved
