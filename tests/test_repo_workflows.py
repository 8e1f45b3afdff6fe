"""Repository workflows: --changed-since through the dependency graph, --baseline, the hook
command, and parallel runs that agree with serial ones."""
from __future__ import annotations

import json
import shutil
import subprocess

from conftest import CORPUS, DESCRIPTIONS, run_cli


def git(*args, cwd):
    subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True)


def make_repo(tmp_path):
    repo = tmp_path / "repo"
    shutil.copytree(DESCRIPTIONS / "r2d2_description", repo / "r2d2_description")
    shutil.copytree(DESCRIPTIONS / "double_pendulum_description", repo / "double_pendulum_description")
    git("init", "-q", cwd=repo)
    git("-c", "user.email=t@t", "-c", "user.name=t", "add", "-A", cwd=repo)
    git("-c", "user.email=t@t", "-c", "user.name=t", "commit", "-qm", "init", cwd=repo)
    return repo


def models(p):
    return sorted(m["entry"] for m in json.loads(p.stdout)["models"])


def test_changed_since_follows_dependencies(tmp_path):
    repo = make_repo(tmp_path)
    p = run_cli("check", ".", "--changed-since", "HEAD", "--format", "json", cwd=repo)
    assert p.returncode == 0 and models(p) == []
    yaml = repo / "r2d2_description/config/joint_limits.yaml"
    yaml.write_text(yaml.read_text().replace("upper: 0.548", "upper: 0.5"))
    p = run_cli("check", ".", "--changed-since", "HEAD", "--format", "json", cwd=repo)
    assert models(p) == ["r2d2_description/urdf/r2d2.urdf.xacro"]
    p = run_cli("check", ".", "--changed-since", "no-such-ref", cwd=repo)
    assert p.returncode == 2 and "no-such-ref" in p.stderr


def test_hook_reports_only_affected_models_and_unused_files(tmp_path):
    repo = make_repo(tmp_path)
    macros = repo / "r2d2_description/urdf/r2d2_macros.xacro"
    macros.write_text(macros.read_text().replace('<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>'))
    (repo / "notes.xacro").write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="x"/></robot>')
    p = run_cli("hook", "r2d2_description/urdf/r2d2_macros.xacro", "notes.xacro", cwd=repo)
    assert p.returncode == 1
    assert "r2d2_description/urdf/r2d2_macros.xacro:" in p.stdout and "UL307" in p.stdout
    assert "double_pendulum" not in p.stdout
    # the note about unused files is for -v only (issue 9): not on every pre-commit run
    assert "not used by any model" not in p.stderr
    p = run_cli("hook", "-v", "r2d2_description/urdf/r2d2_macros.xacro", "notes.xacro", cwd=repo)
    assert p.returncode == 1
    assert "note: notes.xacro is not used by any model" in p.stderr
    p = run_cli("hook", "double_pendulum_description/urdf/double_pendulum.urdf.xacro", cwd=repo)
    assert p.returncode == 0 and p.stdout == ""


def test_baseline(tmp_path):
    repo = make_repo(tmp_path)
    macros = repo / "r2d2_description/urdf/r2d2_macros.xacro"
    macros.write_text(macros.read_text().replace('<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>'))
    p = run_cli("check", ".", "--write-baseline", "baseline.json", cwd=repo)
    # writing a baseline succeeds and says what it wrote (issue 9; it used to exit 1)
    assert p.returncode == 0, p.stderr
    # one macro line used four times: one finding, four instances (the one counting rule)
    assert "wrote 1 finding(s) (4 instances) in 1 file(s) to baseline.json" in p.stderr
    assert len(json.loads((repo / "baseline.json").read_text())["findings"]) == 4
    p = run_cli("check", ".", "--baseline", "baseline.json", "--format", "json", cwd=repo)
    assert p.returncode == 0 and json.loads(p.stdout)["findings"] == []
    # a new problem still fails; moving lines does not resurrect old ones
    text = macros.read_text().replace("<robot ", "\n\n<robot ", 1)   # moves every line down
    macros.write_text(text.replace("${limits.gripper.lower}", "0.9"))
    p = run_cli("check", ".", "--baseline", "baseline.json", "--format", "json", cwd=repo)
    codes = [f["code"] for f in json.loads(p.stdout)["findings"]]
    assert p.returncode == 1 and codes and set(codes) == {"UL302"}


def test_parallel_equals_serial(corpus, tmp_path):
    sub = ["ur_description", "franka_description", "fanuc"]
    a = run_cli("check", *sub, "--no-cache", "-j", "1", "--format", "json", "--fail-on", "never", cwd=corpus)
    b = run_cli("check", *sub, "--no-cache", "-j", "2", "--format", "json", "--fail-on", "never", cwd=corpus)
    assert json.loads(a.stdout)["findings"] == json.loads(b.stdout)["findings"]
    assert json.loads(a.stdout)["models"] == json.loads(b.stdout)["models"]


def test_affected_resolves_each_file_as_realpath_does(tmp_path, monkeypatch):
    """The hook's "which models does this commit touch" resolves every file a model read once
    per folder (a workspace's models share most of their folders); each file must still be
    matched exactly as ``os.path.realpath`` would: through a symlinked folder, a symlinked
    file, a dangling symlink, a file that is gone, a relative name and ``..``."""
    import os

    from urdf_lint.core.jobs import ModelReport
    from urdf_lint.discovery.changes import _real, affected
    real = tmp_path / "real"
    (real / "urdf").mkdir(parents=True)
    (real / "urdf" / "a.xacro").write_text("<robot/>")
    (real / "urdf" / "b.xacro").write_text("<robot/>")
    (tmp_path / "link").symlink_to(real)                             # a symlinked folder
    (real / "urdf" / "c.xacro").symlink_to(real / "urdf" / "b.xacro")   # a symlinked file
    (real / "urdf" / "d.xacro").symlink_to(tmp_path / "nowhere")     # dangling
    monkeypatch.chdir(real / "urdf")
    names = [str(tmp_path / "link/urdf/a.xacro"), str(tmp_path / "link/urdf/c.xacro"),
             str(tmp_path / "link/urdf/d.xacro"), str(tmp_path / "link/urdf/gone.xacro"),
             "a.xacro", "c.xacro", "gone.xacro", str(tmp_path / "link/urdf/.."),
             str(tmp_path / "link/urdf/../urdf/b.xacro"), str(tmp_path / "link/urdf/")]
    folders: dict[str, str] = {}
    for f in names:
        want = os.path.realpath(f) if os.path.exists(f) else \
            os.path.join(os.path.realpath(os.path.dirname(f)), os.path.basename(f))
        assert _real(f, folders) == _real(f) == want, f
    m = ModelReport(str(tmp_path / "link/urdf/a.xacro"), {},
                    deps=[str(tmp_path / "link/urdf/c.xacro")],
                    missing=[str(tmp_path / "link/urdf/gone.xacro")])
    other = ModelReport(str(real / "urdf" / "d.xacro"), {})
    hit, unused = affected([m, other], ["b.xacro", "gone.xacro", "../urdf/x.yaml"])
    assert hit == [m] and unused == [str(real / "urdf" / "x.yaml")]
