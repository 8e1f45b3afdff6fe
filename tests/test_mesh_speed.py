"""Issue 12: mesh facts from the loaders' arrays (no trimesh processing), big STLs streamed in
chunks, hashing/listing/texture scans done once, and package-grouped worker scheduling."""
from __future__ import annotations

import json
import os
import re
import struct
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from conftest import CORPUS, REPO, make_package, run_cli

sys.path.insert(0, str(REPO / "bench"))
from heavy_repo import sphere, write_dae, write_obj, write_png  # noqa: E402 - the bench's generator


def binary_stl(path: Path, tris) -> Path:
    rec = np.zeros(len(tris), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rec["v"] = tris
    path.write_bytes(b"x" * 80 + struct.pack("<I", len(tris)) + rec.tobytes())
    return path


def ascii_stl(path: Path, tris) -> Path:
    out = ["solid part"]
    for t in tris:
        out += ["facet normal 0 0 1", "outer loop", *(f"vertex {p[0]:.9g} {p[1]:.9g} {p[2]:.9g}" for p in t),
                "endloop", "endfacet"]
    path.write_text("\n".join(out + ["endsolid part"]) + "\n")
    return path


def trimesh_facts(path) -> dict:
    """The facts as urdf-lint measured them before issue 12: on trimesh's concatenated mesh."""
    from urdf_lint.meshes import resolve as meshes
    m = meshes.load_mesh(str(path))
    v = np.asarray(m.vertices, dtype=float)
    finite = bool(np.isfinite(v).all()) if len(v) else True
    return {"ok": True, "error": "", "vertices": len(v), "faces": len(m.faces), "finite": finite,
            "bounds": [list(map(float, v.min(0))), list(map(float, v.max(0)))]
            if len(v) and finite else None,
            "broken_refs": list(m.metadata.get("broken_refs", ()))}


def counted(facts: dict, path) -> dict:
    """``facts`` as compared with trimesh's: a COLLADA file's vertex count only says whether it
    has any (urdf-lint counts the positions its triangles use, read without merging them;
    trimesh's mesh, its merged corners; the rules ask nothing more of it)."""
    if str(path).lower().endswith(".dae"):
        return {**facts, "vertices": bool(facts["vertices"])}
    return facts


def same_as_trimesh(got: dict, want: dict, path) -> bool:
    """urdf-lint's facts ``got`` are trimesh's ``want`` (:func:`counted`), a COLLADA file's
    bounds as :func:`same_bounds` compares them."""
    got, want = counted(got, path), counted(want, path)
    if not str(path).lower().endswith(".dae") or got["bounds"] is None or want["bounds"] is None:
        return got == want
    return {**got, "bounds": None} == {**want, "bounds": None} and \
        same_bounds(got["bounds"], want["bounds"])


def lint_in_process(path, cache=None):
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import RunRequest, run_check
    cfg = load_config(None)
    return run_check(RunRequest([str(path)], cfg, build_resolver([str(path)], cfg), cache=cache,
                                in_process=True)).findings


@pytest.fixture
def fresh(monkeypatch):
    """The mesh module with empty per-process memories."""
    from urdf_lint.core import hashing
    from urdf_lint.meshes import resolve as meshes
    for name in ("_memory", "_mass_memory", "_textures", "_arrays_memo", "_kept_bytes",
                 "_lean_read"):
        monkeypatch.setattr(meshes, name, type(getattr(meshes, name))())
    monkeypatch.setattr(hashing, "_memo", {})
    monkeypatch.setattr(meshes, "_loaded", type(meshes._loaded)())
    return meshes


# -- item 1: the same facts, without trimesh's processing ------------------------------------
def test_binary_and_ascii_stl_facts_equal_trimesh(tmp_path, fresh):
    v, f = sphere(3000)
    b = binary_stl(tmp_path / "b.stl", v[f])
    a = ascii_stl(tmp_path / "a.STL", v[f][:200])
    for p in (b, a):
        assert fresh.mesh_facts(str(p)) == trimesh_facts(p)
    assert fresh.mesh_facts(str(b))["faces"] == len(f)
    assert fresh._loaded == {}, "plain facts must not keep a loaded trimesh"


def test_stl_that_trimesh_reads_otherwise_still_goes_through_trimesh(tmp_path, fresh):
    v, f = sphere(300)
    p = binary_stl(tmp_path / "short.stl", v[f])
    p.write_bytes(p.read_bytes()[:-7])            # the header says more than the file holds
    got = fresh.mesh_facts(str(p))
    try:
        want = trimesh_facts(p)
    except Exception as e:  # noqa: BLE001
        from urdf_lint.meshes.resolve import error_text
        assert not got["ok"] and got["error"] == error_text(e)[:300]
    else:
        assert got == want
    two = tmp_path / "two.stl"                       # two solids: trimesh stacks them
    ascii_stl(tmp_path / "one.stl", v[f][:10])
    two.write_text((tmp_path / "one.stl").read_text() * 2)
    assert fresh.mesh_facts(str(two)) == trimesh_facts(two)


def test_dae_unit_and_obj_facts_equal_trimesh(tmp_path, fresh):
    v, f = sphere(800, center=(0.1, -0.2, 0.3))
    write_png(tmp_path / "skin.png")
    write_dae(tmp_path / "m.dae", v, f, "skin.png")
    write_obj(tmp_path / "m.obj", v, f, "m.mtl", "skin.png")
    for name in ("m.dae", "m.obj"):
        got = fresh.mesh_facts(str(tmp_path / name))
        assert same_as_trimesh(got, trimesh_facts(tmp_path / name), name)
        assert got["ok"] and got["vertices"] > 0
    # the COLLADA file is in millimetres: the facts are in metres (<unit meter="0.001">)
    assert fresh.mesh_facts(str(tmp_path / "m.dae"))["bounds"][1][0] == pytest.approx(0.15, abs=2e-3)


@pytest.mark.skipif(not (CORPUS / "MANIFEST.md").is_file(), reason="../shared/corpus is not present")
def test_corpus_mesh_facts_equal_trimesh(fresh):
    """Every mesh of the real robots: the same counts, bounds and finiteness as trimesh's mesh,
    and the same mass properties as measured on it."""
    paths = sorted(p for p in CORPUS.rglob("*") if p.suffix.lower() in (".stl", ".dae", ".obj"))
    assert len(paths) > 100
    for p in paths[::3]:
        try:
            want = trimesh_facts(p)
        except Exception:  # noqa: BLE001 - unloadable meshes: checked by the UL404 tests
            continue
        assert same_as_trimesh(fresh.mesh_facts(str(p)), want, p), p
        got, want = fresh.mass_facts(str(p)), fresh.trimesh_mass_properties(fresh.load_mesh(str(p)))
        # (the convex hull of an open mesh can differ in the last bit between calls)
        assert got.keys() == want.keys() and got.get("hull") == want.get("hull"), p
        for k in ("volume", "first", "second", "bounds"):
            if k in want:
                assert np.allclose(got[k], want[k], rtol=1e-12, atol=0), (p, k)


# -- COLLADA without trimesh: pycollada's scene assembled like trimesh's loader ----------------
def _geometry(gid, v, polys, with_uv=True, kind="triangles", material="m", normals=None,
              uv=None, exact=False):
    """A <geometry> of positions ``v`` and polygons (lists of vertex indices), with normals
    and UVs (``normals``, ``uv``: those given, one per position), as a <triangles> or a
    <polylist>; ``exact``: the numbers as float32, written to their last digit."""
    if uv is None:
        uv = (v[:, :2] - v[:, :2].min(0)) / max(float(np.ptp(v[:, :2])), 1e-9)
    nrm = v / np.linalg.norm(v, axis=1, keepdims=True).clip(1e-9) if normals is None else normals
    fl = (lambda a: " ".join(f"{float(x):.9g}" for x in np.asarray(a, dtype=np.float32).ravel())) \
        if exact else (lambda a: " ".join(f"{x:.6f}" for x in a.ravel()))
    inputs = [("VERTEX", f"#{gid}-v"), ("NORMAL", f"#{gid}-n")] + \
        ([("TEXCOORD", f"#{gid}-uv")] if with_uv else [])
    p = " ".join(" ".join(str(i) for _ in inputs) for poly in polys for i in poly)
    tc_set = ' set="0"'
    ins = "".join(f'<input semantic="{s}" source="{src}" offset="{k}"{tc_set if s == "TEXCOORD" else ""}/>'
                  for k, (s, src) in enumerate(inputs))
    vc = f"<vcount>{' '.join(str(len(q)) for q in polys)}</vcount>" if kind == "polylist" else ""
    xyz = '<param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>'
    st = '<param name="S" type="float"/><param name="T" type="float"/>'

    def source(sid, a, stride, params):
        return (f'<source id="{sid}"><float_array id="{sid}a" count="{a.size}">{fl(a)}</float_array>'
                f'<technique_common><accessor source="#{sid}a" count="{len(a)}" stride="{stride}">'
                f"{params}</accessor></technique_common></source>")
    return (f'<geometry id="{gid}"><mesh>{source(gid + "-p", v, 3, xyz)}'
            f'{source(gid + "-n", nrm, 3, xyz)}{source(gid + "-uv", uv, 2, st)}'
            f'<vertices id="{gid}-v"><input semantic="POSITION" source="#{gid}-p"/></vertices>'
            f'<{kind} material="{material}" count="{len(polys)}">{ins}{vc}<p>{p}</p></{kind}>'
            "</mesh></geometry>")


def _dae(path: Path, geometries: str, nodes: str, unit="0.001", extra="") -> Path:
    path.write_text(f"""<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="u" meter="{unit}"/><up_axis>Z_UP</up_axis></asset>
  <library_images><image id="img"><init_from>skin.png</init_from></image></library_images>
  <library_effects><effect id="eff"><profile_COMMON>
    <newparam sid="surf"><surface type="2D"><init_from>img</init_from></surface></newparam>
    <newparam sid="samp"><sampler2D><source>surf</source></sampler2D></newparam>
    <technique sid="common"><phong><diffuse><texture texture="samp" texcoord="UV"/></diffuse>
    </phong></technique>
  </profile_COMMON></effect>{extra}</library_effects>
  <library_materials><material id="mat"><instance_effect url="#eff"/></material></library_materials>
  <library_geometries>{geometries}</library_geometries>
  <library_visual_scenes><visual_scene id="scene">{nodes}</visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
""")
    return path


def _inst(gid, target="#mat"):
    return (f'<instance_geometry url="#{gid}"><bind_material><technique_common>'
            f'<instance_material symbol="m" target="{target}"/></technique_common></bind_material>'
            '</instance_geometry>')


def _generated_daes(tmp_path):
    """COLLADA files in the shapes exporters write: nested nodes with every transform kind, a
    mirrored node, a float32 rotation matrix (repaired by trimesh's scene graph), a polylist of
    quads and pentagons, an instanced geometry, metres and millimetres, a broken material
    reference and a lines-only geometry (both left to trimesh)."""
    write_png(tmp_path / "skin.png")
    v, f = sphere(600, radius=40.0, center=(5.0, -3.0, 12.0))
    v2 = np.vstack([v, v[:1] * 0.5])       # a vertex no face uses
    quads = [[i, i + 1, i + 2, i + 3] for i in range(0, len(v) - 4, 3)] + \
        [[0, 2, 4, 6, 8], [1, 3, 5, 7, 9]]
    tri = _geometry("tri", v2, f.tolist())
    poly = _geometry("poly", v, quads, kind="polylist", with_uv=False)
    c, s = 0.7071068, 0.7071067        # float32 digits: not quite a rotation
    nested = f"""<node id="a"><translate>1 2 3</translate><rotate>0 0 1 30</rotate><scale>1 1 2</scale>
      {_inst("tri")}
      <node id="b"><matrix>{c} -{s} 0 0.1 {s} {c} 0 0.2 0 0 1 0.3 0 0 0 1</matrix>{_inst("poly")}
        <node id="mirror"><scale>-1 1 1</scale>{_inst("tri")}</node></node></node>"""
    out = {
        "nested.dae": _dae(tmp_path / "nested.dae", tri + poly, nested),
        "metres.dae": _dae(tmp_path / "metres.dae", tri, f"<node>{_inst('tri')}</node>", unit="1"),
        "broken.dae": _dae(tmp_path / "broken.dae", tri + poly,
                           f"<node>{_inst('tri', '#nothing')}{_inst('poly')}</node>"),
        "lines.dae": _dae(tmp_path / "lines.dae", tri + _geometry("ln", v, [[0, 1], [1, 2]], kind="lines"),
                          f"<node>{_inst('tri')}{_inst('ln')}</node>"),
    }
    return out


def _trimesh_arrays(meshes, path):
    """The arrays of the trimesh path (``load_scene`` and ``scene_arrays``, or ``load_mesh``)."""
    got = meshes._scene_arrays(str(path), True, lean=False)
    if got is None:
        m = meshes.load_mesh(str(path))
        got = (np.asarray(m.vertices, dtype=np.float64), np.asarray(m.faces, dtype=np.int64), [])
    return got


def test_collada_reader_gives_trimesh_arrays_and_facts(tmp_path, fresh):
    from urdf_lint.meshes import readers as meshio
    daes = _generated_daes(tmp_path)
    lean = {}
    for name, p in daes.items():
        data = p.read_bytes()
        lean[name] = meshio.collada_arrays(data)
        want = _trimesh_arrays(fresh, p)
        if lean[name] is not None:
            unit = fresh._unit_of(data)
            v = meshio.scale_points(lean[name][0], unit) if unit != 1.0 else lean[name][0]
            assert np.array_equal(v, want[0]) and np.array_equal(lean[name][1], want[1]), name
        # whichever path reads it: the facts and mass properties of trimesh's mesh
        assert same_as_trimesh(fresh.mesh_facts(str(p)), trimesh_facts(p), p), name
        assert fresh.mass_facts(str(p)) == fresh.trimesh_mass_properties(fresh.load_mesh(str(p))), name
    # read without trimesh where it can be, left to trimesh where a geometry is lost
    assert lean["nested.dae"] is not None and lean["metres.dae"] is not None
    assert lean["broken.dae"] is None
    # a geometry of lines alone is no mesh in trimesh either (not lost): read without it,
    # and equal to trimesh's arrays (above)
    assert lean["lines.dae"] is not None
    assert fresh.mesh_facts(str(daes["broken.dae"]))["broken_refs"]
    # the triangle set twice (the mirrored node too), the polylist fanned (quads: 2 triangles,
    # the two pentagons: 3 each)
    sv, sf = sphere(600)
    quads = len(range(0, len(sv) - 4, 3))
    assert len(lean["nested.dae"][1]) == 2 * len(sf) + 2 * quads + 6


def test_collada_sources_shared_by_triangle_sets_are_parsed_once(tmp_path, fresh, monkeypatch):
    """Two triangle sets of one geometry (an exporter writes one per material) index the same
    positions, normals and UVs: each <float_array> is parsed once, and the arrays are still
    trimesh's."""
    from urdf_lint.meshes import readers as meshio
    write_png(tmp_path / "skin.png")
    v, f = sphere(600, radius=40.0)
    half = len(f) // 2
    # the same sources (of v) in both; each half of the faces in a <triangles> of its own
    first, second = (_geometry("g", v, part.tolist()) for part in (f[:half], f[half:]))
    end = first.index("</triangles>") + len("</triangles>")
    geometry = first[:end] + second[second.index("<triangles"):]
    assert geometry.count("<triangles") == 2 and geometry.count("<float_array") == 3
    p = _dae(tmp_path / "two_sets.dae", geometry, f"<node>{_inst('g')}</node>")
    data = p.read_bytes()
    parsed = []
    real = meshio._floats

    def counting(text, dtype=np.float32):
        if dtype == np.float32:
            parsed.append(len(text or ""))
        return real(text, dtype)
    monkeypatch.setattr(meshio, "_floats", counting)
    got = meshio.collada_arrays_lean(data)
    assert got is not None and len(parsed) == data.count(b"<float_array")
    monkeypatch.setattr(meshio, "_floats", real)
    want = _trimesh_arrays(fresh, p)
    unit = fresh._unit_of(data)
    assert np.array_equal(meshio.scale_points(got[0], unit), want[0])
    assert np.array_equal(got[1], want[1]) and len(got[1]) == len(f)
    assert same_as_trimesh(fresh.mesh_facts(str(p)), trimesh_facts(p), p)


_UNUSED_EFFECT = ('<effect id="unused"><profile_COMMON><newparam sid="s1"><surface type="2D">'
                  '<init_from>img</init_from></surface></newparam><newparam sid="s2"><sampler2D>'
                  '<source>s1</source></sampler2D></newparam></profile_COMMON></effect>'
                  '</library_effects>')
_TEXTURED = {
    # (how the effect of _dae is changed, whether the lxml reader vouches for it)
    "as written": ((), True),
    "a bump map": ((("</phong>", "</phong><extra><technique profile='x'><bump>"
                    "<texture texture='samp' texcoord='UV'/></bump></technique></extra>"),), True),
    "two samplers": ((('<newparam sid="samp">', '<newparam sid="s2"><sampler2D><source>surf'
                      '</source></sampler2D></newparam><newparam sid="samp">'),
                     ("<diffuse>", "<ambient><texture texture='s2' texcoord='UV'/></ambient>"
                      "<diffuse>")), True),
    "a sampler of no surface": ((("<source>surf</source>", "<source>nowhere</source>"),), False),
    "a surface of no image": ((("<init_from>img</init_from>", "<init_from>none</init_from>"),),
                              False),
    "a 3D surface": ((('type="2D"', 'type="3D"'),), False),
    "a texture of no sampler": ((('texture="samp"', 'texture="nothing"'),), False),
    "a bump map of no sampler": ((("</phong>", "</phong><extra><technique profile='x'><bump>"
                                  "<texture texture='lost' texcoord='UV'/></bump></technique>"
                                  "</extra>"),), False),
    "an image without a file": ((("<init_from>skin.png</init_from>", ""),), False),
    "a float parameter": ((('<newparam sid="samp">', '<newparam sid="f"><float>1</float>'
                           '</newparam><newparam sid="samp">'),), False),
    # pycollada loads effects no material uses, and fails on a profile without technique
    # (AttributeError, not a DaeError: trimesh does not ignore it)
    "an unused effect without technique": ((("</library_effects>", _UNUSED_EFFECT),), False),
    # pycollada finds the technique in the document's namespace only
    "a technique in another namespace": ((
        ('<technique sid="common">', '<x:technique xmlns:x="urn:x" sid="common">'),
        ("</phong></technique>", "</phong></x:technique>")), False),
    # pycollada loads the first bump map in the document's namespace (the other: ignored)
    "a bump map after one in another namespace": ((("</phong>", (
        "</phong><extra><technique profile='x'><x:texture xmlns:x='urn:x' texture='samp'/>"
        "<texture texture='lost' texcoord='UV'/></technique></extra>")),), False),
}


@pytest.mark.parametrize("case", sorted(_TEXTURED))
def test_textured_collada_is_read_by_lxml_only_when_pycollada_loads_its_textures(
        tmp_path, fresh, case, monkeypatch):
    """Textures (parameters, samplers, bump maps) do not change the geometry: the lxml reader
    reads a file whose textures pycollada loads, and leaves any other to pycollada and
    trimesh, trying it once. Whichever reads it, the facts are trimesh's."""
    from urdf_lint.meshes import readers as meshio
    edits, vouched = _TEXTURED[case]
    p = _generated_daes(tmp_path)["nested.dae"]
    text = p.read_text()
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new, 1)
    p.write_text(text)
    lean = meshio.collada_arrays_lean(text.encode())
    assert (lean is not None) == vouched, case
    try:
        want = trimesh_facts(p)
    except Exception:  # noqa: BLE001 - trimesh cannot load it: neither can urdf-lint
        assert not vouched and not fresh.mesh_facts(str(p))["ok"]
        return
    tried, scenes = [], []
    real = meshio.collada_soups
    monkeypatch.setattr(meshio, "collada_soups", lambda *a, **k: tried.append(1) or real(*a, **k))
    import trimesh
    real_scene = trimesh.load_scene
    monkeypatch.setattr(trimesh, "load_scene", lambda *a, **k: scenes.append(1) or real_scene(*a, **k))
    assert same_as_trimesh(fresh.mesh_facts(str(p)), want, p), case
    assert len(tried) == 1, "a file the lean reader leaves to pycollada is parsed by it once"
    if meshio.collada_arrays(text.encode(), lean=False) is not None:
        assert not scenes, "pycollada reads it, not trimesh's scene loader"
    monkeypatch.setattr(meshio, "collada_soups", real)
    if lean is not None:
        got = _trimesh_arrays(fresh, p)
        v = meshio.scale_points(lean[0], fresh._unit_of(text.encode()))
        assert np.array_equal(v, got[0]) and np.array_equal(lean[1], got[1]), case


