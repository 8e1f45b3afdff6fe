"""Snapshots a reviewer can trust: the findings a picture and a recording show are the report's
(after suppressions, per-file ignores, severities and the baseline); missing visuals become
ghosted, labelled collision geometry joined by a skeleton; views, triad and crop; texture,
multi-material and back-face fidelity; exit codes and stale files. Pixel assertions on real
renders."""
from __future__ import annotations

import json
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from conftest import make_package, run_cli

from urdf_lint.render import raster

BG = np.array([236, 238, 241])


def _img(path):
    return np.asarray(Image.open(path).convert("RGB"), dtype=int)


def _fg(a):
    return np.abs(a - BG).max(axis=2) > 12


def _no_triads(a, fr):
    """``a`` with the triad corner of every view painted background."""
    a = a.copy()
    for v in fr.views:
        a[v.y0 + v.h - 45:v.y0 + v.h, v.x0:v.x0 + 50] = BG
    return a


JOINT = ('  <joint name="{n}" type="revolute"><parent link="{p}"/><child link="{c}"/>'
         '<origin xyz="0 0 0.2"/><axis xyz="0 0 1"/>'
         '<limit lower="1" upper="-1" effort="1" velocity="1"/></joint>\n')
LINK = ('  <link name="{n}"><visual><geometry><box size="0.1 0.1 0.2"/></geometry></visual>'
        '</link>\n')


