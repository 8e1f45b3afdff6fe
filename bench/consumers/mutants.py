"""Defect classes as mutants of clean robots (issue 38): each class is one edit of a base's XML
tree, applied to every base it fits, and names the urdf-lint rule that should report it.

The bases are a small clean robot written here (:data:`PROBE`, primitive geometry, inertials,
a transmission) and real robots from the corpus (``BASE_ENTRIES``), expanded by urdf-lint.
Used by ``harness.py`` (the full run) and ``tests/test_consumer_verdicts.py`` (the fast part).
"""
from __future__ import annotations

import copy
import struct
from typing import Callable

from lxml import etree

LIMIT = '<limit lower="-1" upper="1" effort="10" velocity="1"/>'
PROBE = f"""<?xml version="1.0"?>
<robot name="probe">
  <link name="base">
    <inertial><mass value="2"/><inertia ixx="0.008" ixy="0" ixz="0" iyy="0.008" iyz="0" izz="0.013"/></inertial>
    <visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
  </link>
  <link name="upper">
    <inertial><origin xyz="0 0 0.25"/><mass value="1"/>
      <inertia ixx="0.0215" ixy="0" ixz="0" iyy="0.0215" iyz="0" izz="0.00125"/></inertial>
    <visual><origin xyz="0 0 0.25"/><geometry><cylinder radius="0.05" length="0.5"/></geometry></visual>
    <collision><origin xyz="0 0 0.25"/><geometry><cylinder radius="0.05" length="0.5"/></geometry></collision>
  </link>
  <link name="lower">
    <inertial><origin xyz="0 0 0.2"/><mass value="0.5"/>
      <inertia ixx="0.0068" ixy="0" ixz="0" iyy="0.0068" iyz="0" izz="0.0002"/></inertial>
    <visual><origin xyz="0 0 0.2"/><geometry><box size="0.05 0.05 0.4"/></geometry></visual>
    <collision><origin xyz="0 0 0.2"/><geometry><box size="0.05 0.05 0.4"/></geometry></collision>
  </link>
  <link name="tool">
    <inertial><mass value="0.1"/><inertia ixx="0.0001" ixy="0" ixz="0" iyy="0.0001" iyz="0" izz="0.0001"/></inertial>
  </link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.05"/><axis xyz="0 1 0"/>{LIMIT}</joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="lower"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 1 0"/>{LIMIT}</joint>
  <joint name="wrist" type="revolute"><parent link="lower"/><child link="tool"/>
    <origin xyz="0 0 0.4"/><axis xyz="0 0 1"/>{LIMIT}</joint>
  <transmission name="shoulder_trans"><type>transmission_interface/SimpleTransmission</type>
    <joint name="shoulder"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>
    <actuator name="shoulder_motor"/></transmission>
</robot>
"""
# real bases: corpus entries (file, args) that every consumer loads (primitive geometry only)
BASE_ENTRIES = [("ros2_control_demos/ros2_control_demo_example_1/urdf/rrbot.urdf.xacro", {}),
                ("robot_properties_fingers/urdf/stage.urdf", {})]

Tree = etree._Element
Edit = Callable[[Tree], "Tree | None"]


# -- helpers on a tree -------------------------------------------------------------------------
def links(r: Tree) -> list:
    return r.findall("link")


def joints(r: Tree) -> list:
    return r.findall("joint")


def moving(r: Tree) -> list:
    """Joints that move, leaf-most last (document order)."""
    return [j for j in joints(r) if j.get("type") not in (None, "fixed", "floating", "planar")]


def link(r: Tree, name: str):
    for lk in links(r):
        if lk.get("name") == name:
            return lk
    return None


def child(j) -> str:
    return j.find("child").get("link")


def children_of(r: Tree, name: str) -> list:
    return [j for j in joints(r) if j.find("parent") is not None
            and j.find("parent").get("link") == name]


def moving_massive(r: Tree):
    """A link moved by a joint that has an <inertial> with <inertia> and a positive mass."""
    for j in reversed(moving(r)):
        lk = link(r, child(j))
        m = lk.find("inertial/mass") if lk is not None else None
        if m is not None and lk.find("inertial/inertia") is not None and \
                float(m.get("value", "0")) > 0:
            return lk
    return None


def moving_leaf(r: Tree):
    """A moving link with no children and no collision, with an inertial."""
    for j in reversed(moving(r)):
        lk = link(r, child(j))
        if lk is not None and not children_of(r, lk.get("name")) and \
                lk.find("collision") is None and lk.find("inertial") is not None:
            return lk
    return None


