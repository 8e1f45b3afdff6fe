"""The .rrd of a snapshot, read back with rerun's own reader: Z-up at the root, the blueprint,
axes scaled to the robot, the ``joint_sweep`` timeline (yourdfpy kinematics, checked against the
zero-configuration transforms of :mod:`urdf_lint.render.scene`) and no path of the machine inside."""
from __future__ import annotations

import dataclasses
import importlib.util
import os
import re
import warnings
from pathlib import Path

import numpy as np
import pytest
from lxml import etree

from conftest import (CORPUS, DESCRIPTIONS, REPO, SEED_PACKAGES, corpus_entries, make_package,
                      run_cli)

# (rerun is imported by the tests that read a recording: 0.4 s of every collection otherwise)
if importlib.util.find_spec("rerun") is None:
    pytest.skip("rerun-sdk is not installed (Python 3.10)", allow_module_level=True)
pytest.importorskip("yourdfpy")

SEEDS = [(DESCRIPTIONS / "r2d2_description" / "urdf" / "r2d2.urdf.xacro", {}),
         (DESCRIPTIONS / "double_pendulum_description" / "urdf" / "double_pendulum.urdf.xacro",
          {})]


def corpus_robot(file, **want):
    for f, args in corpus_entries():
        if f == file and all(args.get(k) == v for k, v in want.items()):
            return CORPUS / f, args
    pytest.skip(f"{file} is not in ../shared/corpus")


def load_model(entry: Path, args: dict):
    """The expanded Model of a trusted entry, linted in process."""
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.core.jobs import LintJob
    from urdf_lint.engine.lint import lint_model
    from urdf_lint.run.pipeline import settings_for
    cfg = load_config(None)
    settings = dataclasses.replace(settings_for(cfg, build_resolver([str(entry)], cfg), None),
                                   keep_model=True)
    _report, model, _ctx = lint_model(LintJob(str(entry), dict(args), "xacro", explicit=True),
                                      settings)
    assert model is not None, entry
    return model


def chunks(path, store=None):
    from rerun.chunk import RrdReader
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        reader = RrdReader(str(path))
        yield from reader.stream(store=store)


def columns(path, store=None):
    """entity path -> {column name: list of values} over every chunk (time columns as ints)."""
    import pyarrow as pa
    out: dict = {}
    for ch in chunks(path, store):
        b = ch.to_record_batch()
        ent = out.setdefault(str(ch.entity_path), {})
        for name in b.schema.names:
            col = b.column(name)
            if pa.types.is_timestamp(col.type) or pa.types.is_duration(col.type):
                col = col.cast(pa.int64())
            vals = [v[0] if isinstance(v, list) and len(v) == 1 else v for v in col.to_pylist()]
            ent.setdefault(name.split(":")[-1] if "joint_sweep" not in name else "joint_sweep",
                           []).extend(vals)
    return out


def strings(path):
    """Every string stored in the recording and its blueprints, entity paths included."""
    from rerun.chunk import RrdReader
    reader = RrdReader(str(path))
    out = []
    for store in [None, *reader.blueprints()]:
        for ent, cols in columns(path, store).items():
            out.append(ent)

            def walk(v):
                if isinstance(v, str):
                    out.append(v)
                elif isinstance(v, (list, tuple)):
                    for x in v:
                        walk(x)
            for vals in cols.values():
                walk(vals)
    return out


# -- yourdfpy against the zero configuration ---------------------------------------------------
def _poses_agree(model):
    from urdf_lint.render.scene import kinematic_tree
    from urdf_lint.render.sweep import build_urdf, link_poses
    world, _tree, _roots = kinematic_tree(model)
    urdf = build_urdf(model.root)
    assert urdf is not None
    poses = link_poses(urdf)
    assert set(poses) == set(world)
    worst = max(float(np.abs(world[k] - poses[k]).max()) for k in world)
    assert worst < 1e-9, worst
    return len(world)