@pytest.mark.parametrize("old,new", [
    # effects no material uses: pycollada loads them too (no technique: AttributeError;
    # a bad float: TypeError)
    ("</library_effects>", '<effect id="unused"><profile_COMMON/></effect></library_effects>'),
    ("</library_effects>", '<effect id="unused"><profile_COMMON><technique sid="c"><phong>'
     '<shininess><float>abc</float></shininess></phong></technique></profile_COMMON></effect>'
     '</library_effects>'),
    # a float where trimesh takes a colour (its [3], its [:3]: TypeError)
    ("</diffuse>", "</diffuse><transparent><float>0.5</float></transparent>"),
    ("</diffuse>", "</diffuse><emission><float>0.5</float></emission>")])
def test_collada_effect_trimesh_cannot_load_is_left_to_it(tmp_path, fresh, old, new):
    """An untextured document whose effects pycollada or trimesh fail on with an error
    trimesh does not ignore (not a DaeError): trimesh cannot load it, so the lxml reader must
    not vouch for it (the mesh does not load, whichever path reads it)."""
    from urdf_lint.meshes import readers as meshio
    p = _generated_daes(tmp_path)["nested.dae"]
    text = p.read_text()
    text = text.replace('<texture texture="samp" texcoord="UV"/>', "<color>1 0 0 1</color>")
    text = re.sub(r"<newparam.*?</newparam>", "", text, flags=re.S).replace(old, new, 1)
    p.write_text(text)
    assert "texture" not in text and "newparam" not in text and new in text
    with pytest.raises((AttributeError, TypeError)):     # (not pycollada's DaeError)
        trimesh_facts(p)
    assert meshio.collada_arrays_lean(text.encode()) is None
    assert not fresh.mesh_facts(str(p))["ok"]