def collision_geometry(r: Tree, shape: str = ""):
    """The <geometry> of a moving link's collision (of that shape when given)."""
    for j in reversed(moving(r)):
        lk = link(r, child(j))
        for g in (lk.findall("collision/geometry") if lk is not None else []):
            if not shape or g.find(shape) is not None:
                return g
    return None


def visual_geometry(r: Tree):
    for j in reversed(moving(r)):
        lk = link(r, child(j))
        for g in (lk.findall("visual/geometry") if lk is not None else []):
            return g
    return None


def set_inertia(lk, **vals) -> None:
    i = lk.find("inertial/inertia")
    for k, v in vals.items():
        i.set(k, v)


def el(xml: str):
    return etree.fromstring(xml)


# -- the edits (None: the class does not apply to this base) -----------------------------------
def no_inertial_leaf(r):
    lk = moving_leaf(r)
    if lk is None:
        return None
    lk.remove(lk.find("inertial"))
    return r


def no_inertial_anywhere(r):
    for lk in links(r):
        for i in lk.findall("inertial"):
            lk.remove(i)
    return r


def _mass(value):
    def edit(r):
        lk = moving_massive(r)
        if lk is None:
            return None
        lk.find("inertial/mass").set("value", value)
        return r
    return edit


def _inertia(**vals):
    def edit(r):
        lk = moving_massive(r)
        if lk is None:
            return None
        set_inertia(lk, **vals)
        return r
    return edit


def inertia_not_pd(r):
    lk = moving_massive(r)
    if lk is None:
        return None
    i = lk.find("inertial/inertia")
    a = float(i.get("ixx"))
    i.set("ixy", repr(a * 2))
    return r


def diagonal_triangle(r):
    lk = moving_massive(r)
    if lk is None:
        return None
    i = lk.find("inertial/inertia")
    i.set("izz", repr(3 * (float(i.get("ixx")) + float(i.get("iyy")))))
    return r


