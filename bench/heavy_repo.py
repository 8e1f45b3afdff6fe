"""Generate a synthetic mesh-heavy ROS description repository (issue 12).

    generate(root, packages=6, stl_triangles=200_000) -> list of (entry file, args)

Every package has a ``package.xml``, large binary STLs (closed spheres, so the inertia rules
measure real volumes), an ASCII STL, a textured COLLADA file (``<unit meter="0.001">``, a PNG
through ``<init_from>``), an OBJ with its MTL and a ``map_Kd`` texture, a macro file and two
robot variants chosen by a xacro arg (the same meshes, the way real description packages
share them). One more package holds a 200-link serial robot built by a recursive-free macro
called 200 times. Only numpy is needed (the PNG is written by hand).
"""
from __future__ import annotations

import os
import struct
import zlib
from pathlib import Path

import numpy as np

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def sphere(n_tris: int, radius: float = 0.05, center=(0.0, 0.0, 0.0)):
    """(vertices (V, 3), faces (F, 3)) of a closed UV sphere with about ``n_tris`` triangles."""
    n = max(4, int((n_tris / 2) ** 0.5))
    lat = np.linspace(0, np.pi, n + 1)
    lon = np.linspace(0, 2 * np.pi, n + 1)[:-1]
    la, lo = np.meshgrid(lat, lon, indexing="ij")
    v = np.stack([np.sin(la) * np.cos(lo), np.sin(la) * np.sin(lo), np.cos(la)], -1) * radius
    v = v.reshape(-1, 3)
    v[:n] = [0, 0, radius]          # one pole vertex per ring position: merged when read
    v[-n:] = [0, 0, -radius]
    i = np.arange(n)[:, None] * n
    j = np.arange(n)[None, :]
    a, b = i + j, i + (j + 1) % n
    c, d = a + n, b + n
    f = np.concatenate([np.stack([a, c, b], -1).reshape(-1, 3),
                        np.stack([b, c, d], -1).reshape(-1, 3)])
    return v + np.asarray(center, dtype=float), f