@pytest.mark.parametrize("entry,args", SEEDS, ids=lambda x: getattr(x, "name", ""))
def test_yourdfpy_agrees_with_zero_configuration_on_the_seeds(entry, args):
    assert _poses_agree(load_model(entry, args)) >= 4


@pytest.mark.parametrize("file,want", [("ur_description/urdf/ur5e.xacro", {}),
                                       ("franka_description/robots/panda/panda.urdf.xacro",
                                        {"hand": "true"})])
def test_yourdfpy_agrees_with_zero_configuration_on_ur5e_and_panda(corpus, file, want):
    entry, args = corpus_robot(file, **want)
    assert _poses_agree(load_model(entry, args)) >= 10


def test_yourdfpy_reads_no_file(tmp_path, monkeypatch):
    """The mesh exists, yet yourdfpy neither opens it nor resolves its name."""
    from urdf_lint.render import sweep
    mesh = tmp_path / "secret.stl"
    mesh.write_bytes(b"solid x\nendsolid x\n")
    root = etree.fromstring(f"""<robot name="r">
      <link name="a"><visual><geometry><mesh filename="{mesh}"/></geometry></visual>
        <collision><geometry><mesh filename="file://{mesh}"/></geometry></collision></link>
      <link name="b"/>
      <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
        <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    </robot>""".encode())
    opened = []
    real_open = open

    def spy(file, *a, **kw):
        opened.append(str(file))
        return real_open(file, *a, **kw)
    monkeypatch.setattr("builtins.open", spy)
    monkeypatch.setattr(os.path, "isfile", lambda p: opened.append(str(p)) or False)
    urdf = sweep.build_urdf(root)
    plan = sweep.plan(urdf)
    monkeypatch.undo()
    assert [s.joint for s in plan.segments] == ["j"]
    assert not [p for p in opened if "secret" in p], opened
    with pytest.raises(PermissionError):
        urdf._filename_handler(fname=str(mesh))


def test_sweep_plan_moves_each_joint_through_its_range():
    from urdf_lint.render import sweep
    root = etree.fromstring(b"""<robot name="r">
      <link name="a"/><link name="b"/><link name="c"/><link name="d"/><link name="e"/>
      <link name="f"/>
      <joint name="rev" type="revolute"><parent link="a"/><child link="b"/>
        <axis xyz="0 0 1"/><limit lower="0.5" upper="1.5" effort="1" velocity="1"/></joint>
      <joint name="fix" type="fixed"><parent link="b"/><child link="c"/></joint>
      <joint name="pri" type="prismatic"><parent link="c"/><child link="d"/>
        <origin xyz="0 0 1"/><axis xyz="1 0 0"/>
        <limit lower="-0.2" upper="0.3" effort="1" velocity="1"/></joint>
      <joint name="mim" type="prismatic"><parent link="d"/><child link="e"/>
        <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
        <mimic joint="pri" multiplier="2" offset="0.1"/></joint>
      <joint name="cont" type="continuous"><parent link="e"/><child link="f"/>
        <axis xyz="0 0 1"/></joint>
    </robot>""")
    plan = sweep.plan(sweep.build_urdf(root))
    assert [(s.joint, s.followers) for s in plan.segments] == [
        ("rev", []), ("pri", ["mim"]), ("cont", [])]
    rev, pri, cont = plan.segments
    assert min(rev.values) == pytest.approx(0.5) and max(rev.values) == pytest.approx(1.5)
    assert rev.values[0] == pytest.approx(0.5) and rev.values[-1] == pytest.approx(0.5)  # rest
    assert min(cont.values) == pytest.approx(-np.pi) and max(cont.values) == pytest.approx(np.pi)
    # the prismatic joint's child moves along x from origin + lower to origin + upper, and the
    # mimic follows with 2 q + 0.1 along y
    xs = [plan.frames[s]["pri"][0, 3] for s in range(pri.start, pri.end + 1)
          if "pri" in plan.frames[s]]
    assert min(xs) == pytest.approx(-0.2) and max(xs) == pytest.approx(0.3)
    ys = [plan.frames[s]["mim"][1, 3] for s in range(pri.start, pri.end + 1)
          if "mim" in plan.frames[s]]
    assert min(ys) == pytest.approx(-0.3) and max(ys) == pytest.approx(0.7)
    # segments do not overlap and each ends with its joint back at rest
    assert rev.end < pri.start and pri.end < cont.start
    assert plan.frames[0]["rev"][:3, :3] == pytest.approx(
        sweep.build_urdf(root).get_transform("b")[:3, :3] @ _rz(0.5))


