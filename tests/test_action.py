"""The GitHub Action (``action.yml``) as users get it: its steps run as the runner would run them
(bash, with the step's ``env`` and ``if`` evaluated from the inputs), on a repository whose pull
request breaks a joint. Only the ``${{ }}`` forms the action uses are understood: any other
makes the test fail, so the action cannot grow an expression this test does not run.

The install step runs for real, with the ``python3`` on ``PATH`` a Python like the runner's
(not a virtual environment, its standard library marked ``EXTERNALLY-MANAGED``, PEP 668: the
system Python of ubuntu-24.04, and of Debian 12 here). The ``uses:`` steps are played by the
test: ``actions/upload-artifact`` reads the folder it is given as the real one does (following
symlinks) and answers an ``artifact-url``; ``actions/cache`` restores what the test hands it.
SECURITY.md, "The GitHub Action", names these tests."""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest
import yaml

from conftest import DESCRIPTIONS, REPO

pytestmark = pytest.mark.skipif(shutil.which("git") is None, reason="needs git")

ACTION = yaml.safe_load((REPO / "action.yml").read_text())
TOKEN = "ghs_0123456789SecretCheckoutToken"      # what actions/checkout leaves in .git/config
OUTSIDE = "secret-from-outside-the-checkout"     # a file of the runner, beside the checkout
ARTIFACT_URL = "https://github.com/o/r/actions/runs/1/artifacts/2"


def _eval(expr: str, ctx: dict) -> str:
    expr = expr.strip()
    for op, join in (("||", any), ("&&", all)):
        if op in expr:
            parts = [_eval(part, ctx) for part in expr.split(op)]
            if op == "||":
                return next((v for v in parts if v), "")
            return parts[-1] if join(parts) else ""
    m = re.fullmatch(r"(\w[\w.-]*) (==|!=) '([^']*)'", expr)
    if m:
        equal = _eval(m.group(1), ctx) == m.group(3)
        return "true" if equal == (m.group(2) == "==") else ""
    m = re.fullmatch(r"(inputs|github|runner|steps)\.([\w.-]+)", expr)
    assert m, f"action.yml uses an expression this test does not evaluate: {expr}"
    if m.group(1) != "steps":
        return ctx[m.group(1)][m.group(2)]
    step, _, out = m.group(2).partition(".outputs.")
    return ctx["outputs"].get(step, {}).get(out, "")


def _subst(text: str, ctx: dict) -> str:
    return re.sub(r"\$\{\{(.*?)\}\}", lambda m: _eval(m.group(1), ctx), text)


def _upload(workspace: Path, path: str) -> dict:
    """What actions/upload-artifact@v4 would upload from ``path`` (relative to the workspace):
    every file below it, its symlinks followed (as @actions/glob does by default), by name."""
    path = os.path.join(workspace, path) if path else ""
    if not path or not os.path.exists(path):
        return {}
    if os.path.isfile(path):
        return {os.path.basename(path): Path(path).read_bytes()}
    out = {}
    for folder, _dirs, files in os.walk(path, followlinks=True):
        for f in files:
            full = os.path.join(folder, f)
            if os.path.isfile(full):
                out[os.path.relpath(full, path)] = Path(full).read_bytes()
    return out


