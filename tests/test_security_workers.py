"""Every command that expands runs in the sandboxed worker (issue 21, item 7): ``generate`` (it
expanded in the parent: no sandbox, no limits, the parent's environment), and the ``diff
--render`` recorder process is sandboxed like a worker. Real repositories, run as a user would."""
from __future__ import annotations

import os
import time

from conftest import make_package, run_cli, terminated

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
SECRET = "ghp_TOPSECRET_0123456789abcdef"
HANG = '<link name="${python.sum(python.range(10**13))}"/>'


def _generated_repo(tmp_path, body: str, timeout: float | None = None):
    """A package whose config names a generated output for its xacro."""
    repo = tmp_path / "repo"
    make_package(repo, "p", {"urdf/r.urdf.xacro":
                             f'<?xml version="1.0"?>\n<robot name="r" {X}>\n  <link name="base"/>\n'
                             f'  {body}\n</robot>\n'})
    (repo / "urdf-lint.toml").write_text(
        (f"timeout = {timeout}\n" if timeout else "")
        + '[[models]]\npath = "p/urdf/r.urdf.xacro"\noutput = "p/urdf/r.urdf"\n')
    return repo


def test_generate_expands_in_a_worker_with_the_time_limit(tmp_path):
    """A hang in a generated model's xacro is a located UL904 within the time limit (it ran
    forever in the parent), nothing is written, and the other outputs are still generated."""
    repo = _generated_repo(tmp_path, HANG, timeout=2)
    make_package(repo, "q", {"urdf/ok.urdf.xacro":
                             f'<?xml version="1.0"?>\n<robot name="ok" {X}>\n  <link name="a"/>\n</robot>\n'})
    with open(repo / "urdf-lint.toml", "a") as f:
        f.write('[[models]]\npath = "q/urdf/ok.urdf.xacro"\noutput = "q/urdf/ok.urdf"\n')
    t0 = time.monotonic()
    p = run_cli("generate", cwd=repo, timeout=60)
    assert time.monotonic() - t0 < 20
    assert p.returncode == 1, (p.stdout, p.stderr)
    assert "p/urdf/r.urdf.xacro:1:1: UL904" in p.stderr and "time limit" in p.stderr, p.stderr
    assert not (repo / "p/urdf/r.urdf").exists()
    assert "regenerated q/urdf/ok.urdf from q/urdf/ok.urdf.xacro" in p.stdout, p.stdout
    assert '<link name="a"/>' in (repo / "q/urdf/ok.urdf").read_text()


def test_generate_stops_on_sigterm(tmp_path):
    """SIGTERM during generate stops it at once, like Ctrl-C, and leaves no worker behind."""
    repo = _generated_repo(tmp_path, HANG, timeout=60)
    rc, out, err = terminated("generate", cwd=repo, after=2)
    assert rc == 130, (out, err)
    assert "Traceback" not in err


def test_generate_reads_no_secret_and_no_environment(tmp_path):
    """generate expands with the run's confined roots and a scrubbed environment: neither a
    package name that is a path nor a variable outside env-allow reaches the output."""
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "secret.yaml").write_text(f"token: {SECRET}\n")
    prefix = tmp_path / "prefix"
    (prefix / "share" / "ament_index" / "resource_index" / "packages").mkdir(parents=True)
    repo = _generated_repo(tmp_path, f'<xacro:property name="s" value="${{xacro.load_yaml('
                                     f'\'$(find {outside})/secret.yaml\')}}"/><link name="${{s.token}}"/>')
    env = {"AMENT_PREFIX_PATH": str(prefix), "CI_DEPLOY_TOKEN": SECRET}
    p = run_cli("generate", cwd=repo, env=env, timeout=60)
    assert p.returncode == 1 and SECRET not in p.stdout + p.stderr, (p.stdout, p.stderr)
    assert "p/urdf/r.urdf.xacro:4:" in p.stderr and "UL004" in p.stderr, p.stderr
    assert not (repo / "p/urdf/r.urdf").exists()
    leak = _generated_repo(tmp_path / "env", '<link name="$(optenv CI_DEPLOY_TOKEN nothing)"/>')
    p = run_cli("generate", cwd=leak, env=env, timeout=60)
    assert p.returncode == 1 and SECRET not in p.stdout + p.stderr, (p.stdout, p.stderr)
    assert '<link name="nothing"/>' in (leak / "p/urdf/r.urdf").read_text()


