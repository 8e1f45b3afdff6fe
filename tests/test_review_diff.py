"""``urdf-lint diff``: the semantic diff of what a commit did to the robots, on a git repository
built here from the seed robots (issue #13)."""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from conftest import DESCRIPTIONS
from urdf_lint.cli.main import main
from urdf_lint.core.locations import picture_name

# the name both `diff --render` and `render` give the pictures of the seed robot
R2D2 = picture_name("r2d2_description/urdf/r2d2.urdf.xacro")


def git(repo, *args):
    subprocess.run(["git", *args], cwd=repo, check=True, capture_output=True)


def edit(path: Path, old: str, new: str, count=1):
    text = path.read_text()
    assert old in text, (path, old)
    path.write_text(text.replace(old, new, count))


@pytest.fixture()
def repo(tmp_path, monkeypatch):
    r = tmp_path / "repo"
    r.mkdir()
    for name in ("r2d2_description", "double_pendulum_description"):
        shutil.copytree(DESCRIPTIONS / name, r / name)
    r2 = r / "r2d2_description"
    # the head's mass comes from YAML, as robots with per-variant parameters do
    (r2 / "config" / "inertial.yaml").write_text("head_mass: 2.0\n")
    edit(r2 / "urdf" / "r2d2.urdf.xacro", '<xacro:box_inertial mass="2" x=',
         '<xacro:box_inertial mass="${xacro.load_yaml(\'$(find r2d2_description)/config/'
         'inertial.yaml\').head_mass}" x=')
    git(r, "init", "-q")
    git(r, "add", "-A")
    git(r, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "base")
    monkeypatch.chdir(r)
    return r


def line_of(path: Path, needle: str) -> int:
    for i, ln in enumerate(path.read_text().splitlines(), 1):
        if needle in ln:
            return i
    raise AssertionError(needle)


def run_json(capsys, *argv):
    rc = main(["diff", *argv, "--format", "json", "--no-cache"])
    out = capsys.readouterr().out
    return rc, json.loads(out)


def test_each_kind_of_change_is_listed_at_its_xacro_line(repo, capsys):
    r2 = repo / "r2d2_description"
    macros, top = r2 / "urdf" / "r2d2_macros.xacro", r2 / "urdf" / "r2d2.urdf.xacro"
    # 1. a joint limit inside a macro (the four wheel joints)
    edit(macros, '<limit effort="100" velocity="10"/>', '<limit effort="120" velocity="10"/>')
    # 2. a mesh moved to another folder
    (r2 / "meshes" / "tips").mkdir()
    git(repo, "mv", "r2d2_description/meshes/l_finger_tip.stl",
        "r2d2_description/meshes/tips/l_finger_tip.stl")
    edit(macros, "meshes/l_finger_tip.stl", "meshes/tips/l_finger_tip.stl", count=-1)
    # 3. a mass through YAML
    (r2 / "config" / "inertial.yaml").write_text("head_mass: 2.5\n")
    # 4. a new link, 5. a renamed joint
    edit(top, '<joint name="tobox" type="fixed">', '<joint name="to_box" type="fixed">')
    edit(top, "</robot>", '  <link name="antenna"/>\n  <joint name="antenna_joint" type="fixed">'
         '<parent link="head"/><child link="antenna"/></joint>\n</robot>')

    rc, doc = run_json(capsys, "HEAD")
    assert rc == 0, json.dumps(doc)[-3000:]
    assert doc["models_total"] == 2
    assert doc["base_expanded"] == 1          # the unchanged double pendulum is not expanded
    [m] = doc["models"]
    assert m["model"] == "r2d2_description/urdf/r2d2.urdf.xacro" and m["status"] == "changed"

    def src(c):
        h = c["head"]
        return f"{Path(h['file']).name}:{h['line']}"
    got = {(c["kind"], c["name"], c["change"], c["field"], src(c)) for c in m["changes"]}
    wheel = line_of(macros, 'effort="120"')
    tip = line_of(macros, "meshes/tips/l_finger_tip.stl")
    mass = line_of(macros, '<mass value="${mass}"/>')
    inertia = line_of(macros, "<inertia ")
    expected = {("joint", f"{side}_{end}_wheel_joint", "changed", "limit.effort",
                 f"r2d2_macros.xacro:{wheel}") for side in ("left", "right") for end in ("front", "back")}
    ctip = [i for i, ln in enumerate(macros.read_text().splitlines(), 1)
            if "meshes/tips/l_finger_tip.stl" in ln][1]
    expected |= {("link", f"{side}_tip", "changed", f"{part}[0].filename",
                  f"r2d2_macros.xacro:{line}")
                 for side in ("left", "right") for part, line in (("visual", tip), ("collision", ctip))}
    expected |= {("link", "head", "changed", "inertial.mass", f"r2d2_macros.xacro:{mass}"),
                 ("link", "head", "changed", "inertial.inertia", f"r2d2_macros.xacro:{inertia}"),
                 ("link", "antenna", "added", "", f"r2d2.urdf.xacro:{line_of(top, 'antenna')}"),
                 ("joint", "antenna_joint", "added", "",
                  f"r2d2.urdf.xacro:{line_of(top, 'antenna_joint')}"),
                 ("joint", "to_box", "renamed", "name", f"r2d2.urdf.xacro:{line_of(top, 'to_box')}")}
    assert got == expected
    by = {(c["name"], c["field"]): c for c in m["changes"]}
    assert all(not c["base"] or not c["base"]["file"].startswith("/") for c in m["changes"])
    assert by[("head", "inertial.mass")]["before"] == 2.0 and by[("head", "inertial.mass")]["after"] == 2.5
    assert by[("to_box", "name")]["before"] == "tobox"
    assert by[("left_front_wheel_joint", "limit.effort")]["head"]["chain"], "macro chain kept"
    # a moved mesh file with the same bytes: same content hash, only the path changed
    assert not [c for c in m["changes"] if c["field"].endswith(".content")]
    assert m["moved"] == [] and m["findings_introduced"] == [] and m["findings_fixed"] == []