def _rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


# -- the recording -------------------------------------------------------------------------
def _stem(entry) -> str:
    """The name `render` gives the pictures of ``entry``, run from the checkout (REPO)."""
    from urdf_lint.core.locations import snapshot_name
    return snapshot_name(os.path.realpath(entry), {}, str(REPO))   # render names the real path


GRIPPER = CORPUS / "robotiq_description" / "urdf" / "robotiq_2f_85_gripper.urdf.xacro"
UR5E = CORPUS / "ur_description" / "urdf" / "ur5e.xacro"


@pytest.fixture(scope="module")
def recordings(tmp_path_factory):
    out = tmp_path_factory.mktemp("rec")
    paths = [str(p) for p in SEED_PACKAGES]
    extra = [str(p) for p in (GRIPPER, UR5E) if p.is_file()]
    p = run_cli("render", *paths, *extra, "--out", out)
    assert p.returncode in (0, 1), p.stderr
    return out


def _expected_segments(model):
    """(movable joint, its mimic followers) in document order, from the XML alone."""
    joints = [j for j in model.root if j.tag == "joint"]
    followers = {}
    for j in joints:
        m = j.find("mimic")
        if m is not None:
            followers.setdefault(m.get("joint"), set()).add(j.get("name"))
    out = []
    for j in joints:
        if j.get("type") not in ("revolute", "prismatic", "continuous") or \
                j.find("mimic") is not None:
            continue
        lim = j.find("limit")
        if j.get("type") != "continuous" and (lim is None or float(lim.get("upper", 0)) <=
                                              float(lim.get("lower", 0))):
            continue
        out.append((j.get("name"), followers.get(j.get("name"), set())))
    return out


def _segments_in(rrd):
    """From the recording alone: per /sweep segment, the joints whose transform it logs."""
    cols = columns(rrd)
    starts = sorted(cols["/sweep"]["joint_sweep"])
    texts = cols["/sweep"]["text"]
    moved: list = [set() for _ in starts]
    for ent, c in cols.items():
        if not ent.startswith("/robot/") or "joint_sweep" not in c:
            continue
        assert "translation" in c and "mat3x3" in c, ent
        for t in c["joint_sweep"]:
            if t == 0:
                continue
            i = max(k for k, s in enumerate(starts) if s <= t)
            moved[i].add(ent.rsplit("/", 1)[1])
    return starts, texts, moved


@pytest.mark.parametrize("entry", [
    SEEDS[0][0], SEEDS[1][0], GRIPPER, UR5E], ids=lambda e: e.name)
def test_sweep_timeline_has_one_segment_per_movable_joint(recordings, entry):
    rrd = recordings / f"{_stem(entry)}.rrd"
    if not entry.is_file():
        pytest.skip("../shared/corpus is not present")
    want = _expected_segments(load_model(entry, {}))
    assert want, "the model has movable joints"
    starts, texts, moved = _segments_in(rrd)
    assert len(starts) == len(want)
    for (joint, followers), text, got in zip(want, texts, moved, strict=True):
        assert text.startswith(f"sweep {joint}")
        assert got == {joint} | followers, (joint, got)
    # the collision tree moves with the visual one
    cols = columns(rrd)
    assert sum(1 for e, c in cols.items() if e.startswith("/collision/") and "joint_sweep" in c) \
        == sum(1 for e, c in cols.items() if e.startswith("/robot/") and "joint_sweep" in c)


