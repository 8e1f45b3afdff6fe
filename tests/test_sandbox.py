"""The OS sandbox of the workers, tested as if the evaluator had fallen.

The test injects arbitrary Python into a REAL worker (``run_jobs`` forks it from this process,
so replacing ``urdf_lint.run.worker.process_job`` here is what the worker runs) and has it try what an
escaped expression would: read a file outside the roots, read the parent's environment from
``/proc``, run a program, open a network connection, write outside the cache, trace or signal
the parent. Every attempt goes through ``ctypes`` (which the audit hook does not see), so what
stops it is Landlock and seccomp, not Python.
"""
from __future__ import annotations

import ctypes
import json
import os
import signal
import socket
import subprocess
import sys
import time

import pytest

from conftest import REPO, carried, carried_data, make_package, run_cli, terminated

from urdf_lint.runner import sandbox

LANDLOCK = sandbox.landlock_status()[0]
SECCOMP = sandbox.seccomp_status()[0]
SECRET = "ghp_SANDBOX_0123456789abcdef"


def _attacks(job, settings):
    """Runs inside the worker. Each attempt reports 'ok' or the errno name it failed with."""
    import errno as E
    libc = ctypes.CDLL(None, use_errno=True)
    p = job["paths"]
    out = {}

    def res(rc):
        return "ok" if rc >= 0 else E.errorcode.get(ctypes.get_errno(), str(ctypes.get_errno()))

    def read(path):
        fd = libc.open(path.encode(), os.O_RDONLY)
        r = res(fd)
        if fd >= 0:
            buf = ctypes.create_string_buffer(4096)
            n = libc.read(fd, buf, 4096)
            out.setdefault("leaked", []).append(buf.raw[:max(n, 0)].decode("latin-1"))
            libc.close(fd)
        return r
    out["read_inside"] = read(p["inside"])
    out["read_cache"] = read(p["cache_file"])     # the user's mesh facts store: read only
    out["read_outside"] = read(p["secret"])
    out["read_parent_environ"] = read(f"/proc/{job['parent']}/environ")
    out["read_own_environ"] = read("/proc/self/environ")
    out["list_root"] = res(libc.open(b"/", os.O_RDONLY | os.O_DIRECTORY))
    if job.get("mild"):  # the sandbox is off: only what does no harm
        out["socket_inet"] = res(libc.socket(socket.AF_INET, socket.SOCK_STREAM, 0))
        try:
            os.fstat(job["parent_fd"])
            out["parent_fd"] = "open"
        except OSError as e:
            out["parent_fd"] = E.errorcode[e.errno]
        return out
    fd = libc.open(p["marker"].encode(), os.O_WRONLY | os.O_CREAT, 0o644)
    out["write_outside"] = res(fd)
    fd = libc.open(p["cache_file"].encode(), os.O_WRONLY | os.O_CREAT, 0o644)
    out["write_cache"] = res(fd)
    if fd >= 0:
        libc.write(fd, b"{}", 2)
        libc.close(fd)
    out["write_cache_result"] = res(libc.open(p["cache_result"].encode(),
                                              os.O_WRONLY | os.O_CREAT, 0o644))
    argv = (ctypes.c_char_p * 4)(b"/bin/sh", b"-c", f"touch {p['marker']}".encode(), None)
    out["execve"] = res(libc.execve(b"/bin/sh", argv, None))
    out["system"] = "ok" if libc.system(f"touch {p['marker']}".encode()) == 0 else "failed"
    out["socket_inet"] = res(libc.socket(socket.AF_INET, socket.SOCK_STREAM, 0))
    out["socket_unix"] = res(libc.socket(socket.AF_UNIX, socket.SOCK_STREAM, 0))
    try:
        s = socket.create_connection(("127.0.0.1", job["port"]), timeout=2)
        s.close()
        out["python_connect"] = "ok"
    except OSError as e:
        out["python_connect"] = type(e).__name__
    out["ptrace_parent"] = res(libc.ptrace(16, job["parent"], None, None))  # PTRACE_ATTACH
    out["signal_parent"] = res(libc.kill(job["parent"], 0))
    return out