def run_action(work: Path, inputs: dict, base_ref: str, bin_dir: Path, temp: Path):
    """Run every step of the action with ``RUNNER_TEMP`` = ``temp``; returns the step logs,
    the summary, the final exit code, the ``uses:`` steps that ran (with their inputs), what
    the artifact got, and the steps' outputs."""
    values = {k: str(v.get("default", "")) for k, v in ACTION["inputs"].items()}
    values.update(inputs)
    temp.mkdir(exist_ok=True)
    ctx = {"inputs": values, "outputs": {}, "runner": {"os": "Linux", "temp": str(temp)},
           "github": {"base_ref": base_ref, "run_id": "7", "run_attempt": "1"}}
    summary = temp / "summary.md"
    summary.write_text("")
    logs, used, uploaded, code = {}, [], {}, 0
    for i, step in enumerate(ACTION["runs"]["steps"]):
        sid = step.get("id", str(i))
        if "if" in step and not _eval(re.sub(r"^\$\{\{|\}\}$", "", step["if"].strip()), ctx):
            continue
        if "uses" in step:
            given = {k: _subst(str(v), ctx) for k, v in step["with"].items()}
            used.append((step["uses"], given))
            if step["uses"].startswith("actions/upload-artifact@"):
                uploaded = _upload(work, given["path"])
                ctx["outputs"][sid] = {"artifact-url": ARTIFACT_URL if uploaded else ""}
            continue
        assert step["shell"] == "bash"
        out_file = temp / f"output{i}"
        out_file.write_text("")
        env = {k: v for k, v in os.environ.items()
               if k not in ("GITHUB_ACTIONS", "VIRTUAL_ENV", "PYTHONPATH")}
        env.update({k: _subst(str(v), ctx) for k, v in step.get("env", {}).items()})
        env.update({"GITHUB_OUTPUT": str(out_file), "GITHUB_STEP_SUMMARY": str(summary),
                    "GITHUB_ACTION_PATH": str(REPO), "RUNNER_TEMP": str(temp),
                    "PATH": f"{bin_dir}{os.pathsep}{env['PATH']}"})
        p = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", _subst(step["run"], ctx)],
                           cwd=work, env=env, capture_output=True, text=True, timeout=900)
        logs[sid] = p
        ctx["outputs"][sid] = dict(
            line.split("=", 1) for line in out_file.read_text().splitlines() if "=" in line)
        if p.returncode != 0:
            code = p.returncode
            break
    return SimpleNamespace(logs=logs, summary=summary.read_text(), code=code, used=used,
                           uploaded=uploaded, outputs=ctx["outputs"])


def _runner_python() -> str | None:
    """A Python like the runner's own: not a virtual environment, with venv, its standard
    library marked EXTERNALLY-MANAGED (Debian's and Ubuntu's python3)."""
    probe = ("import sys, sysconfig, os, venv, ensurepip; print(sys.prefix == sys.base_prefix "
             "and os.path.isfile(os.path.join(sysconfig.get_path('stdlib'), "
             "'EXTERNALLY-MANAGED')))")
    for cand in (getattr(sys, "_base_executable", None), "/usr/bin/python3"):
        if cand and os.path.isfile(cand):
            p = subprocess.run([cand, "-I", "-c", probe], capture_output=True, text=True)
            if p.stdout.strip() == "True":
                return cand
    return None


RUNNER_PYTHON = _runner_python()
needs_runner_python = pytest.mark.skipif(
    RUNNER_PYTHON is None, reason="needs a python3 marked EXTERNALLY-MANAGED, with venv "
                                  "(Debian's or Ubuntu's, as on ubuntu-24.04)")


def _git(cwd, *a):
    subprocess.run(["git", *a], cwd=cwd, check=True, capture_output=True)


@pytest.fixture
def pull_request(tmp_path):
    """A description repository (``origin``) whose pull request swaps the limits of a joint,
    checked out as actions/checkout leaves it: the pull request's branch only (no base
    branch), the token in ``.git/config``; ``python3`` on ``PATH`` is the runner's."""
    origin = tmp_path / "origin"
    shutil.copytree(DESCRIPTIONS / "r2d2_description", origin / "r2d2_description")
    _git(origin, "init", "-q", "-b", "main")
    _git(origin, "config", "user.email", "t@example.invalid")
    _git(origin, "config", "user.name", "t")
    _git(origin, "add", "-A")
    _git(origin, "commit", "-qm", "base")
    xacro = origin / "r2d2_description" / "urdf" / "r2d2.urdf.xacro"
    text = xacro.read_text()
    limits = 'lower="${ext[\'lower\']}" upper="${ext[\'upper\']}"'
    assert limits in text, "R2D2's gripper extension has limits"
    text = text.replace(limits, 'lower="${ext[\'upper\']}" upper="${ext[\'lower\']}"')
    xacro.write_text(text)
    line = text[:text.index("lower=\"${ext['upper']}\"")].count("\n") + 1
    _git(origin, "checkout", "-qb", "pr")
    _git(origin, "commit", "-qam", "swap the limits")
    (tmp_path / "secret.txt").write_text(OUTSIDE + "\n")
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    if RUNNER_PYTHON:
        (bin_dir / "python3").symlink_to(RUNNER_PYTHON)
    return SimpleNamespace(origin=origin, tmp=tmp_path, line=line, bin_dir=bin_dir,
                           work=tmp_path / "work", temp=tmp_path / "runner-temp")


