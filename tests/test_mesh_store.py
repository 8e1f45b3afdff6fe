"""The user's mesh facts store (issue 34): content-keyed, signed, written by the parent only,
bounded, emptied by ``urdf-lint clean``; and the COLLADA reader that needs no pycollada."""
from __future__ import annotations

import dataclasses
import json
import os

import numpy as np
import pytest

from conftest import CORPUS, make_package, run_cli
from urdf_lint.meshes.resolve import FACTS_VERSION
from urdf_lint.rules._meshes import TETRA_STL, scaled

FACTS = f"v{FACTS_VERSION}"   # the facts' prefix in the store

ROBOT = ('<robot name="r"><link name="a"><visual><geometry>'
         '<mesh filename="package://p/meshes/big.stl"/></geometry></visual></link>'
         '<link name="b"><visual><geometry><mesh filename="package://p/meshes/part.stl"/>'
         '</geometry></visual></link><joint name="j" type="fixed"><parent link="a"/>'
         '<child link="b"/></joint></robot>\n')


@pytest.fixture
def fresh(monkeypatch, tmp_path):
    """Empty per-process mesh memories and a user cache folder of the test's own."""
    from urdf_lint.core import hashing
    from urdf_lint.meshes import resolve as meshes
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    monkeypatch.delenv("URDF_LINT_CACHE_DIR", raising=False)

    def forget():
        for name in ("_memory", "_mass_memory", "_textures", "_scan_memory", "_arrays_memo",
                     "_kept_bytes", "_loaded"):
            monkeypatch.setattr(meshes, name, type(getattr(meshes, name))())
        monkeypatch.setattr(hashing, "_memo", {})
    forget()
    return forget


def _package(tmp_path):
    return make_package(tmp_path / "ws", "p", {"urdf/r.urdf": ROBOT,
                                               "meshes/big.stl": scaled(1000.0),
                                               "meshes/part.stl": TETRA_STL})


def _check(pkg, cache_dir):
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.cache import Cache
    from urdf_lint.run.pipeline import RunRequest, run_check
    cfg = load_config(None)
    found = run_check(RunRequest([str(pkg)], cfg, build_resolver([str(pkg)], cfg),
                                 cache=Cache(str(cache_dir)), in_process=True)).findings
    return sorted((f.code, f.file, f.line, f.message) for f in found)


def _store():
    from urdf_lint.core.signing import derive
    from urdf_lint.meshes.store import KEY_PURPOSE, FactsStore, facts_dir
    from urdf_lint.run.cache import _load_key
    key = _load_key()
    assert key is not None
    return FactsStore(facts_dir(), derive(key, KEY_PURPOSE))


def _name(path, prefix=FACTS):
    from urdf_lint.core.hashing import memo_digest
    got = memo_digest(str(path))
    assert got is not None
    return f"{prefix}-{got[1]}"


def test_a_forged_or_changed_store_entry_changes_no_finding(tmp_path, fresh):
    from urdf_lint.core import signing
    pkg = _package(tmp_path)
    want = _check(pkg, tmp_path / "c0")
    assert any(code == "UL406" for code, *_ in want), want   # the mesh in millimetres
    store = _store()
    big, small = _name(pkg / "meshes/big.stl"), _name(pkg / "meshes/part.stl")
    entry = os.path.join(store.dir, big + ".json")
    assert os.path.isfile(entry), "the parent stored the facts it was sent"
    real = store.get(big)
    assert real is not None and real["bounds"][1][0] > 10
    lie = dict(real, bounds=[[0.0, 0.0, 0.0], [0.01, 0.01, 0.01]])
    blob = json.dumps(lie).encode()
    signed_elsewhere = open(os.path.join(store.dir, small + ".json"), "rb").read()
    poisons = {
        "bytes changed": open(entry, "rb").read().split(b"\n", 1)[0] + b"\n" + blob,
        "signature forged": signing.signed(b"another key" * 4, big + ".json", blob),
        "entry of another digest": signed_elsewhere,
    }
    for n, (what, data) in enumerate(poisons.items(), 1):
        with open(entry, "wb") as f:
            f.write(data)
        fresh()
        assert _check(pkg, tmp_path / f"c{n}") == want, what
        assert store.get(big) == real, f"{what}: measured again and stored again"
    # the same lie signed with the user's key is believed: the runs above did read the store
    with open(entry, "wb") as f:
        f.write(signing.signed(store.secret, big + ".json", blob))
    fresh()
    assert not any(code == "UL406" for code, *_ in _check(pkg, tmp_path / "c9"))