def _fromstring(text: str) -> np.ndarray | str:
    """pycollada's own parse of a ``<float_array>`` (NaN read as 0), or the error it raises."""
    try:
        out = np.fromstring(text, dtype=np.float32, sep=" ")
    except ValueError as e:
        return f"ValueError: {e}"
    out[np.isnan(out)] = 0
    return out


@pytest.mark.parametrize("text", [
    "1 2 3", "  1\t2\n3\r4\v5\f6  ", ".5 5. -.5 +.5 1.e5 .1e-2 1E-5 00012 -0 +0",
    "inf -inf nan -nan +nan NaN INF Infinity -infinity", "1e39 -1e39 1e-46 1e-45 1e400 -1e-400",
    "3.4028235e38 3.4028236e38 1.17549435e-38 1.4e-45 7e-46",
    # what numpy's text reader refuses or reads otherwise: fromstring decides, as before
    "nan(0x7) 1", "1 2 junk", "1,2", "1_0 2", "0x1p3", "1 # 2", "1d5", "- 1", "1e 2",
    "1\xa02", "\u0663 1", "1 2\x00 3", "+-1"])
def test_collada_float_arrays_are_read_as_fromstring_reads_them(text):
    """The lean COLLADA reader's fast parse of a ``<float_array>`` gives fromstring's float32
    values bit for bit, or its very error (then the file goes to pycollada)."""
    from urdf_lint.meshes import readers as meshio
    want = _fromstring(text)
    try:
        got: np.ndarray | str = meshio._floats(text)
    except ValueError as e:
        got = f"ValueError: {e}"
    if isinstance(want, str):
        assert got == want
    else:
        assert isinstance(got, np.ndarray) and got.dtype == np.float32
        assert got.tobytes() == want.tobytes(), (got, want)


def test_obj_vertex_numbers_are_read_as_fromstring_reads_them():
    """The OBJ reader's parse of its ``v`` rows (numpy's text reader) gives fromstring's
    float64 values bit for bit: decimals halfway between doubles and a hair either side, every
    spelling the reader's pattern lets through (``1.``, ``.5``, ``+3``, exponents), subnormals
    and the largest doubles."""
    from urdf_lint.meshes import readers as meshio
    rng = np.random.default_rng(11)
    f = rng.standard_normal(20000) * 10.0 ** rng.integers(-300, 300, 20000)
    up = np.nextafter(f, np.inf)
    words = [f"{x:.17g}" for x in f] + [f"{x:.25e}" for x in (f + up) / 2] + \
        ["1.", ".5", "+3", "-0", "+.25e-3", "1E5", "4.9e-324", "2.4e-324", "1.7976931348623157e308",
         "2.2250738585072011e-308", "0.1", "123456789012345678901234567890"]
    text = " ".join(w.replace("e+", "e") for w in words)
    got = meshio.number_row(text, np.float64)
    want = np.fromstring(text, sep=" ", dtype=np.float64)
    assert got.dtype == np.float64 and got.tobytes() == want.tobytes()


def test_collada_float_arrays_round_like_fromstring_near_every_float32_boundary():
    """Decimals halfway between float32 neighbours (and a hair either side), in every format
    exporters write, read to the same float32 bits as fromstring's."""
    from urdf_lint.meshes import readers as meshio
    rng = np.random.default_rng(7)
    f = rng.standard_normal(20000).astype(np.float32) * np.float32(10.0) ** rng.integers(
        -40, 39, 20000).astype(np.float32)
    f = f[np.isfinite(f)]
    up = np.nextafter(f, np.float32(np.inf))
    mid = (f.astype(np.float64) + up.astype(np.float64)) / 2
    values = np.concatenate([mid, np.nextafter(mid, np.inf), np.nextafter(mid, -np.inf),
                             f.astype(np.float64)])
    for fmt in ("%.17g", "%.9g", "%.8e", "%.6f", "%r"):
        text = " \n".join(fmt % v for v in values) if fmt != "%r" else \
            "\t".join(repr(float(v)) for v in values)
        got, want = meshio._floats(text), _fromstring(text)
        assert isinstance(want, np.ndarray) and got.tobytes() == want.tobytes(), fmt


def same_bounds(got, want) -> bool:
    """Bounds equal but for the last bits a matrix product may round otherwise: a node's
    matrix places the positions used in one array and the merged vertices in another, and a
    BLAS may sum a product differently by where a row lies (bit for bit equal with this
    machine's OpenBLAS), and for a zero's sign. A vertex kept wrongly is ~1e-8 of the
    coordinate off: ~1e7 times the 8 ulps allowed, axis by axis."""
    got, want = np.asarray(got, dtype=np.float64), np.asarray(want, dtype=np.float64)
    scale = np.maximum(np.abs(want).max(axis=0), np.finfo(np.float64).tiny)
    return bool((np.abs(got - want) <= 8 * np.spacing(scale)).all())


def _one_set_dae(path, v, tris, node="", kind="triangles", with_uv=True, normals=None,
                 unit="1"):
    """A COLLADA file of one triangle set of float32 positions ``v`` written to the last digit
    (normals +z unless given, UVs 0), instanced in a node holding ``node`` (or ``node`` whole)."""
    v = np.asarray(v, dtype=np.float32)
    normals = np.tile(np.float32([0, 0, 1]), (len(v), 1)) if normals is None else normals
    geometry = _geometry("g", v, tris, normals=np.asarray(normals, dtype=np.float32),
                         uv=np.zeros((len(v), 2), dtype=np.float32), exact=True, kind=kind,
                         with_uv=with_uv)
    nodes = node if "<node" in node else f"<node>{node}{_inst('g')}</node>"
    return _dae(path, geometry, nodes, unit=unit)


def _hair_apart(sign, first_hair, same_normal=True):
    """A tetrahedron-like set whose lowest (``sign`` 1) or highest (-1) x is held by two
    positions 4e-9 apart, which the merge groups (8 decimals) unless their normals differ;
    ``first_hair``: the one a hair inside comes first in the corners' order, so the merge
    keeps it and the merged bounds are not the positions' bounds."""
    v = np.array([[0, 0, 0], [4e-9, 0, 0], [1, 0, 0], [1, 1, 0], [1, 0, 1], [1, 1, 1]],
                 dtype=np.float32) * sign
    normals = np.tile(np.float32([0, 0, 1]), (6, 1))
    if not same_normal:
        normals[1] = (0, 1, 0)
    exact, hair = ([1, 2, 3], [0, 4, 5]) if first_hair else ([0, 2, 3], [1, 4, 5])
    return v, normals, [exact, hair, [2, 3, 4], [3, 4, 5]]


def test_collada_bounds_without_merging_are_the_merged_vertices_bounds(tmp_path, fresh):
    """meshio.collada_bounds (the facts of a COLLADA file, no vertex merge) gives the bounds of
    the merged vertices bit for bit: where two positions a hair apart hold an extreme, those
    corners are grouped as the merge groups them (the kept one decides), also through a
    rotating, scaling node; its counts are the triangles and the positions they use."""
    from urdf_lint.meshes import readers as meshio
    write_png(tmp_path / "skin.png")
    cases = {}
    for sign in (1, -1):
        for first_hair in (True, False):
            for same in (True, False):
                v, n, tris = _hair_apart(sign, first_hair, same)
                for placed, node in (("plain", ""),
                                     ("rotated", "<rotate>0 0 1 90</rotate><scale>2 2 2</scale>")):
                    name = f"{sign}-{first_hair}-{same}-{placed}"
                    cases[name] = (_one_set_dae(tmp_path / f"{name}.dae", v, tris, node, normals=n,
                                                unit="0.001"),
                                   sign, first_hair and same, placed)
    moved = 0
    for name, (path, sign, kept_hair, placed) in cases.items():
        data = path.read_bytes()
        merged = meshio.collada_arrays_lean(data)
        got = meshio.collada_bounds(data)
        assert merged is not None and got is not None, name
        lo, hi = meshio.bounds(merged[0])
        assert same_bounds((got[0], got[1]), (lo, hi)), name
        assert got[2:] == (6, 4), name        # the positions used, the triangles
        want = _trimesh_arrays(fresh, path)
        assert np.allclose(meshio.scale_points(np.array([lo, hi]), fresh._unit_of(data)),
                           meshio.bounds(want[0]), rtol=0, atol=1e-15), name
        # the case is what it claims: the merge kept the position a hair inside the extreme
        # (x, which the node turns to y), else the exact one at 0
        axis = 1 if placed == "rotated" else 0
        extreme = lo[axis] if sign == 1 else hi[axis]
        assert (extreme != 0) == kept_hair and abs(extreme) < 1e-8, (name, extreme)
        moved += kept_hair
    assert moved == 4
    # the facts: the merged bounds in metres, the triangles, positions counted once
    facts = fresh.mesh_facts(str(cases["1-True-True-plain"][0]))
    assert facts["ok"] and facts["faces"] == 4 and facts["vertices"] == 6
    assert facts["bounds"][0][0] == float(np.float32(4e-9)) * 0.001


def test_collada_bounds_without_merging_hold_where_the_merge_is_unusual(tmp_path, fresh):
    """What a red-team pass found, and more: a translation cancelling coordinates of 1e9 (the
    placed corners of one merge group land 1.2e-7 apart, more than 1e-8 times the matrix),
    the lowest corner in a second instance, hairs in a polylist and in sets without normals
    or bound UVs; and coordinates so large (1e11) that the merge's integer keys overflow
    and merge unrelated corners: the merged arrays are read then."""
    from urdf_lint.meshes import readers as meshio
    write_png(tmp_path / "skin.png")
    x, z1, z2 = 1e9, np.float32(5.6e-8), np.float32(6.4e-8)    # (merge keys 6 and 6)
    cancel = [[x, 0, z2], [x, 0, z1], [x + 64, 1, 0], [x + 64, 0, 1], [x + 128, 1, 1]]
    hair = [[4e-9, 0, 0], [0, 0, 0], [1, 1, 0], [1, 0, 1], [1, 1, 1]]
    tris = [[0, 2, 3], [1, 3, 4], [2, 3, 4]]
    cases = {
        "cancel": _one_set_dae(tmp_path / "cancel.dae", cancel, tris,
                               "<matrix>1 0 1 -1e9 0 1 0 0 0 0 1 0 0 0 0 1</matrix>"),
        "second instance": _one_set_dae(
            tmp_path / "second.dae", hair, tris,
            f"<node>{_inst('g')}</node><node><translate>-1 0 0</translate>{_inst('g')}</node>"),
        "polylist": _one_set_dae(tmp_path / "poly.dae", hair, [[0, 2, 3, 4], [1, 3, 4]],
                                 kind="polylist"),
        "no uv": _one_set_dae(tmp_path / "no_uv.dae", hair, tris, with_uv=False),
    }
    for name, path in cases.items():
        data = path.read_bytes()
        merged = meshio.collada_arrays_lean(data)
        got = meshio.collada_bounds(data)
        assert merged is not None and got is not None, name
        assert same_bounds((got[0], got[1]), meshio.bounds(merged[0])), name
        assert got[3] == len(merged[1]), name
    # (the hair is kept: it comes first; the grouping decided, not the lowest position)
    got = meshio.collada_bounds(cases["polylist"].read_bytes())
    assert got[0][0] == float(np.float32(4e-9))
    assert meshio.collada_bounds(cases["cancel"].read_bytes())[0][0] > 0
    huge = _one_set_dae(tmp_path / "huge.dae", [[-1e11, 0, 0], [1e11, 0, 0], [0, 1, 0]],
                        [[0, 1, 2]])
    assert meshio.collada_arrays_lean(huge.read_bytes()) is not None
    assert meshio.collada_bounds(huge.read_bytes()) is None, "overflowing keys: arrays read"
    assert same_as_trimesh(fresh.mesh_facts(str(huge)), trimesh_facts(huge), huge)
    # None exactly where the lean reader declines
    for name, path in _generated_daes(tmp_path).items():
        data = path.read_bytes()
        assert (meshio.collada_bounds(data) is None) == \
            (meshio.collada_arrays_lean(data) is None), name