def test_moved_links_and_introduced_findings(repo, capsys):
    top = repo / "r2d2_description" / "urdf" / "r2d2.urdf.xacro"
    edit(top, 'origin xyz="0 0 ${bodylen/2}"', 'origin xyz="0 0 ${bodylen/2 + 0.02}"')
    edit(repo / "r2d2_description" / "config" / "joint_limits.yaml",
         "gripper: {lower: 0.0, upper: 0.548", "gripper: {lower: 0.6, upper: 0.548")
    rc, doc = run_json(capsys, "HEAD")
    [m] = doc["models"]
    moved = {x["link"]: x["distance"] for x in m["moved"]}
    assert set(moved) == {"head", "box"} and all(abs(d - 0.02) < 1e-9 for d in moved.values())
    assert {f["code"] for f in m["findings_introduced"]} == {"UL302"}
    assert rc == 1                               # the change introduces an error
    # fixing it again: the findings are fixed relative to a base that had them
    git(repo, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qam", "bad")
    edit(repo / "r2d2_description" / "config" / "joint_limits.yaml", "lower: 0.6", "lower: 0.0")
    rc, doc = run_json(capsys, "HEAD")
    [m] = doc["models"]
    assert {f["code"] for f in m["findings_fixed"]} == {"UL302"} and rc == 0


def test_deleted_model_and_committed_revisions(repo, capsys):
    git(repo, "rm", "-q", "double_pendulum_description/urdf/double_pendulum.urdf.xacro")
    git(repo, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "drop")
    rc, doc = run_json(capsys, "HEAD~1", "HEAD")
    assert [(m["model"], m["status"]) for m in doc["models"]] == [
        ("double_pendulum_description/urdf/double_pendulum.urdf.xacro", "removed")]
    removed = {c["name"] for c in doc["models"][0]["changes"] if c["change"] == "removed"}
    assert {"link_A", "link_B"} <= removed or len(removed) >= 2


def test_nothing_changed_and_bad_revision(repo, capsys):
    rc, doc = run_json(capsys, "HEAD")
    assert rc == 0 and doc["models"] == [] and doc["base_expanded"] == 0
    rc = main(["diff", "no-such-ref", "--format", "json"])
    err = capsys.readouterr().err
    assert rc == 2 and "not a commit" in err and len(err.strip().splitlines()) == 1


def test_markdown_is_valid_gfm_and_escapes_names(repo, capsys):
    cmarkgfm = pytest.importorskip("cmarkgfm")
    top = repo / "r2d2_description" / "urdf" / "r2d2.urdf.xacro"
    edit(top, '<joint name="tobox" type="fixed">', '<joint name="to|box&lt;b&gt;" type="fixed">')
    assert main(["diff", "HEAD", "--format", "markdown", "--no-cache",
                 "--image-base-url", "https://example.invalid/run/1"]) == 0
    md = capsys.readouterr().out
    html = cmarkgfm.github_flavored_markdown_to_html(md)
    assert "<table>" in html and "<details>" in md
    assert "<b>" not in re.sub(r"<summary><b>[^<]*</b>", "", md.replace("<b>r2d2", "")), md
    assert "to|box&lt;b&gt;" in html                 # the pipe did not split the cell
    assert f"https://example.invalid/run/1/{R2D2}.after.png" in md


def test_markdown_stays_under_the_limit():
    from urdf_lint.review.run import DiffResult
    from urdf_lint.report.diff.markdown import to_markdown
    from urdf_lint.review.robotdiff import Change, ModelDiff
    r = DiffResult(base="a", head="b", total_models=400)
    for i in range(400):
        r.models.append(ModelDiff(model=f"pkg/urdf/robot_{i}.urdf.xacro", status="changed",
                                  changes=[Change("joint", f"j{k}", "changed", "limit.upper",
                                                  1.0, 2.0) for k in range(50)]))
    md = to_markdown(r)
    assert len(md) <= 60_000 and "robot_0" in md and "more model(s)" in md


# -- diff --render ---------------------------------------------------------------------------
def _img(path):
    from PIL import Image
    import numpy as np
    return np.asarray(Image.open(path).convert("RGB"), dtype=int)


def test_render_moved_link_is_highlighted_exactly_there(repo, tmp_path, capsys):
    top = repo / "r2d2_description" / "urdf" / "r2d2.urdf.xacro"
    edit(top, 'origin xyz="0 0 ${bodylen/2}"', 'origin xyz="0 0 ${bodylen/2 + 0.05}"')
    out = tmp_path / "snap"
    out.mkdir()
    (out / "stale.diff.png").write_bytes(b"old")        # an earlier run's file is cleared
    (out / "notes.diff.png").write_bytes(b"mine")       # a file urdf-lint did not write stays
    from urdf_lint.render.snapshot import MANIFEST, _digest
    (out / MANIFEST).write_text(json.dumps({"files": {      # what the earlier run wrote
        "stale.diff.png": _digest(out / "stale.diff.png"), "notes.diff.png": "0" * 32}}))
    assert main(["diff", "HEAD", "--render", str(out), "--no-rrd", "--no-cache"]) == 0
    capsys.readouterr()
    stem = out / R2D2
    before, after, diff = (_img(f"{stem}.{s}.png") for s in ("before", "after", "diff"))
    assert not (out / "stale.diff.png").exists()
    assert (out / "notes.diff.png").read_bytes() == b"mine"
    assert before.shape == after.shape == diff.shape
    tinted = (diff[:, :, 0] > 180) & (diff[:, :, 1] < 120) & (diff[:, :, 2] > 100)   # magenta
    outline = (diff[:, :, 2] > 150) & (diff[:, :, 0] < 80)                        # blue
    from urdf_lint.render.raster import LEGEND_H
    tinted[-LEGEND_H:] = outline[-LEGEND_H:] = False   # the legend's swatches
    marked = tinted | outline
    # where the moved links are, computed here from both revisions with the same framing
    base_copy = tmp_path / "base"
    shutil.copytree(repo, base_copy)
    git(base_copy, "checkout", "-q", "--", ".")
    masks = [_link_mask(root, {"head", "box"}) for root in (base_copy, repo)]
    frame = render_frame(masks)
    m_before, m_after = (render_mask(g, frame, links) for g, links in masks)
    assert m_after.sum() > 1000 and (m_before ^ m_after).sum() > 500
    assert (tinted & m_after).sum() >= 0.9 * m_after.sum()       # the new place is tinted
    near = dilate(m_before | m_after, 3)
    assert marked.sum() > 500 and not (marked & ~near).any()      # nothing else is marked


def test_pictures_drawn_in_two_threads_are_those_drawn_in_one(repo, tmp_path):
    """diff --render draws the views of the before/after pictures and highlight masks in two
    threads: the PNGs are byte for byte those drawn in one thread, each picture is draw() of
    its revision through the shared frame, and an unchanged robot is encoded once into two
    identical files."""
    from PIL import Image
    from urdf_lint.render import raster
    top = repo / "r2d2_description" / "urdf" / "r2d2.urdf.xacro"
    base_geom, _ = _link_mask(repo, ())
    edit(top, 'origin xyz="0 0 ${bodylen/2}"', 'origin xyz="0 0 ${bodylen/2 + 0.05}"')
    head_geom, _ = _link_mask(repo, ())
    changed = frozenset({"head", "box"})
    files = {}
    for n in (1, 2):
        d = tmp_path / str(n)
        d.mkdir()
        info = raster.render_pair(base_geom, head_geom, str(d / "r"), changed, threads=n)
        files[n] = {s: Path(info[s]).read_bytes() for s in ("before", "after", "diff")}
        assert info["changed_pixels"] > 500
    assert files[1] == files[2]
    frame = raster.frame_for([base_geom, head_geom], views="sheet")
    for side, g in (("before", base_geom), ("after", head_geom)):
        got = np.asarray(Image.open(tmp_path / "2" / f"r.{side}.png").convert("RGB"))
        want = np.asarray(raster.draw(g, frame))
        top_strip = raster.CAPTION_H    # the caption is written over the strip above the views
        assert (got[top_strip:] == want[top_strip:]).all()
    info = raster.render_pair(head_geom, head_geom, str(tmp_path / "same"), changed, threads=2)
    assert Path(info["before"]).read_bytes() == Path(info["after"]).read_bytes()
    # the same robot on both sides: nothing is marked changed (issue 24, item 23)
    assert info["changed_pixels"] == 0


def _link_mask(root, links):
    from urdf_lint.expansion import expand_file
    from urdf_lint.engine.lint import Context
    from urdf_lint.engine.model import model_from_xml
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.render import snapshot as render
    pkg = root / "r2d2_description"
    res = PackageResolver.build([str(root)], extra_roots=[str(root)])
    e = expand_file(str(pkg / "urdf" / "r2d2.urdf.xacro"), resolver=res)
    model = model_from_xml(e.entry, {}, e.xml, e.origins, e.deps, res)
    ctx = Context({}, None)
    return render.scene_geometry(render.build_scene(model, ctx), ctx), links


def render_frame(masks):
    from urdf_lint.render import snapshot as render
    return render.frame_for([g for g, _ in masks], views="sheet")   # diff's default


def render_mask(g, frame, links):
    """Where the parts of ``links`` are drawn in ``frame`` (no labels, skeleton or triads)."""
    from urdf_lint.render import raster
    return raster._mask(raster.draw(g.only(links), frame, annotate=False))


def dilate(m, n):
    out = m.copy()
    for _ in range(n):
        grown = out.copy()
        grown[1:, :] |= out[:-1, :]
        grown[:-1, :] |= out[1:, :]
        grown[:, 1:] |= out[:, :-1]
        grown[:, :-1] |= out[:, 1:]
        out = grown
    return out


def test_render_unchanged_model_gives_identical_pictures(repo, tmp_path, capsys):
    top = repo / "r2d2_description" / "urdf" / "r2d2.urdf.xacro"
    edit(top, "<robot name", "<!-- a comment changes the file, not the robot -->\n<robot name")
    out = tmp_path / "snap"
    assert main(["diff", "HEAD", "--render", str(out), "--no-cache", "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert [m["status"] for m in doc["models"]] == ["unchanged"]
    stem = out / R2D2
    assert Path(f"{stem}.before.png").read_bytes() == Path(f"{stem}.after.png").read_bytes()
    from urdf_lint.render.raster import LEGEND_H
    diff = _img(f"{stem}.diff.png")[:-LEGEND_H]   # (the legend's swatches below)
    assert not ((diff[:, :, 0] > 180) & (diff[:, :, 1] < 120) & (diff[:, :, 2] > 100)).any()


def test_render_recording_holds_both_revisions(repo, tmp_path, capsys):
    pytest.importorskip("rerun")
    from rerun.chunk import RrdReader
    edit(repo / "r2d2_description" / "urdf" / "r2d2.urdf.xacro", '<box size="0.08 0.08 0.08"/>',
         '<box size="0.1 0.08 0.08"/>')
    out = tmp_path / "snap"
    assert main(["diff", "HEAD", "--render", str(out), "--no-cache"]) == 0
    capsys.readouterr()
    rrd = out / f"{R2D2}.rrd"
    assert {"base", "head"} <= recording_roots(rrd)
    assert not list(out.glob("*.base.rrd")) and not list(out.glob("*.head.rrd"))
    # each revision sweeps its joints, the layout shows both, and no path of this machine
    from test_recording import _expected_segments, columns, load_model, strings
    movable = _expected_segments(load_model(repo / "r2d2_description" / "urdf" /
                                            "r2d2.urdf.xacro", {}))
    cols = columns(rrd)
    for side in ("base", "head"):
        assert len(cols[f"/{side}/sweep"]["joint_sweep"]) == len(movable) > 0
    reader = RrdReader(str(rrd))
    assert reader.blueprints()
    queries = [q for c in columns(rrd, reader.blueprints()[0]).values()
               for q in c.get("query", [])]
    assert ["+ /base/robot/**", "+ /base/collision/**"] in queries
    assert ["+ /head/robot/**", "+ /head/collision/**"] in queries
    assert not [t for t in strings(rrd) if str(tmp_path) in t or str(repo) in t]


def recording_roots(rrd) -> set:
    """The top entity of every chunk of a recording (read with rerun's own reader)."""
    import warnings
    from rerun.chunk import RrdReader
    roots = set()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for ch in RrdReader(str(rrd)).stream():
            roots.add(str(ch.entity_path).strip("/").split("/")[0])
    return roots


def test_render_recording_needs_no_rerun_in_the_workers(repo, tmp_path, capsys, monkeypatch):
    """The workers hand back plain plans; one recorder process, forked before them with rerun
    imported, writes both revisions into one recording (no half files, no merge)."""
    rerun = pytest.importorskip("rerun")
    import sys
    from urdf_lint.review import run as review
    from urdf_lint.render.recording import Plan
    real = review._start_recorder
    started = []

    def start(render_dir):
        rec = real(render_dir)
        started.append(rec)
        monkeypatch.setitem(sys.modules, "rerun", None)   # any later `import rerun` fails
        return rec
    monkeypatch.setattr(review, "_start_recorder", start)
    plans = []
    from urdf_lint.run import worker
    real_jobs = worker.run_jobs

    def spy(*a, **kw):
        for job, res in real_jobs(*a, **kw):
            plans.append(res.diff_rrd)
            yield job, res
    monkeypatch.setattr(worker, "run_jobs", spy)
    edit(repo / "r2d2_description" / "urdf" / "r2d2.urdf.xacro", '<box size="0.08 0.08 0.08"/>',
         '<box size="0.1 0.08 0.08"/>')
    out = tmp_path / "snap"
    assert main(["diff", "HEAD", "--render", str(out), "--no-cache"]) == 0
    assert "snapshot incomplete" not in capsys.readouterr().err
    assert len(started) == 1 and not started[0].proc.is_alive()
    assert sum(isinstance(p, Plan) for p in plans) == 2      # one per revision
    monkeypatch.setitem(sys.modules, "rerun", rerun)   # this process reads the recording
    rrd = out / f"{R2D2}.rrd"
    assert sorted(p.name for p in out.iterdir()) == [".urdf-lint-snapshots.json"] + sorted(
        f"{R2D2}.{x}" for x in ("before.png", "after.png", "diff.png", "rrd"))
    assert {"base", "head"} <= recording_roots(rrd)


@pytest.fixture()
def expanded(monkeypatch):
    """The entry of every job a worker expands, as the run goes."""
    from urdf_lint.run import worker
    seen: list = []
    real = worker.run_jobs

    def spy(jobs, *a, **kw):
        jobs = list(jobs)
        seen.extend(j.entry for j in jobs)
        return real(jobs, *a, **kw)
    monkeypatch.setattr(worker, "run_jobs", spy)
    # a run that explores lints both its passes on one pool (worker.RunPool)
    real_pool = worker.RunPool.run

    def pool_spy(self, jobs):
        jobs = list(jobs)
        seen.extend(j.entry for j in jobs)
        return real_pool(self, jobs)
    monkeypatch.setattr(worker.RunPool, "run", pool_spy)
    return seen


def test_each_side_expands_a_changed_model_once(repo, capsys, expanded):
    """Without pictures the robot comes back from the lint pass: one expansion per revision
    of the changed model; the unchanged one, which the include graph shows the changed macro
    file cannot reach, is expanded at neither revision yet still counted."""
    seen = expanded
    edit(repo / "r2d2_description" / "urdf" / "r2d2_macros.xacro",
         '<limit effort="100" velocity="10"/>', '<limit effort="120" velocity="10"/>')
    rc, doc = run_json(capsys, "HEAD")
    assert rc == 0 and [m["status"] for m in doc["models"]] == ["changed"]
    r2d2 = [e for e in seen if e.endswith("r2d2.urdf.xacro")]
    pendulum = [e for e in seen if e.endswith("double_pendulum.urdf.xacro")]
    assert len(r2d2) == 2 and len({os.path.dirname(e) for e in r2d2}) == 2   # head, base
    assert pendulum == []
    assert doc["models_total"] == 2


def test_a_generated_pair_is_linted_only_when_the_change_reaches_it(repo, capsys, expanded):
    """A checked-in URDF generated from a xacro (UL011 compares them) is linted, with its
    xacro, only when the change reaches one of them: a change to another robot's macros
    expands neither; hand-editing the generated file lints its xacro, which reports it stale."""
    pend = repo / "double_pendulum_description" / "urdf"
    out = pend / "double_pendulum.urdf"
    out.write_text("<?xml version=\"1.0\"?>\n<!-- autogenerated by xacro from "
                   "urdf/double_pendulum.urdf.xacro -->\n<robot name=\"x\"/>\n")
    assert main(["generate", str(repo)]) == 1 and "<link" in out.read_text()
    git(repo, "add", "-A")
    git(repo, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "generated")
    capsys.readouterr()
    expanded.clear()   # (generate expands in the workers too; what follows is about diff)
    edit(repo / "r2d2_description" / "urdf" / "r2d2_macros.xacro",
         '<limit effort="100" velocity="10"/>', '<limit effort="120" velocity="10"/>')
    rc, doc = run_json(capsys, "HEAD")
    assert rc == 0 and [m["model"] for m in doc["models"]] == [
        "r2d2_description/urdf/r2d2.urdf.xacro"]
    assert not [e for e in expanded if "double_pendulum" in e], expanded
    assert doc["models_total"] == 3

    git(repo, "checkout", "--", ".")
    expanded.clear()
    edit(out, "<robot ", "<!-- by hand -->\n<robot ")
    edit(out, 'type="continuous"', 'type="revolute"')
    rc, doc = run_json(capsys, "HEAD")
    assert rc == 1, doc
    assert {e[len(str(repo)) + 1:] if e.startswith(str(repo)) else os.path.basename(e)
            for e in expanded} >= {"double_pendulum_description/urdf/double_pendulum.urdf.xacro",
                                   "double_pendulum_description/urdf/double_pendulum.urdf"}
    assert not [e for e in expanded if "r2d2" in e], expanded
    by_model = {m["model"]: m for m in doc["models"]}
    xacro = by_model["double_pendulum_description/urdf/double_pendulum.urdf.xacro"]
    assert [f["code"] for f in xacro["findings_introduced"]] == ["UL011"], xacro


def test_a_yaml_change_lints_every_model(repo, capsys, expanded):
    """A change the include graph cannot follow (YAML read by xacro.load_yaml) lints every
    model, and the recorded inputs find the one affected."""
    seen = expanded
    (repo / "r2d2_description" / "config" / "inertial.yaml").write_text("head_mass: 2.5\n")
    rc, doc = run_json(capsys, "HEAD")
    assert rc == 0 and [m["model"] for m in doc["models"]] == [
        "r2d2_description/urdf/r2d2.urdf.xacro"]
    assert any(e.endswith("double_pendulum.urdf.xacro") for e in seen)


def test_base_resolves_packages_it_does_not_lint(tmp_path, capsys, monkeypatch):
    """The changed model includes a file of another package: at the base, that package is
    found as it is at HEAD (no 'unknown package' reported as fixed by the change)."""
    from conftest import make_package
    r = tmp_path / "ws"
    make_package(r, "common_description", {"urdf/colours.xacro": """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>
</robot>
"""})
    make_package(r, "arm_description", {"urdf/arm.urdf.xacro": """<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find common_description)/urdf/colours.xacro"/>
  <link name="base"><visual><geometry><box size="0.1 0.1 0.1"/></geometry>
    <material name="grey"/></visual></link>
  <link name="upper"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
</robot>
"""})
    git(r, "init", "-q")
    git(r, "add", "-A")
    git(r, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "base")
    monkeypatch.chdir(r)
    edit(r / "arm_description" / "urdf" / "arm.urdf.xacro", 'upper="1"', 'upper="1.5"')
    rc, doc = run_json(capsys, "HEAD")
    assert rc == 0
    [m] = doc["models"]
    assert m["status"] == "changed"
    assert m["findings_introduced"] == [] and m["findings_fixed"] == [], m
    assert [c["field"] for c in m["changes"]] == ["limit.upper"]


def test_an_include_only_expansion_resolves_is_followed(tmp_path, capsys, monkeypatch):
    """A model that includes ``${part}.xacro`` cannot be ruled out from the include graph:
    it is linted, and the change to that file is found through its recorded inputs."""
    from conftest import make_package
    r = tmp_path / "ws"
    make_package(r, "bot_description", {
        "urdf/arm_parts.xacro": """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm"><link name="arm"/>
    <joint name="elbow" type="revolute"><parent link="base"/><child link="arm"/>
      <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="5" velocity="1"/></joint>
  </xacro:macro>
</robot>
""",
        "urdf/bot.urdf.xacro": """<?xml version="1.0"?>
<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="part" value="arm_parts"/>
  <xacro:include filename="${part}.xacro"/>
  <link name="base"/>
  <xacro:arm/>
</robot>
""",
        "urdf/other.urdf.xacro": """<?xml version="1.0"?>
<robot name="other"><link name="only"/></robot>
"""})
    git(r, "init", "-q")
    git(r, "add", "-A")
    git(r, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "base")
    edit(r / "bot_description" / "urdf" / "arm_parts.xacro", 'upper="1"', 'upper="2"')
    monkeypatch.chdir(r)
    rc, doc = run_json(capsys, "HEAD")
    assert rc == 0
    assert [(m["model"], m["status"]) for m in doc["models"]] == [
        ("bot_description/urdf/bot.urdf.xacro", "changed")]
    assert doc["models_total"] == 2


def test_markdown_links_the_pictures_diff_render_wrote(repo, tmp_path, capsys):
    """A model linted with xacro args: every image the markdown links is a file that
    `diff --render` wrote (the link and the file name come from the same key)."""
    top = repo / "r2d2_description" / "urdf" / "r2d2.urdf.xacro"
    edit(top, 'xmlns:xacro="http://www.ros.org/wiki/xacro">',
         'xmlns:xacro="http://www.ros.org/wiki/xacro">\n  <xacro:arg name="tint" default="blue"/>')
    (repo / "urdf-lint.toml").write_text(
        '[[models]]\npath = "r2d2_description/urdf/r2d2.urdf.xacro"\nargs = [{tint = "red"}]\n')
    git(repo, "add", "-A")
    git(repo, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "args")
    edit(top, 'origin xyz="0 0 ${bodylen/2}"', 'origin xyz="0 0 ${bodylen/2 + 0.05}"')
    out = tmp_path / "snap"
    assert main(["diff", "HEAD", "--render", str(out), "--no-rrd", "--no-cache", "--format",
                 "markdown", "--image-base-url", "https://example.invalid/run/1"]) == 0
    md = capsys.readouterr().out
    assert "[tint:=red]" in md
    linked = re.findall(r"https://example\.invalid/run/1/([^)]+\.png)", md)
    assert len(linked) == 3, md
    for name in linked:
        assert (out / name).is_file(), (name, sorted(p.name for p in out.iterdir()))


def test_a_diff_render_worker_may_write_nothing(tmp_path, monkeypatch):
    """A diff --render worker sends its picture's geometry and its recording plan back through
    the pipe: the sandbox gives it no write access to the snapshot folder, unlike a render
    worker, which writes its own files. Neither writes the mesh facts store (the parent
    stores the facts workers send back)."""
    import dataclasses
    from urdf_lint.runner import forked
    from urdf_lint.runner import sandbox
    from urdf_lint.core.jobs import LintSettings
    got = []
    monkeypatch.setattr(sandbox, "enter", lambda pid, read, write, keep_fds=(): got.append(
        list(write)) or {})
    cache, snaps = tmp_path / "cache", tmp_path / "snaps"
    conn, other = forked.pipe()
    try:
        for extra in ({"diff_render": True}, {"render_dir": str(snaps)}):
            sandbox.enter_worker(conn, dataclasses.replace(
                LintSettings(resolver={}), mesh_cache_dir=str(cache), **extra))
    finally:
        conn.close()
        other.close()
    diff_worker, render_worker = got
    assert diff_worker == []
    assert render_worker == [str(snaps)]


def test_a_finding_is_introduced_once_per_model(tmp_path, monkeypatch, capsys):
    """A swapped limit in a macro that one model calls twice is one introduced finding of that
    model (it was listed once per joint), and once in the other model that calls it once."""
    from test_grouping import ARM, ONE_ARM, TWO_ARMS
    r = tmp_path / "repo"
    r.mkdir()
    (r / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="3"><name>arms</name><version>0.0.1</version>'
        '<description>x</description><maintainer email="a@b.c">a</maintainer>'
        "<license>MIT</license></package>\n")
    (r / "arm.xacro").write_text(ARM.replace('lower="1" upper="-1"', 'lower="-1" upper="1"'))
    (r / "one.urdf.xacro").write_text(ONE_ARM)
    (r / "two.urdf.xacro").write_text(TWO_ARMS)
    git(r, "init", "-q")
    git(r, "add", "-A")
    git(r, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "base")
    (r / "arm.xacro").write_text(ARM)
    monkeypatch.chdir(r)
    rc, d = run_json(capsys, "HEAD")
    assert rc == 1
    new = {m["model"].split(" ")[0]: [(f["code"], f["message"]) for f in m["findings_introduced"]]
           for m in d["models"]}
    assert new["two.urdf.xacro"] == [
        ("UL302", "joint 'l_joint': lower 1 > upper -1 (swap them?) (and 1 more like it)")], new
    assert new["one.urdf.xacro"] == [("UL302", "joint 'h_joint': lower 1 > upper -1 (swap them?)")]


def test_a_changed_yaml_value_names_its_yaml_line_through_a_sub_dict(repo, capsys):
    """R2D2 reads its gripper limits as ``ext = limits['gripper_extension']`` (a property holding
    a sub-dict): a limit changed in the YAML is shown at the xacro line that uses it, with the
    YAML line it comes from."""
    limits = repo / "r2d2_description" / "config" / "joint_limits.yaml"
    edit(limits, "gripper_extension: {lower: -0.38, upper: 0.0,",
         "gripper_extension: {lower: -0.38, upper: 0.1,")
    rc, d = run_json(capsys, "HEAD")
    (m,) = [m for m in d["models"] if "r2d2" in m["model"]]
    (c,) = [c for c in m["changes"] if c["field"] == "limit.upper"] or [None]
    assert c is not None, m["changes"]
    assert c["value_from"][0].endswith("config/joint_limits.yaml") and c["value_from"][1] == 2, c


def test_a_picture_of_a_limit_change_says_what_it_cannot_show(repo, tmp_path, monkeypatch,
                                                              capsys):
    """Swapped gripper limits move nothing: the difference picture's caption lists the joint's
    limit changes and the new finding instead of 'changed: nothing'."""
    from urdf_lint.render import snapshot
    said = []
    real = snapshot.render_pair

    def spy(*a, **kw):
        info = real(*a, **kw)
        said.append(info["caption"])
        return info
    monkeypatch.setattr(snapshot, "render_pair", spy)
    limits = repo / "r2d2_description" / "config" / "joint_limits.yaml"
    edit(limits, "gripper_extension: {lower: -0.38, upper: 0.0,",
         "gripper_extension: {lower: 0.0, upper: -0.38,")
    rc = main(["diff", "HEAD", "--render", str(tmp_path / "pics"), "--no-rrd", "--no-cache"])
    capsys.readouterr()
    assert rc == 1
    (caption,) = said
    assert caption.startswith("changed: nothing visible; not drawn: joint 'gripper_extension' "
                              "limit.lower, limit.upper"), caption
    assert "1 new finding(s)" in caption, caption


def test_the_markdown_names_the_pictures_of_each_model(repo, tmp_path, capsys):
    """Without --image-base-url (a job summary cannot show an artifact's images) the markdown
    names each model's picture files and what its difference picture says."""
    limits = repo / "r2d2_description" / "config" / "joint_limits.yaml"
    edit(limits, "gripper_extension: {lower: -0.38, upper: 0.0,",
         "gripper_extension: {lower: 0.0, upper: -0.38,")
    out = tmp_path / "review.md"
    main(["diff", "HEAD", "--render", str(tmp_path / "pics"), "--no-rrd", "--no-cache",
          "--format", "markdown", "-o", str(out)])
    capsys.readouterr()
    text = out.read_text()
    assert f"Pictures (in the review's artifact): `{R2D2}.before.png`, `{R2D2}.after.png`, " \
        f"`{R2D2}.diff.png` (changed: nothing visible; not drawn: joint" in text, text


def test_introduced_and_fixed_findings_name_their_line_as_check_does(repo, capsys):
    # the diff said "UL302 r2d2_description/urdf/r2d2.urdf.xacro: joint ..." with no line,
    # where check names file:line:col; now each names its line in the revision that has it
    edit(repo / "r2d2_description" / "config" / "joint_limits.yaml",
         "gripper: {lower: 0.0, upper: 0.548", "gripper: {lower: 0.6, upper: 0.548")
    main(["check", ".", "--format", "json", "--no-cache"])
    [want] = [f for f in json.loads(capsys.readouterr().out)["findings"] if f["code"] == "UL302"]
    _, doc = run_json(capsys, "HEAD")
    [got] = doc["models"][0]["findings_introduced"]
    assert (got["file"], got["line"], got["col"]) == (want["file"], want["line"], want["col"])
    main(["diff", "HEAD", "--no-cache"])
    text = capsys.readouterr().out
    assert f"introduced error: UL302 {want['file']}:{want['line']}:{want['col']}: " in text
    git(repo, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qam", "bad")
    edit(repo / "r2d2_description" / "config" / "joint_limits.yaml", "lower: 0.6", "lower: 0.0")
    _, doc = run_json(capsys, "HEAD")
    [fixed] = doc["models"][0]["findings_fixed"]
    assert (fixed["file"], fixed["line"]) == (want["file"], want["line"])


def test_an_introduced_or_fixed_finding_names_the_yaml_line_of_its_value(tmp_path, monkeypatch,
                                                                         capsys):
    """franka_description: link1's mass made negative in a YAML file only ``gazebo:=true``
    loads (through a property holding ``$(find arm)/config/inertial.yaml``). The introduced
    UL602 names the YAML line its value comes from, as ``check`` does, in text, JSON and
    markdown (the diff said only the xacro line); the fixed one names BASE's line."""
    from test_explore import LAZY_MASS_LINE, lazy_yaml_repo
    pkg = lazy_yaml_repo(tmp_path)
    monkeypatch.chdir(pkg)
    edit(pkg / "config/inertial.yaml", "mass: 2.0", "mass: -2.0")
    rc, d = run_json(capsys, "HEAD")
    assert rc == 1
    where = ["config/inertial.yaml", LAZY_MASS_LINE]
    for m in d["models"]:
        [f] = m["findings_introduced"]
        assert (f["code"], f["file"], f["value_from"][:2]) == ("UL602", "urdf/utils.xacro",
                                                              where), f
    main(["diff", "HEAD", "--no-cache"])
    text = capsys.readouterr().out
    said = f"      value from config/inertial.yaml:{LAZY_MASS_LINE}\n"
    assert text.count("introduced error: UL602 urdf/utils.xacro:") == 2, text
    assert text.count(said) == 2, text
    main(["diff", "HEAD", "--no-cache", "--format", "markdown"])
    md = capsys.readouterr().out
    assert md.count(f"<sub>value from `config/inertial.yaml:{LAZY_MASS_LINE}`</sub>") == 2, md
    # fixed: the value came from BASE's YAML line (the fix moved it one line down)
    git(pkg, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qam", "bad")
    edit(pkg / "config/inertial.yaml", "link1:\n  mass: -2.0", "link1:\n  # kg\n  mass: 2.0")
    _, d = run_json(capsys, "HEAD")
    for m in d["models"]:
        assert m["findings_introduced"] == [], m
        [f] = m["findings_fixed"]
        assert (f["code"], f["value_from"][:2]) == ("UL602", where), f