def checkout(pr) -> Path:
    """The pull request's branch as actions/checkout leaves it (persist-credentials on)."""
    _git(pr.tmp, "clone", "-q", "--branch", "pr", str(pr.origin), str(pr.work))
    _git(pr.work, "update-ref", "-d", "refs/remotes/origin/main")
    _git(pr.work, "config", "http.https://github.com/.extraheader",
         f"AUTHORIZATION: basic {TOKEN}")
    return pr.work


def untracked(work: Path) -> str:
    """What is in the checkout that git did not check out (ignored files too)."""
    return subprocess.run(["git", "status", "--porcelain", "--ignored"], cwd=work,
                          capture_output=True, text=True, check=True).stdout


@needs_runner_python
def test_the_action_annotates_writes_sarif_and_fails_the_job(pull_request):
    pr = pull_request
    work = checkout(pr)
    r = run_action(work, {}, "main", pr.bin_dir, pr.temp)
    assert r.logs["install"].returncode == 0, r.logs["install"].stderr
    out = r.logs["check"].stdout
    assert re.search(rf"^::error file=r2d2_description/urdf/r2d2\.urdf\.xacro,line={pr.line},"
                     r"col=\d+.*UL302", out, re.M), out + r.logs["check"].stderr
    sarif_path = Path(r.outputs["check"]["sarif"])
    assert sarif_path.parent.parent == pr.temp           # under RUNNER_TEMP
    results = json.loads(sarif_path.read_text())["runs"][0]["results"]
    assert any(x["ruleId"] == "UL302" and x["locations"][0]["physicalLocation"]["region"]
               ["startLine"] == pr.line for x in results), results
    assert r.code == 1                                   # the job fails on the error
    assert [u.split("@")[0] for u, _ in r.used] == ["actions/cache"]
    assert r.summary == ""                               # no review unless asked
    assert untracked(work) == ""                         # nothing written in the checkout


@needs_runner_python
def test_the_action_installs_in_its_own_venv_where_the_system_python_is_externally_managed(
        pull_request):
    """ubuntu-24.04's python3 refuses `pip install` (PEP 668); the action installs urdf-lint in
    a virtual environment of its own, and two fresh installs agree on the build id, so
    actions/cache hands the second run the first run's signed entries and they are used."""
    pr = pull_request
    refused = subprocess.run([str(pr.bin_dir / "python3"), "-I", "-m", "pip", "install",
                              "--dry-run", "--no-deps", "--no-index", str(REPO)],
                             capture_output=True, text=True)
    assert refused.returncode != 0 and ("externally-managed" in refused.stderr
                                        or "No module named pip" in refused.stderr)
    work = checkout(pr)
    first = run_action(work, {"sarif": ""}, "main", pr.bin_dir, pr.temp)
    assert first.logs["install"].returncode == 0, first.logs["install"].stderr
    assert first.code == 1, first.logs["check"].stderr
    venv = Path(first.outputs["install"]["dir"], "venv")
    assert (venv / "pyvenv.cfg").is_file() and (venv / "bin" / "urdf-lint").is_file()
    (_, cache), = [u for u in first.used if u[0].startswith("actions/cache@")]
    build = first.outputs["install"]["build"]
    assert cache["key"].startswith(cache["restore-keys"]) and build in cache["restore-keys"]
    state = Path(cache["path"])
    assert state.parent == pr.temp
    entries = {p: p.stat().st_mtime_ns for p in state.rglob("results/*/*.json")}
    assert entries and (state / "xdg" / "urdf-lint" / "key").is_file()
    # a new job: a fresh RUNNER_TEMP, actions/cache restores the saved folder
    temp2 = pr.tmp / "runner-temp-2"
    temp2.mkdir()
    shutil.copytree(state, temp2 / state.name, symlinks=True)
    second = run_action(work, {"sarif": ""}, "main", pr.bin_dir, temp2)
    assert second.outputs["install"]["build"] == build          # the same cache key
    assert second.outputs["install"]["dir"] != first.outputs["install"]["dir"]
    assert second.code == 1 and second.logs["check"].stdout == first.logs["check"].stdout
    again = {p.relative_to(temp2): p.stat().st_mtime_ns
             for p in (temp2 / state.name).rglob("results/*/*.json")}
    assert again == {p.relative_to(pr.temp): t for p, t in entries.items()}  # no redo
    assert untracked(work) == ""


