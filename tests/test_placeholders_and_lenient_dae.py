"""Right on robots it has never seen (issue 33, items 7 and 8): the physics rules judge a link by
its real collision sphere, not by a 1 mm placeholder visual box; UL404 says who refuses a
COLLADA file that assimp loads (and warns); UL408 quotes a malformed colour instead of blaming
a missing effect. Each test lints a package written in tmp_path, in process."""
from __future__ import annotations

import json

from conftest import make_package, run_main
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
