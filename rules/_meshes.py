"""Mesh helpers shared by the UL4xx rules, and a tiny ASCII STL for their examples (not a rule)."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, Collection, Iterator

from urdf_lint.engine.api import Cause, MeshStatus, Report
from urdf_lint.rules._schema import urdf_iter

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.engine.api import Context, Model

UNKNOWN_PACKAGE = "UL004"   # the root cause of references to an unknown package (ul004)
# the resolution statuses that mean "there is no such file" (UL401, and UL407 for textures)
NOT_FOUND = frozenset({MeshStatus.NOT_FOUND, MeshStatus.UNKNOWN_PACKAGE})

TETRA_STL = """solid tetra
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 0.1 0 0
  vertex 0 0.1 0
 endloop
endfacet
facet normal 0 -1 0
 outer loop
  vertex 0 0 0
  vertex 0 0 0.1
  vertex 0.1 0 0
 endloop
endfacet
facet normal -1 0 0
 outer loop
  vertex 0 0 0
  vertex 0 0.1 0
  vertex 0 0 0.1
 endloop
endfacet
facet normal 1 1 1
 outer loop
  vertex 0.1 0 0
  vertex 0 0 0.1
  vertex 0 0.1 0
 endloop
endfacet
endsolid tetra
"""


# a COLLADA tetrahedron whose material samples a <surface> that does not exist (pycollada
# drops the geometry bound to it), and the same file without the broken sampler
BROKEN_SURFACE_DAE = """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Z_UP</up_axis></asset>
  <library_images/>
  <library_effects>
    <effect id="skin-effect">
      <profile_COMMON>
        <newparam sid="skin-sampler">
          <sampler2D><source>skin-surface</source></sampler2D>
        </newparam>
        <technique sid="common">
          <lambert>
            <diffuse><texture texture="skin-sampler" texcoord="UVMap"/></diffuse>
          </lambert>
        </technique>
      </profile_COMMON>
    </effect>
  </library_effects>
  <library_materials>
    <material id="skin-material" name="skin"><instance_effect url="#skin-effect"/></material>
  </library_materials>
  <library_geometries>
    <geometry id="tetra-mesh" name="tetra">
      <mesh>
        <source id="tetra-positions">
          <float_array id="tetra-positions-array" count="12">0 0 0 0.1 0 0 0 0.1 0 0 0 0.1</float_array>
          <technique_common><accessor source="#tetra-positions-array" count="4" stride="3">
            <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
          </accessor></technique_common>
        </source>
        <vertices id="tetra-vertices"><input semantic="POSITION" source="#tetra-positions"/></vertices>
        <triangles material="skin-material" count="4">
          <input semantic="VERTEX" source="#tetra-vertices" offset="0"/>
          <p>0 2 1 0 1 3 0 3 2 1 2 3</p>
        </triangles>
      </mesh>
    </geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="Scene" name="Scene">
      <node id="tetra" name="tetra" type="NODE">
        <matrix sid="transform">1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1</matrix>
        <instance_geometry url="#tetra-mesh" name="tetra">
          <bind_material><technique_common>
            <instance_material symbol="skin-material" target="#skin-material"/>
          </technique_common></bind_material>
        </instance_geometry>
      </node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#Scene"/></scene>
</COLLADA>
"""
PLAIN_DAE = BROKEN_SURFACE_DAE.replace(
    '<newparam sid="skin-sampler">\n          <sampler2D><source>skin-surface</source></sampler2D>\n'
    '        </newparam>\n', "").replace(
    '<texture texture="skin-sampler" texcoord="UVMap"/>', "<color>0.8 0.8 0.8 1</color>")


def scaled(factor: float) -> str:
    out = []
    for line in TETRA_STL.splitlines():
        s = line.strip()
        if s.startswith("vertex"):
            x, y, z = (float(v) * factor for v in s.split()[1:])
            line = f"  vertex {x:g} {y:g} {z:g}"
        out.append(line)
    return "\n".join(out) + "\n"


def resolution_problems(model: Model, ctx: Context, statuses: Collection[MeshStatus],
                        tag: str = "mesh") -> Iterator[Report]:
    """(element, message) for every ``<tag filename>`` in the URDF part of the document whose
    resolution ended in one of ``statuses`` (:class:`urdf_lint.meshes.resolve.MeshStatus`). A
    reference to an unknown package is an instance of that package's root cause (one
    ``UL004`` with every reference listed under it), not a finding of its own."""
    for m in urdf_iter(model, tag):
        uri = m.get("filename")
        if uri:
            ref = ctx.mesh_ref(model, uri)
            if ref.status in statuses:
                if ref.status is MeshStatus.UNKNOWN_PACKAGE and ref.package:
                    yield Report(m, f"{tag} '{uri}'", cause=Cause(UNKNOWN_PACKAGE,
                                                            f"package:{ref.package}", ref.cause))
                else:
                    yield Report(m, ref.message)


def resolved_meshes(model: Model, ctx: Context) -> Iterator[tuple[Any, str, str]]:
    """(mesh element, uri, path) for every <mesh> that resolved inside the roots."""
    for m in urdf_iter(model, "mesh"):
        uri = m.get("filename")
        if not uri:
            continue
        ref = ctx.mesh_ref(model, uri)
        if ref.status is MeshStatus.OK and ref.path:
            yield m, uri, ref.path