def test_robotiq_mimic_joints_follow(recordings):
    rrd = recordings / f"{_stem(GRIPPER)}.rrd"
    if not rrd.is_file():
        pytest.skip("../shared/corpus is not present")
    _starts, _texts, moved = _segments_in(rrd)
    assert len(moved) == 1 and len(moved[0]) == 6   # the knuckle and its 5 mimic joints


def test_z_up_blueprint_and_scaled_axes(recordings):
    import rerun as rr
    from rerun.chunk import RrdReader
    r2d2 = recordings / f"{_stem(SEEDS[0][0])}.rrd"
    cols = columns(r2d2)
    zup = rr.ViewCoordinates.RIGHT_HAND_Z_UP.as_component_batches()[0].as_arrow_array()
    assert cols["/"]["xyz"] == zup.to_pylist()             # ViewCoordinates at the root
    (bp,) = RrdReader(str(r2d2)).blueprints()
    bcols = columns(r2d2, bp)
    kinds = [v for c in bcols.values() for v in c.get("class_identifier", [])]
    assert "3D" in kinds and "TextLog" in kinds
    hidden = [e for e, c in bcols.items() if c.get("visible") == [False]]
    assert len(hidden) == 1 and hidden[0].endswith("/overrides/collision/visualizers")
    queries = [q for c in bcols.values() for q in c.get("query", [])]
    assert ["+ /robot/**", "+ /collision/**"] in queries
    # axes scale with the robot: a few percent of its extent (link origins and geometry)
    for entry in (SEEDS[0][0], SEEDS[1][0]):
        from urdf_lint.render.scene import kinematic_tree
        stem = _stem(entry)
        length = _axis_length(recordings / f"{stem}.rrd")
        world, _tree, _roots = kinematic_tree(load_model(entry, {}))
        origins = np.array([T[:3, 3] for T in world.values()])
        size = float(np.ptp(origins, axis=0).max())        # the extent of the link origins
        assert 0.03 * size < length < 0.15 * size, (stem, length, size)


def test_axes_of_an_arm_and_a_gripper_differ_by_their_size(recordings):
    arm = recordings / f"{_stem(UR5E)}.rrd"
    gripper = recordings / f"{_stem(GRIPPER)}.rrd"
    if not arm.is_file() or not gripper.is_file():
        pytest.skip("../shared/corpus is not present")
    assert _axis_length(arm) > 4 * _axis_length(gripper)
    assert 0.03 < _axis_length(arm) < 0.1        # a ~1 m arm: a few centimetres


def _axis_length(rrd):
    vals = {v for col in columns(rrd).values() for v in col.get("axis_length", [])}
    assert len(vals) == 1, vals
    return vals.pop()