def test_the_editors_lints_store_the_facts_of_meshes_no_buffer_stands_for(tmp_path, fresh):
    """The language server's jobs carry the open buffers: the mesh facts they measure are
    stored (and shared with its other workers) like check's, so a worker started after a
    keystroke stopped the one before finds them (before, none was stored: each such worker
    measured every mesh again). A buffer standing for a mesh is measured under its own
    digest: its facts are never stored as the file's, and the file's facts stay right."""
    import shutil
    from urdf_lint.lsp.state import Workspace
    from urdf_lint.meshes import resolve
    pkg = _package(tmp_path)
    robot = pkg / "urdf" / "r.urdf"
    big, part = pkg / "meshes" / "big.stl", pkg / "meshes" / "part.stl"

    def lint(buffers):
        fresh()
        store = _store()
        shutil.rmtree(store.dir, ignore_errors=True)
        ws = Workspace(str(pkg), in_process=True)
        try:
            ws.buffers.update({str(p): data for p, data in buffers.items()})
            ws.lint()
        finally:
            ws.close()
        return {p.name: store.get(_name(p)) for p in (big, part) if store.get(_name(p))}
    fresh()
    truth = {p.name: resolve.mesh_facts(str(p), store=resolve.MeshStore()) for p in (big, part)}
    edited = ROBOT.replace("</robot>", "<!-- typing -->\n</robot>").encode()
    assert lint({robot: edited}) == truth
    # an unsaved part.stl twice the size: linted as such, and nothing of it stored
    assert lint({robot: edited, part: scaled(2.0).encode()}) == {"big.stl": truth["big.stl"]}
    assert _facts_of(scaled(2.0), tmp_path) != truth["part.stl"]   # (the case means something)


def _facts_of(text, tmp_path):
    from urdf_lint.meshes import resolve
    f = tmp_path / "elsewhere" / "part.stl"
    f.parent.mkdir(exist_ok=True)
    f.write_text(text)
    return resolve.mesh_facts(str(f), store=resolve.MeshStore())


def test_the_parent_stores_only_facts_of_the_content_it_hashed_itself(tmp_path, fresh):
    from urdf_lint.meshes.store import FactsStore
    store = FactsStore(str(tmp_path / "facts"), b"k" * 32)
    mesh = tmp_path / "roots" / "part.stl"
    mesh.parent.mkdir()
    mesh.write_text(TETRA_STL)
    name = _name(mesh)
    digest = name.split("-", 1)[1]
    rec = {"ok": True, "vertices": 3}
    inside = lambda p: p.startswith(str(tmp_path / "roots"))  # noqa: E731
    other = "0" * len(digest)
    assert store.accept([[f"{FACTS}-{other}", str(mesh), other, rec]], inside) == 0  # not its bytes
    assert store.accept([[name, "/etc/hostname", digest, rec]], inside) == 0    # outside
    assert store.accept([[name, str(mesh), digest, "not a record"]], inside) == 0
    assert store.accept([["../x-" + digest, str(mesh), digest, rec]], inside) == 0
    assert store.accept(["garbage", None, [1]], inside) == 0
    assert os.listdir(store.dir) == [] if os.path.isdir(store.dir) else True
    assert store.accept([[name, str(mesh), digest, rec]], inside) == 1
    assert store.get(name) == rec


def test_without_a_store_the_parent_hashes_only_what_another_worker_may_reuse(tmp_path, fresh,
                                                                              monkeypatch):
    """A run without a facts store (``--no-cache``) does not hash a mesh for nothing: a
    worker's measurements are checked (the parent hashes the mesh) only when another worker is
    handed a job of the same package (a stolen job, a model's variant), and then reach it."""
    from urdf_lint.core.jobs import LintJob, LintSettings, ModelReport
    from urdf_lint.meshes import resolve, store
    from urdf_lint.run import worker
    from urdf_lint.runner import pool
    roots = tmp_path / "roots"
    packages = {n: roots / n for n in ("arm", "gripper")}
    for d in packages.values():
        (d / "meshes").mkdir(parents=True)
        (d / "meshes" / "part.stl").write_text(TETRA_STL)
    measured = resolve.MeshStore()
    resolve.mesh_facts(str(packages["arm"] / "meshes" / "part.stl"), store=measured)
    report = ModelReport.failed(LintJob(str(packages["arm"] / "a.urdf")))
    report.mesh_facts = measured.measured
    hashed = []
    real = store._digest_of
    monkeypatch.setattr(store, "_digest_of", lambda p: hashed.append(p) or real(p))
    settings = LintSettings(resolver={"roots": [str(roots)], "scanned": {
        n: str(d) for n, d in packages.items()}})
    p = pool.WorkerPool(settings, worker.LINT, size=2)
    a, b = (object.__new__(pool.Worker) for _ in range(2))
    for w in (a, b):
        w.told = 0
    p.workers = [a, b]
    p._learn(a, LintJob(str(packages["arm"] / "a.urdf")), report)
    assert hashed == [] and p.shared == []
    assert p._with_shared(a, LintJob(str(packages["arm"] / "b.urdf"))).shared == ()
    assert p._with_shared(b, LintJob(str(packages["gripper"] / "g.urdf"))).shared == ()
    assert hashed == []                      # no other worker's job of the arm: nothing hashed
    stolen = p._with_shared(b, LintJob(str(packages["arm"] / "b.urdf")))
    assert [n for n, _ in stolen.shared if not n.startswith("at-")] == [measured.measured[0][0]]
    assert hashed == [measured.measured[0][1]]


