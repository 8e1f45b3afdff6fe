"""The result cache is invalidated when, and only when, an input changes: the entry, an
included file, a YAML value, a mesh, the config or an arg. A corrupt entry is ignored."""
from __future__ import annotations

import json
import os
import shutil
import time

import pytest

from conftest import DESCRIPTIONS, age, run_cli


@pytest.fixture()
def repo(tmp_path):
    r = tmp_path / "repo"
    shutil.copytree(DESCRIPTIONS / "r2d2_description", r / "r2d2_description")
    return r


def run(repo, *extra):
    p = run_cli("check", ".", "--format", "json", *extra, cwd=repo)
    assert p.returncode in (0, 1), p.stderr
    doc = json.loads(p.stdout)
    return {m["entry"]: m["cached"] for m in doc["models"]}, doc


def cached(repo, *extra):
    state, _ = run(repo, *extra)
    return list(state.values())


ENTRY = "r2d2_description/urdf/r2d2.urdf.xacro"


def edit(path, old, new):
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new))


def test_invalidation(repo):
    pkg = repo / "r2d2_description"
    assert cached(repo) == [False]
    assert cached(repo) == [True]
    assert (repo / ".urdf_lint_cache" / ".gitignore").read_text().strip().endswith("*")
    # an included macro file
    edit(pkg / "urdf/r2d2_macros.xacro", 'mass="0.05"', 'mass="0.06"')
    assert cached(repo) == [False]
    assert cached(repo) == [True]
    # same content, new mtime: still a hit
    os.utime(pkg / "urdf/r2d2_macros.xacro", (time.time() + 5, time.time() + 5))
    assert cached(repo) == [True]
    # a YAML value
    edit(pkg / "config/joint_limits.yaml", "upper: 0.548", "upper: 0.5")
    assert cached(repo) == [False]
    assert cached(repo) == [True]
    # a mesh
    data = (pkg / "meshes/l_finger.stl").read_bytes()
    (pkg / "meshes/l_finger.stl").write_bytes(data[:80] + b"changed header".ljust(0) + data[94:])
    assert cached(repo) == [False]
    assert cached(repo) == [True]
    # a file no model reads: still a hit
    (pkg / "README.md").write_text("notes\n")
    assert cached(repo) == [True]
    # the config
    (repo / "urdf-lint.toml").write_text('ignore = ["UL801"]\n')
    assert cached(repo) == [False]
    assert cached(repo) == [True]
    # an arg (one the entry declares: an undeclared one is a config error)
    entry = repo / ENTRY
    entry.write_text(entry.read_text().replace("<xacro:include", '<xacro:arg name="x" default="0"/>\n  <xacro:include', 1))
    assert cached(repo) == [False]
    assert cached(repo) == [True]
    (repo / "urdf-lint.toml").write_text(f'ignore = ["UL801"]\n[[models]]\npath = "{ENTRY}"\nargs = {{ x = "1" }}\n')
    assert cached(repo) == [False]
    assert cached(repo) == [True]
    # the CLI selection is part of the key
    assert cached(repo, "--select", "UL3") == [False]
    # --no-cache neither reads nor writes
    assert cached(repo, "--no-cache") == [False]


def test_missing_file_that_appears_invalidates(repo):
    pkg = repo / "r2d2_description"
    edit(pkg / "urdf/r2d2_macros.xacro", "meshes/l_finger_tip.stl", "meshes/l_finger_tip2.stl")
    state, doc = run(repo)
    assert [f["code"] for f in doc["findings"]].count("UL401") == 2
    assert run(repo)[0] == {ENTRY: True}
    shutil.copy(pkg / "meshes/l_finger_tip.stl", pkg / "meshes/l_finger_tip2.stl")
    state, doc = run(repo)
    assert state == {ENTRY: False} and not [f for f in doc["findings"] if f["code"] == "UL401"]


def test_corrupt_cache_is_ignored(repo):
    run(repo)
    for d, _, files in os.walk(repo / ".urdf_lint_cache" / "results"):
        for f in files:
            with open(os.path.join(d, f), "w") as fh:
                fh.write('{"version": "0.1.0", "deps": {"/etc/passwd": [[0, 0], "x"]}, "result": 5}')
    state, doc = run(repo)
    assert state == {ENTRY: False}
    for d, _, files in os.walk(repo / ".urdf_lint_cache" / "results"):
        for f in files:
            with open(os.path.join(d, f), "wb") as fh:
                fh.write(b"\x00\xff not json")
    assert run(repo)[0] == {ENTRY: False}