def tiny_dummy(r):
    """The quadrupeds' dummy links: 1e-6 kg, all six tensor entries 1e-6, on a moving link."""
    lk = moving_massive(r)
    if lk is None:
        return None
    lk.find("inertial/mass").set("value", "1e-6")
    set_inertia(lk, **{k: "1e-6" for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")})
    return r


def inertial_without_inertia(r):
    lk = moving_massive(r)
    if lk is None:
        return None
    lk.find("inertial").remove(lk.find("inertial/inertia"))
    return r


def massless_hub(r):
    """A link with no inertial and no geometry between two moving joints whose child has mass:
    the last moving joint's parent gets its inertial and geometry removed."""
    js = moving(r)
    for j in reversed(js):
        p = j.find("parent").get("link")
        pj = [k for k in js if child(k) == p]
        lk = link(r, p)
        if pj and lk is not None and moving_massive(r) is not None:
            for tag in ("inertial", "visual", "collision"):
                for e in lk.findall(tag):
                    lk.remove(e)
            return r
    return None


def _joint_attr(fn):
    def edit(r):
        js = moving(r)
        if not js:
            return None
        return r if fn(js[-1]) is not False else None
    return edit


def _set_axis(xyz):
    def fn(j):
        a = j.find("axis")
        if a is None:
            a = etree.SubElement(j, "axis")
        a.set("xyz", xyz)
    return _joint_attr(fn)


def _nan_origin(j):
    o = j.find("origin")
    if o is None:
        o = etree.SubElement(j, "origin")
    o.set("xyz", "0 nan 0")


def _no_limit(j):
    if j.get("type") != "revolute":
        return False
    j.remove(j.find("limit"))


def _limit_no_effort(j):
    lim = j.find("limit")
    if lim is None or "effort" not in lim.attrib:
        return False
    del lim.attrib["effort"]


def _lower_gt_upper(j):
    lim = j.find("limit")
    if j.get("type") not in ("revolute", "prismatic") or lim is None:
        return False
    lim.set("lower", "1")
    lim.set("upper", "-1")


def _orgin_typo(j):
    o = j.find("origin")
    if o is None:
        return False
    o.tag = "orgin"


def missing_link(r):
    js = joints(r)
    js[-1].find("child").set("link", "no_such_link")
    return r


def duplicate_link(r):
    ls = links(r)
    dup = copy.deepcopy(ls[-1])
    r.insert(r.index(ls[-1]) + 1, dup)
    return r


def duplicate_joint(r):
    js = joints(r)
    if len(js) < 2:
        return None
    js[-1].set("name", js[-2].get("name"))
    return r


def two_roots(r):
    r.append(el('<link name="spare"/>'))
    return r


def kinematic_loop(r):
    js = moving(r)
    if len(js) < 2:
        return None
    leaf = child(js[-1])
    first = child(js[0])
    r.append(el(f'<joint name="loop" type="fixed"><parent link="{leaf}"/>'
                f'<child link="{first}"/></joint>'))
    return r


def mimic_missing(r):
    js = moving(r)
    etree.SubElement(js[-1], "mimic").set("joint", "no_such_joint")
    return r


def mimic_fixed(r):
    js = moving(r)
    if len(js) < 2:
        return None
    j = js[-1]
    j.set("type", "fixed")
    for tag in ("axis", "limit"):
        for e in j.findall(tag):
            j.remove(e)
    etree.SubElement(j, "mimic").set("joint", js[-2].get("name"))
    return r


def _transmission(name, joint):
    return el(f'<transmission name="{name}"><type>transmission_interface/SimpleTransmission'
              f'</type><joint name="{joint}"><hardwareInterface>EffortJointInterface'
              f'</hardwareInterface></joint><actuator name="{name}_motor"/></transmission>')


def duplicate_transmission(r):
    js = moving(r)
    r.append(_transmission("dup_trans", js[0].get("name")))
    r.append(_transmission("dup_trans", js[-1].get("name")))
    return r


def transmission_missing_joint(r):
    r.append(_transmission("lost_trans", "no_such_joint"))
    return r


def gazebo_missing_reference(r):
    r.append(el('<gazebo reference="no_such_link"><material>Gazebo/Red</material></gazebo>'))
    return r


def empty_geometry(r):
    g = collision_geometry(r)
    if g is None:
        return None
    for c in list(g):
        g.remove(c)
    return r


def _shape_edit(shape, attr, value):
    def edit(r):
        g = collision_geometry(r, shape)
        if g is None:
            return None
        g.find(shape).set(attr, value)
        return r
    return edit


def capsule(version):
    def edit(r):
        g = collision_geometry(r)
        if g is None:
            return None
        for c in list(g):
            g.remove(c)
        etree.SubElement(g, "capsule", radius="0.02", length="0.1")
        if version:
            r.set("version", version)
        return r
    return edit


def _version(v):
    def edit(r):
        r.set("version", v)
        return r
    return edit


def same_name_joint_link(r):
    js = moving(r)
    old = child(js[-1])
    new = js[-1].get("name")
    for e in r.iter():
        if e.tag in ("child", "parent") and e.get("link") == old:
            e.set("link", new)
        if e.tag == "link" and e.get("name") == old:
            e.set("name", new)
        if e.tag == "gazebo" and e.get("reference") == old:
            e.set("reference", new)
    return r


def undefined_material(r):
    g = visual_geometry(r)
    if g is None:
        return None
    etree.SubElement(g.getparent(), "material").set("name", "nowhere")
    return r


def rgba_out_of_range(r):
    g = visual_geometry(r)
    if g is None:
        return None
    m = etree.SubElement(g.getparent(), "material", name="too_red")
    etree.SubElement(m, "color", rgba="2 0 0 1")
    return r


def _mesh(which, filename):
    def edit(r):
        g = collision_geometry(r) if which == "collision" else visual_geometry(r)
        if g is None:
            return None
        for c in list(g):
            g.remove(c)
        etree.SubElement(g, "mesh", filename=filename)
        return r
    return edit


# -- mesh files a mutant may name (written next to the URDF) -----------------------------------
def _stl(tris) -> bytes:
    out = bytearray(b"\0" * 80) + struct.pack("<I", len(tris))
    for t in tris:
        out += struct.pack("<3f", 0, 0, 0)
        for v in t:
            out += struct.pack("<3f", *v)
        out += b"\0\0"
    return bytes(out)


def _box_tris(s):
    v = [(x, y, z) for x in (0, s) for y in (0, s) for z in (0, s)]
    f = [(0, 2, 1), (1, 2, 3), (4, 5, 6), (5, 7, 6), (0, 1, 4), (1, 5, 4),
         (2, 6, 3), (3, 6, 7), (0, 4, 2), (2, 4, 6), (1, 3, 5), (3, 7, 5)]
    return [tuple(v[i] for i in t) for t in f]


def _obj(tris) -> bytes:
    verts, lines = [], []
    for t in tris:
        idx = []
        for v in t:
            verts.append(v)
            idx.append(len(verts))
        lines.append("f " + " ".join(map(str, idx)))
    return ("\n".join(f"v {x} {y} {z}" for x, y, z in verts) + "\n" + "\n".join(lines)
            + "\n").encode()


MESH_FILES = {
    "box.stl": _stl(_box_tris(0.05)),
    "box.obj": _obj(_box_tris(0.05)),
    "tiny.obj": _obj(_box_tris(2e-6)),            # closed, 8e-18 m^3
    "empty.obj": b"# no vertices\n",
    "flat.obj": _obj([((0, 0, 0), (0.05, 0, 0), (0, 0.05, 0)),
                      ((0.05, 0, 0), (0.05, 0.05, 0), (0, 0.05, 0))]),
}

# class -> (the codes urdf-lint reports for it, the edit)
CLASSES: dict[str, tuple[tuple[str, ...], Edit]] = {
    "no <inertial> on a moving leaf link": (("UL601",), no_inertial_leaf),
    "no <inertial> on any link": (("UL601",), no_inertial_anywhere),
    "zero mass on a moving link": (("UL602",), _mass("0")),
    "negative mass": (("UL602",), _mass("-0.5")),
    "1e-9 kg on a moving link": (("UL602",), _mass("1e-9")),
    "inertia not positive definite": (("UL603",), inertia_not_pd),
    "principal moments break A+B>=C": (("UL603",), _inertia(
        ixx="4.7e-3", ixy="0", ixz="2.5e-3", iyy="3.65e-3", iyz="0", izz="4.7e-3")),
    "diagonal breaks A+B>=C": (("UL603",), diagonal_triangle),
    "six equal tiny tensor entries": (("UL603",), _inertia(
        ixx="1e-6", ixy="1e-6", ixz="1e-6", iyy="1e-6", iyz="1e-6", izz="1e-6")),
    "<inertial> without <inertia>": (("UL206",), inertial_without_inertia),
    "six equal tiny entries on a 1e-6 kg link": (("UL603",), tiny_dummy),
    "massless link without geometry carrying mass": (("UL601",), massless_hub),
    "axis 0 0 0": (("UL307",), _set_axis("0 0 0")),
    "NaN in an origin": (("UL207",), _joint_attr(_nan_origin)),
    "revolute without <limit>": (("UL301",), _joint_attr(_no_limit)),
    "<limit> without effort": (("UL304",), _joint_attr(_limit_no_effort)),
    "lower > upper": (("UL302",), _joint_attr(_lower_gt_upper)),
    "<orgin> typo in a joint": (("UL209",), _joint_attr(_orgin_typo)),
    "joint names a missing link": (("UL103",), missing_link),
    "duplicate link": (("UL105",), duplicate_link),
    "duplicate joint": (("UL105",), duplicate_joint),
    "two roots": (("UL101",), two_roots),
    "kinematic loop": (("UL102",), kinematic_loop),
    "mimic of a missing joint": (("UL308",), mimic_missing),
    "mimic on a fixed joint": (("UL309",), mimic_fixed),
    "duplicate transmission name": (("UL704",), duplicate_transmission),
    "transmission names a missing joint": (("UL701",), transmission_missing_joint),
    "<gazebo> reference to a missing link": (("UL703",), gazebo_missing_reference),
    "empty <geometry/>": (("UL204",), empty_geometry),
    "negative box size": (("UL205",), _shape_edit("box", "size", "0.05 -0.05 0.4")),
    "zero radius": (("UL205",), _shape_edit("cylinder", "radius", "0")),
    "<capsule> in a 1.1 robot": (("UL213", "UL204"), capsule("1.1")),
    "version 1": (("UL211",), _version("1")),
    "version 1.1": (("UL211",), _version("1.1")),
    "version 1.2": (("UL211",), _version("1.2")),
    "version 2.0": (("UL211",), _version("2.0")),
    "a joint and a link of the same name": (("UL105",), same_name_joint_link),
    "undefined material": (("UL502",), undefined_material),
    "rgba 2 0 0 1": (("UL208",), rgba_out_of_range),
    "missing collision mesh": (("UL401",), _mesh("collision", "nowhere.stl")),
    "missing visual mesh": (("UL401",), _mesh("visual", "nowhere.stl")),
    "binary STL collision mesh": ((), _mesh("collision", "box.stl")),
    "OBJ collision mesh": ((), _mesh("collision", "box.obj")),
    "tiny closed collision mesh": (("UL410",), _mesh("collision", "tiny.obj")),
    "empty collision mesh": (("UL404",), _mesh("collision", "empty.obj")),
    "flat collision mesh": (("UL410",), _mesh("collision", "flat.obj")),
}
# Classes where a consumer that loads the mutant cannot hold the robot as written: an element
# is dropped or contradicted (the origin under a misspelt tag, one of two same-named links or
# joints, a joint whose child does not exist, a NaN pose, a loop in what must be a tree, a mimic
# of nothing). A load of one of these is recorded as "W" (loads a different robot), which the
# issue's promise counts like a refusal: urdf-lint's error is right there.
CHANGES_ROBOT = {"<orgin> typo in a joint", "duplicate link", "duplicate joint",
                 "joint names a missing link", "NaN in an origin", "kinematic loop",
                 "mimic of a missing joint"}
# ... and classes where this holds for the consumers that read meshes and load the robot without
# the part that names a missing or empty mesh (yourdfpy, PyBullet, the Isaac importer: their
# own warnings say the geometry was dropped)
MESH_READERS = {"yourdfpy", "pybullet", "isaac", "isaac_isolated"}
CHANGES_ROBOT_FOR = {"missing collision mesh": MESH_READERS, "missing visual mesh": MESH_READERS,
                     "empty collision mesh": MESH_READERS}
# verdicts that say nothing about the class: sdf_probe parses, it opens no mesh file
NOT_MEASURED = {("sdformat", k) for k in ("missing collision mesh", "missing visual mesh",
                                          "empty collision mesh", "tiny closed collision mesh",
                                          "flat collision mesh", "binary STL collision mesh",
                                          "OBJ collision mesh")}
# classes that make a joint fixed: sdformat lumps the child into its parent, so a smaller link
# count there is no dropped link
LUMPS = {"mimic on a fixed joint"}


def bodies(text: str) -> int | None:
    """How many links a consumer that merges fixed joints (sdformat) must keep of this model to
    hold it as written: one per root link (a root named world is the world, not a link) and
    one per joint that is not fixed. None when the XML does not parse."""
    try:
        r = etree.fromstring(text.encode(), etree.XMLParser(recover=True))
    except etree.XMLSyntaxError:
        return None
    if r is None:
        return None
    children = {c.get("link") for j in r.findall("joint") for c in j.findall("child")}
    roots = [lk for lk in r.findall("link") if lk.get("name") not in children
             and lk.get("name") != "world"]
    return len(roots) + sum(1 for j in r.findall("joint") if j.get("type") != "fixed")


def different_robot(text: str, consumer: str) -> str | None:
    """Why a consumer that loads this (real) model cannot hold the robot as written, checked on
    the model itself (the corpus has no class): a joint naming a link that does not exist, or,
    for the consumers that read meshes, a mesh file that is not there."""
    try:   # recovering: a consumer that loads it read past an undeclared prefix (drake:)
        r = etree.fromstring(text.encode(), etree.XMLParser(recover=True))
    except etree.XMLSyntaxError:
        return None
    if r is None:
        return None
    names = {lk.get("name") for lk in r.iter("link")}
    for j in r.iter("joint"):
        for end in ("parent", "child"):
            e = j.find(end)
            if e is not None and e.get("link") not in names and j.getparent() is r:
                return f"joint '{j.get('name')}' names a missing link '{e.get('link')}'"
    if consumer in MESH_READERS:
        import os
        for m in r.iter("mesh"):
            f = m.get("filename") or ""
            if f.startswith("/") and not os.path.exists(f):
                return f"mesh '{os.path.basename(f)}' does not exist: the part is dropped"
    return None


# text edits after serialisation (XML-level defects the tree cannot hold)
TEXT_CLASSES: dict[str, tuple[tuple[str, ...], Callable[[str], str]]] = {
    "malformed XML declaration": (("UL001",), lambda t: '<?xml verison="1.0"?>\n' + t),
    "undeclared namespace prefix": (("UL001",), lambda t: t.replace(
        "</robot>", '  <drake:joint_damping value="1"/>\n</robot>', 1)),
}


def mutate(text: str, name: str) -> str | None:
    """The mutant of ``text`` for the class ``name``, or None when it does not apply."""
    if name in TEXT_CLASSES:
        root = etree.fromstring(text.encode())
        body = etree.tostring(root, encoding="unicode")
        return TEXT_CLASSES[name][1](body)
    root = etree.fromstring(text.encode())
    try:
        got = CLASSES[name][1](root)
    except (IndexError, AttributeError, TypeError, ValueError):
        return None                       # the base lacks what the class edits
    if got is None:
        return None
    return '<?xml version="1.0"?>\n' + etree.tostring(got, encoding="unicode") + "\n"


def all_classes() -> dict[str, tuple[str, ...]]:
    out = {k: v[0] for k, v in CLASSES.items()}
    out.update({k: v[0] for k, v in TEXT_CLASSES.items()})
    return out