def write_binary_stl(path: Path, v, f) -> None:
    tri = v[f].astype("<f4")
    rec = np.zeros(len(f), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rec["v"] = tri
    with open(path, "wb") as fh:
        fh.write(b"synthetic heavy".ljust(80, b" "))
        fh.write(struct.pack("<I", len(f)))
        fh.write(rec.tobytes())


def write_ascii_stl(path: Path, v, f) -> None:
    lines = ["solid part"]
    for t in v[f]:
        lines += ["facet normal 0 0 0", " outer loop"]
        lines += [f"  vertex {p[0]:.6e} {p[1]:.6e} {p[2]:.6e}" for p in t]
        lines += [" endloop", "endfacet"]
    lines.append("endsolid part")
    path.write_text("\n".join(lines) + "\n")


def write_png(path: Path, w: int = 64, h: int = 64) -> None:
    img = (np.indices((h, w)).sum(0) % 256).astype(np.uint8)
    raw = b"".join(b"\x00" + bytes(np.stack([row, row[::-1], row], -1).ravel()) for row in img)

    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                     + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def write_dae(path: Path, v, f, texture: str) -> None:
    """A textured COLLADA 1.4.1 triangle mesh in millimetres."""
    uv = (v[:, :2] - v[:, :2].min(0)) / max(float(np.ptp(v[:, :2])), 1e-9)
    pos = " ".join(f"{x:.3f}" for x in (v * 1000).ravel())
    tex = " ".join(f"{x:.4f}" for x in uv.ravel())
    idx = " ".join(str(x) for x in np.repeat(f.ravel(), 2))
    path.write_text(f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="millimeter" meter="0.001"/><up_axis>Z_UP</up_axis></asset>
  <library_images><image id="img"><init_from>{texture}</init_from></image></library_images>
  <library_effects><effect id="eff"><profile_COMMON>
    <newparam sid="surf"><surface type="2D"><init_from>img</init_from></surface></newparam>
    <newparam sid="samp"><sampler2D><source>surf</source></sampler2D></newparam>
    <technique sid="common"><phong><diffuse><texture texture="samp" texcoord="UV"/></diffuse>
    </phong></technique>
  </profile_COMMON></effect></library_effects>
  <library_materials><material id="mat"><instance_effect url="#eff"/></material></library_materials>
  <library_geometries><geometry id="geo"><mesh>
    <source id="pos"><float_array id="pos-a" count="{v.size}">{pos}</float_array>
      <technique_common><accessor source="#pos-a" count="{len(v)}" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <source id="uv"><float_array id="uv-a" count="{uv.size}">{tex}</float_array>
      <technique_common><accessor source="#uv-a" count="{len(uv)}" stride="2">
        <param name="S" type="float"/><param name="T" type="float"/>
      </accessor></technique_common></source>
    <vertices id="vtx"><input semantic="POSITION" source="#pos"/></vertices>
    <triangles material="m" count="{len(f)}">
      <input semantic="VERTEX" source="#vtx" offset="0"/>
      <input semantic="TEXCOORD" source="#uv" offset="1" set="0"/>
      <p>{idx}</p>
    </triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="n">
    <instance_geometry url="#geo"><bind_material><technique_common>
      <instance_material symbol="m" target="#mat"/>
    </technique_common></bind_material></instance_geometry>
  </node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
""")


def write_obj(path: Path, v, f, mtl: str, texture: str) -> None:
    uv = (v[:, :2] - v[:, :2].min(0)) / max(float(np.ptp(v[:, :2])), 1e-9)
    lines = [f"mtllib {mtl}", "o part"]
    lines += [f"v {a:.6f} {b:.6f} {c:.6f}" for a, b, c in v]
    lines += [f"vt {a:.4f} {b:.4f}" for a, b in uv]
    lines.append("usemtl skin")
    lines += [f"f {a + 1}/{a + 1} {b + 1}/{b + 1} {c + 1}/{c + 1}" for a, b, c in f]
    path.write_text("\n".join(lines) + "\n")
    path.with_name(mtl).write_text(f"newmtl skin\nKd 0.8 0.8 0.8\nmap_Kd {texture}\n")


def package_xml(name: str) -> str:
    return f"""<?xml version="1.0"?>
<package format="3">
  <name>{name}</name><version>1.0.0</version><description>synthetic</description>
  <maintainer email="a@b.c">a</maintainer><license>BSD</license>
  <buildtool_depend>ament_cmake</buildtool_depend>
</package>
"""


def _link(name, mesh_visual, mesh_collision, mass=1.0, scale=None):
    sc = f' scale="{scale}"' if scale else ""
    return f"""  <link name="{name}">
    <inertial><mass value="{mass}"/><origin xyz="0 0 0"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
    <visual><geometry><mesh filename="{mesh_visual}"{sc}/></geometry></visual>
    <collision><geometry><mesh filename="{mesh_collision}"{sc}/></geometry></collision>
  </link>
"""


def generate(root: Path, packages: int = 6, stl_triangles: int = 200_000,
             big_stls: int = 2, links: int = 200) -> list:
    """Write the repository under ``root``; return [(entry file, xacro args)] of its models."""
    root = Path(root)
    models = []
    big = sphere(stl_triangles)
    small = sphere(2_000)
    mid = sphere(20_000)
    for p in range(packages):
        name = f"arm{p}_description"
        pkg = root / "src" / name
        (pkg / "meshes" / "visual").mkdir(parents=True, exist_ok=True)
        (pkg / "meshes" / "collision").mkdir(parents=True, exist_ok=True)
        (pkg / "urdf").mkdir(parents=True, exist_ok=True)
        (pkg / "package.xml").write_text(package_xml(name))
        for k in range(big_stls):
            v, f = big
            write_binary_stl(pkg / "meshes" / "visual" / f"link{k}.stl", v * (1 + 0.01 * p + 0.1 * k), f)
        write_binary_stl(pkg / "meshes" / "collision" / "link0.stl", *small)
        write_ascii_stl(pkg / "meshes" / "collision" / "link1.stl", *small)
        write_png(pkg / "meshes" / "visual" / "skin.png")
        write_dae(pkg / "meshes" / "visual" / "cover.dae", mid[0] * (1 + 0.01 * p), mid[1], "skin.png")
        write_obj(pkg / "meshes" / "visual" / "tool.obj", small[0] * (1 + 0.01 * p), small[1],
                  "tool.mtl", "skin.png")
        u = f"package://{name}/meshes"
        macro = f"""<?xml version="1.0"?>
<robot {X}>
  <xacro:macro name="arm" params="prefix tool">
{_link("${prefix}base", f"{u}/visual/link0.stl", f"{u}/collision/link0.stl", 2.0)}
{_link("${prefix}upper", f"{u}/visual/link1.stl", f"{u}/collision/link1.stl", 1.5)}
{_link("${prefix}cover", f"{u}/visual/cover.dae", f"{u}/visual/cover.dae", 0.5)}
    <xacro:if value="${{tool}}">
{_link("${prefix}tool", f"{u}/visual/tool.obj", f"{u}/visual/tool.obj", 0.2)}
      <joint name="${{prefix}}tool_joint" type="fixed"><parent link="${{prefix}}cover"/>
        <child link="${{prefix}}tool"/></joint>
    </xacro:if>
    <joint name="${{prefix}}j1" type="revolute"><parent link="${{prefix}}base"/>
      <child link="${{prefix}}upper"/>
      <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="10" velocity="1"/></joint>
    <joint name="${{prefix}}j2" type="fixed"><parent link="${{prefix}}upper"/><child link="${{prefix}}cover"/>
      <origin xyz="0 0 0.2"/></joint>
  </xacro:macro>
</robot>
"""
        (pkg / "urdf" / "arm.macro.xacro").write_text(macro)
        entry = pkg / "urdf" / "arm.urdf.xacro"
        entry.write_text(f"""<?xml version="1.0"?>
<robot name="arm{p}" {X}>
  <xacro:arg name="tool" default="false"/>
  <xacro:include filename="$(find {name})/urdf/arm.macro.xacro"/>
  <xacro:arm prefix="" tool="$(arg tool)"/>
</robot>
""")
        (pkg / "urdf" / "arm_tool.urdf.xacro").write_text(f"""<?xml version="1.0"?>
<robot name="arm{p}_tool" {X}>
  <xacro:include filename="$(find {name})/urdf/arm.macro.xacro"/>
  <xacro:arm prefix="" tool="true"/>
</robot>
""")
        models += [(entry, {}), (pkg / "urdf" / "arm_tool.urdf.xacro", {})]
    # the 200-link robot
    name = "snake_description"
    pkg = root / "src" / name
    (pkg / "meshes").mkdir(parents=True, exist_ok=True)
    (pkg / "urdf").mkdir(parents=True, exist_ok=True)
    (pkg / "package.xml").write_text(package_xml(name))
    write_binary_stl(pkg / "meshes" / "segment.stl", *mid)
    write_binary_stl(pkg / "meshes" / "segment_collision.stl", *small)
    u = f"package://{name}/meshes"
    calls = "\n".join(f'  <xacro:seg i="{i}"/>' for i in range(1, links))
    (pkg / "urdf" / "snake.urdf.xacro").write_text(f"""<?xml version="1.0"?>
<robot name="snake" {X}>
  <xacro:property name="seg_len" value="0.1"/>
  <xacro:macro name="seg" params="i">
{_link("s${i}", f"{u}/segment.stl", f"{u}/segment_collision.stl", 0.3)}
    <joint name="j${{i}}" type="revolute"><parent link="s${{i-1}}"/><child link="s${{i}}"/>
      <origin xyz="0 0 ${{seg_len}}"/><axis xyz="0 1 0"/>
      <limit lower="-1" upper="1" effort="5" velocity="1"/></joint>
  </xacro:macro>
{_link("s0", f"{u}/segment.stl", f"{u}/segment_collision.stl", 0.3)}
{calls}
</robot>
""")
    models.append((pkg / "urdf" / "snake.urdf.xacro", {}))
    return models


if __name__ == "__main__":  # pragma: no cover - manual use
    import sys
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "heavy_repo")
    for m, a in generate(out):
        print(m, a)
    print(sum(f.stat().st_size for f in out.rglob("*") if f.is_file()) >> 20, "MB")
    os.sys.exit(0)
