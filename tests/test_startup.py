"""The worker plumbing without multiprocessing (urdf_lint.runner.forked), modules loaded on first use
(urdf_lint.core.lazy), and the console script's quick exit."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time

import pytest

from conftest import DESCRIPTIONS, REPO, carried, carried_data

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="needs os.fork")

LINT = [sys.executable, "-m", "urdf_lint"]


def _echo(conn):
    while True:
        msg = conn.recv()
        if msg is None:
            return
        conn.send(msg)


def _die(conn, how):
    conn.recv()
    if how == "kill":
        os.kill(os.getpid(), signal.SIGKILL)
    if how == "exit3":
        sys.exit(3)
    raise RuntimeError("a worker crash")


def _fds(conn):
    conn.recv()
    open_fds = []
    for fd in range(256):
        try:
            os.fstat(fd)
        except OSError:
            continue
        open_fds.append(fd)
    conn.send(open_fds)


def test_messages_of_any_size_round_trip():
    conn, proc = forked_start(_echo)
    try:
        big = {"blob": os.urandom(3 << 20), "nested": [list(range(1000))] * 3}  # > pipe buffer
        for msg in ("small", big, ("tuple", None, 1.5)):
            conn.send(msg)
            assert forked_wait([conn], 10) == [conn]
            assert conn.recv() == msg
        conn.send(None)
        proc.join(5)
        assert proc.exitcode == 0 and not proc.is_alive()
    finally:
        proc.kill()
        conn.close()


@pytest.mark.parametrize("how,code", [("kill", -signal.SIGKILL), ("exit3", 3), ("raise", 1)])
def test_a_dead_child_reads_as_end_of_file_with_its_exit_code(how, code, capfd):
    conn, proc = forked_start(_die, how)
    try:
        conn.send("go")
        assert forked_wait([conn], 10) == [conn]
        with pytest.raises(EOFError):
            conn.recv()
        proc.join(5)
        assert proc.exitcode == code
        assert proc not in forked_active()
    finally:
        conn.close()
    if how == "raise":
        assert "RuntimeError: a worker crash" in capfd.readouterr().err


def test_join_with_a_timeout_returns_and_kill_ends_the_child():
    conn, proc = forked_start(_echo)
    try:
        t0 = time.monotonic()
        proc.join(0.2)
        assert 0.15 < time.monotonic() - t0 < 2 and proc.is_alive()
        assert proc in forked_active()
        assert forked_wait([conn], 0.05) == []   # nothing to read yet
        proc.kill()
        proc.join(5)
        assert proc.exitcode == -signal.SIGKILL
    finally:
        conn.close()


def _end_later(conn):
    conn.recv()
    time.sleep(0.1)


def test_join_wakes_when_the_child_ends_without_polling(monkeypatch):
    """``join`` waits on the child's pidfd: it returns when the child ends, not at the next
    of a series of growing sleeps (each ~10 ms late on average at the end of every run)."""
    from urdf_lint.runner import forked
    if not hasattr(os, "pidfd_open"):
        pytest.skip("no pidfd on this system")
    conn, proc = forked_start(_end_later)
    slept = []
    monkeypatch.setattr(forked.time, "sleep", lambda s: slept.append(s))
    try:
        conn.send("go")
        proc.join(5)
        assert proc.exitcode == 0 and slept == []
        assert proc not in forked_active()
    finally:
        conn.close()


def test_a_released_pool_s_workers_end_before_it_is_closed(monkeypatch):
    """After the run's last pass the workers are told there is no further job: they exit
    while the parent finishes the run, and closing the pool only reaps them."""
    from urdf_lint.runner import forked
    from urdf_lint.run import worker
    from urdf_lint.core.jobs import LintJob, LintSettings
    from urdf_lint.discovery.packages import PackageResolver
    monkeypatch.setattr(worker, "process_job", lambda job, settings: carried(job, job.entry))
    resolver = PackageResolver.build([str(DESCRIPTIONS)], extra_roots=[str(DESCRIPTIONS)])
    runs = worker.RunPool(LintSettings(resolver=resolver.to_dict(), timeout=30), 2)
    jobs = [LintJob(f"m{i}.urdf", kind="urdf") for i in range(4)]
    try:
        assert sorted(carried_data(r) for _, r in runs.run(jobs)) == [j.entry for j in jobs]
        assert runs.pool is not None
        procs = [w.proc for w in runs.pool.workers]
        assert len(procs) == 2 and all(p.is_alive() for p in procs)
        runs.release()
        if hasattr(os, "pidfd_open"):   # (ended, not reaped yet: closing the pool reaps them)
            assert all(forked._ended_within(p.pid, 5) for p in procs)
    finally:
        runs.close()
    assert not any(p in forked_active() for p in procs)
    assert all(p.exitcode == 0 for p in procs)


_CYCLE: list = []


def _cycle_then_look(job, settings):
    """A job that leaves a reference cycle behind (``a_young``: then allocates 30,000 objects
    it keeps, past Python's young-collection thresholds; ``a_old``: outlives three million
    allocations of garbage cycles, whose collections move it to the oldest generation, then
    drops it), or one that looks whether the cycle is still there (``b_look``)."""
    import weakref

    class Node:
        other = None
    if job.entry.startswith("b_look"):
        return carried(job, [0, _CYCLE[0]() is not None])
    a, b = Node(), Node()
    a.other, b.other = b, a        # garbage only the cycle collector frees
    _CYCLE[:] = [weakref.ref(a)]
    kept: list = []
    if job.entry.startswith("a_young"):
        del a, b
        kept = [[] for _ in range(30_000)]
    else:
        for _ in range(3_000_000):      # the count only grows: collections run
            x: list = []
            x.append(x)
        del a, b, x
    return carried(job, [len(kept), _CYCLE[0]() is not None])


def _first_then_look(monkeypatch, first: str) -> list:
    """What a job ``first`` and then a ``look`` job report, in order, on one real worker."""
    from urdf_lint.core.jobs import LintJob, LintSettings
    from urdf_lint.run import worker
    monkeypatch.setattr(worker, "process_job", _cycle_then_look)
    runs = worker.RunPool(LintSettings(resolver=None, timeout=60), 1)
    try:   # (one block of jobs outside any package: run in the order of their names)
        return [carried_data(r) for _, r in runs.run([LintJob(first, kind="urdf"),
                                                      LintJob("b_look.urdf", kind="urdf")])]
    finally:
        runs.close()


def test_a_worker_collects_a_job_s_garbage_after_the_job_not_during_it(monkeypatch):
    """The collector walks every object still alive; within a job those are mostly the job's
    own trees, walked again and again for nothing. A worker collects after each job (its
    cycles do not pile up from job to job) and, within a job, only past
    ``WORKER_GC_THRESHOLD`` allocations."""
    assert _first_then_look(monkeypatch, "a_young.urdf") == [[30_000, True], [0, False]]


def test_a_big_job_s_garbage_is_gone_before_the_next_job(monkeypatch):
    """A job that allocates past ``WORKER_GC_THRESHOLD`` is collected during it, and what those
    collections moved to the oldest generation and then died is freed after it: the next job
    starts without it (its memory limit counts what the worker holds)."""
    assert _first_then_look(monkeypatch, "a_old.urdf") == [[0, True], [0, False]]


def _return():
    return None


def test_a_one_shot_command_s_parent_keeps_what_it_froze_at_the_fork(monkeypatch, capsys):
    """A command that ends with its run (check, hook, diff...) keeps the objects it had when
    it forked its workers frozen: its last full collection walks only what the run made
    since. The servers, which live on, collect them again."""
    import gc
    import urdf_lint.runner as runner
    from urdf_lint.cli import main
    from urdf_lint.runner import forked
    for command, one_shot in (("check", True), ("hook", True), ("server", False),
                              ("mcp", False), ("preview", False)):
        monkeypatch.setattr(runner, "ONE_SHOT", False)
        assert main._main([command, "--help"]) == 0
        assert runner.ONE_SHOT is one_shot, command
    capsys.readouterr()
    try:
        for one_shot in (True, False):
            monkeypatch.setattr(runner, "ONE_SHOT", one_shot)
            gc.unfreeze()
            p = forked.Process(_return)
            p.start()
            assert p.join(10) is None and p.exitcode == 0
            assert (gc.get_freeze_count() > 0) is one_shot
    finally:
        gc.unfreeze()


def _pipe_ends(conn):
    conn.recv()
    import fcntl
    ends = []
    for fd in range(256):
        try:
            ino = os.fstat(fd).st_ino
            ends.append((ino, fcntl.fcntl(fd, fcntl.F_GETFL) & os.O_ACCMODE))
        except OSError:
            continue
    conn.send(ends)


def _ends_of(conn):
    import fcntl
    return {(os.fstat(fd).st_ino, fcntl.fcntl(fd, fcntl.F_GETFL) & os.O_ACCMODE)
            for fd in conn.fds}


def test_a_child_does_not_hold_the_parents_ends_of_its_channel():
    """The child's copies of the parent's ends are closed at the fork: otherwise the child
    would never see end of file when the parent goes, and could read its own results."""
    conn, proc = forked_start(_pipe_ends)
    try:
        conn.send("go")
        child_ends = set(conn.recv())
        assert not (_ends_of(conn) & child_ends), (_ends_of(conn), child_ends)
    finally:
        proc.kill()
        proc.join(5)
        conn.close()


def test_sandboxed_workers_keep_no_descriptor_of_a_sibling(monkeypatch):
    from urdf_lint.run import worker
    from urdf_lint.core.jobs import LintJob, LintSettings
    from urdf_lint.discovery.packages import PackageResolver

    def probe(job, settings):
        return carried(job, [fd for fd in range(256) if _is_open(fd)])
    monkeypatch.setattr(worker, "process_job", probe)
    resolver = PackageResolver.build([str(DESCRIPTIONS)], extra_roots=[str(DESCRIPTIONS)])
    jobs = [LintJob(f"m{i}.urdf", kind="urdf") for i in range(4)]
    results = [carried_data(r) for _, r in worker.run_jobs(
        jobs, LintSettings(resolver=resolver.to_dict(), timeout=30), jobs_n=2)]
    assert len(results) == 4
    for fds in results:
        # stdin, stdout, stderr and the worker's own two pipe ends: nothing of its sibling
        assert len(fds) == 5 and fds[:3] == [0, 1, 2], fds


def _is_open(fd):
    try:
        os.fstat(fd)
        return True
    except OSError:
        return False


def forked_start(target, *args):
    from urdf_lint.runner import forked
    return forked.start(target, args)


def forked_wait(conns, timeout):
    from urdf_lint.runner import forked
    return forked.wait(conns, timeout)


def forked_active():
    from urdf_lint.runner import forked
    return forked.active_children()


# -- urdf_lint.core.lazy ---------------------------------------------------------------------------
LAZY = """
import sys
from urdf_lint.core import lazy
lazy.enable()
lazy.defer("json")
import json                                    # binds the placeholder, loads nothing
placeholder = json
print(type(sys.modules["json"]).__name__, "json.decoder" in sys.modules)
print(json.dumps({"a": 1}), "json.decoder" in sys.modules)   # first use loads it
import json as again
print(again.loads("[2]"), placeholder.JSONDecodeError is again.JSONDecodeError)
lazy.defer("no_such_module_anywhere")
print("no_such_module_anywhere" in sys.modules)
lazy.defer("zipfile")                          # a dunder attribute loads it too (as PyYAML's
import zipfile                                 # __with_libyaml__ must)
print(getattr(zipfile, "__all__", None) is not None, type(sys.modules["zipfile"]).__name__)
"""


def test_a_deferred_module_loads_on_first_use_and_is_the_same_module():
    p = subprocess.run([sys.executable, "-c", LAZY], capture_output=True, text=True, cwd=REPO)
    assert p.returncode == 0, p.stderr
    assert p.stdout.split("\n")[:5] == ["_Deferred False", '{"a": 1} True', "[2] True", "False",
                                         "True module"]


LIBRARY = """
import sys
import urdf_lint.meshes.readers
from urdf_lint.expansion import expand_file   # xacro imports PyYAML, pycollada Pillow
import collada
print(sorted(type(sys.modules[n]).__name__ for n in ("yaml", "PIL.Image") if n in sys.modules))
"""


def test_a_library_importer_gets_no_placeholder_modules():
    """Deferring is the command's own business: a program that imports urdf-lint's modules
    gets the real PyYAML and Pillow in its ``sys.modules``, never a placeholder."""
    p = subprocess.run([sys.executable, "-c", LIBRARY], capture_output=True, text=True, cwd=REPO)
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == "['module', 'module']", p.stdout


EXPAND_MODULES = """
import os, sys
from urdf_lint.run import worker
from urdf_lint.cli.main import main
# (not inspect, platform, ctypes.util: landlock and pyseccomp import them, and urdf-lint imports
# those packages as they are, never with the standard library swapped under them: issue 22)
NAMES = ("multiprocessing", "yaml", "_hashlib")