def test_the_action_installs_with_a_python_that_is_not_externally_managed(pull_request):
    """As after actions/setup-python: python3 is a Python of its own (this test's, which no
    distribution marks), and the action still installs in a virtual environment it makes."""
    pr = pull_request
    base = getattr(sys, "_base_executable", sys.executable)
    (pr.bin_dir / "python3").unlink(missing_ok=True)
    (pr.bin_dir / "python3").symlink_to(base)
    work = checkout(pr)
    r = run_action(work, {"sarif": ""}, "main", pr.bin_dir, pr.temp)
    assert r.logs["install"].returncode == 0, r.logs["install"].stderr
    cfg = Path(r.outputs["install"]["dir"], "venv", "pyvenv.cfg").read_text()
    assert os.path.dirname(os.path.realpath(base)) in cfg or str(Path(base).parent) in cfg
    assert r.code == 1 and "UL302" in r.logs["check"].stdout, r.logs["check"].stderr
    assert untracked(work) == ""


@needs_runner_python
def test_the_review_goes_to_the_job_summary_with_pictures(pull_request):
    pr = pull_request
    work = checkout(pr)
    r = run_action(work, {"review": "true", "sarif": ""}, "main", pr.bin_dir, pr.temp)
    assert "review" in r.logs, r.logs
    assert r.logs["review"].returncode == 0, r.logs["review"].stderr
    assert "r2d2" in r.summary and "UL302" in r.summary, r.summary
    # the base named as the user gave it (fetched from origin), not FETCH_HEAD
    assert "`origin/main`" in r.summary and "FETCH_HEAD" not in r.summary, r.summary
    pictures = r.outputs["review"]["pictures"]
    assert Path(pictures).parent.parent == pr.temp
    assert any(name.endswith(".png") for name in r.uploaded), r.uploaded
    assert [w for u, w in r.used if u.startswith("actions/upload-artifact@")] == [
        {"name": "urdf-lint-review", "path": pictures, "if-no-files-found": "ignore"}]
    assert r.summary.rstrip().endswith("in a browser (no server needed).")
    assert r.summary.count(f"]({ARTIFACT_URL})") == 2            # the pictures are linked
    # ... and the interactive review page, in the same artifact
    assert "`page/index.html`" in r.summary
    assert {"page/index.html", "page/review-data.js", "page/vendor.js"} <= set(r.uploaded)
    assert r.code == 1
    assert untracked(work) == ""


@needs_runner_python
@pytest.mark.parametrize("base", ["main", "no-such-branch"])
def test_a_pull_request_cannot_put_a_file_in_the_summary_or_the_artifact(pull_request, base):
    """The pull request commits ``urdf-lint-review.md`` as a symlink to ``.git/config`` (the
    token) and ``urdf-lint-review/`` holding symlinks to a file outside the checkout and to
    ``.git/config``; with a base that cannot be found the review fails before writing."""
    pr = pull_request
    _git(pr.origin, "checkout", "-q", "pr")
    (pr.origin / "urdf-lint-review.md").symlink_to(".git/config")
    (pr.origin / "urdf-lint-review").mkdir()
    (pr.origin / "urdf-lint-review" / "leak.png").symlink_to("../../secret.txt")
    (pr.origin / "urdf-lint-review" / "config.png").symlink_to("../.git/config")
    (pr.origin / "urdf-lint.sarif").symlink_to("../secret.txt")
    _git(pr.origin, "add", "-A")
    _git(pr.origin, "commit", "-qm", "plant symlinks")
    work = checkout(pr)
    assert TOKEN in (work / "urdf-lint-review.md").read_text()
    inputs = {"review": "true"} if base == "main" else {"review": "true", "base": base}
    r = run_action(work, inputs, "main", pr.bin_dir, pr.temp)
    assert "review" in r.logs, r.logs
    assert r.logs["review"].returncode == (0 if base == "main" else 2), r.logs["review"].stderr
    everything = r.summary + "".join(v.decode("latin-1") for v in r.uploaded.values())
    assert TOKEN not in everything and OUTSIDE not in everything
    assert "extraheader" not in everything
    for name in r.uploaded:                              # only what urdf-lint wrote
        full = Path(r.outputs["review"]["pictures"], name)
        assert not full.is_symlink() and full.suffix in (".png", ".rrd", ".json", ".md",
                                                         ".html", ".js", ".css", ".txt"), name
    sarif = work / r.outputs["check"]["sarif"]     # relative to the workspace, if ever
    assert OUTSIDE not in sarif.read_text() and sarif.parent.parent == pr.temp
    assert untracked(work) == ""


