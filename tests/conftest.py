"""Shared fixtures. Tests read ../shared (the corpus of real robots) when it exists and skip
cleanly when it does not."""
from __future__ import annotations

import functools
import json
import os
import subprocess
import sys
from pathlib import Path
from subprocess import CompletedProcess

import pytest

REPO = Path(__file__).resolve().parents[1]


def _shared() -> Path:
    """``../shared`` beside the checkout, or beside the main checkout of this git worktree."""
    here = REPO.parent / "shared"
    git = REPO / ".git"
    if not here.is_dir() and git.is_file():
        text = git.read_text().strip()
        if text.startswith("gitdir:"):   # <main>/.git/worktrees/<name>
            return Path(text[7:].strip()).resolve().parents[2].parent / "shared"
    return here


SHARED = _shared()
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


def run_main(*args, cwd=None, env=None):
    """:func:`run_cli` in this process: ``urdf_lint.cli.main.main`` with the same working
    directory, environment and result (a ``CompletedProcess``: exit code, stdout, stderr); a
    traceback is an exception that fails the test. Half a second less per run than a
    subprocess: for tests of what the command says and does, not of the process (its start,
    signals, stdin, what a worker writes to the descriptors themselves)."""
    import contextlib
    import io

    from urdf_lint.cli.main import main
    saved_env, saved_cwd = dict(os.environ), os.getcwd()
    out, err = io.StringIO(), io.StringIO()
    try:
        os.environ.pop("GITHUB_ACTIONS", None)
        os.environ.update(env or {})
        os.chdir(cwd or REPO)
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                rc = main([str(a) for a in args])
            except SystemExit as e:         # argparse's usage errors and --help
                rc = e.code if isinstance(e.code, int) else int(e.code is not None)
    finally:
        os.chdir(saved_cwd)
        os.environ.clear()
        os.environ.update(saved_env)
    return CompletedProcess(["urdf-lint", *map(str, args)], rc, out.getvalue(), err.getvalue())


@pytest.fixture(scope="session")
def corpus_report(corpus):
    """``urdf-lint check . --no-cache --format json --fail-on never`` in the corpus, run once
    for the session (the tests that need the whole corpus's findings share it)."""
    p = run_cli("check", ".", "--no-cache", "--format", "json", "--fail-on", "never",
                cwd=corpus, timeout=900)
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


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


def age(root: Path, seconds: float = 60) -> None:
    """Make ``root`` and every file and folder under it look last edited ``seconds`` ago: the
    run memo (urdf_lint/run/runcache.py) ignores inputs that changed in the last seconds (a
    coarse clock could hide a later edit)."""
    import time
    t = time.time() - seconds
    for d, dirs, files in os.walk(root):
        for n in dirs + files:
            os.utime(os.path.join(d, n), (t, t), follow_symlinks=False)
    os.utime(root, (t, t))


# -- unit and e2e ------------------------------------------------------------------------------
# Every test is marked by what it uses, never by a hand-kept list of names: `e2e` when it (its
# body, the module-level helpers it calls, transitively, or its fixtures) runs a subprocess
# (``run_cli``, ``terminated``, ``subprocess``, ``sys.executable``) or reads the corpus (the
# ``corpus`` fixtures, ``corpus_entries`` or a module-level path under ../shared/corpus), or
# lives in one of E2E_FILES; `unit` otherwise (in process: `pytest -m unit` is the inner loop).
# A test marked by hand keeps its marker; marked `unit` against the rule it gets both, and
# tests/test_markers.py fails. A `unit` test that still spawns a program (the rule missed it)
# fails with the command line (see _spawn_audit below).
E2E_NAMES = frozenset({"run_cli", "terminated", "subprocess", "Popen", "executable",
                       "corpus_entries"})
E2E_FIXTURES = frozenset({"corpus", "corpus_resolver", "corpus_report"})
# what the names cannot show: servers started by a plugin's fixture, real consumers
E2E_FILES = {"test_server.py": "the language server runs as a subprocess (pytest-lsp's fixture)",
             "test_consumers.py": "MuJoCo, Pinocchio and PyBullet load each model in a subprocess",
             "test_lsp_preview.py": "the language server runs as a subprocess (pytest-lsp's fixture)",
             "test_srdf_server.py": "the language server runs as a subprocess (pytest-lsp's fixture)",
             "test_server_explore.py": "the language server runs as a subprocess (pytest-lsp's "
                                       "fixture)",
             "test_preview.py": "the preview lints in sandboxed workers and serves over HTTP",
             "test_preview_browser.py": "headless Chromium loads the preview and review pages",
             "test_consumer_verdicts.py": "the consumer harness (bench/consumers) runs each "
                                          "consumer and urdf-lint in subprocesses"}
_TESTS = Path(__file__).resolve().parent


@functools.lru_cache(maxsize=None)
def _ours(filename: str) -> bool:
    """Whether code from ``filename`` is a test file's or tests/support's, to follow. Not this
    file's: its helpers that run something are named above (run_cli, terminated, the corpus
    fixtures), and the rule's own code reads the corpus's path."""
    path = Path(filename).resolve()
    return path.is_relative_to(_TESTS) and path != Path(__file__).resolve()


