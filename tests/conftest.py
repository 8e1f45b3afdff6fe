"""Shared fixtures. Tests read ../shared (the corpus of real robots) when it exists and skip
cleanly when it does not."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
SHARED = REPO.parent / "shared"
CORPUS = SHARED / "corpus"
DESCRIPTIONS = REPO / "descriptions"
# the seed robots (descriptions/ also holds the deliberately broken models of the demo)
SEED_PACKAGES = [DESCRIPTIONS / "r2d2_description", DESCRIPTIONS / "double_pendulum_description"]

sys.path.insert(0, str(Path(__file__).resolve().parent / "support"))


def corpus_entries():
    f = CORPUS / "entries.json"
    if not f.is_file():
        return []
    out = []
    for e in json.loads(f.read_text()):
        args = {k: v.replace("{CORPUS}", str(CORPUS)) for k, v in e["args"].items()}
        out.append((e["file"], args))
    return out


@pytest.fixture(scope="session")
def corpus():
    if not (CORPUS / "MANIFEST.md").is_file():
        pytest.skip("../shared/corpus is not present")
    return CORPUS


@pytest.fixture(scope="session")
def corpus_resolver(corpus):
    from urdf_lint.discovery.packages import PackageResolver
    return PackageResolver.build([corpus], extra_roots=[corpus])


def run_cli(*args, cwd=None, env=None, timeout=300, input=None):
    """Run ``urdf-lint`` as a user would; never accept a traceback."""
    e = dict(os.environ)
    e.pop("GITHUB_ACTIONS", None)
    if env:
        e.update(env)
    p = subprocess.run([sys.executable, "-m", "urdf_lint", *map(str, args)], cwd=cwd or REPO,
                       capture_output=True, text=True, env=e, timeout=timeout, input=input)
    assert "Traceback" not in p.stderr, p.stderr
    assert "Traceback" not in p.stdout, p.stdout
    return p


def terminated(*args, cwd, after: float):
    """Run ``urdf-lint ARGS``, send it SIGTERM ``after`` seconds, and return (exit code,
    stdout, stderr); it must end within 10 s of the signal."""
    import signal
    import time
    p = subprocess.Popen([sys.executable, "-m", "urdf_lint", *map(str, args)], cwd=cwd,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        time.sleep(after)
        p.send_signal(signal.SIGTERM)
        out, err = p.communicate(timeout=10)
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
    return p.returncode, out, err


def carried(job, data):
    """What a test's replacement of ``worker.process_job`` reports from inside the worker
    (JSON ``data``), sent back inside a lint result: the parent accepts nothing else."""
    from urdf_lint.core.jobs import ModelReport
    return ModelReport(job.entry, {}, name=json.dumps(data))


def carried_data(report):
    """The ``data`` of :func:`carried` (a report the run made itself, e.g. a limit: as is)."""
    try:
        return json.loads(report.name)
    except (TypeError, ValueError):
        return report


def make_package(root: Path, name: str, files: dict, depends=()) -> Path:
    """Write a ROS-style package: package.xml (declaring ``depends``) plus the given files
    (text or bytes)."""
    from repo_shapes import package_xml, write
    pkg = root / name
    pkg.mkdir(parents=True, exist_ok=True)
    (pkg / "package.xml").write_text(package_xml(name, depends))
    return write(pkg, files)
