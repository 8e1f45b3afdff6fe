"""Start-up stays light: a warm (cached) run imports none of xacro, trimesh, yourdfpy, rerun;
one that reuses the last run's whole result not the fix machinery either (the fix-scope rule,
which every run's end applies, is a light module of its own)."""
from __future__ import annotations

import shutil
import subprocess
import sys

from conftest import DESCRIPTIONS, age

CODE = """
import sys
from urdf_lint.cli.main import main
rc = main(["check", ".", "-q"])
heavy = sorted(m for m in ("xacro", "trimesh", "yourdfpy", "rerun", "collada", "PIL") if m in sys.modules)
print(rc, heavy, "urdf_lint.fix.fixes" in sys.modules)
# (stdlib modules a run without a mistake, a TOML config or help does not need: ~10 ms)
print(sorted(m for m in ("difflib", "tomllib", "shutil", "datetime") if m in sys.modules))
"""


def test_warm_run_imports_nothing_heavy(tmp_path):
    shutil.copytree(DESCRIPTIONS / "r2d2_description", tmp_path / "r2d2_description")
    run = lambda: subprocess.run([sys.executable, "-c", CODE], cwd=tmp_path,  # noqa: E731
                                 capture_output=True, text=True)
    first = run()
    # cold: expands, and the rules loaded ahead of the workers attach fix requests
    assert first.stdout.splitlines()[0] == "0 ['xacro'] True", first.stdout + first.stderr
    age(tmp_path, 3600)    # (the first run made the cache folder; the memo trusts old inputs)
    warm = run()           # every model's result from the cache; the run's end made again
    assert warm.stdout.startswith("0 [] "), warm.stdout + warm.stderr
    memo = run()           # the whole result of the last run
    assert memo.stdout.splitlines() == ["0 [] False", "[]"], memo.stdout + memo.stderr
    assert warm.stdout.splitlines()[1] == "[]", warm.stdout


LINT_IN_PROCESS = """
import sys
from urdf_lint.config.schema import load_config
from urdf_lint.discovery.discover import build_resolver, discover
from urdf_lint.engine.lint import run_job
from urdf_lint.run.pipeline import settings_for
cfg = load_config(None)
cfg.ignore = IGNORE
settings = settings_for(cfg, build_resolver(["."], cfg), None)
results = [run_job(job, settings) for job in discover(["."], cfg)]
assert [r.status for r in results].count("model") == 1, results
print(sorted(m for m in ("trimesh", "collada", "yourdfpy", "rerun", "urdf_lint.meshes.readers")
             if m in sys.modules))
"""


def test_mesh_loading_only_when_a_rule_needs_it(tmp_path):
    shutil.copytree(DESCRIPTIONS / "r2d2_description", tmp_path / "r2d2_description")
    run = lambda ignore: subprocess.run(  # noqa: E731
        [sys.executable, "-c", LINT_IN_PROCESS.replace("IGNORE", repr(ignore))], cwd=tmp_path,
        capture_output=True, text=True)
    from urdf_lint.engine.registry import load_rules
    mesh_rules = sorted(c for c, r in load_rules().items() if "meshes" in r.needs)
    assert {"UL404", "UL406", "UL605", "UL606", "UL607"} <= set(mesh_rules)
    p = run(mesh_rules)
    assert p.stdout.strip() == "[]", p.stdout + p.stderr
    p = run([])
    # the rules read R2D2's STL meshes, with urdf-lint's own readers: no trimesh (issue 12)
    assert p.stdout.strip() == "['urdf_lint.meshes.readers']", p.stdout + p.stderr


EXPAND = """
import sys
from urdf_lint.cli.main import main
rc = main(["expand", "r2d2_description/urdf/r2d2.urdf.xacro", "-o", "out.urdf"])
print(rc, sorted(m for m in ("urdf_lint.report", "xacro", "urdf_lint.expansion.expand")
                 if m in sys.modules))
"""


def test_expand_builds_only_its_parser_and_expands_in_the_worker(tmp_path):
    """`urdf-lint expand` stays a start-up-sized command: the parent builds only the expand
    parser (no output-format registry) and leaves xacro to the worker it forked first."""
    shutil.copytree(DESCRIPTIONS / "r2d2_description", tmp_path / "r2d2_description")
    p = subprocess.run([sys.executable, "-c", EXPAND], cwd=tmp_path, capture_output=True,
                       text=True, timeout=60)
    assert p.stdout.strip() == "0 []", p.stdout + p.stderr
    assert (tmp_path / "out.urdf").read_text().count("<link ") == 17


def test_expand_usage_error_after_the_worker_was_forked(tmp_path):
    """The worker forked ahead of the settings is stopped cleanly when the run ends early: one
    diagnostic, exit 2, no traceback from the child, no hang waiting for it."""
    shutil.copytree(DESCRIPTIONS / "r2d2_description", tmp_path / "r2d2_description")
    p = subprocess.run([sys.executable, "-m", "urdf_lint", "expand",
                        "r2d2_description/urdf/r2d2.urdf.xacro", "not-a-mapping"],
                       cwd=tmp_path, capture_output=True, text=True, timeout=30)
    assert p.returncode == 2
    assert p.stderr == "urdf-lint: error: expected name:=value, got not-a-mapping\n"