@pytest.fixture()
def attack_world(tmp_path):
    repo = tmp_path / "repo"
    pkg = make_package(repo, "p", {"urdf/r.urdf": '<robot name="r"><link name="a"/></robot>\n'})
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "secret.txt").write_text(SECRET)
    cache = tmp_path / "xdg" / "urdf-lint" / "mesh-facts"     # the user's mesh facts store
    cache.mkdir(parents=True)
    (cache / "v3-00.json").write_text("signed\n{}")
    return {"inside": str(pkg / "urdf/r.urdf"), "secret": str(outside / "secret.txt"),
            "marker": str(tmp_path / "pwned"), "cache_file": str(cache / "v3-00.json"),
            "cache_result": str(cache / "forged.json"),
            "repo": str(repo), "cache": str(cache)}


class AttackJob(dict):
    """A job carrying the attack's parameters (the worker hands it to the patched
    ``process_job`` as is); ``entry``/``args`` as a LintJob has them, for the limit results."""

    @property
    def entry(self):
        return self["entry"]

    @property
    def args(self):
        return {}


def _run_in_worker(monkeypatch, paths, port, env=None, mild=False, parent_fd=-1):
    from urdf_lint.run import worker
    from urdf_lint.core.jobs import LintSettings
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.run.worker import run_jobs
    monkeypatch.setattr(worker, "process_job", lambda job, s: carried(job, _attacks(job, s)))
    for k, v in (env or {}).items():
        monkeypatch.setenv(k, v)
    resolver = PackageResolver.build([paths["repo"]], extra_roots=[paths["repo"]])
    settings = LintSettings(resolver=resolver.to_dict(), mesh_cache_dir=paths["cache"], timeout=30)
    job = AttackJob(entry=paths["inside"], kind="urdf", paths=paths, parent=os.getpid(),
                    port=port, mild=mild, parent_fd=parent_fd)
    results = [r for _, r in run_jobs([job], settings, jobs_n=1)]
    assert len(results) == 1
    return carried_data(results[0])


@pytest.mark.skipif(not (LANDLOCK and SECCOMP), reason="needs Landlock and seccomp (Linux)")
def test_escaped_code_in_a_real_worker_is_contained(attack_world, monkeypatch):
    server = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    server.bind(("127.0.0.1", 0))
    server.listen(1)
    server.settimeout(0.5)
    port = server.getsockname()[1]
    try:
        r = _run_in_worker(monkeypatch, attack_world, port, env={"CI_TOKEN": SECRET})
        # nobody connected
        with pytest.raises(socket.timeout):
            server.accept()
    finally:
        server.close()
    assert r["read_inside"] == "ok", r          # the sandbox still lets the worker do its job
    # the mesh facts store is the parent's to write (workers send their facts back)
    assert r["read_cache"] == "ok", r
    assert open(attack_world["cache_file"]).read() == "signed\n{}"
    assert not os.path.exists(attack_world["cache_result"])
    for k in ("read_outside", "read_parent_environ", "read_own_environ", "list_root",
              "write_outside", "write_cache", "write_cache_result"):
        assert r[k] == "EACCES", (k, r)
    for k in ("execve", "socket_inet", "socket_unix", "ptrace_parent", "signal_parent"):
        assert r[k] == "EPERM", (k, r)
    assert r["system"] == "failed" and r["python_connect"] == "PermissionError", r
    assert not os.path.exists(attack_world["marker"])
    assert SECRET not in json.dumps(r)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="Linux only")
