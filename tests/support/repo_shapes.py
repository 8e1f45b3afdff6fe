"""Fixture repositories in the shape of real description repositories (issue 10): an entry
made only of includes, fragments that use links and properties defined elsewhere, a file
included only under ``xacro:if``, a colcon workspace of package repositories, an install
layout, a generated URDF next to its xacro, meshes relative to the generated URDF."""
from __future__ import annotations

import struct
from pathlib import Path

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def package_xml(name: str, depends=()) -> str:
    deps = "".join(f"<exec_depend>{d}</exec_depend>" for d in depends)
    return (f'<?xml version="1.0"?>\n<package format="3"><name>{name}</name>'
            f'<version>0.0.0</version><description>t</description>'
            f'<maintainer email="a@b.c">t</maintainer><license>BSD</license>{deps}</package>\n')


def stl_box(size: float = 0.1) -> bytes:
    """A closed binary STL cube (12 triangles), metres-sized."""
    s = size
    v = [(x, y, z) for x in (0, s) for y in (0, s) for z in (0, s)]
    faces = [(0, 2, 1), (1, 2, 3), (4, 5, 6), (5, 7, 6), (0, 1, 4), (1, 5, 4),
             (2, 6, 3), (3, 6, 7), (0, 4, 2), (2, 4, 6), (1, 3, 5), (3, 7, 5)]
    out = bytearray(b"urdf-lint test cube".ljust(80, b" "))
    out += struct.pack("<I", len(faces))
    for a, b, c in faces:
        out += struct.pack("<3f", 0, 0, 0)
        for i in (a, b, c):
            out += struct.pack("<3f", *v[i])
        out += b"\0\0"
    return bytes(out)


def link(name: str, mesh: str | None = None) -> str:
    geom = f'<mesh filename="{mesh}"/>' if mesh else '<box size="0.1 0.1 0.1"/>'
    return (f'  <link name="{name}">\n'
            f'    <visual><geometry>{geom}</geometry></visual>\n'
            f'    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>\n'
            f'    <inertial><mass value="1.0"/>'
            f'<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>\n'
            f'  </link>\n')


def joint(name: str, parent: str, child: str, limit_upper: str = "1.0") -> str:
    return (f'  <joint name="{name}" type="revolute">\n'
            f'    <parent link="{parent}"/><child link="{child}"/>\n'
            f'    <origin xyz="0 0 0.1" rpy="0 0 0"/><axis xyz="0 0 1"/>\n'
            f'    <limit lower="-1.0" upper="{limit_upper}" effort="10" velocity="1"/>\n'
            f'  </joint>\n')


def write(root: Path, files: dict) -> Path:
    for rel, content in files.items():
        p = root / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(content, bytes):
            p.write_bytes(content)
        else:
            p.write_text(content)
    return root


def includes_only_repo(root: Path) -> Path:
    """robot_v3.xacro holds nothing but includes; main.xacro defines base_link and torso and
    the property deg_to_rad; arm.xacro and head.xacro hang off 'torso'; tool.xacro is
    included only under xacro:if and uses deg_to_rad."""
    pkg = "v3_description"
    return write(root, {
        f"{pkg}/package.xml": package_xml(pkg),
        f"{pkg}/urdf/robot_v3.xacro":
            f'<?xml version="1.0"?>\n<robot name="robot_v3" {XACRO_NS}>\n'
            f'  <xacro:arg name="with_tool" default="true"/>\n'
            f'  <xacro:include filename="$(find {pkg})/urdf/main.xacro"/>\n'
            f'  <xacro:include filename="arm.xacro"/>\n'
            f'  <xacro:include filename="package://{pkg}/urdf/head.xacro"/>\n'
            f'  <xacro:if value="$(arg with_tool)">\n'
            f'    <xacro:include filename="tool.xacro"/>\n'
            f'  </xacro:if>\n'
            f'</robot>\n',
        f"{pkg}/urdf/main.xacro":
            f'<?xml version="1.0"?>\n<robot {XACRO_NS}>\n'
            f'  <xacro:property name="deg_to_rad" value="0.017453"/>\n'
            + '  <link name="base_link"/>\n' + link("torso") +
            '  <joint name="torso_joint" type="fixed"><parent link="base_link"/>'
            '<child link="torso"/></joint>\n</robot>\n',
        f"{pkg}/urdf/arm.xacro":
            f'<?xml version="1.0"?>\n<robot {XACRO_NS}>\n'
            + link("arm", f"package://{pkg}/meshes/arm.stl") + joint("arm_joint", "torso", "arm")
            + '</robot>\n',
        f"{pkg}/urdf/head.xacro":
            f'<?xml version="1.0"?>\n<robot {XACRO_NS}>\n'
            + link("head") + joint("head_joint", "torso", "head") + '</robot>\n',
        f"{pkg}/urdf/tool.xacro":
            f'<?xml version="1.0"?>\n<robot {XACRO_NS}>\n'
            + link("tool") + joint("tool_joint", "arm", "tool", "${90 * deg_to_rad}")
            + '</robot>\n',
        f"{pkg}/meshes/arm.stl": stl_box(),
    })