def test_no_path_of_the_machine_in_recording_or_summary(tmp_path):
    """A robot outside the working directory, with a missing mesh and findings: the tmp dir
    appears in no entity path, label, text log or blueprint string, and not in summary.md."""
    ws = tmp_path / "ci-machine-secret-dir" / "ws"
    make_package(ws, "bot_description", {"urdf/bot.urdf.xacro": """<?xml version="1.0"?>
<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base"><visual><geometry>
    <mesh filename="package://bot_description/meshes/gone.stl"/></geometry></visual></link>
  <link name="arm"><visual><geometry><box size="0.1 0.1 0.5"/></geometry></visual></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""})
    out = tmp_path / "out"
    p = run_cli("render", ws, "--out", out, cwd=DESCRIPTIONS)
    assert p.returncode in (0, 1), p.stderr
    rrds = list(out.glob("*.rrd"))
    assert len(rrds) == 1 and "secret" not in rrds[0].name
    texts = strings(rrds[0])
    assert any("gone.stl" in t for t in texts)            # the placeholder says what is missing
    assert any(re.match(r"UL\d{3} ", t) for t in texts)     # findings are logged
    leaks = [t for t in texts if str(tmp_path) in t or "ci-machine-secret-dir" in t]
    assert not leaks, leaks
    summary = (out / "summary.md").read_text()
    assert "bot_description/urdf/bot.urdf.xacro" in summary
    assert str(tmp_path) not in summary and "ci-machine-secret-dir" not in summary


def test_rerun_verifies_the_recordings(recordings):
    """rerun's own checker loads every recording (sweep columns and blueprint included)."""
    import subprocess
    import sys
    exe = str(Path(sys.executable).parent / "rerun")
    rrds = sorted(recordings.glob("*.rrd"))
    assert len(rrds) >= 2
    p = subprocess.run([exe, "rrd", "verify", *map(str, rrds)], capture_output=True, text=True,
                       env=dict(os.environ, RERUN_ANALYTICS="off"), timeout=120)
    assert p.returncode == 0, p.stdout + p.stderr


def test_recorder_writes_what_record_rrd_writes_and_says_what_failed(tmp_path):
    """A plan made from a model (what a diff worker sends) and written by the recorder process
    gives the recording record_rrd writes in one process; a recording that cannot be written
    comes back as a reason, and a dead recorder is an error, never a hang."""
    import subprocess
    import sys
    from urdf_lint.render.recording import Recorder, label_base, plan_rrd, record_rrd
    from urdf_lint.render.scene import build_scene
    entry = DESCRIPTIONS / "r2d2_description" / "urdf" / "r2d2.urdf.xacro"
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.core.jobs import LintJob
    from urdf_lint.engine.lint import lint_model
    from urdf_lint.run.pipeline import settings_for
    cfg = load_config(None)
    settings = dataclasses.replace(settings_for(cfg, build_resolver([str(entry)], cfg), None),
                                   keep_model=True)
    _report, model, ctx = lint_model(LintJob(str(entry), {}, "xacro", explicit=True), settings)
    scene = build_scene(model, ctx)
    here = tmp_path / "here.rrd"
    facts = record_rrd(scene, ctx, str(here), recording_id="r", prefix="head/", model=model)
    plan = plan_rrd(build_scene(model, ctx), ctx, model, label_base(model.entry))
    # the plan a diff worker pickles holds the robot's meshes, as the recording written here
    assert plan.meshes == facts["meshes"] > 0 and len(plan.paths) > 1
    rec = Recorder(str(tmp_path))
    try:
        there = tmp_path / "there.rrd"
        rec.write(str(there), "r", [("head/", plan)])
        rec.write(str(tmp_path / "no" / "such" / "folder" / "x.rrd"), "r", [("head/", plan)])
        done = rec.results()
    finally:
        rec.close()
    assert done[str(there)] is None
    assert done[str(tmp_path / "no" / "such" / "folder" / "x.rrd")]     # a reason
    assert not (tmp_path / "no").exists()
    rerun_exe = str(Path(sys.executable).parent / "rerun")
    same = subprocess.run([rerun_exe, "rrd", "compare", "--unordered", str(here), str(there)],
                          capture_output=True, text=True, env=dict(os.environ,
                                                                   RERUN_ANALYTICS="off"))
    assert same.returncode == 0, same.stdout + same.stderr
    for when in ("before", "after"):   # it dies before it is given the plan, or while writing
        dead = Recorder(str(tmp_path))
        try:
            if when == "before":
                dead.proc.kill()
                dead.proc.join(5)
            else:   # frozen: the plan waits in the pipe until the recorder is killed
                import signal
                os.kill(dead.proc.pid, signal.SIGSTOP)
            dead.write(str(tmp_path / "y.rrd"), "r", [("head/", plan)])
            if when == "after":
                dead.proc.kill()
            assert "recorder died" in dead.results(timeout=10)[str(tmp_path / "y.rrd")]
        finally:
            dead.close()