def test_a_collada_files_facts_and_mass_properties_parse_it_once(tmp_path, fresh, monkeypatch):
    """A collision mesh's facts (its bounds, read without merging) and then its mass
    properties (merged arrays) come from one lxml parse of the file: what the facts read is
    kept for the arrays, and they are trimesh's."""
    from urdf_lint.meshes import readers as meshio
    v, f = sphere(500, radius=40.0, center=(5.0, -3.0, 12.0))
    write_png(tmp_path / "skin.png")
    p = _dae(tmp_path / "part.dae", _geometry("g", v, f.tolist()),
             f"<node><rotate>0 0 1 30</rotate>{_inst('g')}</node>")
    parsed = []
    real = meshio.collada_soups
    monkeypatch.setattr(meshio, "collada_soups", lambda *a, **k: parsed.append(1) or real(*a, **k))
    facts, mass = fresh.mesh_facts(str(p)), fresh.mass_facts(str(p))
    assert len(parsed) == 1, "parsed again for its arrays"
    monkeypatch.setattr(meshio, "collada_soups", real)
    assert same_as_trimesh(facts, trimesh_facts(p), p)
    want = fresh.trimesh_mass_properties(fresh.load_mesh(str(p)))
    assert mass.keys() == want.keys() and mass["ok"] and mass.get("hull") == want.get("hull")
    for k in ("volume", "first", "second", "bounds"):
        assert np.allclose(mass[k], want[k], rtol=1e-12, atol=0), k
    assert not fresh._lean_read, "taken by the arrays, not kept"


@pytest.mark.skipif(not (CORPUS / "MANIFEST.md").is_file(), reason="../shared/corpus is not present")
def test_corpus_collada_bounds_without_merging_are_the_merged_bounds():
    """Every COLLADA file of the real robots the lean reader reads: the bounds without
    merging are those of the merged vertices, bit for bit."""
    from urdf_lint.meshes import readers as meshio
    paths = sorted(p for p in CORPUS.rglob("*") if p.suffix.lower() == ".dae")
    read = 0
    for p in paths:
        data = p.read_bytes()
        merged = meshio.collada_arrays_lean(data)
        got = meshio.collada_bounds(data)
        assert (merged is None) == (got is None), p
        if merged is None:
            continue
        read += 1
        lo, hi = meshio.bounds(merged[0])
        assert same_bounds((got[0], got[1]), (lo, hi)), p
        assert got[3] == len(merged[1]), p
    assert read >= 30, read


@pytest.mark.skipif(not (CORPUS / "MANIFEST.md").is_file(), reason="../shared/corpus is not present")
def test_corpus_collada_read_without_trimesh_gives_the_same_arrays(fresh):
    from urdf_lint.meshes import readers as meshio
    paths = sorted(p for p in CORPUS.rglob("*") if p.suffix.lower() == ".dae")
    assert len(paths) > 30
    lean_read = 0
    for p in paths:
        data = p.read_bytes()
        got = meshio.collada_arrays(data)
        if got is None:
            continue
        lean_read += 1
        unit = fresh._unit_of(data)
        want = _trimesh_arrays(fresh, p)
        v = meshio.scale_points(got[0], unit) if unit != 1.0 else got[0]
        assert np.array_equal(v, want[0]) and np.array_equal(got[1], want[1]), p
    assert lean_read >= len(paths) - 2    # (turtlebot3's r200.dae loses a geometry: trimesh)


# -- OBJ without trimesh: trimesh's loader, grouping and unmerging, for plain files -------------
def _obj_text(v, faces, form="v", materials=None, normals=False, extra="", crlf=False):
    """An OBJ of positions ``v`` and ``faces`` (rows of 3 or 4 zero-based indices) written in
    ``form``, the faces spread over ``materials`` (a list: the material of each face)."""
    n = len(v)
    lines = ["# generated", "mtllib m.mtl", "o part"] + [f"v {a:.6f} {b:.6f} {c:.6f}" for a, b, c in v]
    lines += [f"vt {(i % 7) / 7:.4f} {(i % 5) / 5:.4f}" for i in range(n)]
    if normals:
        lines += ["vn 0 0 1", "vn 0 1 0", "vn 1 0 0"]
    current = object()
    for k, face in enumerate(faces):
        if materials is not None and materials[k] != current:
            current = materials[k]
            lines.append(f"usemtl {current}")
        refs = []
        for j, i in enumerate(face):
            t, nn = (i * 3 + j) % n + 1, (i + k) % 3 + 1
            refs.append({"v": f"{i + 1}", "v/t": f"{i + 1}/{t}", "v//n": f"{i + 1}//{nn}",
                         "v/t/n": f"{i + 1}/{t}/{nn}"}[form])
        lines.append("f " + " ".join(refs))
    text = "\n".join(lines) + "\n" + extra
    return text.replace("\n", "\r\n") if crlf else text