def test_facts_one_worker_measured_reach_the_others_under_the_parents_digest(tmp_path, fresh,
                                                                           monkeypatch):
    """Within a run, what one worker measured is handed to the others with their next job
    (``Handler.share`` in the parent, ``LintJob.shared``, ``resolve.remember`` in the worker):
    a stolen job or a model's variant on another worker measures none of its meshes again.
    The parent keeps only facts of content it hashed itself, inside the run's roots, and
    hands none back to the worker that measured them."""
    from urdf_lint.core.jobs import LintJob, LintSettings, ModelReport
    from urdf_lint.meshes import resolve
    from urdf_lint.run import worker
    from urdf_lint.runner import pool
    mesh = tmp_path / "roots" / "part.stl"
    mesh.parent.mkdir()
    mesh.write_text(TETRA_STL)
    measured = resolve.MeshStore()
    facts = resolve.mesh_facts(str(mesh), store=measured)
    assert facts["ok"] and len(measured.measured) == 1        # noted for the parent
    name, path, digest, record = measured.measured[0]
    report = ModelReport.failed(LintJob(str(mesh)))
    other = "0" * len(digest)
    report.mesh_facts = [[name, path, digest, record],
                         [f"{FACTS}-{other}", path, other, dict(record, bounds=None)],   # forged
                         [name, "/etc/hostname", digest, record]]                   # outside
    settings = LintSettings(resolver={"roots": [str(tmp_path / "roots")]})
    shared = worker.share(report, settings)
    # the facts, and the parent's digest of the file at its version (hashing.memo_entry)
    st = os.stat(path)
    at = (f"at-{digest}-{path}", [path, st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns])
    assert shared == [(name, record), at]
    assert worker.share(report, LintSettings(resolver=None)) == []   # no roots: not confined

    # the pool: learnt from worker a's result, handed to b's next job, not back to a (with a
    # facts store, checked as it arrives; without, when b is handed a job)
    job = LintJob(str(tmp_path / "m.urdf"))
    for store in (str(tmp_path / "store"), None):
        p = pool.WorkerPool(dataclasses.replace(settings, mesh_cache_dir=store), worker.LINT,
                            size=2)
        a, b = (object.__new__(pool.Worker) for _ in range(2))
        for w in (a, b):
            w.told = 0
        p.workers = [a, b]
        p._learn(a, job, report)
        assert len(p.shared) == (2 if store else 0)
        assert p._with_shared(a, job).shared == ()
        assert p._with_shared(b, job).shared == ((name, record), at)
        assert p._with_shared(b, job) is job                      # told once

    # the worker that gets them neither measures that mesh nor reads it to hash it
    from urdf_lint.core import hashing
    fresh()
    monkeypatch.setattr(resolve, "_measure", lambda *a: pytest.fail("measured again"))
    real_read = hashing.read_regular
    reads: list[str] = []
    monkeypatch.setattr(hashing, "read_regular", lambda p, *a, **k: reads.append(p) or
                        real_read(p, *a, **k))
    monkeypatch.setattr(hashing, "file_digest", lambda p: reads.append(p) or None)
    bad_keys = [(f"at-{other}-{path}", [path, 1, 2, 3]), (f"at-{other}-x", "x"),
                ("at-garbage-" + path, at[1])]
    resolve.remember(((name, record), at, (f"{FACTS}-" + other, {"ok": True}), ("garbage", 1),
                      *bad_keys))
    assert resolve.mesh_facts(str(mesh), store=resolve.MeshStore()) == record
    assert reads == []
    assert resolve._memory[other] == {"ok": True}   # (a name it never looks up: harmless)
    assert list(hashing._memo.values()) == [digest]  # the malformed digests were not taken
    # the file changed since the parent hashed it (another version): read and hashed here
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns + 1))
    assert resolve.mesh_facts(str(mesh), store=resolve.MeshStore()) == record
    assert reads == [path]


