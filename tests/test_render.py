"""Snapshots: rerun recordings read back through RrdReader and the rerun CLI, PNGs checked for
framing, determinism, placeholders for missing meshes, and no leak of files outside the roots."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from conftest import DESCRIPTIONS, SEED_PACKAGES, make_package, run_cli
from urdf_lint.core.locations import picture_name

# picture names of the seed robots, rendered from the checkout's root (the repository)
R2D2 = picture_name("descriptions/r2d2_description/urdf/r2d2.urdf.xacro")
PENDULUM = picture_name("descriptions/double_pendulum_description/urdf/double_pendulum.urdf.xacro")

rr = pytest.importorskip("rerun")
RERUN = str(Path(sys.executable).parent / "rerun")
SECRET = "TOP-SECRET-MESH-BYTES-42"


def entity_data(path):
    from rerun.chunk import RrdReader
    out = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for ch in RrdReader(str(path)).stream():
            cols = {c.split(":")[-1] for c in ch.to_record_batch().schema.names}
            out.setdefault(str(ch.entity_path), set()).update(cols)
    return out


def text_logs(path):
    from rerun.chunk import RrdReader
    texts = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for ch in RrdReader(str(path)).stream():
            b = ch.to_record_batch()
            for name in b.schema.names:
                if name.endswith(":text"):
                    for v in b.column(name).to_pylist():
                        texts.append((str(ch.entity_path), v[0] if isinstance(v, list) else v))
    return texts


@pytest.fixture(scope="module")
def snaps(tmp_path_factory):
    out = tmp_path_factory.mktemp("snaps")
    for run in ("a", "b"):
        p = run_cli("render", *SEED_PACKAGES, "--out", out / run)
        assert p.returncode == 0, p.stderr
    return out


def test_recording_follows_the_kinematic_tree(snaps):
    rrd = snaps / "a" / f"{R2D2}.rrd"
    ents = entity_data(rrd)
    links = ["base_footprint", "base_link", "head", "box", "left_leg", "left_base", "left_front_wheel",
             "gripper_pole", "left_gripper", "left_tip", "right_tip"]
    for link in links:
        assert any(p.startswith("/robot/") and p.endswith("/" + link) for p in ents), link
    head = next(p for p in ents if p.endswith("/head") and p.startswith("/robot/"))
    assert head == "/robot/base_footprint/base_footprint_joint/base_link/head_swivel/head"
    visual = [p for p in ents if p.startswith("/robot/") and p.endswith("/visual/0/mesh")]
    collision = [p for p in ents if p.startswith("/collision/") and p.endswith("/collision/0/mesh")]
    assert len(visual) == 16 and len(collision) == 16
    assert "vertex_positions" in ents[visual[0]] and "triangle_indices" in ents[visual[0]]
    assert any(p.endswith("/joint_axis") for p in ents)                       # movable joints
    assert sum(1 for p, c in ents.items() if "axis_length" in c) == 17        # a frame per link


def test_two_runs_compare_equal_and_compare_can_fail(snaps):
    a = snaps / "a" / f"{R2D2}.rrd"
    b = snaps / "b" / f"{R2D2}.rrd"
    env = dict(os.environ, RERUN_ANALYTICS="off")
    same = subprocess.run([RERUN, "rrd", "compare", "--unordered", str(a), str(b)],
                          capture_output=True, text=True, env=env)
    assert same.returncode == 0, same.stdout + same.stderr
    other = snaps / "a" / f"{PENDULUM}.rrd"
    diff = subprocess.run([RERUN, "rrd", "compare", "--unordered", str(a), str(other)],
                          capture_output=True, text=True, env=env)
    assert diff.returncode != 0


def foreground_share(png):
    img = np.asarray(Image.open(png).convert("RGB")).astype(int)
    bg = img[-1, -1]
    mask = np.abs(img - bg).sum(axis=2) > 30
    mask[:40, :] = False  # caption
    ys, xs = np.nonzero(mask)
    assert len(ys), "blank image"
    span = max((xs.max() - xs.min() + 1) / img.shape[1], (ys.max() - ys.min() + 1) / img.shape[0])
    return span, mask.mean(), img


def test_png_frames_the_model_and_is_deterministic(snaps):
    for name in (f"{R2D2}.png",
                 f"{PENDULUM}.png"):
        span, fill, img = foreground_share(snaps / "a" / name)
        assert span > 0.7, (name, span)      # auto-framed: the model spans the frame
        assert fill > 0.03, (name, fill)     # and is not a few stray pixels
        assert (snaps / "a" / name).read_bytes() == (snaps / "b" / name).read_bytes()
    _, _, img = foreground_share(snaps / "a" / f"{R2D2}.png")
    blue = ((img[:, :, 2] > 150) & (img[:, :, 0] < 60)).mean()
    assert blue > 0.02  # the model's own colours (R2D2's blue body)
    summary = (snaps / "a" / "summary.md").read_text()
    assert "| `descriptions/r2d2_description/urdf/r2d2.urdf.xacro` | 17 | 16 | 8 | 0 | 0 | 0 |" in summary
    assert rf"![descriptions/r2d2\_description/urdf/r2d2.urdf.xacro]({R2D2}.png)" in summary


def test_broken_model_renders_safely_with_findings(tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "secret.stl").write_text(f"solid {SECRET}\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                                        "vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n")
    body = ('<robot name="broken">\n'
            '  <link name="base"><visual><geometry><box size="0.2 0.2 0.2"/></geometry></visual></link>\n'
            '  <link name="ghost"><visual><geometry><mesh filename="package://p/meshes/gone.stl"/></geometry></visual></link>\n'
            '  <link name="thief"><visual><geometry><mesh filename="package://p/meshes/link.stl"/></geometry></visual></link>\n'
            '  <joint name="j1" type="fixed"><parent link="base"/><child link="ghost"/><origin xyz="0.5 0 0"/></joint>\n'
            '  <joint name="j2" type="fixed"><parent link="base"/><child link="thief"/><origin xyz="0 0.5 0"/></joint>\n'
            '</robot>\n')
    pkg = make_package(tmp_path / "repo", "p", {"urdf/broken.urdf": body})
    (pkg / "meshes").mkdir()
    os.symlink(outside / "secret.stl", pkg / "meshes/link.stl")
    out = tmp_path / "snap"
    p = run_cli("check", pkg, "--no-cache", "--render", out, cwd=tmp_path / "repo")
    assert p.returncode == 1
    assert "UL401" in p.stdout and "UL403" in p.stdout
    rrd = next(out.glob("*.rrd"))
    png = next(out.glob("*.png"))
    assert SECRET.encode() not in rrd.read_bytes() and SECRET.encode() not in png.read_bytes()
    logs = text_logs(rrd)
    assert any(e.endswith("/ghost/findings/" + e.rsplit("/", 1)[-1]) and t.startswith("UL401") for e, t in logs), logs
    assert any("/thief/findings/" in e and t.startswith("UL403") for e, t in logs), logs
    ents = entity_data(rrd)
    assert any(p.endswith("/ghost/visual/0/missing") for p in ents)
    img = np.asarray(Image.open(png).convert("RGB")).astype(int)
    red = ((img[:, :, 0] > 180) & (img[:, :, 1] < 80) & (img[:, :, 2] < 80)).sum()
    assert red > 200  # the red placeholder boxes


def test_corpus_robots_render_with_textures(corpus, tmp_path):
    cfg = tmp_path / "urdf-lint.toml"
    cfg.write_text(f'[[models]]\npath = "{corpus}/franka_description/robots/panda/panda.urdf.xacro"\n'
                   'args = [{hand = "true"}]\n')
    out = tmp_path / "snap"
    p = run_cli("render", "ur_description/urdf/ur5e.xacro", "franka_description/robots/panda/panda.urdf.xacro",
                "turtlebot3_description/urdf/turtlebot3_waffle_pi.urdf.xacro",
                "urdf_tutorial/urdf/08-macroed.urdf.xacro", "--config", cfg, "--out", out, cwd=corpus)
    assert p.returncode == 0, p.stderr
    pngs = sorted(out.glob("*.png"))
    assert len(pngs) == 4
    for png in pngs:
        span, fill, _ = foreground_share(png)
        assert span > 0.6 and fill > 0.03, png.name
    ents = entity_data(out / f"{picture_name('urdf_tutorial/urdf/08-macroed.urdf.xacro')}.rrd")
    textured = [p for p, c in ents.items() if "vertex_texcoords" in c and "albedo_texture_buffer" in c]
    assert len(textured) == 4  # the gripper fingers' DAE textures
    panda = entity_data(next(out.glob("franka*.rrd")))
    assert sum(1 for p in panda if p.startswith("/robot/") and p.endswith("/visual/0/mesh")) == 11  # link0-7, hand, 2 fingers