def test_sandbox_off_really_is_off(attack_world, monkeypatch):
    """The same attacks with URDF_LINT_SANDBOX=0 succeed: the test above measures the sandbox,
    not something else that happens to fail."""
    with open(attack_world["secret"]) as held:  # a descriptor the parent happens to hold
        r = _run_in_worker(monkeypatch, attack_world, 9, env={"URDF_LINT_SANDBOX": "0"},
                           mild=True, parent_fd=held.fileno())
    assert r["read_outside"] == "ok" and SECRET in "".join(r["leaked"]), r
    assert r["socket_inet"] == "ok", r
    # inherited descriptors are closed even then
    assert r["parent_fd"] == "EBADF", r


def _state(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0]
    except OSError:
        return None


PARENT = """
import os, sys, time
from urdf_lint.run import worker
from urdf_lint.core.jobs import LintJob, LintSettings
from urdf_lint.discovery.packages import PackageResolver
from urdf_lint.run.worker import run_jobs
def slow(job, settings):
    from urdf_lint.core.jobs import ModelReport
    if job.entry == "slow":
        time.sleep(120)
    return ModelReport(job.entry, {{}})
worker.process_job = slow
r = PackageResolver.build([{repo!r}], extra_roots=[{repo!r}])
settings = LintSettings(resolver=r.to_dict(), timeout=300)
jobs = [LintJob("slow", kind="urdf"), LintJob("quick", kind="urdf")]
from urdf_lint.runner import forked
gen = run_jobs(jobs, settings, jobs_n=2)  # one busy worker, one idle
import threading
def report():
    time.sleep(1.0)
    print(" ".join(str(p.pid) for p in forked.active_children()), flush=True)
threading.Thread(target=report, daemon=True).start()
for _ in gen:
    pass
"""