def test_generate_runs_in_a_sandboxed_worker(tmp_path, monkeypatch, capsys):
    """What generate's expansion sees from inside: a worker process (not the parent) with the
    memory limit, the scrubbed environment and Landlock (a file outside the roots cannot be
    opened, even through ctypes); its XML comes back as data, which the parent writes."""
    import ctypes
    import errno as E
    import json
    import resource

    from urdf_lint.runner import sandbox

    from urdf_lint.run import worker
    from urdf_lint.cli.main import main
    from urdf_lint.core.jobs import KeptModel, ModelReport
    repo = _generated_repo(tmp_path, '<link name="x"/>')
    (tmp_path / "secret.txt").write_text(SECRET)
    parent = os.getpid()

    def probe(job, settings):
        libc = ctypes.CDLL(None, use_errno=True)
        fd = libc.open(str(tmp_path / "secret.txt").encode(), os.O_RDONLY)
        return ModelReport(job.entry, {}, kept_model=KeptModel(json.dumps({
            "pid": os.getpid(), "kind": job.kind,
            "memory": resource.getrlimit(getattr(resource, "RLIMIT_DATA", resource.RLIMIT_AS))[0],
            "read_outside": "ok" if fd >= 0 else E.errorcode.get(ctypes.get_errno()),
            "env": "CI_DEPLOY_TOKEN" in os.environ})))
    monkeypatch.setattr(worker, "process_job", probe)
    monkeypatch.setenv("CI_DEPLOY_TOKEN", SECRET)
    monkeypatch.delenv("URDF_LINT_SANDBOX", raising=False)
    monkeypatch.chdir(repo)
    assert main(["generate"]) == 1
    seen = json.loads((repo / "p/urdf/r.urdf").read_text())
    assert seen["pid"] != parent and seen["kind"] == "expand", seen
    assert seen["memory"] != resource.RLIM_INFINITY, seen      # the memory limit
    assert seen["env"] is False, seen                           # the scrubbed environment
    if sandbox.landlock_status()[0]:
        assert seen["read_outside"] == "EACCES", seen
    capsys.readouterr()


def _recorder_attacks(path, recording_id, plans, blueprint=True):
    """Runs inside the recorder (in place of writing the recording): what it can reach."""
    import ctypes
    import errno as E
    import json
    import socket
    libc = ctypes.CDLL(None, use_errno=True)
    p = plans

    def res(rc):
        return "ok" if rc >= 0 else E.errorcode.get(ctypes.get_errno(), str(ctypes.get_errno()))
    out = {"pid": os.getpid(), "env": "CI_DEPLOY_TOKEN" in os.environ,
           "read_repo": res(libc.open(p["inside"].encode(), os.O_RDONLY)),
           "read_secret": res(libc.open(p["secret"].encode(), os.O_RDONLY)),
           "read_parent_environ": res(libc.open(f"/proc/{p['parent']}/environ".encode(), os.O_RDONLY)),
           "write_outside": res(libc.open(p["marker"].encode(), os.O_WRONLY | os.O_CREAT, 0o644)),
           "write_out": res(libc.open(path.encode(), os.O_WRONLY | os.O_CREAT, 0o644)),
           "socket": res(libc.socket(socket.AF_INET, socket.SOCK_STREAM, 0))}
    return json.dumps(out)


def _probe_recorder(tmp_path, monkeypatch):
    import json

    from urdf_lint.render import recording
    repo = tmp_path / "repo"
    pkg = make_package(repo, "p", {"urdf/r.urdf": '<robot name="r"><link name="a"/></robot>\n'})
    (tmp_path / "secret.txt").write_text(SECRET)
    out = tmp_path / "snaps"
    out.mkdir()
    monkeypatch.setattr(recording, "write_recording", _recorder_attacks)
    monkeypatch.setenv("CI_DEPLOY_TOKEN", SECRET)
    rec = recording.Recorder(str(out))
    try:
        target = str(out / "m.rrd")
        rec.write(target, "r", {"inside": str(pkg / "urdf/r.urdf"), "parent": os.getpid(),
                                "secret": str(tmp_path / "secret.txt"),
                                "marker": str(tmp_path / "pwned")})
        rec.write(str(tmp_path / "elsewhere.rrd"), "r", {})
        done = rec.results(timeout=30)
    finally:
        rec.close()
    assert "not in the output folder" in done[str(tmp_path / "elsewhere.rrd")]
    return json.loads(done[target])


def test_the_recorder_is_sandboxed_like_a_worker(tmp_path, monkeypatch):
    """``diff --render``'s recorder reads nothing (not the repository, not a secret, not the
    parent's environment), writes only into the output folder, opens no socket, and runs with
    a scrubbed environment."""
    from urdf_lint.runner import sandbox
    monkeypatch.delenv("URDF_LINT_SANDBOX", raising=False)
    got = _probe_recorder(tmp_path, monkeypatch)
    assert got["pid"] != os.getpid() and got["env"] is False, got
    assert got["write_out"] == "ok", got
    if sandbox.landlock_status()[0]:
        assert got["read_repo"] == got["read_secret"] == "EACCES", got
        assert got["read_parent_environ"] == got["write_outside"] == "EACCES", got
    if sandbox.seccomp_status()[0]:
        assert got["socket"] == "EPERM", got
    assert not (tmp_path / "pwned").exists()