def test_measuring_never_writes_the_store(tmp_path, fresh):
    """A worker only notes what it measured; the store is the parent's to write."""
    from urdf_lint.meshes import resolve as meshes
    from urdf_lint.meshes.store import FactsStore, MeshStore, register
    facts = FactsStore(str(tmp_path / "facts"), b"k" * 32)
    register(facts)
    p = tmp_path / "part.stl"
    p.write_text(TETRA_STL)
    run = MeshStore(cache_dir=facts.dir)
    assert meshes.mesh_facts(str(p), store=run)["vertices"] == 12
    assert meshes.mass_facts(str(p), store=run)["ok"]
    assert not os.path.exists(facts.dir)
    assert sorted(m[0].split("-")[0] for m in run.measured) == [f"mass{meshes.MASS_FACTS_VERSION}", FACTS]
    assert facts.accept(run.measured) == 2
    fresh()
    again = MeshStore(cache_dir=facts.dir)
    assert meshes.mesh_facts(str(p), store=again)["vertices"] == 12
    assert again.measured == []            # read from the store, not measured


def test_the_store_is_bounded_and_evicts_the_oldest(tmp_path):
    from urdf_lint.meshes.store import FactsStore
    store = FactsStore(str(tmp_path / "facts"), b"k" * 32)
    names = [f"{FACTS}-{i:032x}" for i in range(10)]
    for i, name in enumerate(names):
        assert store.put(name, {"ok": True, "pad": "x" * 200})
        os.utime(os.path.join(store.dir, name + ".json"), (1000 + i, 1000 + i))
    size = os.path.getsize(os.path.join(store.dir, names[0] + ".json"))
    store.max_bytes = 4 * size
    assert store.evict() == 6
    kept = sorted(f[:-5] for f in os.listdir(store.dir) if f.endswith(".json"))
    assert kept == names[6:]                       # the four newest
    assert sum(s for _, s, _ in store.entries()) <= store.max_bytes


def test_clean_empties_the_store(tmp_path):
    xdg = tmp_path / "xdg"
    store_dir = xdg / "urdf-lint" / "mesh-facts"
    pkg = _package(tmp_path)
    env = {"XDG_CACHE_HOME": str(xdg), "URDF_LINT_CACHE_DIR": str(tmp_path / "cache")}
    p = run_cli("check", str(pkg), "--fail-on", "never", env=env)
    assert p.returncode == 0, p.stderr
    # the workers measured, the parent stored (facts, mass and texture scans of both meshes)
    assert len(list(store_dir.glob(f"{FACTS}-*.json"))) == 2, list(store_dir.iterdir())
    p = run_cli("clean", str(pkg), env=env)
    assert p.returncode == 0, p.stderr
    assert not store_dir.exists()
    assert str(store_dir) in p.stdout + p.stderr


def test_no_cache_reads_and_writes_no_store(tmp_path):
    xdg = tmp_path / "xdg"
    pkg = _package(tmp_path)
    env = {"XDG_CACHE_HOME": str(xdg), "URDF_LINT_CACHE_DIR": str(tmp_path / "cache")}
    p = run_cli("check", str(pkg), "--no-cache", "--fail-on", "never", env=env)
    assert p.returncode == 0, p.stderr
    assert not (xdg / "urdf-lint" / "mesh-facts").exists()


# -- the COLLADA reader without pycollada ---------------------------------------------------------
def _corpus_meshes(*suffixes):
    return sorted(p for p in CORPUS.rglob("*") if p.suffix.lower() in suffixes)


@pytest.mark.skipif(not (CORPUS / "MANIFEST.md").is_file(), reason="../shared/corpus is not present")
def test_corpus_collada_read_by_lxml_alone_gives_pycolladas_arrays_bit_for_bit():
    from urdf_lint.meshes import readers
    paths = _corpus_meshes(".dae")
    lean = 0
    for p in paths:
        data = p.read_bytes()
        got = readers.collada_arrays_lean(data)
        if got is None:
            continue
        lean += 1
        monkey = readers.collada_arrays_lean
        try:
            readers.collada_arrays_lean = lambda d: None    # the pycollada path
            want = readers.collada_arrays(data)
        finally:
            readers.collada_arrays_lean = monkey
        assert want is not None, p
        assert np.array_equal(got[0], want[0]) and got[0].dtype == want[0].dtype, p
        assert np.array_equal(got[1], want[1]), p
    assert lean >= 0.8 * len(paths), f"only {lean} of {len(paths)} read without pycollada"