def loaded():
    return sorted(m for m in NAMES if m in sys.modules
                  and type(sys.modules[m]).__name__ != "_Deferred")


real = worker.process_job
def spy(job, settings):   # runs in the (forked, sandboxed) worker
    report = real(job, settings)
    os.write(2, ("worker loaded " + repr(loaded()) + "\\n").encode())
    return report
worker.process_job = spy
rc = main(["expand", sys.argv[1], "-o", sys.argv[2]])
print(rc, loaded())
"""


def test_expand_without_yaml_loads_no_yaml_and_no_multiprocessing(tmp_path):
    pend = DESCRIPTIONS / "double_pendulum_description" / "urdf" / "double_pendulum.urdf.xacro"
    assert "load_yaml" not in pend.read_text()
    p = subprocess.run([sys.executable, "-c", EXPAND_MODULES, str(pend), str(tmp_path / "o.urdf")],
                       capture_output=True, text=True, cwd=tmp_path)
    assert p.stdout.strip() == "0 []", p.stdout + p.stderr   # the parent
    assert "worker loaded []" in p.stderr, p.stderr
    assert "<robot" in (tmp_path / "o.urdf").read_text()


# -- the console script ------------------------------------------------------------------------
def test_the_command_flushes_everything_and_keeps_its_exit_code(tmp_path):
    """The quick exit skips the interpreter's teardown, not the output: a large JSON report
    through a pipe is complete, and a run with findings still exits 1."""
    broken = DESCRIPTIONS / "broken"
    p = subprocess.run([*LINT, "check", str(broken), "--format", "json", "--no-cache"],
                       capture_output=True, text=True, cwd=tmp_path)
    assert p.returncode == 1, p.stderr
    doc = json.loads(p.stdout)
    assert len(doc["findings"]) > 50 and len(p.stdout) > 30000
    # a reader that leaves early (`| head -1`) is no error, and the run still exits 1 for its
    # findings (a `set -o pipefail` CI step must not pass: it exited 0)
    sh = subprocess.run(["bash", "-c", f"{' '.join(LINT)} check {broken} --no-cache | head -1; "
                         "exit ${PIPESTATUS[0]}"], capture_output=True, text=True, cwd=tmp_path)
    assert sh.stdout.count("\n") == 1 and sh.stderr == "", sh.stderr
    assert sh.returncode == 1, sh.returncode


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="no /dev/full here")
@pytest.mark.parametrize("argv", [["check", "broken"], ["check", "broken", "--format", "json"],
                                  ["check", "r2d2_description"], ["rules"], ["--version"],
                                  ["--help"], ["check", "--help"]])
def test_output_that_cannot_be_written_is_one_error_and_status_2(tmp_path, argv):
    """Standard output on a full disk (``> /dev/full``): the report is lost, so the run says so
    in one line and exits 2; not an internal error "to report", not a traceback, and never
    the status of a run whose report was read (it gave 2 with "please report", and 1 with a
    traceback for --version)."""
    cmd = [*LINT, *argv, "--no-cache"] if argv[:1] == ["check"] and "--help" not in argv \
        else [*LINT, *argv]
    with open("/dev/full", "w") as full:
        p = subprocess.run(cmd, stdout=full, stderr=subprocess.PIPE, text=True,
                           cwd=DESCRIPTIONS)
    assert p.stderr == "urdf-lint: error: cannot write to standard output: No space left on " \
        "device\n", p.stderr
    assert p.returncode == 2


@pytest.mark.parametrize("argv", [["--help"], ["check", "--help"], ["--version"], ["rules"]])
def test_output_nobody_reads_is_no_error(argv):
    """Standard output whose reader has already gone (a closed pipe) is no error: exit 0,
    nothing on stderr (not a traceback)."""
    r, w = os.pipe()
    os.close(r)
    try:
        p = subprocess.run([*LINT, *argv], stdout=w, stderr=subprocess.PIPE, text=True)
    finally:
        os.close(w)
    assert (p.returncode, p.stderr) == (0, "")


# -- what a cached run loads ---------------------------------------------------------------------
def test_no_rule_modules_is_an_error_not_a_clean_run(tmp_path):
    import urdf_lint.engine.registry as registry
    (tmp_path / "ul001_x.pyc").write_bytes(b"")     # compiled only: no source to list
    with pytest.raises(RuntimeError, match="without its sources"):
        registry.submodule_names([str(tmp_path)])


def test_the_catalogue_read_from_sources_matches_the_loaded_rules():
    """The rule catalogue (no imports) says what importing every rule module says."""
    import urdf_lint.engine.registry as registry
    saved = registry._RULES, registry._CATALOGUE
    try:
        registry._RULES = registry._CATALOGUE = None
        read = registry.catalogue()
        loaded = registry.load_rules()
        assert list(read) == list(loaded) and len(read) >= 60
        for code, r in loaded.items():
            assert read[code] == registry.Entry(r.code, r.name, r.severity, r.scope, r.origin,
                                                r.module, r.targets), code
    finally:
        registry._RULES, registry._CATALOGUE = saved


def test_every_dataclass_has_a_docstring():
    """Every dataclass says what it is (dataclasses would otherwise make a docstring of the
    signature, which tells a reader nothing)."""
    import dataclasses
    import importlib
    import pkgutil
    import urdf_lint
    missing = []
    for m in pkgutil.walk_packages(urdf_lint.__path__, "urdf_lint."):
        if m.name.endswith("__main__"):
            continue
        try:
            mod = importlib.import_module(m.name)
        except ImportError:   # an optional dependency (rerun, yourdfpy) that is not installed
            continue
        for obj in vars(mod).values():
            if isinstance(obj, type) and dataclasses.is_dataclass(obj) \
                    and obj.__module__ == mod.__name__ \
                    and (not obj.__doc__ or obj.__doc__.startswith(obj.__name__ + "(")):
                missing.append(f"{mod.__name__}.{obj.__qualname__}")
    assert not missing, missing


WARM = """
import json, os, sys
from urdf_lint.cli.main import main
sys.stdout = open(os.devnull, "w")
rc = main(["check", ".", "--format", "json"])
sys.stdout = sys.__stdout__
loaded = lambda m: m in sys.modules and type(sys.modules[m]).__name__ != "_Deferred"
# (``inspect`` is not in the list: ``dataclasses`` imports it, and nothing swaps it out: issue 22)
print(rc, sorted(m for m in ("lxml", "yaml", "xacro", "multiprocessing", "pkgutil")
                 if loaded(m)),
      len([m for m in sys.modules if m.startswith("urdf_lint.rules.ul")]))
"""


def test_a_cached_run_loads_no_rule_module_lxml_or_yaml(tmp_path):
    import shutil
    shutil.copytree(DESCRIPTIONS / "r2d2_description", tmp_path / "r2d2_description")
    run = lambda: subprocess.run([sys.executable, "-c", WARM], cwd=tmp_path,  # noqa: E731
                                 capture_output=True, text=True)
    cold = run()
    assert cold.returncode == 0, cold.stderr
    warm = run()
    rc, rest = warm.stdout.split(" ", 1)
    assert rc == "0", warm.stdout + warm.stderr
    loaded, rules = rest.rsplit(" ", 1)
    assert loaded == "[]", warm.stdout
    assert int(rules) <= 12, warm.stdout   # engine codes only, not the 69 rule modules