def _policy_repo(tmp_path):
    """A model whose findings meet every policy step: an inline suppression, a per-file
    ignore (the included file), a severity override and (later) a baseline entry."""
    links = "".join(LINK.format(n=f"l{i}") for i in range(6))
    main = ('<?xml version="1.0"?>\n<robot name="pol" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            + links
            + '  <!-- urdf-lint: disable-next UL302 -->\n'
            + JOINT.format(n="j1", p="l0", c="l1")
            + JOINT.format(n="j2", p="l1", c="l2")
            + JOINT.format(n="j3", p="l2", c="l3")
            + JOINT.format(n="j4", p="l3", c="l4")
            + '  <xacro:include filename="more.xacro"/>\n</robot>\n')
    more = ('<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            + JOINT.format(n="j5", p="l4", c="l5") + '</robot>\n')
    repo = tmp_path / "repo"
    pkg = make_package(repo, "pol", {"urdf/robot.urdf.xacro": main, "urdf/more.xacro": more})
    return repo, pkg


def test_picture_and_recording_show_the_reports_findings(tmp_path):
    pytest.importorskip("rerun")
    from test_render import text_logs
    repo, pkg = _policy_repo(tmp_path)
    (repo / ".git").mkdir()
    raw = json.loads(run_cli("check", pkg, "--isolated", "--format", "json", "--no-cache",
                             cwd=repo).stdout)["findings"]
    cfg = repo / "urdf-lint.toml"
    cfg.write_text('per-file-ignores = { "more.xacro" = ["UL302"] }\n'
                   'severity = { UL302 = "warning" }\n')
    before_baseline = json.loads(run_cli("check", pkg, "--format", "json", "--no-cache",
                                         cwd=repo).stdout)["findings"]
    known = next(f for f in before_baseline if f["code"] == "UL302")
    (repo / "baseline.json").write_text(json.dumps({"version": 1, "findings": [
        {"code": "UL302", "file": str(Path(known["file"]).relative_to(repo))
         if Path(known["file"]).is_absolute() else known["file"], "message": known["message"]}]}))
    cfg.write_text(cfg.read_text() + 'baseline = "baseline.json"\n')
    report = json.loads(run_cli("check", pkg, "--format", "json", "--no-cache",
                                cwd=repo).stdout)["findings"]
    # every policy step removed something, so a picture of the raw findings would differ
    assert len(report) < len(before_baseline) < len(raw)
    assert all(f["severity"] == "warning" for f in report if f["code"] == "UL302")
    for cmd in (["render", pkg, "--out", tmp_path / "r"],
                ["check", pkg, "--no-cache", "--render", tmp_path / "c"]):
        p = run_cli(*cmd, cwd=repo)
        assert p.returncode in (0, 1), p.stderr
        out = Path(cmd[-1])
        png = next(out.glob("*.png"))
        a = np.asarray(Image.open(png).convert("RGB"))
        strip = Image.new("RGB", (a.shape[1], raster.CAPTION_H), tuple(BG))
        for n, same in ((len(report), True), (len(raw), False)):
            exp = strip.copy()
            raster.caption(exp, raster.model_caption("pol", 6, 0, n))
            assert bool((np.asarray(exp) == a[:raster.CAPTION_H]).all()) is same, (n, cmd[0])
        texts = [t for _, t in text_logs(next(out.glob("*.rrd")))]
        got = Counter(t.split()[0] for t in texts)
        assert got == Counter(f["code"] for f in report), (got, cmd[0])
        assert any(t.startswith("UL302") for t in texts)


# -- missing meshes ----------------------------------------------------------------------------
GHOST = ('<robot name="torn">\n'
         '  <link name="base"><visual><geometry><box size="0.3 0.3 0.1"/></geometry></visual></link>\n'
         '  <link name="arm"><visual><geometry><mesh filename="package://p/meshes/gone.stl"/>'
         '</geometry></visual>\n'
         '    <collision><origin xyz="0 0 0.25"/><geometry><box size="0.08 0.08 0.5"/></geometry>'
         '</collision></link>\n'
         '  <link name="tip"><visual><geometry><mesh filename="package://p/meshes/gone2.stl"/>'
         '</geometry></visual></link>\n'
         '  <joint name="j1" type="fixed"><parent link="base"/><child link="arm"/>'
         '<origin xyz="0 0 0.05"/></joint>\n'
         '  <joint name="j2" type="fixed"><parent link="arm"/><child link="tip"/>'
         '<origin xyz="0 0 0.5"/></joint>\n</robot>\n')


def _geometry(urdf_text, tmp_path, name="m"):
    """The geometry of a plain URDF, computed in process like the worker does."""
    from urdf_lint.expansion import expand_file
    from urdf_lint.engine.lint import Context
    from urdf_lint.engine.model import model_from_xml
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.render import snapshot as render
    f = tmp_path / f"{name}.urdf"
    f.write_text(urdf_text)
    res = PackageResolver.build([str(tmp_path)], extra_roots=[str(tmp_path)])
    e = expand_file(str(f), resolver=res)
    model = model_from_xml(e.entry, {}, e.xml, e.origins, e.deps, res)
    ctx = Context({}, None)
    return render.scene_geometry(render.build_scene(model, ctx), ctx)


def test_missing_visual_shows_ghosted_collision_label_and_skeleton(tmp_path):
    pkg = make_package(tmp_path / "repo", "p", {"urdf/torn.urdf": GHOST})
    out = tmp_path / "snap"
    p = run_cli("render", pkg, "--out", out, "--no-rrd", cwd=tmp_path / "repo")
    assert p.returncode == 0, p.stderr
    img = _img(next(out.glob("*.png")))
    g = _geometry(GHOST, tmp_path)
    assert g.placeholders == ["arm", "tip"] and sum(g.ghost) == 1 and g.wire_links == ["tip"]
    fr = raster.frame_for([g])
    v = fr.views[0]
    # where the collision box of "arm" projects (its middle third), the picture is a grey ghost
    X, Y, _ = raster._project(v, np.array([[0, 0, 0.05 + 0.17], [0, 0, 0.05 + 0.33]]))
    xs, ys = X / raster._SS + v.x0, Y / raster._SS + v.y0
    col = img[int(ys[1]):int(ys[0]), int(xs.mean()) - 2:int(xs.mean()) + 3].reshape(-1, 3)
    assert len(col) > 20 and (np.abs(col - BG).max(axis=1) > 12).mean() > 0.9
    assert (np.ptp(col, axis=1) < 40).mean() > 0.9          # grey, not the red of a wire box
    # the labels of both placeholders (dark red text on white boxes) and the red wire box
    text = (img[:, :, 0] > 110) & (img[:, :, 0] < 190) & (img[:, :, 1] < 60) & (img[:, :, 2] < 60)
    assert text.sum() > 30
    red = (img[:, :, 0] > 180) & (img[:, :, 1] < 80) & (img[:, :, 2] < 80)
    assert red.sum() > 100
    # the skeleton: dark thin line pixels between base and arm origins, drawn only because
    # something is missing (the same robot with a real visual has none)
    import dataclasses
    no_bones = dataclasses.replace(g, bones=np.zeros((0, 2, 3)))
    skeleton = (np.asarray(raster.draw(g, fr)) != np.asarray(raster.draw(no_bones, fr))).any(axis=2)
    assert skeleton.sum() > 30
    whole = _geometry(GHOST.replace('<mesh filename="package://p/meshes/gone.stl"/>',
                                    '<box size="0.08 0.08 0.5"/>').replace(
        '<mesh filename="package://p/meshes/gone2.stl"/>', '<box size="0.05 0.05 0.05"/>'),
        tmp_path, "whole")
    assert not whole.labels and not any(whole.ghost) and len(whole.bones) == 2
    whole_no_bones = dataclasses.replace(whole, bones=np.zeros((0, 2, 3)))
    assert (np.asarray(raster.draw(whole, fr)) == np.asarray(raster.draw(whole_no_bones, fr))).all()


# -- views -------------------------------------------------------------------------------------
TALL = ('<robot name="tall">\n'
        '  <link name="base"><visual><geometry><box size="0.2 0.2 0.1"/></geometry>'
        '<material name="r"><color rgba="0.8 0.1 0.1 1"/></material></visual></link>\n'
        '  <link name="mast"><visual><origin xyz="0 0 0.9"/><geometry><box size="0.05 0.05 1.8"/>'
        '</geometry></visual></link>\n'
        '  <link name="nose"><visual><geometry><box size="0.1 0.05 0.05"/></geometry>'
        '<material name="b"><color rgba="0.1 0.1 0.9 1"/></material></visual></link>\n'
        '  <joint name="j" type="fixed"><parent link="base"/><child link="mast"/></joint>\n'
        '  <joint name="n" type="fixed"><parent link="base"/><child link="nose"/>'
        '<origin xyz="0.2 0 0.05"/></joint>\n</robot>\n')


def test_sheet_has_four_views_triads_and_crops_tall_robots(tmp_path):
    g = _geometry(TALL, tmp_path)
    single = np.asarray(raster.draw(g, raster.frame_for([g])), dtype=int)
    h, w = single.shape[:2]
    assert h > 1.5 * w                                       # cropped to a tall robot
    fg = _fg(single[raster.CAPTION_H:])
    ys = np.nonzero(fg.any(axis=1))[0]
    assert (ys.max() - ys.min()) > 0.85 * (h - raster.CAPTION_H)   # and fills it
    fr = raster.frame_for([g], views="sheet")
    sheet = np.asarray(raster.draw(g, fr), dtype=int)
    plain = np.asarray(raster.draw(g, fr, annotate=False), dtype=int)
    assert [v.name for v in fr.views] == ["front", "side", "top", "3/4"]

    def pure(a, ch):
        return (a[:, :, ch] > 150) & (np.delete(a, ch, axis=2).max(axis=2) < 110)
    for v in fr.views:
        cell = sheet[v.y0:v.y0 + v.h, v.x0:v.x0 + v.w]
        body = _fg(cell[20:, 50:])
        assert body.mean() > 0.01, v.name                   # every quadrant shows the robot
        corner = cell[-45:, :45]
        bare = plain[v.y0:v.y0 + v.h, v.x0:v.x0 + v.w][-45:, :45]
        for ch in range(3):                                 # the triad: red, green, blue axes
            if v.name == "front" and ch == 0 or v.name == "side" and ch == 1 \
                    or v.name == "top" and ch == 2:
                continue                                    # that axis points at the camera
            drawn = pure(corner, ch) & (corner != bare).any(axis=2)
            assert drawn.sum() >= 3, (v.name, ch)


def test_forward_axis_turns_the_named_views(tmp_path):
    g = _geometry(TALL, tmp_path)
    # the robot turned by 180 degrees, seen with forward = -x, is the same front view
    turned = _geometry(TALL.replace('<link name="base">', '<link name="world"/>\n'
                                '  <joint name="w" type="fixed"><parent link="world"/>'
                                '<child link="base"/><origin rpy="0 0 3.14159265358979"/></joint>\n'
                                '  <link name="base">'), tmp_path, "turned")
    a = np.asarray(raster.draw(g, raster.frame_for([g], views="sheet")), dtype=int)
    b = np.asarray(raster.draw(turned, raster.frame_for([turned], views="sheet", forward="-x")),
                   dtype=int)
    c = np.asarray(raster.draw(turned, raster.frame_for([turned], views="sheet")), dtype=int)
    assert a.shape == b.shape
    fa, fb, fc = _fg(a), _fg(b), _fg(c)
    assert (fa ^ fb).mean() < 0.01          # the same picture, up to rounding
    assert (fa ^ fc).mean() > 0.01          # while the default forward axis sees its back


# -- fidelity ----------------------------------------------------------------------------------
def _flat(tris, cols, **kw):
    tris = [np.asarray(t, dtype=float) for t in tris]
    return raster.Geometry("t", tris, [np.asarray(c, dtype=float) for c in cols], [],
                           np.zeros((1, 3)), 1, ["a"] * len(tris), [], **kw)


def test_texture_is_sampled_per_pixel(tmp_path):
    tri = np.array([[[0, -1, -1], [0, 1, -1], [0, 0, 1]]])            # faces +x
    uv = np.array([[[0.05, 0.5], [0.95, 0.5], [0.5, 0.9]]], dtype=np.float32)
    tex = np.zeros((8, 8, 3), dtype=np.uint8)
    tex[:, :4] = (220, 20, 20)
    tex[:, 4:] = (20, 20, 220)
    g = _flat([tri], [[[1, 1, 1]]], uvs=[uv], texs=[tex])
    fr = raster.frame_for([g], views="sheet")
    a = _no_triads(np.asarray(raster.draw(g, fr), dtype=int), fr)
    v = fr.views[0]                                                    # front: looks at +x
    cell = a[v.y0:v.y0 + v.h, v.x0:v.x0 + v.w]
    red = (cell[:, :, 0] > 120) & (cell[:, :, 2] < 60)
    blue = (cell[:, :, 2] > 120) & (cell[:, :, 0] < 60)
    assert red.sum() > 500 and blue.sum() > 500        # one triangle, both colours
    # the colours follow the UVs pixel by pixel: mirrored UVs swap the two halves
    mirrored = uv.copy()
    mirrored[..., 0] = 1.0 - mirrored[..., 0]
    gm = _flat([tri], [[[1, 1, 1]]], uvs=[mirrored], texs=[tex])
    b = _no_triads(np.asarray(raster.draw(gm, fr), dtype=int), fr)[v.y0:v.y0 + v.h,
                                                                   v.x0:v.x0 + v.w]
    red_m = (b[:, :, 0] > 120) & (b[:, :, 2] < 60)
    blue_m = (b[:, :, 2] > 120) & (b[:, :, 0] < 60)
    assert (red & blue_m).sum() > 0.9 * red.sum() and (blue & red_m).sum() > 0.9 * blue.sum()


def _box_tris():
    import trimesh
    m = trimesh.creation.box(extents=(0.4, 0.3, 0.2))
    return np.asarray(m.vertices)[np.asarray(m.faces)]


def test_coincident_back_faces_do_not_stripe_the_front():
    t = _box_tris()
    front = _flat([t], [np.tile([0.2, 0.7, 0.3], (len(t), 1))])
    back = t[:, ::-1]                                   # the same faces, facing inwards
    both = _flat([back, t], [np.tile([0.9, 0.1, 0.1], (len(t), 1)),
                             np.tile([0.2, 0.7, 0.3], (len(t), 1))])
    fr = raster.frame_for([front], views="sheet")
    a = _no_triads(np.asarray(raster.draw(front, fr), dtype=int), fr)
    b = _no_triads(np.asarray(raster.draw(both, fr), dtype=int), fr)
    assert ((b[:, :, 0] > 150) & (b[:, :, 1] < 80)).sum() == 0     # no red stripe shows
    body = _fg(a)
    assert (np.abs(a - b).max(axis=2)[body] <= 40).mean() > 0.97     # the front image holds


def test_dark_parts_keep_an_outline():
    t = _box_tris()
    g = _flat([t], [np.zeros((len(t), 3))])             # a black box
    fr = raster.frame_for([g])
    a = np.asarray(raster.draw(g, fr), dtype=int)
    lum = a.mean(axis=2)
    body = _fg(a)
    dark = body & (lum < 60)
    edge_light = body & (lum > 90) & (lum < 200)
    assert dark.sum() > 1000 and edge_light.sum() > 200   # lightened silhouette and edges


def test_multi_material_obj_gets_each_materials_colour(tmp_path):
    mtl = "newmtl red\nKd 0.9 0.1 0.1\n\nnewmtl blue\nKd 0.1 0.1 0.9\n"
    obj = ("mtllib two.mtl\n"
           "v 0 0 0\nv 0.2 0 0\nv 0.2 0.2 0\nv 0 0.2 0\nv 0.4 0 0\nv 0.4 0.2 0\n"
           "usemtl red\nf 1 2 3\nf 1 3 4\nusemtl blue\nf 2 5 6\nf 2 6 3\n")
    urdf = ('<robot name="mm"><link name="a"><visual><geometry>'
            '<mesh filename="package://p/meshes/two.obj"/></geometry></visual></link></robot>\n')
    pkg = make_package(tmp_path / "repo", "p", {"urdf/mm.urdf": urdf, "meshes/two.obj": obj,
                                                "meshes/two.mtl": mtl})
    out = tmp_path / "snap"
    p = run_cli("render", pkg, "--out", out, "--no-rrd", "--views", "sheet", cwd=tmp_path / "repo")
    assert p.returncode == 0, p.stderr
    a = _img(next(out.glob("*.png")))
    red = (a[:, :, 0] > 120) & (a[:, :, 2] < 70) & (a[:, :, 1] < 70)
    blue = (a[:, :, 2] > 120) & (a[:, :, 0] < 70) & (a[:, :, 1] < 70)
    assert red.sum() > 300 and blue.sum() > 300


# -- exit codes and stale files -----------------------------------------------------------------
def test_failed_snapshot_exits_1_and_stale_files_go_but_users_stay(tmp_path):
    box = ('<robot name="{n}"><link name="a"><visual><geometry><box size="0.1 0.1 0.1"/>'
           '</geometry></visual></link></robot>\n')
    repo = tmp_path / "repo"
    pkg = make_package(repo, "p", {"urdf/one.urdf": box.format(n="one"),
                                   "urdf/two.urdf": box.format(n="two")})
    out = tmp_path / "snap"
    out.mkdir()
    (out / "notes.png").write_bytes(b"the user's own file")
    (out / "two.png").write_bytes(b"also the user's")
    p = run_cli("render", pkg, "--out", out, "--no-rrd", cwd=repo)
    assert p.returncode == 0, p.stderr
    assert len(list(out.glob("p__urdf__*.png"))) == 2
    (pkg / "urdf/two.urdf").unlink()
    (pkg / "urdf/one.urdf").write_text("<robot name='one'><link name='a'>")   # broken
    p = run_cli("render", pkg, "--out", out, "--no-rrd", cwd=repo)
    assert p.returncode == 1
    lines = [ln for ln in p.stderr.splitlines() if "no snapshot" in ln]
    assert len(lines) == 1 and lines[0].startswith("p/urdf/one.urdf: no snapshot"), p.stderr
    assert not list(out.glob("p__urdf__*.png"))         # last run's pictures are gone
    assert (out / "notes.png").read_bytes() == b"the user's own file"
    assert (out / "two.png").read_bytes() == b"also the user's"
    assert (out / "summary.md").exists()
    # a manifest planted in the folder (or edited), even with the files' true digests, cannot
    # make urdf-lint delete a file outside the folder or one that is not a snapshot output;
    # a listed output whose bytes changed since is kept too
    from urdf_lint.render.snapshot import MANIFEST, _digest
    (out / "keep.txt").write_text("the user's notes")
    (out / MANIFEST).write_text(json.dumps({"files": {
        "notes.png": "0" * 32,
        "../repo/p/package.xml": _digest(pkg / "package.xml"),
        "keep.txt": _digest(out / "keep.txt")}}))
    p = run_cli("render", pkg, "--out", out, "--no-rrd", cwd=repo)
    assert p.returncode == 1 and "no snapshot" in p.stderr     # one.urdf is still broken
    assert (out / "notes.png").exists() and (pkg / "package.xml").exists()
    assert (out / "keep.txt").exists()


def test_render_time_per_png_on_the_biggest_corpus_meshes(corpus, tmp_path):
    """The triangle cap is above what the corpus needs: the biggest meshes render whole."""
    import time
    from urdf_lint.meshes import resolve as meshes
    big = sorted((p for p in Path(corpus).rglob("*") if p.suffix.lower() in (".stl", ".dae", ".obj")),
                 key=lambda p: -p.stat().st_size)[:3]
    for path in big:
        m = meshes.load_mesh(str(path))
        tris = np.asarray(m.vertices)[np.asarray(m.faces)]
        assert len(tris) < raster.MAX_TRIANGLES
        g = _flat([tris], [np.tile([0.7, 0.7, 0.7], (len(tris), 1))])
        t0 = time.perf_counter()
        raster.draw(g, raster.frame_for([g]))
        assert time.perf_counter() - t0 < 10, path          # generous: a shared CI machine


def test_diff_render_exits_1_when_a_revision_cannot_be_drawn(tmp_path):
    import subprocess
    box = ('<robot name="r"><link name="a"><visual><geometry><box size="0.1 0.1 0.1"/>'
           '</geometry></visual></link></robot>\n')
    repo = tmp_path / "repo"
    pkg = make_package(repo, "p", {"urdf/r.urdf": box})

    def git(*a):
        subprocess.run(["git", "-c", "user.email=t@t", "-c", "user.name=t", *a], cwd=repo,
                       check=True, capture_output=True)
    git("init", "-q")
    git("add", "-A")
    git("commit", "-qm", "base")
    (pkg / "urdf/r.urdf").write_text(box.replace("0.1 0.1 0.1", "0.2 0.1 0.1"))
    ok = run_cli("diff", "HEAD", "--render", tmp_path / "a", "--no-rrd", "--no-cache",
                 "--fail-on", "never", cwd=repo)
    assert ok.returncode == 0, ok.stderr
    assert len(list((tmp_path / "a").glob("*.png"))) == 3
    (pkg / "urdf/r.urdf").write_text("<robot name='r'><link name='a'>")     # does not parse
    bad = run_cli("diff", "HEAD", "--render", tmp_path / "b", "--no-rrd", "--no-cache",
                  "--fail-on", "never", cwd=repo)
    assert bad.returncode == 1
    lines = [ln for ln in bad.stderr.splitlines() if "snapshot incomplete" in ln]
    assert len(lines) == 1 and lines[0].startswith("p/urdf/r.urdf"), bad.stderr
    assert "head revision" in lines[0]
