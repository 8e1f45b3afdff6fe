"""Optional parts behave the same everywhere (issue 22): without rerun-sdk, ``render`` and
``diff --render`` both make the pictures, say once that there are no recordings, and exit 0;
an unknown flag is one line with the suggestion; ``generate --check`` says what it checked."""
from __future__ import annotations

import os
import shutil
import subprocess

import pytest

from conftest import DESCRIPTIONS, run_cli

NOTE = "note: no .rrd recordings: rerun-sdk is not installed"


@pytest.fixture()
def no_rerun(tmp_path):
    """An environment where ``import rerun`` fails, as in a lint-only install."""
    shadow = tmp_path / "shadow"
    (shadow / "rerun").mkdir(parents=True)
    (shadow / "rerun" / "__init__.py").write_text(
        "raise ImportError(\"No module named 'rerun'\")\n")
    return {"PYTHONPATH": os.pathsep.join([str(shadow), os.environ.get("PYTHONPATH", "")])}


@pytest.fixture()
def repo(tmp_path):
    repo = tmp_path / "repo"
    shutil.copytree(DESCRIPTIONS / "double_pendulum_description",
                    repo / "double_pendulum_description")
    return repo


def test_render_without_rerun_makes_the_pictures(repo, tmp_path, no_rerun):
    out = tmp_path / "snap"
    p = run_cli("render", ".", "--out", out, cwd=repo, env=no_rerun)
    assert p.returncode == 0, p.stderr
    assert p.stderr.count(NOTE) == 1, p.stderr
    assert "snapshot incomplete" not in p.stderr
    assert list(out.glob("*.png")) and not list(out.glob("*.rrd"))
    # --no-rrd: nothing to say
    p = run_cli("render", ".", "--out", out, "--no-rrd", cwd=repo, env=no_rerun)
    assert p.returncode == 0 and NOTE not in p.stderr, p.stderr


@pytest.mark.skipif(shutil.which("git") is None, reason="needs git")
def test_diff_render_without_rerun_says_so(repo, tmp_path, no_rerun):
    def git(*a):
        subprocess.run(["git", "-c", "user.email=t@t", "-c", "user.name=t", *a], cwd=repo,
                       check=True, capture_output=True)
    git("init", "-q")
    git("add", "-A")
    git("commit", "-qm", "init")
    xacro = next((repo / "double_pendulum_description").rglob("*.urdf.xacro"))
    xacro.write_text(xacro.read_text().replace("<robot ", "<!-- changed -->\n<robot ", 1)
                     .replace('name="rod_length" value="1.0"', 'name="rod_length" value="1.5"'))
    out = tmp_path / "review"
    p = run_cli("diff", "HEAD", "--render", out, "--no-cache", cwd=repo, env=no_rerun)
    assert p.returncode == 0, p.stdout + p.stderr
    assert p.stderr.count(NOTE) == 1, p.stderr
    assert list(out.glob("*.png")) and not list(out.glob("*.rrd"))


def test_unknown_flag_is_one_line_with_the_suggestion():
    p = run_cli("check", "--fial-on", "warning", cwd=DESCRIPTIONS)
    assert p.returncode == 2
    assert p.stderr.splitlines() == [
        "urdf-lint check: error: unrecognized arguments: --fial-on (did you mean --fail-on?); "
        "see 'urdf-lint check --help'"], p.stderr
    p = run_cli("chek", ".")
    assert p.returncode == 2 and len(p.stderr.splitlines()) == 1, p.stderr
    assert "did you mean check?" in p.stderr


def test_generate_check_says_what_it_checked(tmp_path):
    from repo_shapes import generated_output_repo
    generated_output_repo(tmp_path)
    (tmp_path / "urdf-lint.toml").write_text(
        '[[models]]\npath = "gen_description/xacro/robot.xacro"\n'
        'output = "gen_description/robot.urdf"\n')
    p = run_cli("generate", "--check", cwd=tmp_path)
    assert p.returncode == 1
    assert p.stdout.splitlines()[-1] == ("urdf-lint generate: 1 generated URDF(s) checked, "
                                         "1 would be regenerated."), p.stdout
    assert run_cli("generate", cwd=tmp_path).returncode == 1
    p = run_cli("generate", "--check", cwd=tmp_path)
    assert p.returncode == 0
    assert p.stdout == "urdf-lint generate: 1 generated URDF(s) checked, all up to date.\n"
    empty = tmp_path / "empty"
    empty.mkdir()
    p = run_cli("generate", "--check", cwd=empty)
    assert p.returncode == 0 and p.stdout.startswith("urdf-lint generate: no generated URDF")