def _generated_objs(tmp_path):
    v, f = sphere(600, radius=0.2, center=(0.3, -0.1, 0.05))
    quads = np.column_stack([f[:-1:2, 0], f[:-1:2, 1], f[1::2, 2], f[:-1:2, 2]])
    k = len(f)
    mats = [("red", "blue", "red", "green")[(i // 50) % 4] for i in range(k)]
    specs = {
        "plain.obj": dict(faces=f),
        "uv.obj": dict(faces=f, form="v/t"),
        "normals.obj": dict(faces=f, form="v//n", normals=True),
        "normal_refs_without_vn.obj": dict(faces=f, form="v//n"),
        "full.obj": dict(faces=f, form="v/t/n", normals=True),
        "materials.obj": dict(faces=f, form="v/t", materials=mats),
        "quads.obj": dict(faces=quads, form="v/t/n", normals=True, materials=mats[:len(quads)]),
        "crlf.obj": dict(faces=f, form="v/t", crlf=True),
        # not plain: trimesh reads them (the lean reader declines)
        "negative.obj": dict(faces=f, extra="f -1 -2 -3\n"),
        "out_of_range.obj": dict(faces=f, extra=f"f 1 2 {len(v) + 5}\n"),
        "mixed.obj": dict(faces=f, extra="f 1/1 2/2 3/3\n"),
        "polygon.obj": dict(faces=f, extra="f 1 2 3 4 5\n"),
        "comment_usemtl.obj": dict(faces=f, extra="# usemtl hidden\nf 1 2 3\n"),
    }
    out = {}
    for name, kw in specs.items():
        p = tmp_path / name
        p.write_bytes(_obj_text(v, **kw).encode())
        out[name] = p
    (tmp_path / "m.mtl").write_text("newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n")
    return out


def _trimesh_obj_arrays(path):
    import trimesh
    from urdf_lint.meshes import readers as meshio
    return meshio.scene_arrays(trimesh.load_scene(str(path), process=False))


def test_obj_reader_gives_trimesh_arrays_and_facts(tmp_path, fresh):
    from urdf_lint.meshes import readers as meshio
    objs = _generated_objs(tmp_path)
    lean = {}
    for name, p in objs.items():
        lean[name] = meshio.obj_arrays(p.read_bytes())
        if lean[name] is not None:
            want = _trimesh_obj_arrays(p)
            assert np.array_equal(lean[name][0], want[0]), name
            assert np.array_equal(lean[name][1], want[1]) and lean[name][1].dtype == want[1].dtype, name
        # whichever path reads it: the facts and mass properties of trimesh's mesh, or its error
        got = fresh.mesh_facts(str(p))
        try:
            want = trimesh_facts(p)
        except Exception as e:  # noqa: BLE001
            assert not got["ok"] and got["error"] == fresh.error_text(e)[:300], name
            continue
        assert got == want, name
        assert fresh.mass_facts(str(p)) == fresh.trimesh_mass_properties(fresh.load_mesh(str(p))), name
    assert [n for n, got in lean.items() if got is None] == [
        "negative.obj", "out_of_range.obj", "mixed.obj", "polygon.obj", "comment_usemtl.obj"]
    # one mesh per material (three here), texture and normal references unmerged: more
    # vertices than positions, every triangle the same
    v, f = sphere(600, radius=0.2, center=(0.3, -0.1, 0.05))
    assert len(lean["uv.obj"][0]) > len(lean["plain.obj"][0]) == len(np.unique(f))
    assert len(lean["materials.obj"][1]) == len(f)
    assert len(lean["quads.obj"][1]) == 2 * (len(f) // 2)


@pytest.mark.skipif(not (CORPUS / "MANIFEST.md").is_file(), reason="../shared/corpus is not present")
def test_corpus_obj_read_without_trimesh_gives_the_same_arrays():
    from urdf_lint.meshes import readers as meshio
    paths = sorted(p for p in CORPUS.rglob("*") if p.suffix.lower() == ".obj")
    assert len(paths) > 20
    for p in paths:
        got = meshio.obj_arrays(p.read_bytes())
        assert got is not None, p            # every OBJ of the real robots is plain
        want = _trimesh_obj_arrays(p)
        assert np.array_equal(got[0], want[0]) and np.array_equal(got[1], want[1]), p


def _closed_noisy_sphere(subdivisions: int, offset=(1.0, 2.0, -0.5)):
    """(vertices, faces) of a closed, lumpy sphere away from the origin (its vertices moved
    at random: still watertight, no symmetry to hide an error)."""
    import trimesh
    m = trimesh.creation.icosphere(subdivisions=subdivisions, radius=0.3)
    rng = np.random.default_rng(1)
    v = np.asarray(m.vertices) * rng.uniform(0.9, 1.1, size=(len(m.vertices), 1)) + offset
    return v, np.asarray(m.faces)


def _assert_trimeshs_mass(tris):
    """readers.mass_properties equals trimesh's on closed triangles, within rounding."""
    from trimesh.triangles import mass_properties
    from urdf_lint.meshes import readers as meshio
    want = mass_properties(tris, density=1.0)
    vol, com, inertia = meshio.mass_properties(tris)
    assert vol == pytest.approx(want["volume"], rel=1e-13)
    assert np.allclose(com, want["center_mass"], rtol=1e-13, atol=0)
    scale = np.abs(want["inertia"]).max()
    assert np.allclose(inertia, want["inertia"], rtol=1e-11, atol=1e-11 * scale)


def test_mass_properties_equal_trimesh_and_vertex_grouping_bitwise():
    from trimesh.grouping import unique_rows
    from urdf_lint.meshes import readers as meshio
    v, f = _closed_noisy_sphere(3)
    _assert_trimeshs_mass(v[f])
    _assert_trimeshs_mass(v[f][:, ::-1])        # inside out: every integral changes sign
    # repeated vertices (and ones equal to 8 decimals): grouped like unique_rows(digits=8)
    v = np.vstack([v, v[:50], v[50:60] + 1e-12])
    ids = meshio.merged_ids(v)
    _, inv = unique_rows(v, digits=8)
    assert len(set(ids)) == len(set(inv)) < len(v)
    pairs = set(zip(ids.tolist(), np.asarray(inv).tolist(), strict=True))
    assert len(pairs) == len(set(ids))


def test_rows_are_grouped_exactly_even_when_their_mixes_collide(monkeypatch):
    """first_of_equal_rows (the COLLADA merge, merged_ids) groups on a 64-bit mix per row and
    checks each group: rows whose mixes collide are still told apart."""
    from urdf_lint.meshes import readers as meshio
    rng = np.random.default_rng(3)
    rows = rng.integers(-5, 5, size=(400, 5)).astype(np.int64)
    rows = np.vstack([rows, rows[::7]])

    def grouping(index, inverse):   # the partition of the rows, whatever the numbering
        return sorted(map(tuple, (np.flatnonzero(inverse == g) for g in range(len(index)))))
    _, want_index, want_inverse = np.unique(
        rows.view(np.dtype((np.void, 40))).reshape(-1), return_index=True, return_inverse=True)
    want = grouping(want_index, want_inverse.reshape(-1))
    got = meshio.first_of_equal_rows(rows)
    assert grouping(*got) == want and sorted(got[0]) == sorted(want_index)
    monkeypatch.setattr(meshio, "row_mix", lambda r: np.zeros(len(r), dtype=np.uint64))
    got = meshio.first_of_equal_rows(rows)                  # every mix the same
    assert grouping(*got) == want and sorted(got[0]) == sorted(want_index)


def test_unique_first_is_np_uniques_even_when_keys_share_their_high_bits():
    """unique_first sorts mixes with their positions packed in the low 24 bits: its first
    occurrences and inverse are np.unique's, also for keys equal in their high 40 bits only
    (they fall back to an argsort), for signed keys, and for one key."""
    from urdf_lint.meshes import readers as meshio
    rng = np.random.default_rng(5)
    mixes = rng.integers(0, 2**63, size=3000, dtype=np.uint64) * np.uint64(2) + np.uint64(1)
    near = (mixes[:50] & ~np.uint64(0xFFFFFF)) | np.uint64(7)      # same high bits, not equal
    cases = {"mixes": np.concatenate([mixes, mixes[::3], mixes[:10]]),
             "near": np.concatenate([mixes, near, mixes[::5]]),
             "signed": rng.integers(-20, 20, size=500).astype(np.int64),
             "one": mixes[:1]}
    assert meshio._packed_order(cases["mixes"]) is not None
    assert meshio._packed_order(cases["near"]) is None
    for name, keys in cases.items():
        _, index, inverse = np.unique(keys, return_index=True, return_inverse=True)
        got = meshio.unique_first(keys)
        assert np.array_equal(got[0], index) and np.array_equal(got[1], inverse.reshape(-1)), name


def test_stl_collada_and_obj_facts_import_no_trimesh(tmp_path):
    """A worker measuring STL, COLLADA and OBJ meshes (facts, volumes, texture scans) never
    imports trimesh (~0.35 s per process), nor pycollada (~30 ms) for a textured COLLADA file
    the lxml reader vouches for."""
    v, f = sphere(2000, radius=0.05)
    binary_stl(tmp_path / "b.stl", v[f])
    ascii_stl(tmp_path / "a.stl", v[f][:100])
    daes = _generated_daes(tmp_path)
    obj = _generated_objs(tmp_path)["quads.obj"]
    paths = [str(p) for p in (tmp_path / "b.stl", tmp_path / "a.stl", daes["nested.dae"], obj)]
    code = ("import sys, json; from urdf_lint.meshes import resolve as meshes\n"
            f"for p in {paths!r}:\n"
            "    assert meshes.mesh_facts(p)['ok'] and meshes.mass_facts(p)['ok']\n"
            "    meshes.texture_refs(p)\n"
            "print(json.dumps(sorted(m for m in ('trimesh', 'collada', 'scipy') if m in sys.modules)))")
    import subprocess
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == []


def test_a_collada_file_is_read_once_for_hash_facts_volume_and_textures(tmp_path, fresh,
                                                                          monkeypatch):
    import builtins
    dae = str(_generated_daes(tmp_path)["nested.dae"])
    opened = []
    real_open, real_os_open = builtins.open, os.open
    monkeypatch.setattr(builtins, "open", lambda f, *a, **k: (opened.append(str(f)),
                                                              real_open(f, *a, **k))[1])
    monkeypatch.setattr(os, "open", lambda f, *a, **k: (opened.append(str(f)),
                                                        real_os_open(f, *a, **k))[1])
    facts, mass = fresh.mesh_facts(dae), fresh.mass_facts(dae)
    refs = fresh.texture_refs(dae)
    monkeypatch.undo()
    assert facts["ok"] and mass["ok"] and refs == [str(tmp_path / "skin.png")]
    assert opened.count(dae) == 1, opened


def test_the_parent_preloads_trimesh_only_for_formats_read_through_it():
    from urdf_lint.run import worker
    lean = [worker.Block("a", [], 1.0, frozenset({".stl", ".dae"}))]
    # COLLADA is read with lxml: pycollada is imported by a worker only for a document the
    # lean reader leaves to it
    assert "trimesh" not in worker._mesh_modules(lean)
    assert "collada" not in worker._mesh_modules(lean)
    stl = [worker.Block("a", [], 1.0, frozenset({".stl"}))]
    assert "collada" not in worker._mesh_modules(stl)
    obj = lean + [worker.Block("b", [], 1.0, frozenset({".obj"}))]
    assert "trimesh" not in worker._mesh_modules(obj)
    ply = lean + [worker.Block("b", [], 1.0, frozenset({".ply"}))]
    assert "trimesh" in worker._mesh_modules(ply)


def test_the_parent_preloads_numpy_for_the_geometry_rules_even_with_no_mesh_to_read():
    """A re-lint whose mesh facts are stored reads no mesh, but the rules that measure
    geometry (``NEEDS = {"meshes"}``: UL605 on a box or on stored facts) compute with numpy:
    imported once by the parent before it forks two workers, not by each worker's first job
    (~0.1 s of CPU each); not when no such rule is selected. (A fresh interpreter: numpy is
    imported in this one.)"""
    code = ("import sys\n"
            "from urdf_lint.core.jobs import LintSettings\n"
            "from urdf_lint.run import worker\n"
            "for sel in (('UL101', 'UL201'), ('UL101', 'UL605')):\n"
            "    worker._preload_mesh_modules([], LintSettings(resolver={}, selected=sel))\n"
            "    print('numpy' in sys.modules, 'urdf_lint.meshes.readers' in sys.modules)\n")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr
    # (no package holds a mesh format: the readers are not preloaded)
    assert p.stdout.split("\n")[:2] == ["False False", "True False"]


def test_a_variant_goes_to_the_worker_that_linted_its_model():
    """Exploration's variants (:meth:`WorkerPool.more`): each on the worker that linted its
    model in the default pass (its meshes are measured there), the costliest first, unless
    that worker is loaded enough that another ends it sooner at twice the cost; a model
    whose worker is gone goes to the least loaded."""
    from urdf_lint.core.jobs import LintJob
    from urdf_lint.runner.pool import affine_queues

    def job(entry, **args):
        return LintJob(entry, args, "xacro", explicit=True, mesh_base=None)
    heavy = [job("/r/arm.xacro", gazebo="true"), job("/r/arm.xacro", hand="true")]
    light = [job(f"/r/m{i}.xacro", x="1") for i in range(6)]
    home = {"/r/arm.xacro": 1, **{f"/r/m{i}.xacro": 2 for i in range(6)}}
    took = {"/r/arm.xacro": 0.3, **{f"/r/m{i}.xacro": 0.01 for i in range(6)}}
    q = affine_queues(light + heavy, [1, 2], home, took)
    assert list(q[1]) == heavy and list(q[2]) == light
    # a worker loaded with twice the work: the cheap models of its own still stay, the other
    # worker takes the second heavy job (0.6 there against 0.6 + 0.3 here)
    q = affine_queues(heavy + [job("/r/arm.xacro", tool="true")], [1, 2], home, took)
    assert [len(q[1]), len(q[2])] == [2, 1]
    gone = affine_queues(heavy, [2, 3], home, took)        # worker 1 was replaced
    assert [len(gone[2]), len(gone[3])] == [1, 1]


# -- item 2: big meshes are streamed, not errors ---------------------------------------------
def test_binary_stl_is_streamed_in_chunks(tmp_path, fresh, monkeypatch):
    from urdf_lint.meshes import readers as meshio
    v, f = sphere(20_000, radius=0.2, center=(1.0, 2.0, 3.0))
    p = binary_stl(tmp_path / "big.stl", v[f])
    want = trimesh_facts(p)
    want_mass = fresh.trimesh_mass_properties(fresh.load_mesh(str(p)))
    seen = []
    real = meshio.iter_binary_stl

    def spy(path, chunk=None, data=None):
        for c in real(path, chunk, data):
            seen.append(len(c))
            yield c
    monkeypatch.setattr(meshio, "iter_binary_stl", spy)
    monkeypatch.setattr(fresh, "STL_CHUNK", 3000)      # ~7 chunks instead of one
    got = fresh.mesh_facts(str(p))
    assert got == want
    assert max(seen) == 3000 and len(seen) >= 6
    seen.clear()
    mass = fresh.mass_facts(str(p))
    assert len(seen) >= 6, "the mass properties are summed over chunks too"
    assert mass["ok"] and not mass["hull"]
    assert mass["volume"] == pytest.approx(want_mass["volume"], rel=1e-9)
    assert np.allclose(mass["first"], want_mass["first"], rtol=1e-9)
    assert np.allclose(mass["second"], want_mass["second"], rtol=1e-9)
    assert mass["bounds"] == want_mass["bounds"]


def test_chunked_mass_of_an_open_surface_uses_the_hull(tmp_path, fresh, monkeypatch):
    v, f = sphere(8_000, radius=0.1)
    p = binary_stl(tmp_path / "open.stl", np.delete(v[f], range(1000, 1040), axis=0))   # a hole
    want = fresh.trimesh_mass_properties(fresh.load_mesh(str(p)))
    monkeypatch.setattr(fresh, "STL_CHUNK", 1000)
    got = fresh.mass_facts(str(p))
    assert want["hull"] and got["hull"]
    assert got["volume"] == pytest.approx(want["volume"], rel=1e-6)
    assert np.allclose(got["second"], want["second"], rtol=1e-6, atol=1e-12)


def test_non_finite_vertex_in_a_later_chunk(tmp_path, fresh, monkeypatch):
    v, f = sphere(2000)
    tris = v[f].astype(np.float32)
    tris[-1, 2, 1] = np.nan
    p = binary_stl(tmp_path / "nan.stl", tris)
    monkeypatch.setattr(fresh, "STL_CHUNK", 256)
    got = fresh.mesh_facts(str(p))
    assert got["ok"] and not got["finite"] and got["bounds"] is None
    assert got == trimesh_facts(p)


def test_stl_bounds_gathered_per_triangle_equal_the_corners_bounds():
    """readers.triangle_bounds on a binary STL's records (50 bytes apart) gives bounds() of
    its corners bit for bit: signed zeros, subnormals, the extremes, and a NaN or an
    infinity in one column only."""
    from urdf_lint.meshes import readers
    rng = np.random.default_rng(7)
    v, f = sphere(3000)
    base = (v[f] * rng.uniform(-1e3, 1e3, size=(len(f), 3, 3))).astype(np.float32)
    specials = [(0, 0, 0, -0.0), (1, 2, 1, np.float32(1e-45)), (2, 1, 2, np.finfo(np.float32).max),
                (3, 0, 0, np.finfo(np.float32).min)]
    for bad in (None, np.nan, np.inf, -np.inf):
        tris = base.copy()
        for i, j, k, x in specials:
            tris[i, j, k] = x
        if bad is not None:
            tris[len(tris) // 2, 1, 1] = bad
        rec = np.zeros(len(tris), dtype=readers.STL_RECORD)
        rec["v"] = tris
        got = readers.triangle_bounds(rec["v"])
        want = readers.bounds(rec["v"].reshape(-1, 3))
        for g, w in zip(got, want, strict=True):
            assert g.dtype == w.dtype and g.tobytes() == w.tobytes()
        assert (np.isfinite(got[0]).all() and np.isfinite(got[1]).all()) == (bad is None)


def test_a_mesh_over_the_limit_is_a_clear_finding(tmp_path, monkeypatch):
    from urdf_lint.meshes import resolve as meshes
    v, f = sphere(4000)
    pkg = make_package(tmp_path, "big_description", {
        "urdf/r.urdf": '<robot name="r"><link name="a"><visual><geometry>'
                       '<mesh filename="package://big_description/meshes/big.stl"/>'
                       '</geometry></visual></link></robot>\n'})
    (pkg / "meshes").mkdir()
    binary_stl(pkg / "meshes" / "big.stl", v[f])
    # with the real limit, through the CLI: a 200 kB STL gives facts, no finding
    p = run_cli("check", str(pkg), "--no-cache", "--format", "json")
    assert p.returncode == 0, p.stdout + p.stderr
    assert not [x for x in json.loads(p.stdout)["findings"] if x["code"] == "UL404"]
    # over the limit: one UL404 at the mesh that says so, the same on every run
    monkeypatch.setattr(meshes, "MAX_MESH_BYTES", 100_000)
    for _ in range(2):
        got = [x for x in lint_in_process(pkg) if x.code == "UL404"]
        assert [x.message for x in got] == [
            "mesh 'package://big_description/meshes/big.stl' cannot be loaded: the file is 0 MiB, "
            "over the 0.0953674 MiB limit of mesh files urdf-lint reads"]
        assert got[0].file.endswith("r.urdf")


def test_memory_error_says_it_is_the_limit_and_is_not_cached(tmp_path, fresh, monkeypatch):
    v, f = sphere(500)
    p = binary_stl(tmp_path / "m.stl", v[f])

    def boom(path, n):
        raise MemoryError()
    monkeypatch.setattr(fresh, "_stl_facts", boom)
    got = fresh.mesh_facts(str(p), str(tmp_path / "cache"))
    assert not got["ok"] and "memory limit" in got["error"]
    assert not list((tmp_path / "cache").rglob("*.json")), "an environment failure is not cached"


def test_a_model_whose_mesh_hit_the_memory_limit_is_not_cached(tmp_path, fresh, monkeypatch):
    """The memory limit is the environment's, not the file's: neither the mesh facts nor the
    model's result are stored, so the next run (with more memory) measures it."""
    from urdf_lint.run.cache import Cache
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    v, f = sphere(500)
    pkg = make_package(tmp_path / "ws", "m_description", {
        "urdf/r.urdf": '<robot name="r"><link name="a"><visual><geometry>'
                       '<mesh filename="package://m_description/m.stl"/>'
                       '</geometry></visual></link></robot>\n'})
    binary_stl(pkg / "m.stl", v[f])
    cache = Cache(str(tmp_path / "cache"))
    real = fresh._stl_facts

    def boom(path, n):
        raise MemoryError()
    monkeypatch.setattr(fresh, "_stl_facts", boom)
    first = [x.message for x in lint_in_process(pkg, cache) if x.code == "UL404"]
    assert len(first) == 1 and "memory limit" in first[0]
    assert not list((tmp_path / "cache").rglob("results/*/*.json"))
    monkeypatch.setattr(fresh, "_stl_facts", real)
    assert not [x for x in lint_in_process(pkg, cache) if x.code == "UL404"]
    assert list((tmp_path / "cache").rglob("results/*/*.json")), "a clean result is cached"


# -- item 3: models scheduled by package -------------------------------------------------------
def _settings_for(tmp_path, packages: dict):
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import settings_for
    cfg = load_config(None)
    for name, files in packages.items():
        make_package(tmp_path, name, files)
    return settings_for(cfg, build_resolver([str(tmp_path)], cfg), None)


def _robot(mesh=None):
    geo = f'<mesh filename="{mesh}"/>' if mesh else '<box size="1 1 1"/>'
    return f'<robot name="r"><link name="a"><visual><geometry>{geo}</geometry></visual></link></robot>\n'


def _four_small_models(tmp_path):
    """(settings, jobs) of two packages of two small models each, the jobs out of order."""
    from urdf_lint.core.jobs import LintJob
    settings = _settings_for(tmp_path, {
        "small_description": {"urdf/a.urdf": _robot(), "urdf/b.urdf": _robot()},
        "other_description": {"urdf/z.urdf": _robot(), "urdf/y.urdf": _robot()}})
    jobs = [LintJob(str(tmp_path / p / "urdf" / f)) for p, f in (
        ("small_description", "b.urdf"), ("other_description", "z.urdf"),
        ("small_description", "a.urdf"), ("other_description", "y.urdf"))]
    return settings, jobs


def test_jobs_are_grouped_by_package_and_the_default_worker_count_follows_the_work(tmp_path):
    from urdf_lint.runner import pool
    settings, jobs = _four_small_models(tmp_path)
    blocks = pool.package_blocks(jobs, settings)
    assert sorted([os.path.basename(j.entry) for j in b.jobs] for b in blocks) == \
        [["a.urdf", "b.urdf"], ["y.urdf", "z.urdf"]]
    # four small models: one worker (a second process costs more than it saves)
    assert pool.default_workers(blocks, cores=8, load=0.0) == 1
    # a package with 60 MB of COLLADA meshes is worth a second worker, never more than the cores
    mesh_dir = tmp_path / "other_description" / "meshes"
    mesh_dir.mkdir()
    with open(mesh_dir / "big.dae", "wb") as f:
        f.truncate(60 << 20)                     # sparse: only its size is looked at
    blocks = pool.package_blocks(jobs, settings)
    assert blocks[0].key.endswith("other_description") and blocks[0].cost > 1
    assert pool.default_workers(blocks, cores=2, load=0.0) == 2
    assert pool.default_workers(blocks, cores=1, load=0.0) == 1
    # a machine already busy (load 2 on 2 cores): another worker would only add CPU
    assert pool.default_workers(blocks, cores=2, load=2.0) == 1
    assert pool.default_workers(blocks, cores=2, load=0.4) == 2
    queues = pool.assign(blocks, 2)
    assert [sorted({os.path.basename(os.path.dirname(os.path.dirname(j.entry))) for j in q})
            for q in queues] == [["other_description"], ["small_description"]]


def test_the_seconds_models_took_before_plan_the_workers_in_place_of_the_estimates(tmp_path):
    """A re-lint plans its workers at what each model took when last linted (the result
    cache keeps it): four models estimated at a worker's worth of work, which took 0.3 s each
    last time, get two; a package whose models all took a known time gets no mesh estimate
    on top (their seconds include the meshes they measured), one with a model never linted
    does."""
    from urdf_lint.runner import pool
    from urdf_lint.core.jobs import job_key
    settings, jobs = _four_small_models(tmp_path)
    assert pool.default_workers(pool.package_blocks(jobs, settings), cores=2, load=0.0) == 1
    took = {job_key(j): 0.3 for j in jobs}
    blocks = pool.package_blocks(jobs, settings, costs=took)
    assert [b.cost for b in blocks] == [pytest.approx(0.6)] * 2
    assert pool.default_workers(blocks, cores=2, load=0.0) == 2
    assert pool.default_workers(blocks, cores=2, load=2.0) == 1   # a busy machine still says
    mesh_dir = tmp_path / "other_description" / "meshes"
    mesh_dir.mkdir()
    with open(mesh_dir / "big.dae", "wb") as f:
        f.truncate(20 << 20)                     # sparse: only its size is looked at
    estimate = pool._mesh_cost(str(tmp_path / "other_description"))[0]
    assert estimate > 0.5
    by_key = {b.key.rsplit(os.sep, 1)[1]: b for b in pool.package_blocks(jobs, settings, costs=took)}
    assert by_key["other_description"].cost == pytest.approx(0.6)
    assert by_key["other_description"].formats == {".dae"}   # (what the parent preloads)
    del took[job_key(jobs[1])]                   # z.urdf never linted: estimated, and the meshes
    by_key = {b.key.rsplit(os.sep, 1)[1]: b for b in pool.package_blocks(jobs, settings, costs=took)}
    assert by_key["other_description"].cost == pytest.approx(
        0.3 + pool.job_cost(jobs[1]) + estimate)
    assert by_key["small_description"].cost == pytest.approx(0.6)


def test_a_model_of_many_macro_calls_is_scheduled_first(tmp_path):
    """A 200-link robot written as 200 macro calls costs more than a small model with meshes
    to measure: it starts first, so it does not run alone at the end while workers idle."""
    from urdf_lint.runner import pool
    from urdf_lint.core.jobs import LintJob
    calls = "\n".join(f'  <xacro:seg i="{i}"/>' for i in range(200))
    snake = ('<robot name="s" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
             '  <xacro:macro name="seg" params="i"><link name="l${i}"/></xacro:macro>\n'
             f'{calls}\n</robot>\n')
    settings = _settings_for(tmp_path, {
        "arm_description": {"urdf/arm.urdf": _robot("package://arm_description/meshes/a.stl"),
                            "urdf/arm2.urdf": _robot()},
        "snake_description": {"urdf/snake.urdf.xacro": snake}})
    mesh_dir = tmp_path / "arm_description" / "meshes"
    mesh_dir.mkdir()
    with open(mesh_dir / "a.stl", "wb") as f:
        f.truncate(10 << 20)                     # 10 MB of binary STL (sparse)
    jobs = [LintJob(str(tmp_path / "arm_description" / "urdf" / n)) for n in ("arm.urdf", "arm2.urdf")]
    jobs.append(LintJob(str(tmp_path / "snake_description" / "urdf" / "snake.urdf.xacro")))
    assert pool.job_cost(jobs[2]) > 5 * pool.job_cost(jobs[0])
    if hasattr(os, "mkfifo"):   # a FIFO named as a model: costed without being read (no hang)
        os.mkfifo(tmp_path / "pipe.urdf.xacro")
        assert pool.job_cost(LintJob(str(tmp_path / "pipe.urdf.xacro"))) == pool.JOB_COST_S
    blocks = pool.package_blocks(jobs, settings)
    assert [b.key.rsplit(os.sep, 1)[1] for b in blocks] == ["snake_description", "arm_description"]
    queues = pool.assign(blocks, 2)
    assert [j.entry.endswith("snake.urdf.xacro") for j in queues[0]] == [True]


def test_busy_cores_count_a_past_burst_only_while_it_runs(monkeypatch):
    from urdf_lint.runner import pool
    if pool._procs_running() is None:
        pytest.skip("no /proc/stat here")
    # the 1-minute load average says 1.6 cores are busy (the previous command of a script)
    monkeypatch.setattr(os, "getloadavg", lambda: (1.6, 1.0, 0.5))
    monkeypatch.setattr(pool, "_procs_running", lambda: 1)          # only this process now
    assert pool.busy_cores() == 0
    monkeypatch.setattr(pool, "_procs_running", lambda: 2)          # one other running now
    assert pool.busy_cores() == 1
    monkeypatch.setattr(pool, "_procs_running", lambda: 9)          # a short spike: the average
    assert pool.busy_cores() == 1.6
    monkeypatch.setattr(pool, "_procs_running", lambda: None)       # no /proc: the average
    assert pool.busy_cores() == 1.6
    # another process runnable for an instant (exiting, a kernel thread): looked at again,
    # the fewest count; one that keeps running counts
    for seen, busy in (([3, 1, 3], 0), ([2, 2, 1], 0), ([3, 2, 2], 1), ([2, 2, 2], 1),
                       ([2, None, 2], 1)):
        samples = iter(seen)
        monkeypatch.setattr(pool, "_procs_running", lambda s=samples: next(s))
        assert pool.busy_cores() == busy, seen
    monkeypatch.undo()
    assert pool._procs_running() >= 1                               # this test is running


def test_an_idle_worker_takes_from_the_far_end_of_another_block():
    from collections import deque
    from urdf_lint.runner import pool
    mine, other = deque(), deque(["m1", "m2", "m3", "m4"])
    assert pool._next_job(mine, [mine, other]) == "m4"
    assert pool._next_job(other, [mine, other]) == "m1"


def test_an_idle_worker_takes_a_whole_package_nobody_started():
    """Its meshes are then loaded by one worker: the idle one takes the last block of the
    other queue whole (in its order), unless a worker is already on that block."""
    from collections import deque
    from urdf_lint.runner import pool
    b1, b2, c1, c2, c3 = "b1", "b2", "c1", "c2", "c3"
    block_of = {id(b1): 0, id(b2): 0, id(c1): 1, id(c2): 1, id(c3): 1}
    mine, other = deque(), deque([b1, b2, c1, c2, c3])
    assert pool._next_job(mine, [mine, other], block_of, running={0}) == c1
    assert list(mine) == [c2, c3] and list(other) == [b1, b2]
    # the last block is being linted: only its last job moves
    mine, other = deque(), deque([c2, c3])
    assert pool._next_job(mine, [mine, other], block_of, running={1}) == c3
    assert list(mine) == [] and list(other) == [c2]
    # ... but not the only one left: its worker takes it next, with the meshes loaded
    assert pool._next_job(mine, [mine, other], block_of, running={1}) is None
    assert list(other) == [c2]


def test_run_jobs_gives_one_worker_a_package_and_shares_the_rest(tmp_path, monkeypatch):
    """Real forked workers: each package's models land in one process (so the mesh facts it
    loaded are reused); the worker that runs out steals the last models of the other block."""
    import time
    from urdf_lint.run import worker
    from urdf_lint.core.jobs import LintJob, ModelReport
    names = [f"m{i}.urdf" for i in range(8)]
    settings = _settings_for(tmp_path, {"big_description": {f"urdf/{n}": _robot() for n in names},
                                        "one_description": {"urdf/only.urdf": _robot()}})

    def fake(job, settings):            # inherited by the forked workers
        time.sleep(0.15)
        return ModelReport(job.entry, {}, name=str(os.getpid()))
    monkeypatch.setattr(worker, "process_job", fake)
    jobs = [LintJob(str(tmp_path / "big_description" / "urdf" / n)) for n in names]
    jobs.append(LintJob(str(tmp_path / "one_description" / "urdf" / "only.urdf")))
    got = {os.path.basename(j.entry): r.name for j, r in worker.run_jobs(jobs, settings, jobs_n=2)}
    assert len(got) == 9
    big_pid = got["m0.urdf"]
    assert got["only.urdf"] != big_pid
    stolen = [n for n in names if got[n] != big_pid]
    assert stolen, "the idle worker helps with the big package"
    assert stolen == names[len(names) - len(stolen):], "it takes from the far end"
    assert len(stolen) < len(names) - 1


def test_a_worker_starts_its_next_job_while_the_parent_handles_its_last_result(tmp_path,
                                                                              monkeypatch):
    """Real forked worker: the next job is sent as soon as a result is read, not after the
    parent has handled it (hashed its meshes, cached it, planned its variants: here a slow
    reader of the results); before, the worker stood idle all that time."""
    import time
    from urdf_lint.run import worker
    from urdf_lint.core.jobs import LintJob, ModelReport
    names = [f"m{i}.urdf" for i in range(3)]
    settings = _settings_for(tmp_path, {"a_description": {f"urdf/{n}": _robot() for n in names}})

    def fake(job, settings):            # inherited by the forked worker
        started = time.monotonic()      # (CLOCK_MONOTONIC: one clock for both processes)
        time.sleep(0.05)
        return ModelReport(job.entry, {}, name=repr(started))
    monkeypatch.setattr(worker, "process_job", fake)
    jobs = [LintJob(str(tmp_path / "a_description" / "urdf" / n)) for n in names]
    started, read = [], []
    for _, report in worker.run_jobs(jobs, settings, jobs_n=1):
        read.append(time.monotonic())
        started.append(float(report.name))
        time.sleep(0.4)                 # the parent's handling of the result
    assert len(started) == 3
    for k in (1, 2):
        assert started[k] < read[k - 1] + 0.2, (started, read)


# -- item 5: hash and list once ------------------------------------------------------------------
def _textured_repo(tmp_path):
    v, f = sphere(400)
    robot = ('<robot name="r"><link name="a"><visual><geometry>'
             '<mesh filename="package://tex_description/meshes/m.dae"/></geometry></visual></link>'
             '<link name="b"><visual><geometry><mesh filename="package://tex_description/meshes/M2.dae"/>'
             '</geometry></visual></link><joint name="j" type="fixed"><parent link="a"/>'
             '<child link="b"/></joint><link name="c"><visual><geometry>'
             '<mesh filename="package://tex_description/meshes/m3.dae"/></geometry></visual></link>'
             '<joint name="k" type="fixed"><parent link="a"/><child link="c"/></joint></robot>\n')
    pkg = make_package(tmp_path, "tex_description", {"urdf/r.urdf": robot, "urdf/s.urdf": robot,
                                                      "urdf/broken.urdf.xacro": "<robot name='x' "})
    (pkg / "meshes").mkdir()
    write_png(pkg / "meshes" / "skin.png")
    write_dae(pkg / "meshes" / "m.dae", v, f, "skin.png")
    write_dae(pkg / "meshes" / "m2.dae", v, f, "skin.png")      # referred to as M2.dae
    write_dae(pkg / "meshes" / "m3.dae", v, f, "gone.png")      # a lost texture
    old = 1_600_000_000
    for p in [pkg, *pkg.rglob("*")]:
        os.utime(p, (old, old))              # an old checkout: folder listings can be trusted
    return pkg


def test_folders_are_listed_once_and_the_parent_never_hashes(tmp_path, fresh, monkeypatch):
    from urdf_lint.run import cache as cache_mod
    from urdf_lint.run.cache import Cache
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    pkg = _textured_repo(tmp_path / "ws")
    monkeypatch.setattr(fresh, "_listings", {})
    listed = []
    real_listdir = os.listdir
    monkeypatch.setattr(fresh.os, "listdir", lambda p: listed.append(str(p)) or real_listdir(p))

    def no_hash(*a, **k):
        raise AssertionError("the parent hashed an input again when writing the cache")
    monkeypatch.setattr(cache_mod, "file_record", no_hash)
    found = lint_in_process(pkg, Cache(str(tmp_path / "cache")))
    codes = {x.code for x in found}
    assert {"UL402", "UL001"} <= codes, codes    # the case mismatch, the broken file
    assert len(listed) == len(set(listed)), f"a folder was listed twice: {sorted(listed)}"
    assert list((tmp_path / "cache").rglob("results/*/*.json"))


def test_texture_scan_is_cached_on_disk_with_the_mesh_facts(tmp_path, fresh, monkeypatch):
    from urdf_lint.core import hashing
    pkg = _textured_repo(tmp_path / "ws")
    cache = tmp_path / "cache"
    first = sorted((x.code, x.message) for x in lint_in_process(pkg, None) if x.code == "UL407")
    monkeypatch.setattr(fresh, "_textures", {})
    monkeypatch.setattr(fresh, "_scan_memory", {})
    from urdf_lint.meshes.store import FactsStore, MeshStore, register
    facts = FactsStore(str(cache), b"k" * 32)
    register(facts)
    store = MeshStore(cache_dir=str(cache))      # a run whose facts are kept in `cache`
    dae = str(pkg / "meshes" / "m.dae")
    refs = fresh.texture_refs(dae, store)
    assert refs == [str(pkg / "meshes" / "skin.png")]
    facts.accept(store.measured)                 # (what the parent does with a report's facts)
    assert list(cache.glob("tex*.json"))
    # a new run (new process memory): the DAE is not read to find its textures
    monkeypatch.setattr(fresh, "_textures", {})
    monkeypatch.setattr(fresh, "_scan_memory", {})
    import builtins
    real_open = builtins.open
    opened = []
    def spy(f, *a, **k):
        opened.append(str(f))
        return real_open(f, *a, **k)
    monkeypatch.setattr(builtins, "open", spy)
    assert fresh.texture_refs(dae, store) == refs
    monkeypatch.setattr(builtins, "open", real_open)
    assert dae not in opened
    assert hashing._memo, "the cache key is the content digest"
    assert first and all("gone.png" in m for _, m in first)


def test_only_a_render_run_keeps_loaded_meshes(tmp_path, fresh, monkeypatch):
    pkg = _textured_repo(tmp_path / "ws")
    dae = str(pkg / "meshes" / "m.dae")
    plain, plain_mass = fresh.mesh_facts(dae), fresh.mass_facts(dae)
    assert fresh._loaded == {}, "plain linting keeps no trimesh in memory"
    for name in ("_memory", "_mass_memory"):
        monkeypatch.setattr(fresh, name, {})
    monkeypatch.setattr(fresh, "_arrays_memo", type(fresh._arrays_memo)())
    from urdf_lint.meshes.store import MeshStore
    render = MeshStore(keep_loaded=True)                 # a render run
    assert fresh.mesh_facts(dae, store=render) == plain, "the bytes decide the facts"
    assert fresh._loaded == {}, "its bounds are read without trimesh"
    assert fresh.mass_facts(dae, store=render) == plain_mass    # the volume needs the mesh
    assert len(fresh._loaded) == 1
    assert fresh.get_mesh(dae) is next(iter(fresh._loaded.values())), "the renderer reuses it"


@pytest.mark.skipif(not (CORPUS / "MANIFEST.md").is_file(), reason="../shared/corpus is not present")
def test_the_corpus_is_linted_without_importing_trimesh():
    """Every corpus mesh is read by urdf-lint's own readers (a sensor's DAE with line
    primitives too): a cold lint never imports trimesh (~0.35 s of CPU per process)."""
    import subprocess
    import sys
    code = ("import os, sys\nos.chdir(sys.argv[1])\n"
            "from urdf_lint.config.schema import load_config\n"
            "from urdf_lint.discovery.discover import build_resolver\n"
            "from urdf_lint.run.pipeline import run_check, RunRequest\n"
            "cfg = load_config(None)\n"
            "res = run_check(RunRequest(['.'], cfg, build_resolver(['.'], cfg), in_process=True))\n"
            "print(len(res.findings), 'trimesh' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code, str(CORPUS / "turtlebot3_description")],
                         capture_output=True, text=True, check=True).stdout.split()
    assert int(out[0]) > 0 and out[1] == "False", out


def test_a_small_part_far_from_its_origin_keeps_its_precision():
    """A 1 mm part 1 m (and 1 km) from its mesh's origin, as parts exported in an assembly's
    frame are: its volume and inertia about its centre of mass are those of the same part at
    the origin (products of absolute coordinates would lose them: 1% at 1 m), at least as
    close as trimesh's."""
    import trimesh
    from urdf_lint.meshes import readers as meshio
    m = trimesh.creation.icosphere(subdivisions=3, radius=0.001)
    v, f = np.asarray(m.vertices), np.asarray(m.faces)
    vol0, _, inertia0 = meshio.mass_properties(v[f])
    for offset, rtol in ((1.0, 1e-8), (1000.0, 1e-2)):
        t = (v + offset)[f]
        vol, com, inertia = meshio.mass_properties(t)
        theirs = trimesh.triangles.mass_properties(t)
        assert vol == pytest.approx(vol0, rel=1e-10)
        assert np.allclose(com, offset, rtol=1e-12)
        err = np.abs(inertia - inertia0).max() / np.abs(inertia0).max()
        assert err < rtol, (offset, err)
        assert err <= np.abs(theirs["inertia"] - inertia0).max() / np.abs(inertia0).max()


def test_mass_properties_are_trimeshs_across_blocks(monkeypatch):
    """The block-wise integrals give trimesh's volume, centre of mass and inertia (within
    rounding) for a closed surface larger than two blocks, and the blocks do not change them:
    any triangles, any block size, the same sums within rounding."""
    from urdf_lint.meshes import readers
    v, f = _closed_noisy_sphere(6)                  # 81920 triangles
    assert len(f) > 2 * readers._CHUNK
    _assert_trimeshs_mass(v[f])
    rng = np.random.default_rng(7)
    for n in (1, 3, readers._CHUNK, readers._CHUNK + 1, 2 * readers._CHUNK + 5):
        t = rng.normal(size=(n, 3, 3)) * 10 ** rng.uniform(-3, 3)
        whole = readers.volume_integrals(t)
        monkeypatch.setattr(readers, "_CHUNK", 7)
        blocks = readers.volume_integrals(t)
        monkeypatch.undo()
        assert np.allclose(blocks, whole, rtol=1e-9, atol=1e-12 * np.abs(whole).max()), n


@pytest.mark.skipif(not hasattr(os, "sched_setaffinity") or len(os.sched_getaffinity(0)) < 2,
                    reason="needs a process allowed on more than one CPU")
def test_a_hull_is_computed_on_one_cpu_and_the_others_are_given_back():
    """manifold3d's thread pool (TBB) starts with as many threads as the process has CPUs:
    a hull is computed with this thread held to the CPU it is on (no thread to hand work to;
    the run's other workers hold the other cores), and every CPU is allowed again after."""
    from urdf_lint.meshes import resolve
    before = os.sched_getaffinity(0)
    with resolve._one_cpu():
        inside = os.sched_getaffinity(0)
    assert len(inside) == 1 and inside <= before
    assert os.sched_getaffinity(0) == before
    cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    pts = np.concatenate([cube, np.random.default_rng(1).random((5000, 3))])
    h = resolve._convex_hull(pts)
    assert os.sched_getaffinity(0) == before
    assert sorted(map(tuple, np.round(h.vertices, 12))) == sorted(map(tuple, cube))


def test_a_worker_that_dies_is_reported_with_its_exit_code(tmp_path, monkeypatch):
    """A worker that dies mid-job: its UL904 names the exit code every time (the code was read
    before the process was reaped, and said ``None`` at random: the same run reported two
    messages, and Issue 34's early exploration changed which)."""
    from urdf_lint.core.jobs import LintJob
    from urdf_lint.run import worker
    from urdf_lint.run.pipeline import settings_for
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    pkg = make_package(tmp_path, "p", {f"urdf/m{i}.urdf": '<robot name="m"><link name="a"/></robot>\n'
                                       for i in range(24)})
    monkeypatch.setattr(worker, "process_job", lambda job, settings: os._exit(7))
    cfg = load_config(None)
    settings = settings_for(cfg, build_resolver([str(pkg)], cfg, {}), None)
    jobs = [LintJob(str(p)) for p in sorted((pkg / "urdf").iterdir())]
    msgs = [p.message for _, r in worker.run_jobs(jobs, settings, jobs_n=1) for p in r.problems]
    assert len(msgs) == 24 and all("exit code 7" in m for m in msgs), msgs


# -- issue 34: a visual mesh's volume facts only when they decide -----------------------------
@pytest.mark.skipif(not (CORPUS / "MANIFEST.md").is_file(), reason="../shared/corpus is not present")
def test_every_corpus_mesh_has_the_same_bounds_in_its_mesh_facts_and_mass_facts(fresh):
    """The physics rules decide whether a collision shape is a proxy from the visual meshes'
    bounds in their mesh facts, measuring their volumes only when those call it one: the
    same numbers as the mass facts' bounds, for every mesh whose volume can be measured."""
    paths = sorted(p for p in CORPUS.rglob("*") if p.suffix.lower() in (".stl", ".dae", ".obj"))
    measured = 0
    for p in paths:
        mass = fresh.mass_facts(str(p))
        if mass.get("ok"):
            facts = fresh.mesh_facts(str(p))
            assert facts["ok"] and facts["bounds"] == mass["bounds"], p
            measured += 1
    assert measured > 100


def _link_with_visual_mesh(collision: str) -> str:
    return f"""<robot name="r">
  <link name="base"/>
  <link name="arm">
    <inertial><mass value="1"/>
      <inertia ixx="0.5" iyy="0.5" izz="0.5" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><mesh filename="package://shell_description/meshes/shell.stl"/></geometry></visual>
    <collision><geometry>{collision}</geometry></collision>
  </link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""


def test_a_visual_mesh_is_not_measured_for_volume_when_its_box_decides(tmp_path, fresh,
                                                                        monkeypatch):
    """A collision box as large as the open visual shell: not a proxy, so the shell's volume
    (its convex hull: it is open) is never measured. A collision cylinder around a sliver of
    it: a proxy by the shell's bounds, and then the shell's volume facts are measured and the
    link (its declared inertia 100 times too large) is judged against them."""
    v, f = sphere(4000, radius=0.1)
    measured = []
    real = fresh._measure_mass
    monkeypatch.setattr(fresh, "_measure_mass",
                        lambda p, *a, **k: measured.append(os.path.basename(p)) or real(p, *a, **k))
    for name, collision in (("whole", '<box size="0.2 0.2 0.2"/>'),
                            ("sliver", '<cylinder radius="0.01" length="0.02"/>')):
        root = tmp_path / name
        pkg = make_package(root, "shell_description",
                           {"urdf/r.urdf": _link_with_visual_mesh(collision)})
        (pkg / "meshes").mkdir()
        binary_stl(pkg / "meshes" / "shell.stl", np.delete(v[f], range(100, 140), axis=0))
        found = lint_in_process(root)
        if name == "whole":
            assert measured == [], "the open shell's volume was measured for nothing"
        else:
            assert measured == ["shell.stl"]
            assert any("judged against the visual geometry: the collision shape covers only "
                       "part of the link" in x.message for x in found), [x.message for x in found]


def _scan_line_by_line(path: str) -> list[str]:
    """The texture scan as it was written first (every match of the regex over the DAE's
    bytes, every line of the OBJ): what the faster scan must name."""
    refs: list[str] = []
    data = Path(path).read_bytes()
    if path.lower().endswith(".dae"):
        for m in re.finditer(rb"<init_from>\s*([^<]+?)\s*</init_from>", data):
            ref = m.group(1).decode("utf-8", "replace").strip()
            ref = ref[7:] if ref.startswith("file://") else ref
            if re.search(r"\.(png|jpe?g|tga|bmp|tiff?|gif|dds)$", ref, re.I):
                refs.append(ref)
        return refs
    text = data.decode("utf-8", "replace")
    for line in text.replace("\r\n", "\n").replace("\r", "\n").split("\n"):
        parts = line.split(None, 1)
        if line.startswith("mtllib") and len(parts) == 2:
            refs.append(parts[1].strip())
    return refs


def test_the_texture_scan_names_what_a_scan_of_every_line_names(tmp_path):
    """The image names of a DAE are found with ``bytes.find`` and the ``mtllib`` lines of an
    OBJ with one regex; both name exactly what the first, line-by-line scan named, on
    every corpus mesh and on the odd cases."""
    from urdf_lint.meshes import resolve
    odd = {
        "a.dae": b"<init_from> file://skin.png </init_from><init_from>x.txt</init_from>"
                 b"<init_from >no.png</init_from><init_from><init_from>b.JPG</init_from>"
                 b"<init_from>\n  c.tiff\n</init_from><init_from>d.png",
        "none.dae": b"<COLLADA><library_images/></COLLADA>",
        "a.obj": "v 0 0 0\r\nmtllib a.mtl\r\n  mtllib indented.mtl\nmtllibx y.mtl\rmtllib\n"
                 "mtllib  spaced name.mtl  \nmtllib\tt.mtl\x0bz\nmtllib u\u2028v.mtl\n"
                 "usemtl mtllib\n#mtllib c.mtl\nmtllib".encode(),
        "none.obj": b"v 0 0 0\nf 1 1 1\n",
    }
    paths = []
    for name, data in odd.items():
        (tmp_path / name).write_bytes(data)
        paths.append(str(tmp_path / name))
    if CORPUS.is_dir():
        paths += sorted(str(p) for p in CORPUS.rglob("*") if p.suffix.lower() in (".dae", ".obj")
                        and p.is_file())
    named = 0
    for p in paths:
        want = _scan_line_by_line(p)
        assert resolve._scan_texture_names(p) == {"ok": True, "refs": want}, p
        named += bool(want)
    assert resolve._scan_texture_names(paths[0])["refs"] == ["skin.png", "b.JPG", "c.tiff"]
    assert resolve._scan_texture_names(paths[2])["refs"] == [
        "a.mtl", "y.mtl", "spaced name.mtl", "t.mtl\x0bz", "u\u2028v.mtl"]
    assert named >= 2