@pytest.mark.skipif(not sandbox.pdeathsig_status()[0], reason="needs PR_SET_PDEATHSIG")
@pytest.mark.parametrize("how", [signal.SIGKILL, signal.SIGTERM])
def test_no_worker_survives_its_parent(tmp_path, how):
    repo = tmp_path / "repo"
    repo.mkdir()
    p = subprocess.Popen([sys.executable, "-c", PARENT.format(repo=str(repo))], cwd=REPO,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        pids = [int(x) for x in p.stdout.readline().split()]
        assert len(pids) == 2, p.stderr.read()
        assert all(_state(pid) not in (None, "Z") for pid in pids)
        os.kill(p.pid, how)
        p.wait(10)
        deadline = time.monotonic() + 5
        while time.monotonic() < deadline and any(_state(pid) not in (None, "Z") for pid in pids):
            time.sleep(0.05)
        assert all(_state(pid) in (None, "Z") for pid in pids), [_state(x) for x in pids]
    finally:
        if p.poll() is None:
            p.kill()


def test_sigterm_is_handled_like_ctrl_c(tmp_path):
    repo = tmp_path / "repo"
    make_package(repo, "p", {"urdf/r.urdf.xacro":
                             '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                             '<link name="${python.sum(python.range(10**13))}"/></robot>\n'})
    rc, out, err = terminated("check", ".", "--no-cache", cwd=repo, after=1.5)
    assert rc == 130, (out, err)  # like Ctrl-C (main: 130 when interrupted)
    assert "interrupted" in err and "Traceback" not in err
    assert "All checks passed" not in out


def test_doctor_and_version_report_protections():
    d = run_cli("doctor")
    assert d.returncode == 0
    for name in ("landlock", "seccomp", "pdeathsig"):
        line = next(ln for ln in d.stdout.splitlines() if f" {name} " in ln)
        on = sandbox.protections()[name][0]
        assert line.lstrip().startswith("on " if on else "OFF"), d.stdout
    v = run_cli("--version")
    assert v.returncode == 0 and "worker sandbox:" in v.stdout
    off = run_cli("doctor", env={"URDF_LINT_SANDBOX": "0"})
    assert "OFF  landlock" in off.stdout and "URDF_LINT_SANDBOX=0" in off.stdout


def test_expand_runs_in_a_worker_with_limits(tmp_path):
    """`expand` has the time limit (and the rest of the worker) now: a hang becomes UL904."""
    pkg = make_package(tmp_path / "repo", "p", {"urdf/r.urdf.xacro":
                       '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                       '<link name="${python.sum(python.range(10**13))}"/></robot>\n'})
    (tmp_path / "repo" / "urdf-lint.toml").write_text("timeout = 2\n")
    out = tmp_path / "o.urdf"
    t0 = time.monotonic()
    p = run_cli("expand", pkg / "urdf/r.urdf.xacro", "-o", out, timeout=30)
    assert time.monotonic() - t0 < 15
    assert p.returncode == 1 and "UL904" in p.stderr and "time limit" in p.stderr, p.stderr
    assert not out.exists()


def test_missing_kernel_features_are_said_once_and_the_run_goes_on(attack_world, monkeypatch,
                                                                   capsys):
    """A kernel without Landlock or seccomp: one note on stderr per run, the jobs still run
    (with what remains: pdeathsig, closed descriptors, limits, scrubbed environment)."""
    monkeypatch.setattr(sandbox, "landlock_status", lambda: (False, "not on this test kernel"))
    monkeypatch.setattr(sandbox, "seccomp_status", lambda: (False, "no libseccomp here"))
    monkeypatch.setattr(sandbox, "_noted", False)
    for _ in range(2):
        r = _run_in_worker(monkeypatch, attack_world, 9, mild=True)
        assert r["read_inside"] == "ok", r
    err = capsys.readouterr().err
    assert err.count("without landlock: not on this test kernel") == 1, err
    assert err.count("without seccomp: no libseccomp here") == 1, err


class _Evil:
    """What code that escaped the evaluator could send back instead of a lint result: a
    pickle that calls a function (here ``os.mkdir``) while the parent reads it."""

    def __init__(self, path):
        self.path = path

    def __reduce__(self):
        return (os.mkdir, (self.path,))


def _send_evil(conn, path):
    conn.send(_Evil(path))


def _wire_message(value_json: str) -> bytes:
    """A plain-data message (urdf_lint/runner/wire.py) written by hand: what a worker that
    no longer keeps to the protocol could send."""
    from urdf_lint.runner import wire
    text = value_json.encode()
    return wire.MAGIC + wire._HEAD.pack(len(text), 0) + text


# an allowed class called wrongly: a ModelReport without its fields
_BAD_CALL = _wire_message('{"~":"d","c":"urdf_lint.core.jobs:ModelReport","f":{"entry":"x"}}')


def _raw_reply(header_size: int, body: bytes, stall: float):
    """A Conn.send for the worker's side that writes a header saying ``header_size`` bytes,
    then ``body``, then waits ``stall`` seconds (the parent's messages go through as usual)."""
    import time
    from urdf_lint.runner import forked
    real = forked.Conn.send

    def send(self, obj):
        from urdf_lint.core.jobs import ModelReport
        if not isinstance(obj, ModelReport):
            return real(self, obj)
        os.write(self.wfd, forked._HEADER.pack(header_size) + body)
        time.sleep(stall)
    return send


@pytest.mark.parametrize("case", ["bad call", "not a report", "oversized", "stalled"])
def test_a_worker_result_the_parent_cannot_trust_fails_its_model_only(tmp_path, monkeypatch,
                                                                     case):
    """Whatever a worker sends back instead of a whole lint result (an allowed class called
    wrongly, another allowed object, a length of more than a gigabyte, a message that never
    ends) fails its model with an internal error: never the run, never a hang."""
    import time
    from urdf_lint.runner import forked
    from urdf_lint.run import worker
    from urdf_lint.core.jobs import LintJob, LintSettings, Status
    from urdf_lint.discovery.packages import PackageResolver
    if case == "bad call":
        monkeypatch.setattr(forked.Conn, "send", _raw_reply(len(_BAD_CALL), _BAD_CALL, 0))
    elif case == "not a report":
        monkeypatch.setattr(worker, "process_job", lambda job, settings: Status.MODEL)
    else:
        oversized = case == "oversized"
        monkeypatch.setattr(forked.Conn, "send", _raw_reply(
            forked.MAX_MESSAGE + 1 if oversized else 100, b"" if oversized else b"x" * 10, 60))
    resolver = PackageResolver.build([str(tmp_path)], extra_roots=[str(tmp_path)])
    jobs = [LintJob(str(tmp_path / "m.urdf"), kind="urdf")]
    t0 = time.monotonic()
    # (a stalled message is cut at the wall limit, WALL_FACTOR times the CPU limit: 1 s of CPU
    # keeps the test short; the others fail at once)
    limit = 1 if case == "stalled" else 3
    [(_, r)] = list(worker.run_jobs(jobs, LintSettings(resolver=resolver.to_dict(), timeout=limit),
                                    jobs_n=1))
    assert time.monotonic() - t0 < 20
    assert r.internal and "not a lint result" in r.internal[0] and not r.cacheable, r


@pytest.mark.skipif(not os.path.isdir("/proc/self/fd"), reason="needs /proc/self/fd")
def test_runs_leave_no_descriptor_behind(tmp_path):
    """``--fix`` and ``diff`` run several passes in one process: the channels of workers that
    ended are closed, not left to the garbage collector."""
    from urdf_lint.run import worker
    from urdf_lint.core.jobs import LintJob, LintSettings
    from urdf_lint.discovery.packages import PackageResolver
    (tmp_path / "m.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    settings = LintSettings(resolver=PackageResolver.build(
        [str(tmp_path)], extra_roots=[str(tmp_path)]).to_dict())
    jobs = [LintJob(str(tmp_path / "m.urdf"), kind="urdf")] * 2

    def open_fds():
        return len(os.listdir("/proc/self/fd"))
    list(worker.run_jobs(jobs, settings, jobs_n=2))
    before = open_fds()
    for _ in range(5):
        list(worker.run_jobs(jobs, settings, jobs_n=2))
    assert open_fds() == before


def test_a_worker_cannot_run_code_in_the_parent_through_its_result(tmp_path, monkeypatch):
    from urdf_lint.runner import forked
    from urdf_lint.run import worker
    from urdf_lint.core.jobs import LintJob, LintSettings
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.core.locations import display_path
    marker = tmp_path / "pwned"
    resolver = PackageResolver.build([str(tmp_path)], extra_roots=[str(tmp_path)])
    jobs = [LintJob(str(tmp_path / "m.urdf"), kind="urdf")]
    settings = LintSettings(resolver=resolver.to_dict(), timeout=30)
    # a worker's results cross as plain data: an object that would pickle as a call is not sent
    monkeypatch.setattr(worker, "process_job", lambda job, settings: _Evil(str(marker)))
    [(_, r)] = list(worker.run_jobs(jobs, settings, jobs_n=1))
    assert not marker.exists()
    assert r.internal and "could not be sent" in r.internal[0] and "_Evil" in r.internal[0], r
    assert not r.cacheable
    # and a message written by hand that names a function is refused by its name, unread
    forged = _wire_message('{"~":"n","c":"os:mkdir","v":[%s]}' % json.dumps(str(marker)))
    monkeypatch.setattr(forked.Conn, "send", _raw_reply(len(forged), forged, 0))
    [(_, r)] = list(worker.run_jobs(jobs, settings, jobs_n=1))
    monkeypatch.undo()
    assert not marker.exists()
    assert r.internal and "not a lint result (os.mkdir)" in r.internal[0], r
    assert r.entry == jobs[0].entry and not r.cacheable
    assert f"the worker linting {display_path(jobs[0].entry)} sent back" in r.internal[0]
    # the same message read by an end that accepts anything does run: the test measures the
    # restriction, not something else that happens to fail
    conn, proc = forked.start(_send_evil, (str(marker),))
    try:
        conn.recv()
    finally:
        proc.join(5)
        conn.close()
    assert marker.is_dir()


# -- issue 21 item 17: no signal to another process, no child that outlives the worker ----------
# syscall numbers the attempts below make through libc's syscall() (no libc wrapper checks them)
_SYSCALLS = {"x86_64": {"fork": 57, "clone": 56, "clone3": 435, "tkill": 200, "tgkill": 234,
                        "rt_sigqueueinfo": 129, "rt_tgsigqueueinfo": 297},
             "aarch64": {"clone": 220, "clone3": 435, "tkill": 130, "tgkill": 131,
                         "rt_sigqueueinfo": 138, "rt_tgsigqueueinfo": 240}}
_NR = _SYSCALLS.get(os.uname().machine, {})


def _signals_and_children(job, settings):
    """Runs inside the worker: signal 0 (nothing is delivered, the kernel only checks) at the
    parent through every call that takes a pid, and start a child every way there is."""
    import errno as E
    import threading
    libc = ctypes.CDLL(None, use_errno=True)
    sysc = libc.syscall
    sysc.restype = ctypes.c_long
    parent, me = job["parent"], os.getpid()
    out = {}

    def res(rc):
        return "ok" if rc >= 0 else E.errorcode.get(ctypes.get_errno(), str(ctypes.get_errno()))

    def queued_info():
        info = (ctypes.c_int * 32)()       # a siginfo_t as sigqueue() makes it
        info[0], info[2], info[4] = 0, -1, me   # si_signo, si_code SI_QUEUE, si_pid
        return info
    for who, pid in (("parent", parent), ("self", me)):
        out[f"tkill_{who}"] = res(sysc(_NR["tkill"], pid, 0))
        out[f"tgkill_{who}"] = res(sysc(_NR["tgkill"], pid, pid, 0))
        out[f"rt_sigqueueinfo_{who}"] = res(sysc(_NR["rt_sigqueueinfo"], pid, 0, queued_info()))
        out[f"rt_tgsigqueueinfo_{who}"] = res(sysc(_NR["rt_tgsigqueueinfo"], pid, pid, 0,
                                                   queued_info()))
    out["kill_group"] = res(libc.kill(0, 0))
    out["kill_self"] = res(libc.kill(me, 0))
    # a child that would outlive the worker (PR_SET_PDEATHSIG is not inherited): it sleeps.
    # libc's fork() through ctypes, which the audit hook does not see (it refuses os.fork)
    pid = libc.fork()
    if pid == 0:   # pragma: no cover - only without the filter
        time.sleep(60)
        os._exit(0)
    out["fork"] = res(pid)
    if pid > 0:
        out["fork_child"] = pid
    try:
        os.fork()   # the audit hook's refusal, before the kernel's
        out["os_fork"] = "ok"
    except OSError as e:
        out["os_fork"] = type(e).__name__
    for name, call in (("raw_fork", lambda: sysc(_NR["fork"]) if "fork" in _NR else None),
                       ("raw_clone", lambda: sysc(_NR["clone"], signal.SIGCHLD, 0, 0, 0, 0)),
                       ("raw_clone3", lambda: sysc(_NR["clone3"], ctypes.byref(
                           (ctypes.c_uint64 * 11)(0, 0, 0, 0, signal.SIGCHLD)), 88))):
        rc = call()
        if rc is None:
            continue
        if rc == 0:    # pragma: no cover - a child, only without the filter
            os._exit(0)
        out[name] = res(rc)
        if rc > 0:
            os.waitpid(rc, 0)
    # threads still work (numpy, trimesh, rerun start them)
    seen = []
    t = threading.Thread(target=lambda: seen.append(threading.get_native_id()))
    t.start()
    t.join(10)
    out["thread"] = "ok" if seen and seen[0] != me else "failed"
    return out


@pytest.mark.skipif(not SECCOMP or not _NR, reason="needs seccomp on x86_64 or aarch64 Linux")
def test_a_worker_cannot_signal_another_process_or_leave_a_child(tmp_path, monkeypatch):
    """From inside a real worker, tkill, tgkill, rt_sigqueueinfo and rt_tgsigqueueinfo aimed
    at the parent fail (kill did already), and so does every way of starting a process: a
    forked child would have outlived the worker. A thread still starts, and the worker may
    still signal itself."""
    from urdf_lint.run import worker
    from urdf_lint.core.jobs import LintSettings
    from urdf_lint.run.worker import run_jobs
    pkg = make_package(tmp_path / "repo", "p", {"urdf/r.urdf": '<robot name="r"/>\n'})
    monkeypatch.setattr(worker, "process_job",
                        lambda job, s: carried(job, _signals_and_children(job, s)))
    job = AttackJob(entry=str(pkg / "urdf/r.urdf"), kind="urdf", parent=os.getpid())
    [(_, report)] = list(run_jobs([job], LintSettings(resolver={}, timeout=30), jobs_n=1))
    r = carried_data(report)
    child = r.get("fork_child") if isinstance(r, dict) else None
    if child:   # the original code: the child outlived the worker; do not leave it behind
        alive = _state(child) not in (None, "Z")
        os.kill(child, signal.SIGKILL)
        assert not alive, f"a forked child outlived its worker: {r}"
    for k in ("tkill_parent", "tgkill_parent", "rt_sigqueueinfo_parent",
              "rt_tgsigqueueinfo_parent", "kill_group", "fork", "raw_clone"):
        assert r[k] == "EPERM", (k, r)
    assert r["os_fork"] == "PermissionError", r
    if "raw_fork" in r:
        assert r["raw_fork"] == "EPERM", r
    assert r["raw_clone3"] == "ENOSYS", r
    for k in ("tkill_self", "tgkill_self", "rt_sigqueueinfo_self", "rt_tgsigqueueinfo_self",
              "kill_self", "thread"):
        assert r[k] == "ok", (k, r)


def _signals_only(job, settings):
    import errno as E
    libc = ctypes.CDLL(None, use_errno=True)
    libc.syscall.restype = ctypes.c_long
    parent, me = job["parent"], os.getpid()

    def res(rc):
        return "ok" if rc >= 0 else E.errorcode.get(ctypes.get_errno(), str(ctypes.get_errno()))
    return {"kill_parent": res(libc.kill(parent, 0)),
            "tkill_parent": res(libc.syscall(_NR["tkill"], parent, 0)),
            "kill_self": res(libc.kill(me, 0))}


@pytest.mark.skipif(not LANDLOCK or not _NR, reason="needs Landlock (x86_64 or aarch64 Linux)")
def test_landlock_scopes_a_workers_signals_even_without_seccomp(tmp_path, monkeypatch):
    """The second layer: where Landlock has scopes (ABI >= 6), a worker whose seccomp filter
    is missing still cannot signal its parent (the kernel refuses a signal leaving the
    worker's Landlock domain)."""
    from landlock import landlock_abi_version
    if landlock_abi_version() < 6:
        pytest.skip("Landlock ABI < 6: no scopes on this kernel")
    from urdf_lint.run import worker
    from urdf_lint.core.jobs import LintSettings
    from urdf_lint.run.worker import run_jobs
    pkg = make_package(tmp_path / "repo", "p", {"urdf/r.urdf": '<robot name="r"/>\n'})
    monkeypatch.setattr(sandbox, "seccomp_status", lambda: (False, "left out by the test"))
    monkeypatch.setattr(worker, "process_job", lambda job, s: carried(job, _signals_only(job, s)))
    job = AttackJob(entry=str(pkg / "urdf/r.urdf"), kind="urdf", parent=os.getpid())
    [(_, report)] = list(run_jobs([job], LintSettings(resolver={}, timeout=30), jobs_n=1))
    r = carried_data(report)
    assert r == {"kill_parent": "EPERM", "tkill_parent": "EPERM", "kill_self": "ok"}, r