@needs_runner_python
def test_python_never_imports_from_the_checkout(pull_request):
    """A pull request that commits ``pip/``, ``venv/`` and ``urdf_lint/`` packages at the root
    (what ``python -m pip`` run in the checkout would import first) runs none of them."""
    pr = pull_request
    _git(pr.origin, "checkout", "-q", "pr")
    ran = pr.tmp / "ran"
    for pkg in ("pip", "venv", "urdf_lint"):
        (pr.origin / pkg).mkdir()
        for mod in ("__init__.py", "__main__.py"):
            (pr.origin / pkg / mod).write_text(
                f"open({str(ran)!r}, 'a').write({pkg!r} + '\\n')\n")
    _git(pr.origin, "add", "-A")
    _git(pr.origin, "commit", "-qm", "shadow packages")
    work = checkout(pr)
    r = run_action(work, {"sarif": ""}, "main", pr.bin_dir, pr.temp)
    assert r.logs["install"].returncode == 0, r.logs["install"].stderr
    assert not ran.exists(), ran.read_text()
    assert r.code == 1


def _workflows_in_readme() -> list[str]:
    """The workflows docs/ci.md shows (they were the README's)."""
    text = (REPO / "docs" / "ci.md").read_text()
    return [b for b in re.findall(r"```yaml\n(.*?)```", text, re.S) if "runs-on:" in b]


def test_the_documented_workflow_is_least_privilege():
    """docs/ci.md's workflow: no pull_request_target, minimal permissions, no credentials
    left in the checkout, the SARIF uploaded from the action's output."""
    flows = _workflows_in_readme()
    assert flows
    for text in flows:
        flow = yaml.safe_load(text)
        on = flow.get("on", flow.get(True))
        assert "pull_request_target" not in on
        assert flow["permissions"] == {"contents": "read"}
        for job in flow["jobs"].values():
            assert set(job.get("permissions", {})) <= {"contents", "security-events", "actions"}
            steps = job["steps"]
            co = [s for s in steps if str(s.get("uses", "")).startswith("actions/checkout@")]
            assert co and all(s["with"]["persist-credentials"] is False for s in co)
            up = [s for s in steps if "codeql-action/upload-sarif@" in str(s.get("uses"))]
            assert up and "outputs.sarif" in up[0]["with"]["sarif_file"]


def _checked_copy(tmp_path: Path) -> list[Path]:
    """action.yml and docs/ci.md's workflows (the by-hand steps in a workflow of their own)
    in a git repository, with a workflow that uses the action (its inputs get checked)."""
    flows = tmp_path / ".github" / "workflows"
    flows.mkdir(parents=True)
    shutil.copy(REPO / "action.yml", tmp_path / "action.yml")
    files = [tmp_path / "action.yml"]
    text = (REPO / "docs" / "ci.md").read_text()
    blocks = re.findall(r"```yaml\n(.*?)```", text, re.S)
    by_hand = [b for b in blocks if b.startswith("- name:") and "urdf-lint" in b]
    assert by_hand, "docs/ci.md shows the Action's steps by hand"
    for n, b in enumerate(_workflows_in_readme() + by_hand):
        if "runs-on:" not in b:
            b = ("on: [pull_request]\npermissions:\n  contents: read\njobs:\n  by-hand:\n"
                 "    runs-on: ubuntu-24.04\n    steps:\n"
                 + "".join(f"      {line}\n" for line in b.splitlines()))
        files.append(flows / f"readme-{n}.yml")
        files[-1].write_text(b)
    subprocess.run(["git", "init", "-q"], cwd=tmp_path, check=True)
    return files


