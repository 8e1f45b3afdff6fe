"""Right on robots it has never seen (issue 33, items 7 and 8): the physics rules judge a link by
its real collision sphere, not by a 1 mm placeholder visual box; UL404 says who refuses a
COLLADA file that assimp loads (and warns); UL408 quotes a malformed colour instead of blaming
a missing effect. Each test lints a package written in tmp_path, in process."""
from __future__ import annotations

import json

from conftest import make_package, run_main
from urdf_lint.rules._meshes import PLAIN_DAE
from urdf_lint.rules._physics import example

PHYSICS = ("UL605", "UL606", "UL607")


def lint(pkg, *extra):
    p = run_main("check", ".", "--no-cache", "--format", "json", "--fail-on", "never", *extra,
                 cwd=pkg)
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)["findings"]


def _ball(mass: float, radius: float, visual: bool = True, collision: bool = True) -> str:
    # a solid sphere: I = 2/5 m r², so the declared inertia is the sphere's own
    i = 0.4 * mass * radius * radius
    vis = '<visual><geometry><box size="0.001 0.001 0.001"/></geometry></visual>' if visual else ""
    col = (f'<collision><geometry><sphere radius="{radius}"/></geometry></collision>'
           if collision else "")
    # the physics rules' own example link ('arm' on a continuous joint), with these shapes
    return example(mass, i, i, i).replace(
        '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>', vis + col)


def test_physics_rules_use_the_collision_sphere_not_a_placeholder_visual(tmp_path):
    # a 1 kg ball of 5 cm radius (1910 kg/m³) and a 10 g ball of 1 cm radius (2390 kg/m³), both
    # with a 1 mm placeholder visual box: the sphere is the body. The 1 cm sphere is small
    # enough to pass for a contact point, and was judged against the 1 mm box (UL607 "implied
    # density 1e+07 kg/m³", UL605 "480x")
    for name, mass, radius in (("big", 1, 0.05), ("small", 0.01, 0.01)):
        pkg = make_package(tmp_path, name, {"urdf/r.urdf": _ball(mass, radius)})
        fs = [f for f in lint(pkg) if f["code"] in PHYSICS]
        assert fs == [], fs


def test_placeholder_visual_alone_is_still_judged(tmp_path):
    # no collision: the 1 mm box is all there is, and a 10 g link in it is reported as before
    pkg = make_package(tmp_path, "p", {"urdf/r.urdf": _ball(0.01, 0.01, collision=False)})
    fs = lint(pkg)
    (density,) = [f for f in fs if f["code"] == "UL607"]
    assert "1e+07 kg/m³" in density["message"] and "of visual geometry" in density["message"]
    assert [f for f in fs if f["code"] == "UL605"]


def test_a_contact_sphere_on_a_real_visual_is_still_a_proxy(tmp_path):
    # the visual is the body (a 10 cm box) and larger than the 1 cm sphere: judged by the visual
    src = _ball(0.01, 0.01).replace('box size="0.001 0.001 0.001"', 'box size="0.1 0.1 0.1"')
    pkg = make_package(tmp_path, "p", {"urdf/r.urdf": src})
    (f,) = [f for f in lint(pkg) if f["code"] == "UL607"]
    assert "judged against the visual geometry" in f["message"], f["message"]


def _mesh_robot(names) -> str:
    links = "".join(f'<link name="{n}"><visual><geometry><mesh filename="package://p/meshes/{n}.dae"/>'
                    "</geometry></visual></link>" for n in names)
    joints = "".join(f'<joint name="j_{n}" type="fixed"><parent link="base"/><child link="{n}"/>'
                     "</joint>" for n in names)
    return f'<robot name="r"><link name="base"/>{links}{joints}</robot>'


def test_dae_that_only_strict_parsers_refuse_is_a_warning_naming_the_consumers(tmp_path):
    files = {"meshes/lead.dae": "\n  " + PLAIN_DAE,
             "meshes/trail.dae": PLAIN_DAE + "\x00\x00junk\n",
             "meshes/broken.dae": PLAIN_DAE.replace("</library_geometries>", ""),
             "urdf/r.urdf": _mesh_robot(["lead", "trail", "broken"])}
    pkg = make_package(tmp_path, "p", files)
    fs = {f["message"].split("'")[1].rsplit("/", 1)[1]: f for f in lint(pkg) if f["code"] == "UL404"}
    assert set(fs) == {"lead.dae", "trail.dae", "broken.dae"}, fs
    lead, trail = fs["lead.dae"], fs["trail.dae"]
    assert "3 whitespace byte(s) before its '<?xml' declaration" in lead["message"]
    assert "6 byte(s) after its closing '</COLLADA>'" in trail["message"]
    for f in (lead, trail):
        assert f["severity"] == "warning", f
        assert "cannot be loaded" not in f["message"]
        assert "trimesh/pycollada" in f["message"] and "yourdfpy" in f["message"]
        assert "assimp-based consumers (RViz, Gazebo) load it" in f["message"]
    # a file no XML parser reads stays an error, worded as before
    assert fs["broken.dae"]["severity"] == "error"
    assert "cannot be loaded" in fs["broken.dae"]["message"]
    # for the Python parsers' target it is an error again
    fs = [f for f in lint(pkg, "--target", "python") if f["code"] == "UL404"]
    assert {f["severity"] for f in fs} == {"error"}, fs


def test_broken_effect_from_a_malformed_colour_quotes_the_value(tmp_path):
    files = {"meshes/run.dae": PLAIN_DAE.replace("<color>0.8 0.8 0.8 1</color>",
                                                 "<color>0.0 0.0 0.01.0</color>"),
             "meshes/word.dae": PLAIN_DAE.replace("<color>0.8 0.8 0.8 1</color>",
                                                  "<color>0.8 0.8 O.8 1</color>"),
             "urdf/r.urdf": _mesh_robot(["run", "word"])}
    fs = {f["message"].split("'")[1].rsplit("/", 1)[1]: f["message"]
          for f in lint(make_package(tmp_path, "p", files)) if f["code"] == "UL408"}
    assert set(fs) == {"run.dae", "word.dae"}, fs
    assert "malformed colour value <color>0.0 0.0 0.01.0</color> in effect 'skin-effect'" \
        in fs["run.dae"]
    assert "malformed colour value <color>0.8 0.8 O.8 1</color>" in fs["word.dae"]
    assert all("has a broken internal reference" not in m for m in fs.values())