def _under_corpus(value) -> bool:
    if isinstance(value, (str, Path)) and str(value).startswith(str(CORPUS)):
        return True
    return isinstance(value, (list, tuple)) and any(_under_corpus(v) for v in value[:50])


def _uses_e2e(code, globs: dict, seen: set) -> str | None:
    """Why the code (and the test-suite functions it names, transitively) is end to end, or
    None."""
    if code in seen:
        return None
    seen.add(code)
    for name in code.co_names:
        if name in E2E_NAMES:
            return f"{code.co_name} uses {name}"
        value = globs.get(name)
        if _under_corpus(value):
            return f"{code.co_name} reads the corpus ({name})"
        func = getattr(value, "__wrapped__", value)
        sub = getattr(func, "__code__", None)
        if sub is not None and _ours(sub.co_filename):
            why = _uses_e2e(sub, func.__globals__, seen)
            if why:
                return why
    for const in code.co_consts:
        if hasattr(const, "co_names"):
            why = _uses_e2e(const, globs, seen)
            if why:
                return why
    return None


def kind_of(item) -> tuple[str, str]:
    """("e2e" or "unit", why) for a collected test, by the rule above."""
    path = Path(item.path)
    if path.name in E2E_FILES:
        return "e2e", E2E_FILES[path.name]
    names = set(getattr(item, "fixturenames", ()))
    if names & E2E_FIXTURES:
        return "e2e", f"uses the fixture {sorted(names & E2E_FIXTURES)[0]}"
    params = getattr(getattr(item, "callspec", None), "params", {})
    if any(_under_corpus(v) for v in params.values()):
        return "e2e", "is parametrized with corpus files"
    seen: set = set()
    funcs = [getattr(item, "function", None)]
    info = getattr(item, "_fixtureinfo", None)
    for defs in (info.name2fixturedefs.values() if info else ()):
        funcs += [d.func for d in defs]
    for func in funcs:
        func = getattr(func, "__wrapped__", func)
        code = getattr(func, "__code__", None)
        if code is not None and _ours(code.co_filename):
            why = _uses_e2e(code, func.__globals__, seen)
            if why:
                return "e2e", why
    return "unit", "runs in process"


@pytest.hookimpl(tryfirst=True)
def pytest_cmdline_main(config):
    """``pytest -m unit`` over the whole suite (no test paths given) runs on every core with
    pytest-xdist (``-n auto``): the inner loop's minute (issue 34) is a CPU-bound minute and a
    half on one core. ``-n 0`` runs it in one process; the e2e half and runs of chosen files
    stay in one process. (Called before xdist's own hook, which resolves ``auto``; not in
    xdist's workers, which have ``workerinput``.)"""
    if (config.pluginmanager.has_plugin("xdist") and not hasattr(config, "workerinput")
            and config.option.markexpr.strip() == "unit"
            and config.option.numprocesses is None
            and config.args_source == pytest.Config.ArgsSource.TESTPATHS):
        config.option.numprocesses = "auto"


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    """Mark every test unit or e2e before ``-m`` deselects (tryfirst)."""
    for item in items:
        kind, _ = kind_of(item)
        if not any(item.iter_markers(name=kind)):
            item.add_marker(kind)
    config.stash[_COLLECTED] = list(items)


_COLLECTED = pytest.StashKey[list]()


def collected_items(config) -> list:
    """Every test this session collected (before ``-m``/``-k`` deselected any)."""
    return config.stash.get(_COLLECTED, [])


# A `unit` test that spawns a program (other than those in-process code runs too: git, and
# ctypes.util.find_library's helpers) is one the rule above missed: it fails with the command
# line, so the inner loop stays in process. An audit hook only records (in this process, not in
# forked workers); it never blocks anything.
IN_PROCESS_HELPERS = frozenset({"git", "ldconfig", "gcc", "cc", "ld", "objdump", "uname"})
_MAIN_PID = os.getpid()
_spawned: list | None = None


def _spawn_audit(event, args):
    if event == "subprocess.Popen" and _spawned is not None and os.getpid() == _MAIN_PID:
        argv = args[1] if isinstance(args[1], (list, tuple)) else [args[1]]
        if os.path.basename(str(args[0] or argv[0])) not in IN_PROCESS_HELPERS:
            _spawned.append(" ".join(map(str, argv))[:200])


sys.addaudithook(_spawn_audit)


@pytest.hookimpl(wrapper=True)
def pytest_runtest_call(item):
    global _spawned
    _spawned = [] if any(item.iter_markers(name="unit")) else None
    try:
        result = yield
    finally:
        spawned, _spawned = _spawned, None
    if spawned:
        pytest.fail(f"{item.nodeid} is marked unit but runs a subprocess ({spawned[0]}): "
                    "teach the rule in tests/conftest.py what it uses, or mark it e2e",
                    pytrace=False)
    return result