@pytest.mark.skipif(not (CORPUS / "MANIFEST.md").is_file(), reason="../shared/corpus is not present")
def test_every_corpus_mesh_has_trimeshs_facts(monkeypatch):
    """Every .stl/.dae/.obj of the real robots: counts, bounds, finiteness and broken
    references equal to trimesh's mesh, volume, moments and bounds within 1e-12."""
    from test_mesh_speed import counted, trimesh_facts
    from urdf_lint.meshes import resolve as meshes
    paths = _corpus_meshes(".stl", ".dae", ".obj")
    assert len(paths) > 200
    for p in paths:
        try:
            want = trimesh_facts(p)
        except Exception:  # noqa: BLE001 - unloadable: then ours must say so
            assert not meshes.mesh_facts(str(p))["ok"], p
            continue
        got = meshes.mesh_facts(str(p))
        assert {k: v for k, v in counted(got, p).items() if k != "bounds"} == \
            {k: v for k, v in counted(want, p).items() if k != "bounds"}, p
        assert (got["bounds"] is None) == (want["bounds"] is None), p
        if want["bounds"] is not None:
            assert np.allclose(got["bounds"], want["bounds"], rtol=1e-12, atol=0), p
        mass = meshes.mass_facts(str(p))
        ref = meshes.trimesh_mass_properties(meshes.load_mesh(str(p)))
        assert mass.keys() == ref.keys() and mass.get("hull") == ref.get("hull"), p
        for k in ("volume", "first", "second", "bounds"):
            if k in ref:
                assert np.allclose(mass[k], ref[k], rtol=1e-9, atol=0), (p, k)


def _pycollada(readers, data):
    lean = readers.collada_arrays_lean
    readers.collada_arrays_lean = lambda d: None
    try:
        return readers.collada_arrays(data)
    finally:
        readers.collada_arrays_lean = lean


def _untextured(data: bytes) -> bytes:
    """The document with its textures replaced by a colour."""
    from lxml import etree
    root = etree.fromstring(data)
    for el in list(root.iter("{*}newparam")):
        el.getparent().remove(el)
    for el in list(root.iter("{*}texture")):
        colour = etree.SubElement(el.getparent(), el.tag.replace("texture", "color"))
        colour.text = "0.5 0.5 0.5 1"
        el.getparent().remove(el)
    return etree.tostring(root)


def test_generated_collada_read_by_lxml_alone_equals_pycollada_or_is_refused(tmp_path):
    """Nested and mirrored nodes, several transforms, polylists of quads and pentagons, with
    textures and without: the same arrays as through pycollada, bit for bit; a broken
    reference: refused (pycollada and trimesh decide, as before)."""
    from test_mesh_speed import _generated_daes
    from urdf_lint.meshes import readers
    daes = _generated_daes(tmp_path)
    read = set()
    for name, p in daes.items():
        data = _untextured(p.read_bytes())
        got = readers.collada_arrays_lean(data)
        if got is None:
            continue
        read.add(name)
        want = _pycollada(readers, data)
        assert want is not None, name
        assert np.array_equal(got[0], want[0]) and np.array_equal(got[1], want[1]), name
    assert {"nested.dae", "metres.dae", "lines.dae"} <= read   # (lines alone: no mesh)
    assert "broken.dae" not in read
    for name in ("nested.dae", "metres.dae"):     # textured as generated: the same arrays
        data = daes[name].read_bytes()
        assert b"<texture " in data
        got, want = readers.collada_arrays_lean(data), _pycollada(readers, data)
        assert got is not None and want is not None
        assert np.array_equal(got[0], want[0]) and np.array_equal(got[1], want[1]), name
    # more transforms on the outer node (a float32 product of five, mirrored)
    rotated = _untextured(daes["nested.dae"].read_bytes()).replace(
        b'<node id="a">', b'<node id="a"><rotate>0.3 0.4 0.866 33</rotate><scale>1 2 -1</scale>'
        b'<translate>0.1 0 0.2</translate>', 1)
    assert rotated.count(b"<rotate>") == 2
    got, want = readers.collada_arrays_lean(rotated), _pycollada(readers, rotated)
    assert got is not None and want is not None
    assert np.array_equal(got[0], want[0]) and np.array_equal(got[1], want[1])