def test_clean(repo):
    run(repo)
    assert (repo / ".urdf_lint_cache").is_dir()
    p = run_cli("clean", ".", cwd=repo)
    assert p.returncode == 0 and not (repo / ".urdf_lint_cache").exists()


def test_folder_read_as_yaml_is_cached_until_a_file_appears(repo):
    """``load_yaml`` of an arg left empty reads the folder (UR's ``ur.xacro`` without its
    params): the failure is cached like a missing file, and re-linted once a file is there."""
    pkg = repo / "r2d2_description"
    edit(pkg / "urdf/r2d2.urdf.xacro", '<xacro:include filename="r2d2_macros.xacro"/>',
         '<xacro:include filename="r2d2_macros.xacro"/>\n'
         '  <xacro:property name="limits" value="${xacro.load_yaml(\'params\')}" lazy_eval="false"/>')
    (pkg / "urdf" / "params").mkdir()
    state, doc = run(repo)
    assert state == {ENTRY: False}
    assert [f["code"] for f in doc["findings"]] == ["UL003"]
    assert run(repo)[0] == {ENTRY: True}            # before: never cached, re-expanded each run
    (pkg / "urdf" / "params").rmdir()
    (pkg / "urdf" / "params").write_text("a: 1\n")
    state, doc = run(repo)
    assert state == {ENTRY: False} and not [f for f in doc["findings"] if f["code"] == "UL003"]


def test_suppressions_hold_on_warm_runs(repo):
    """The worker records which sources hold urdf-lint comments; a warm run reads only those,
    and suppresses (and reports unused comments) exactly like the cold run."""
    pkg = repo / "r2d2_description"
    macros = pkg / "urdf/r2d2_macros.xacro"
    edit(macros, 'mass="0.05"', 'mass="-0.05"')
    _, doc = run(repo, "--no-cache")
    codes = [f["code"] for f in doc["findings"] if f["file"].endswith("r2d2_macros.xacro")]
    assert codes, "a negative mass in the macro file gives findings to suppress"
    edit(macros, "<robot", "<!-- urdf-lint: disable-file UL6 -->\n<!-- urdf-lint: disable UL999 -->\n<robot")
    cold_state, cold = run(repo)
    warm_state, warm = run(repo)
    assert cold_state == {ENTRY: False} and warm_state == {ENTRY: True}
    assert cold["findings"] == warm["findings"]
    left = [f for f in warm["findings"] if f["file"].endswith("r2d2_macros.xacro")]
    assert [f["code"] for f in left] == ["UL010"]   # UL999 is not a code; the rest suppressed