def colcon_workspace(ws: Path, install_meshes: bool = False) -> Path:
    """ws/src/{robot_description, robot_meshes, gripper_description}, each its own package
    (and, in tests, its own git repository); an ignored copy of gripper_description that must
    not win. With ``install_meshes`` robot_meshes exists only as an install space
    (ws/install/share/robot_meshes)."""
    meshes_root = "install/share/robot_meshes" if install_meshes else "src/robot_meshes"
    write(ws, {
        "src/robot_description/package.xml": package_xml(
            "robot_description", ("robot_meshes", "gripper_description")),
        "src/robot_description/urdf/robot.urdf.xacro":
            f'<?xml version="1.0"?>\n<robot name="wsbot" {XACRO_NS}>\n'
            '  <xacro:include filename="$(find gripper_description)/urdf/gripper.xacro"/>\n'
            '  <link name="base_link"/>\n'
            + link("body", "package://robot_meshes/meshes/body.stl")
            + '  <joint name="body_joint" type="fixed"><parent link="base_link"/>'
            '<child link="body"/></joint>\n'
            '  <xacro:gripper parent="body"/>\n</robot>\n',
        f"{meshes_root}/package.xml": package_xml("robot_meshes"),
        f"{meshes_root}/meshes/body.stl": stl_box(),
        "src/gripper_description/package.xml": package_xml("gripper_description"),
        "src/gripper_description/urdf/gripper.xacro":
            f'<?xml version="1.0"?>\n<robot {XACRO_NS}>\n'
            '  <xacro:macro name="gripper" params="parent">\n'
            + link("finger") + joint("finger_joint", "${parent}", "finger") +
            '  </xacro:macro>\n</robot>\n',
        # an old copy, ignored by colcon: its broken macro must never be used
        "src/attic/COLCON_IGNORE": "",
        "src/attic/gripper_description/package.xml": package_xml("gripper_description"),
        "src/attic/gripper_description/urdf/gripper.xacro":
            f'<robot {XACRO_NS}><xacro:macro name="gripper" params="parent">'
            '<joint name="broken"/></xacro:macro></robot>\n',
    })
    return ws


def generated_output_repo(root: Path) -> Path:
    """xacro/robot.xacro with the generated robot.urdf checked in one folder up, meshes
    written relative to the URDF (./meshes/body.STL), and a header naming the xacro."""
    return write(root, {
        "gen_description/package.xml": package_xml("gen_description"),
        "gen_description/xacro/robot.xacro":
            f'<?xml version="1.0"?>\n<robot name="genbot" {XACRO_NS}>\n'
            '  <xacro:property name="height" value="0.1"/>\n'
            '  <link name="base_link"/>\n'
            + link("body", "./meshes/body.STL") +
            '  <joint name="body_joint" type="fixed"><parent link="base_link"/>'
            '<child link="body"/><origin xyz="0 0 ${height}" rpy="0 0 0"/></joint>\n</robot>\n',
        "gen_description/meshes/body.STL": stl_box(),
    })