def test_zizmor_finds_nothing_in_the_action_or_the_documented_workflows(tmp_path):
    zizmor = shutil.which("zizmor", path=f"{Path(sys.executable).parent}{os.pathsep}"
                                         f"{os.environ.get('PATH', '')}")
    if zizmor is None:
        pytest.skip("zizmor is not installed (the test extra has it)")
    files = _checked_copy(tmp_path)
    p = subprocess.run([zizmor, "--offline", "--no-progress", *map(str, files)], cwd=tmp_path,
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stdout + p.stderr


def test_actionlint_and_shellcheck_find_nothing_in_the_action_or_the_documented_workflow(tmp_path):
    actionlint = shutil.which("actionlint") or shutil.which(
        "actionlint", path=str(Path.home() / "go" / "bin"))
    shellcheck = shutil.which("shellcheck")
    if actionlint is None or shellcheck is None:
        pytest.skip("needs actionlint and shellcheck (go install .../actionlint/cmd/actionlint, "
                    "apt-get install shellcheck)")
    _checked_copy(tmp_path)
    (tmp_path / ".github" / "workflows" / "uses-the-action.yml").write_text(
        "on: [pull_request]\npermissions:\n  contents: read\njobs:\n  lint:\n"
        "    runs-on: ubuntu-24.04\n    steps:\n      - id: lint\n        uses: ./\n"
        "        with: {review: \"true\", cache: \"false\"}\n      - run: echo \"$S\"\n"
        "        env: {S: \"${{ steps.lint.outputs.sarif }}\"}\n")
    p = subprocess.run([actionlint, "-shellcheck", shellcheck], cwd=tmp_path,
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stdout + p.stderr
    # actionlint reads a composite action's inputs, not its scripts: shellcheck them
    for step in ACTION["runs"]["steps"]:
        if "run" in step:
            script = "set -eo pipefail\n" + re.sub(r"\$\{\{.*?\}\}", "x", step["run"])
            p = subprocess.run([shellcheck, "-S", "style", "-s", "bash", "-"], input=script,
                               capture_output=True, text=True, timeout=60)
            assert p.returncode == 0, f"{step.get('id')}: {p.stdout}"


def test_the_base_tree_is_extracted_safely_where_tarfile_has_no_filters(tmp_path):
    """The runner's own Python may predate tarfile's filters (Debian 12's 3.11.2): `diff`
    then extracts the base revision keeping what the ``data`` filter keeps, no more."""
    import io
    import tarfile

    from urdf_lint.review.run import _inside
    buf = io.BytesIO()
    with tarfile.open(fileobj=buf, mode="w") as tf:
        def add(name, kind=tarfile.REGTYPE, link="", mode=0o644, data=b"x"):
            info = tarfile.TarInfo(name)
            info.type, info.linkname, info.mode = kind, link, mode
            info.size = len(data) if kind == tarfile.REGTYPE else 0
            tf.addfile(info, io.BytesIO(data) if kind == tarfile.REGTYPE else None)
        add("pkg", tarfile.DIRTYPE, mode=0o755)
        add("pkg/ok.urdf")
        add("pkg/setuid", mode=0o4777)
        add("pkg/near", tarfile.SYMTYPE, "ok.urdf")
        add("../escape")
        add("/abs")
        add("pkg/abs-link", tarfile.SYMTYPE, "/etc/passwd")
        add("pkg/out-link", tarfile.SYMTYPE, "../../outside")
        add("up", tarfile.SYMTYPE, "..")
        add("up/through-the-link")
        add("dev", tarfile.CHRTYPE)
    dest = tmp_path / "tree"
    dest.mkdir()
    buf.seek(0)
    with tarfile.open(fileobj=buf) as tf:
        tf.extractall(dest, members=_inside(tf, dest))
    got = sorted(str(p.relative_to(tmp_path)) for p in tmp_path.rglob("*"))
    # the link up is left out; the file named through it lands inside, as a folder "up"
    assert got == ["tree", "tree/pkg", "tree/pkg/near", "tree/pkg/ok.urdf", "tree/pkg/setuid",
                   "tree/up", "tree/up/through-the-link"], got
    assert not (tmp_path / "through-the-link").exists() and not (dest / "up").is_symlink()
    assert (dest / "pkg" / "setuid").stat().st_mode & 0o7777 == 0o755
