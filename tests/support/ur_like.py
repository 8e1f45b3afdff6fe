"""A UR-like description package, generated: one macro every variant uses
(``urdf/inc/arm_macro.xacro``), one macro only the first variant uses
(``urdf/inc/<first>_tool.xacro``), one entry per variant (``urdf/<variant>.urdf.xacro``), and
optionally a binary STL mesh per link and variant (for the mesh facts store). For the language
server's test and benchmark (bench/bench_server.py)."""
from __future__ import annotations

import struct
from pathlib import Path

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
VARIANTS = ("ur3", "ur3e", "ur5", "ur5e", "ur10", "ur10e", "ur16e", "ur20", "ur30")
LINKS = ("shoulder", "upper_arm", "forearm", "wrist_1", "wrist_2", "wrist_3")


def arm_macro(marker: str = "", work: int = 0, meshes: bool = False) -> str:
    """The macro all variants call. ``marker`` goes into one link's name (a test tells
    versions apart by it: that link has no inertial, so UL601 names it); ``work`` makes each
    expansion sum that many numbers (a model that takes a while to lint)."""
    body = []
    parent = "${prefix}base_link"
    for name in LINKS:
        link = f"${{prefix}}{name}_link"
        geom = (f'<mesh filename="package://ur_like/meshes/${{variant}}/{name}.stl"/>'
                if meshes else '<cylinder radius="${0.05 * scale}" length="${0.1 * scale}"/>')
        body.append(
            f'    <link name="{link}">\n'
            f'      <visual><geometry>{geom}</geometry></visual>\n'
            f'      <collision><geometry>{geom}</geometry></collision>\n'
            f'      <inertial><mass value="${{2.0 * scale}}"/><origin xyz="0 0 0.05"/>\n'
            f'        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>'
            f'</inertial>\n    </link>\n'
            f'    <joint name="${{prefix}}{name}_joint" type="revolute">\n'
            f'      <parent link="{parent}"/><child link="{link}"/>\n'
            f'      <origin xyz="0 0 ${{0.1 * scale}}" rpy="0 0 0"/><axis xyz="0 0 1"/>\n'
            f'      <limit lower="${{-pi}}" upper="${{pi}}" effort="${{150 * scale}}" '
            f'velocity="3.14"/>\n    </joint>\n')
        parent = link
    if marker:
        body.append(f'    <link name="${{prefix}}{marker}"/>\n'
                    f'    <joint name="${{prefix}}{marker}_joint" type="revolute">\n'
                    f'      <parent link="{parent}"/><child link="${{prefix}}{marker}"/>'
                    f'<axis xyz="0 0 1"/>\n'
                    f'      <limit lower="-1" upper="1" effort="1" velocity="1"/>\n'
                    f'    </joint>\n')
    slow = (f'    <xacro:property name="busy" value="${{python.sum(python.range({work}))}}"/>\n'
            if work else "")
    base = '    <link name="${prefix}base_link"/>\n'
    if work:
        base = f'    <xacro:if value="${{busy >= 0}}">\n  {base}    </xacro:if>\n'
    return (f'<?xml version="1.0"?>\n<robot {X}>\n'
            f'  <xacro:macro name="ur_arm" params="prefix variant scale">\n{slow}' + base +
            "".join(body) +
            '  </xacro:macro>\n</robot>\n')


def tool_macro(marker: str = "") -> str:
    """The macro only the first variant uses (its tool flange)."""
    extra = (f'    <link name="${{prefix}}{marker}"/>\n'
             f'    <joint name="${{prefix}}{marker}_joint" type="revolute">'
             f'<parent link="${{prefix}}tool0"/><child link="${{prefix}}{marker}"/>'
             f'<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
             f'</joint>\n' if marker else "")
    return (f'<?xml version="1.0"?>\n<robot {X}>\n'
            '  <xacro:macro name="ur_tool" params="prefix">\n'
            '    <link name="${prefix}tool0"/>\n'
            '    <joint name="${prefix}flange" type="fixed"><parent link="${prefix}wrist_3_link"/>'
            '<child link="${prefix}tool0"/></joint>\n' + extra +
            '  </xacro:macro>\n</robot>\n')


def entry(variant: str, i: int, tool: bool) -> str:
    inc = '  <xacro:include filename="inc/%s_tool.xacro"/>\n' % variant if tool else ""
    call = '  <xacro:ur_tool prefix=""/>\n' if tool else ""
    return (f'<?xml version="1.0"?>\n<robot name="{variant}" {X}>\n'
            '  <xacro:include filename="inc/arm_macro.xacro"/>\n' + inc +
            f'  <xacro:ur_arm prefix="" variant="{variant}" scale="{1 + i / 4:g}"/>\n' + call +
            '</robot>\n')


def stl(triangles: int, seed: int) -> bytes:
    """A binary STL of ``triangles`` triangles (a fan: not closed; its facts are what count)."""
    import math
    out = [b"ur_like".ljust(80, b" "), struct.pack("<I", triangles)]
    for k in range(triangles):
        a, b = 2 * math.pi * k / triangles, 2 * math.pi * (k + 1) / triangles
        r = 0.05 + 0.001 * (seed % 7)
        out.append(struct.pack("<12fH", 0, 0, 1, 0, 0, 0, r * math.cos(a), r * math.sin(a), 0,
                               r * math.cos(b), r * math.sin(b), 0.01 * (k % 3), 0))
    return b"".join(out)


def write(root: Path, variants: int = 9, marker: str = "", work: int = 0,
          mesh_triangles: int = 0) -> Path:
    """Write the package under ``root/ur_like``; returns its folder."""
    pkg = root / "ur_like"
    (pkg / "urdf" / "inc").mkdir(parents=True, exist_ok=True)
    (pkg / "package.xml").write_text("<package><name>ur_like</name></package>\n")
    names = VARIANTS[:variants]
    (pkg / "urdf" / "inc" / "arm_macro.xacro").write_text(
        arm_macro(marker, work, meshes=mesh_triangles > 0))
    (pkg / "urdf" / "inc" / f"{names[0]}_tool.xacro").write_text(tool_macro())
    for i, v in enumerate(names):
        (pkg / "urdf" / f"{v}.urdf.xacro").write_text(entry(v, i, tool=i == 0))
        if mesh_triangles:
            (pkg / "meshes" / v).mkdir(parents=True, exist_ok=True)
            for j, name in enumerate(LINKS):
                (pkg / "meshes" / v / f"{name}.stl").write_bytes(stl(mesh_triangles, i * 10 + j))
    return pkg