def test_a_limit_is_never_cached_and_the_cache_folder_is_still_marked(tmp_path):
    """A time-limit result depends on the machine and lists no includes (the loop may sit in
    one): every run tries again. The folder the workers created is marked for git anyway."""
    from conftest import make_package
    repo = tmp_path / "repo"
    make_package(repo, "p", {"urdf/r.urdf.xacro":
                             '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                             '<link name="${python.sum(python.range(10**13))}"/></robot>\n'})
    for _ in range(2):
        p = run_cli("check", ".", "--format", "json", "--timeout", "1", cwd=repo)
        doc = json.loads(p.stdout)
        assert [f["code"] for f in doc["findings"]] == ["UL904"], doc["findings"]
        assert [m["cached"] for m in doc["models"]] == [False]
    assert (repo / ".urdf_lint_cache" / ".gitignore").is_file()
    assert (repo / ".urdf_lint_cache" / "CACHEDIR.TAG").is_file()


def test_the_values_of_allowed_environment_variables_key_the_cache(repo):
    """`$(optenv VARIANT)` changes the robot: a run with another value is not served the old
    result."""
    entry = repo / ENTRY
    entry.write_text(entry.read_text().replace(
        "<xacro:include", '<link name="variant_$(optenv VARIANT none)"/>\n  <xacro:include', 1))
    for value, hit in (("a", False), ("a", True), ("b", False), ("a", True)):
        p = run_cli("check", ".", "--format", "json", "--env-allow", "VARIANT", cwd=repo,
                    env={"VARIANT": value})
        assert p.returncode in (0, 1), p.stderr
        assert [m["cached"] for m in json.loads(p.stdout)["models"]] == [hit], value


# -- the run memo (urdf_lint/run/runcache.py): a whole unchanged run reused, every change seen ------
def _reused(repo, *extra):
    p = run_cli("check", ".", "--format", "json", "-v", *extra, cwd=repo)
    assert p.returncode in (0, 1), p.stderr
    return "nothing changed since the last identical run" in p.stderr, json.loads(p.stdout)


def _settle(repo, *extra):
    """Age the tree, run once (the memo is written), and check the next run reuses it."""
    age(repo)
    run(repo, *extra)
    reused, doc = _reused(repo, *extra)
    assert reused, "an unchanged run should reuse the last result"
    return doc


def _codes(doc, code):
    return sorted((f["file"], f["line"]) for f in doc["findings"] if f["code"] == code)


def test_run_memo_reuses_an_unchanged_run_and_sees_every_change(repo):
    pkg = repo / "r2d2_description"
    run(repo)                                   # creates the cache folder
    before = _settle(repo)
    _, fresh = run(repo, "--no-cache")
    assert before["findings"] == fresh["findings"] and before["summary"] == fresh["summary"]
    assert len(list((repo / ".urdf_lint_cache" / "runs").glob("*.json"))) == 1

    # an included file's content
    edit(pkg / "urdf/r2d2_macros.xacro", 'mass="0.05"', 'mass="-0.05"')
    reused, doc = _reused(repo)
    assert not reused and doc["findings"] != before["findings"]
    assert doc["findings"] == run(repo, "--no-cache")[1]["findings"]

    # a new model in a folder discovery walks
    _settle(repo)
    (pkg / "urdf" / "extra.urdf").write_text(
        '<robot name="extra"><link name="a"/><link name="b"/></robot>\n')
    reused, doc = _reused(repo)
    assert not reused and any(m["entry"].endswith("extra.urdf") for m in doc["models"])

    # a mesh deleted
    _settle(repo)
    assert not _codes(run(repo)[1], "UL401")
    (pkg / "meshes" / "l_finger_tip.stl").unlink()
    reused, doc = _reused(repo)
    assert not reused and _codes(doc, "UL401")

    # a file a model looked for, and did not find, appears
    (pkg / "urdf" / "wants.urdf.xacro").write_text(
        '<robot name="w" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="later.xacro"/>\n  <link name="a"/>\n</robot>\n')
    doc = _settle(repo)
    assert [f for f in doc["findings"] if f["code"] == "UL003" and "wants" in f["file"]]
    (pkg / "urdf" / "later.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>\n')
    age(pkg / "urdf" / "later.xacro")            # even with an old time stamp
    reused, doc = _reused(repo)
    assert not reused
    assert not [f for f in doc["findings"] if f["code"] == "UL003" and "wants" in f["file"]]

    # the configuration (and the command line) are part of what a memo is for
    _settle(repo)
    (repo / "pyproject.toml").write_text('[tool.urdf-lint]\nignore = ["UL401"]\n')
    age(repo / "pyproject.toml")
    reused, doc = _reused(repo)
    assert not reused and not _codes(doc, "UL401")
    reused, doc = _reused(repo, "--select", "UL1")
    assert not reused and {f["code"][:3] for f in doc["findings"]} <= {"UL1", "UL0"}


def test_run_memo_is_not_written_for_inputs_edited_just_now(repo):
    run(repo)
    run(repo)          # every file is seconds old: no memo
    assert not (repo / ".urdf_lint_cache" / "runs").exists() or \
        not list((repo / ".urdf_lint_cache" / "runs").glob("*.json"))
    assert not _reused(repo)[0]


def test_run_memo_is_not_written_when_a_folder_changes_during_the_run(repo, monkeypatch):
    """A model file added to a listed folder while the run goes on (a long run: it began
    10 s ago, the file came 5 s ago) was not linted: the run is not remembered, and the next
    one lints the new model."""
    import io
    from contextlib import redirect_stdout
    from urdf_lint.cli import main as cli
    from urdf_lint.run import runcache
    run(repo)          # (the cache folder exists: the repository's folder is settled)
    age(repo)
    late = repo / "r2d2_description" / "urdf" / "late.urdf"
    real_init, real_store = runcache.RunMemo.__init__, runcache.RunMemo.store

    def init(self, *a, **k):
        real_init(self, *a, **k)
        self.started = time.time_ns() - 10 * 10 ** 9

    def store(self, out, results, folders):
        late.write_text('<robot name="late"><link name="a"/></robot>\n')
        t = time.time() - 5
        os.utime(late, (t, t))
        os.utime(late.parent, (t, t))
        real_store(self, out, results, folders)
    monkeypatch.setattr(runcache.RunMemo, "__init__", init)
    monkeypatch.setattr(runcache.RunMemo, "store", store)
    monkeypatch.chdir(repo)
    with redirect_stdout(io.StringIO()) as out:
        assert cli.main(["check", ".", "--format", "json"]) in (0, 1)
    assert not any("late.urdf" in m["entry"] for m in json.loads(out.getvalue())["models"])
    monkeypatch.undo()
    reused, doc = _reused(repo)
    assert not reused and any(m["entry"].endswith("late.urdf") for m in doc["models"])


def test_forged_run_memo_is_ignored(repo):
    pkg = repo / "r2d2_description"
    run(repo)
    _settle(repo)
    edit(pkg / "urdf/r2d2_macros.xacro", 'mass="0.05"', 'mass="-0.05"')
    _settle(repo)
    [memo] = (repo / ".urdf_lint_cache" / "runs").glob("*.json")
    mac, head, body = memo.read_text().split("\n")
    rec = json.loads(body)
    assert rec["findings"]
    rec["findings"] = []
    memo.write_text(mac + "\n" + head + "\n" + json.dumps(rec))
    reused, doc = _reused(repo)
    assert not reused and doc["findings"]


def test_a_file_has_one_digest_whichever_way_it_is_read(tmp_path, monkeypatch):
    """Sources are hashed with BLAKE2b, files from 1 MiB on (meshes) with BLAKE3: the choice
    follows the content's length, so the worker's read-once hash of a mesh, the parent's
    streamed hash and a reader's hash of the same bytes agree."""
    import hashlib
    try:
        from blake3 import blake3
    except ImportError:   # (a machine without its wheel: SHA-256)
        blake3 = hashlib.sha256
    from urdf_lint.core import hashing
    monkeypatch.setattr(hashing, "_memo", {})
    small = tmp_path / "a.xacro"
    small.write_bytes(b"<robot/>" * 1000)
    big = tmp_path / "b.stl"
    big.write_bytes(os.urandom(hashing.LARGE_FROM_BYTES + 5))
    for p, algo in ((small, hashlib.blake2b(digest_size=16)), (big, blake3())):
        data = p.read_bytes()
        algo.update(data)
        want = algo.hexdigest()[:32]
        assert hashing.file_digest(str(p)) == hashing.content_digest(data) == want
        assert hashing.read_recorded(str(p))[1][1] == want
        hashing._memo.clear()
        assert hashing.memo_read(str(p), 1 << 30) == (want, data)
        assert hashing.memo_digest(str(p))[1] == want


@pytest.mark.parametrize("delta", [-1, 1, -(1 << 20)])
def test_a_file_that_changes_size_while_hashed_has_no_digest(tmp_path, monkeypatch, delta):
    """The streamed hash reads at most one byte more than the size the file had when opened:
    a file that grew or shrank meanwhile (here: its size said smaller or larger than its
    content) has no digest, rather than the digest of bytes it no longer holds."""
    import contextlib
    from urdf_lint.core import fsbound, hashing
    p = tmp_path / "m.stl"
    p.write_bytes(os.urandom((3 << 20) + 7))
    real = fsbound.open_regular

    @contextlib.contextmanager
    def resized(path, *a, **k):
        with real(path, *a, **k) as (f, st):
            fields = list(st)
            fields[6] = st.st_size + delta          # st_size
            yield f, os.stat_result(fields)
    assert hashing.file_digest(str(p)) is not None
    monkeypatch.setattr(fsbound, "open_regular", resized)
    assert hashing.file_digest(str(p)) is None


def test_a_result_the_cache_refuses_is_not_remembered_by_the_run_memo(tmp_path):
    """A worker that reports reading a file outside the package roots: the cache stores
    nothing, and says so on the result, so the run memo does not keep the run either."""
    import types
    from urdf_lint.run.cache import Cache
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.core.jobs import LintJob, ModelReport
    from urdf_lint.run.pipeline import settings_for
    from urdf_lint.run.runcache import RunMemo
    repo = tmp_path / "repo"
    entry = repo / "p" / "urdf" / "r.urdf"
    entry.parent.mkdir(parents=True)
    entry.write_text('<robot name="r"><link name="a"/></robot>\n')
    (repo / "p" / "package.xml").write_text("<package><name>p</name></package>\n")
    outside = tmp_path / "secret.txt"
    outside.write_text("x")
    t = time.time() - 60
    for f in (entry, outside, entry.parent, repo):
        os.utime(f, (t, t))
    cfg = load_config(None)
    resolver = build_resolver([str(repo)], cfg)
    settings = settings_for(cfg, resolver, None)
    cache = Cache(str(tmp_path / "cache"))
    job = LintJob(str(entry), kind="urdf")
    memo = RunMemo(cache, [str(repo)], cfg, resolver, settings)
    memo.started = time.time_ns()
    good = ModelReport(str(entry), {}, deps=[str(entry)])
    cache.put(job, settings, good)
    assert good.cacheable and str(entry) in good.digests
    bad = ModelReport(str(entry), {}, deps=[str(entry), str(outside)])
    cache.put(job, settings, bad)
    assert not bad.cacheable
    empty = types.SimpleNamespace(internal=[], models=[], skipped=[], findings=[], fragments={},
                                  generated={})
    memo.store(empty, [good, bad], [])
    assert not os.path.exists(memo.path)
    memo.store(empty, [good], [])              # (the same run without it is remembered)
    assert os.path.exists(memo.path)


def test_a_signed_entry_copied_under_another_key_is_refused(tmp_path):
    """The signature covers the entry's key (its file name): the memo of another command line
    (an --ignore of everything, say) copied over this one's is not read."""
    from urdf_lint.run.cache import Cache
    cache = Cache(str(tmp_path / "cache"))
    here, there = (os.path.join(cache.dir, "runs", f"{k * 40}.json") for k in "ab")
    assert cache.write_signed(here, b'{"findings": []}')
    assert cache.read_signed(here) == b'{"findings": []}'
    os.makedirs(os.path.dirname(there), exist_ok=True)
    shutil.copy(here, there)
    assert cache.read_signed(there) is None


def test_the_wheels_record_is_read_as_importlib_metadata_reads_it(tmp_path):
    """``build_id`` keys the caches on the hashes pip's RECORD gives the installed modules; it
    reads the RECORD itself (importing importlib.metadata cost ~11 ms of every run): the same
    paths, hashes and sizes, a quoted path with a comma and lines without a hash included."""
    from importlib import metadata
    from urdf_lint import __version__
    from urdf_lint.run import cache
    info = tmp_path / f"urdf_lint-{__version__}.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: urdf-lint\nVersion: {__version__}\n")
    (info / "RECORD").write_text(
        "urdf_lint/__init__.py,sha256=AAAAabcd_-x,120\n"
        '"urdf_lint/odd,name.py",sha256=BBBB,7\n'
        "urdf_lint/data.json,sha256=CCCC,9\n"
        f"urdf_lint-{__version__}.dist-info/RECORD,,\n"
        "urdf_lint/__pycache__/x.cpython-311.pyc,,\n")
    (tmp_path / "urdf_lint").mkdir()   # (Python >= 3.12 lists only the files that exist)
    for name in ("__init__.py", "odd,name.py", "data.json"):
        (tmp_path / "urdf_lint" / name).write_text("")
    dist = metadata.Distribution.at(info)
    want = {os.path.realpath(str(f.locate())): (f.hash.value, f.size) for f in dist.files or []
            if f.hash is not None and f.size is not None and str(f).endswith(".py")}
    assert len(want) == 2
    assert cache._recorded(str(tmp_path)) == want
    assert cache._recorded(str(tmp_path / "nowhere")) == {}


def test_a_result_cached_by_other_code_is_not_reused(tmp_path, monkeypatch):
    """The caches are keyed by the code that made a result, not only by the version number: an
    install from a newer commit (still 0.1.0) or an edited rule must not show the old findings
    (``run.cache.build_id``: the version and a digest of every module's size and mtime)."""
    import urdf_lint.rules as rules
    from urdf_lint.run import cache
    cache.build_id.cache_clear()
    before = cache.build_id()
    cache.build_id.cache_clear()
    assert cache.build_id() == before                 # stable while the code is
    extra = tmp_path / "more_rules"
    extra.mkdir()
    (extra / "ul999_new.py").write_text("CODE = 'UL999'\n")
    monkeypatch.setattr(rules, "__path__", [*rules.__path__, str(extra)])
    cache.build_id.cache_clear()
    edited = cache.build_id()
    assert edited != before and edited.startswith(before.split("+")[0] + "+")
    os.utime(extra / "ul999_new.py", ns=(1, 1))       # the same file, changed again
    cache.build_id.cache_clear()
    assert cache.build_id() not in (before, edited)
    cache.build_id.cache_clear()


def test_a_relinted_model_is_planned_at_the_seconds_it_took_when_last_linted(repo, monkeypatch):
    """Each cached result keeps what linting the model took in its worker. When an input
    changes, the result is not reused, but its seconds plan the run's workers in place of the
    first-time estimate (``runner.pool.package_blocks``: a UR macro's nine models take ~0.6 s
    where the estimate said 0.1 s, and got one worker)."""
    from conftest import run_main
    from urdf_lint.core.jobs import job_key
    from urdf_lint.run.cache import Cache
    from urdf_lint.runner import pool
    stored: dict = {}
    real_put = Cache.put

    def put(self, job, settings, result):
        stored[job_key(job)] = round(result.seconds, 4)
        return real_put(self, job, settings, result)
    monkeypatch.setattr(Cache, "put", put)
    planned: list = []
    real = pool.start_pool

    def spy(jobs, settings, handler, jobs_n, costs=None):
        planned.append({job_key(j): (costs or {}).get(job_key(j)) for j in jobs})
        return real(jobs, settings, handler, jobs_n, costs)
    monkeypatch.setattr(pool, "start_pool", spy)

    def check(*extra):
        p = run_main("check", ".", "--format", "json", *extra, cwd=repo)
        assert p.returncode in (0, 1), p.stderr
        return [m["cached"] for m in json.loads(p.stdout)["models"]]
    assert check() == [False]
    entry = (str((repo / ENTRY).resolve()), ())
    took = stored[entry]
    # (the default pass lints the entry and the candidates that turn out to be fragments)
    assert 0 < took < 60 and entry in planned[0]
    assert set(planned[0].values()) == {None}        # nothing recorded yet: estimated
    first, planned[:] = dict(stored), []
    edit(repo / "r2d2_description/urdf/r2d2_macros.xacro", 'mass="0.05"', 'mass="0.06"')
    assert check() == [False]
    assert planned[0][entry] == took      # the default pass: the entry, at what it took
    # every pass is planned at the seconds its models took when last linted
    assert all(c == first[k] for p in planned for k, c in p.items())
    assert stored[entry] > 0
    # a run without the exploration pass (its own pool, not the run's RunPool) alike
    second, planned[:] = dict(stored), []
    edit(repo / "r2d2_description/urdf/r2d2_macros.xacro", 'mass="0.06"', 'mass="0.065"')
    assert check("--explore", "false") == [False]
    assert planned[0][entry] == second[entry]
    edit(repo / "r2d2_description/urdf/r2d2_macros.xacro", 'mass="0.065"', 'mass="0.06"')
    # --no-cache reads no record: the estimates plan the run
    planned.clear()
    edit(repo / "r2d2_description/urdf/r2d2_macros.xacro", 'mass="0.06"', 'mass="0.07"')
    check("--no-cache")
    assert entry in planned[0] and set(planned[0].values()) == {None}


@pytest.mark.parametrize("took", [-1, 0, 1e9, float("inf"), float("nan"), "0.5", None, True,
                                  [0.5]])
def test_a_recorded_cost_that_is_no_number_of_seconds_is_not_believed(tmp_path, took):
    """Neither read from a record nor stored from a worker's report (a worker's message is
    plain data of any shape: a compromised one must not break the run's end)."""
    from urdf_lint.core.jobs import LintJob, LintSettings, ModelReport, job_key
    from urdf_lint.run.cache import Cache
    cache = Cache(str(tmp_path / "cache"))
    (tmp_path / "a.urdf").write_text('<robot name="a"><link name="l"/></robot>\n')
    job, settings = LintJob(str(tmp_path / "a.urdf")), LintSettings(resolver={})
    cache._cost_of(job, {"took": took})
    cache._cost_of(job, ["took", 0.5])
    assert cache.costs == {}
    cache._cost_of(job, {"took": 0.25})
    assert cache.costs == {job_key(job): 0.25}

    def stored(value):
        report = ModelReport(job.entry, {}, deps=[job.entry])
        report.seconds = value
        cache.put(job, settings, report)
        blob = cache.read_signed(cache._path(cache._key(job, settings)))
        assert blob is not None
        return json.loads(blob).get("took")
    assert stored(took) is None
    assert stored(0.123456) == 0.1235
