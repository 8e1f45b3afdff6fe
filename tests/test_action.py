"""The GitHub Action (``action.yml``) as users get it: its steps run as the runner would run them
(bash, with the step's ``env`` and ``if`` evaluated from the inputs), on a repository whose pull
request breaks a joint. Only the ``${{ }}`` forms the action uses are understood: any other
makes the test fail, so the action cannot grow an expression this test does not run."""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from conftest import DESCRIPTIONS, REPO

pytestmark = pytest.mark.skipif(shutil.which("git") is None, reason="needs git")

ACTION = yaml.safe_load((REPO / "action.yml").read_text())


def _eval(expr: str, ctx: dict) -> str:
    expr = expr.strip()
    if "||" in expr:
        for part in expr.split("||"):
            v = _eval(part, ctx)
            if v:
                return v
        return ""
    m = re.fullmatch(r"(\w[\w.]*) == '([^']*)'", expr)
    if m:
        return "true" if _eval(m.group(1), ctx) == m.group(2) else ""
    m = re.fullmatch(r"(inputs|github|steps)\.([\w.-]+)", expr)
    assert m, f"action.yml uses an expression this test does not evaluate: {expr}"
    if m.group(1) == "inputs":
        return ctx["inputs"][m.group(2)]
    if m.group(1) == "github":
        return ctx["github"][m.group(2)]
    step, _, out = m.group(2).partition(".outputs.")
    return ctx["outputs"].get(step, {}).get(out, "")


def _subst(text: str, ctx: dict) -> str:
    return re.sub(r"\$\{\{(.*?)\}\}", lambda m: _eval(m.group(1), ctx), text)


def run_action(work: Path, inputs: dict, base_ref: str, bin_dir: Path):
    """Run every step of the action; returns (step logs, the summary, the final exit code,
    the ``uses:`` steps that ran)."""
    values = {k: str(v.get("default", "")) for k, v in ACTION["inputs"].items()}
    values.update(inputs)
    ctx = {"inputs": values, "github": {"base_ref": base_ref}, "outputs": {}}
    summary = work.parent / "summary.md"
    summary.write_text("")
    logs, used, code = {}, [], 0
    for i, step in enumerate(ACTION["runs"]["steps"]):
        if "if" in step and not _eval(re.sub(r"^\$\{\{|\}\}$", "", step["if"].strip()), ctx):
            continue
        if "uses" in step:
            used.append((step["uses"], {k: _subst(str(v), ctx) for k, v in step["with"].items()}))
            continue
        assert step["shell"] == "bash"
        out_file = work.parent / f"output{i}"
        out_file.write_text("")
        env = {k: v for k, v in os.environ.items() if k != "GITHUB_ACTIONS"}
        env.update({k: _subst(str(v), ctx) for k, v in step.get("env", {}).items()})
        env.update({"GITHUB_OUTPUT": str(out_file), "GITHUB_STEP_SUMMARY": str(summary),
                    "GITHUB_ACTION_PATH": str(REPO),
                    "PATH": f"{bin_dir}{os.pathsep}{env['PATH']}"})
        p = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", _subst(step["run"], ctx)],
                           cwd=work, env=env, capture_output=True, text=True, timeout=600)
        logs[step.get("id", i)] = p
        ctx["outputs"][step.get("id", str(i))] = dict(
            line.split("=", 1) for line in out_file.read_text().splitlines() if "=" in line)
        if p.returncode != 0:
            code = p.returncode
            break
    return logs, summary.read_text(), code, used


@pytest.fixture
def pull_request(tmp_path):
    """A description repository with a base commit and a pull request that swaps the limits
    of a joint; a ``python3`` stand-in records what the install step asks pip for (the
    package itself is installed in this environment)."""
    work = tmp_path / "repo"
    shutil.copytree(DESCRIPTIONS / "r2d2_description", work / "r2d2_description")

    def git(*a):
        subprocess.run(["git", *a], cwd=work, check=True, capture_output=True)
    git("init", "-q", "-b", "main")
    git("config", "user.email", "t@example.invalid")
    git("config", "user.name", "t")
    git("add", "-A")
    git("commit", "-qm", "base")
    xacro = work / "r2d2_description" / "urdf" / "r2d2.urdf.xacro"
    text = xacro.read_text()
    limits = 'lower="${ext[\'lower\']}" upper="${ext[\'upper\']}"'
    assert limits in text, "R2D2's gripper extension has limits"
    text = text.replace(limits, 'lower="${ext[\'upper\']}" upper="${ext[\'lower\']}"')
    xacro.write_text(text)
    line = text[:text.index("lower=\"${ext['upper']}\"")].count("\n") + 1
    git("checkout", "-qb", "pr")
    git("commit", "-qam", "swap the limits")
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    for tool in ("urdf-lint",):
        (bin_dir / tool).symlink_to(Path(sys.executable).parent / tool)
    (bin_dir / "python3").write_text(f'#!/bin/sh\necho "$@" >> "{tmp_path}/pip-args"\n')
    (bin_dir / "python3").chmod(0o755)
    return work, line, bin_dir, tmp_path / "pip-args"


def test_the_action_annotates_writes_sarif_and_fails_the_job(pull_request):
    work, line, bin_dir, pip_args = pull_request
    logs, summary, code, used = run_action(work, {}, "main", bin_dir)
    # lint-only install from the action's own checkout by default
    assert pip_args.read_text().split() == ["-m", "pip", "install", "--quiet", str(REPO)]
    out = logs["check"].stdout
    assert re.search(rf"^::error file=r2d2_description/urdf/r2d2\.urdf\.xacro,line={line},"
                     r"col=\d+.*UL302", out, re.M), out + logs["check"].stderr
    sarif = json.loads((work / "urdf-lint.sarif").read_text())
    results = sarif["runs"][0]["results"]
    assert any(r["ruleId"] == "UL302" and r["locations"][0]["physicalLocation"]["region"]
               ["startLine"] == line for r in results), results
    assert code == 1                                     # the job fails on the error
    assert used == [] and summary == ""                  # no review unless asked


def test_the_review_goes_to_the_job_summary_with_pictures(pull_request):
    work, line, bin_dir, pip_args = pull_request
    logs, summary, code, used = run_action(work, {"review": "true", "sarif": ""}, "main", bin_dir)
    assert pip_args.read_text().split()[-1] == f"{REPO}[render]"
    assert "review" in logs, logs
    assert logs["review"].returncode == 0, logs["review"].stderr
    assert "r2d2" in summary and "UL302" in summary, summary
    pictures = sorted(p.suffix for p in (work / "urdf-lint-review").rglob("*.png"))
    assert pictures, list((work / "urdf-lint-review").rglob("*"))
    assert used == [("actions/upload-artifact@v4", {
        "name": "urdf-lint-review", "path": "urdf-lint-review", "if-no-files-found": "ignore"})]
    assert not (work / "urdf-lint.sarif").exists()
    assert code == 1
