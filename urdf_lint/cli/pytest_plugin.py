"""urdf-lint as pytest tests: every robot model is a test item that fails with its findings.

Installed as a ``pytest11`` entry point, so ``pytest --urdf-lint`` works wherever urdf-lint is
installed; it does nothing without the flag, or the ini option ``urdf_lint = true`` (in
``pytest.ini``, ``setup.cfg``'s ``[tool:pytest]`` or ``pyproject.toml``'s
``[tool.pytest.ini_options]``), which is how ``colcon test`` on an ``ament_python`` package runs
it with no ROS-specific code. ``urdf_lint_paths`` (ini, default: the rootdir) says what to lint.

The lint is one ``urdf-lint check --format json`` run of the paths (the command itself, in a
subprocess: the same discovery, sandboxed workers, ``[tool.urdf-lint]`` config, suppressions,
baseline and cache as on the command line). Each model becomes an item named after it (with its
xacro args); it fails when a finding in it is at or above the config's ``fail-on`` severity,
and its report lists those findings at their source lines. Findings that belong to no single
model (run-wide rules) are one more item; a run that could not complete is an error.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from typing import TYPE_CHECKING, Any

import pytest

if TYPE_CHECKING:  # pragma: no cover
    from _pytest._code.code import TerminalRepr, TracebackStyle

_RANK = {"info": 0, "warning": 1, "error": 2, "never": 3}


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("urdf-lint")
    group.addoption("--urdf-lint", action="store_true", default=False,
                    help="lint every robot model (URDF/xacro) as a test item")
    parser.addini("urdf_lint", type="bool", default=False,
                  help="lint every robot model as a test item (as --urdf-lint)")
    parser.addini("urdf_lint_paths", type="args", default=[],
                  help="files or folders to lint with --urdf-lint (default: the rootdir)")


def _enabled(config: pytest.Config) -> bool:
    return bool(config.getoption("urdf_lint") or config.getini("urdf_lint"))


class UrdfLintError(Exception):
    """A model's findings at or above fail-on: the item's failure."""


class ModelItem(pytest.Item):
    """One robot model (one entry file with one set of xacro args)."""

    def __init__(self, *, label: str, findings: list[dict[str, Any]], fail_on: str, failed: bool,
                 **kw: Any) -> None:
        super().__init__(**kw)
        self.label = label
        self.findings = findings
        self.fail_on = fail_on
        self.failed = failed
        self.add_marker("urdf_lint")

    def runtest(self) -> None:
        bad = [f for f in self.findings if _RANK[f["severity"]] >= _RANK[self.fail_on]]
        if bad or self.failed:
            raise UrdfLintError(bad)

    def repr_failure(self, excinfo: pytest.ExceptionInfo[BaseException],
                     style: TracebackStyle | None = None) -> str | TerminalRepr:
        if isinstance(excinfo.value, UrdfLintError):
            bad = excinfo.value.args[0]
            own = [i for f in bad for i in _own_instances(f, self.label)]
            n = f"{len(bad)} finding(s)" + (f" ({len(own)} instances)" if len(own) != len(bad)
                                            else "")
            lines = [f"{self.label}: {n} at or above '{self.fail_on}'"
                     + ("" if bad or not self.failed else " (the model did not expand)")]
            lines += [_finding_line(i) for i in own]
            return "\n".join(lines)
        return super().repr_failure(excinfo)

    def reportinfo(self) -> tuple[os.PathLike[str] | str, int | None, str]:
        return self.path, None, f"urdf-lint {self.label}"


class RunItem(pytest.Item):
    """The run itself: fails when urdf-lint could not complete (a usage or config error, an
    internal error), with what it said."""

    def __init__(self, *, problem: str, **kw: Any) -> None:
        super().__init__(**kw)
        self.problem = problem

    def runtest(self) -> None:
        if self.problem:
            raise UrdfLintError(self.problem)

    def repr_failure(self, excinfo: pytest.ExceptionInfo[BaseException],
                     style: TracebackStyle | None = None) -> str | TerminalRepr:
        if isinstance(excinfo.value, UrdfLintError):
            return str(excinfo.value.args[0])
        return super().repr_failure(excinfo)

    def reportinfo(self) -> tuple[os.PathLike[str] | str, int | None, str]:
        return self.path, None, "urdf-lint run"


def _finding_line(f: dict[str, Any]) -> str:
    s = f"  {f['file']}:{f['line']}:{f['col']}: {f['code']} {f['severity']}: {f['message']}"
    for file, line, *_ in f.get("chain") or ():
        s += f"\n      called from {file}:{line}"
    return s


def _own_instances(finding: dict[str, Any], label: str) -> list[dict[str, Any]]:
    """What ``finding`` is in the model ``label``: a finding at a macro line that several
    models reach is one finding whose ``instances`` say which element, message and call chain
    belong to which model; a model's item shows its own (all of them), never another model's."""
    own = [i for i in finding.get("instances") or () if label in (i.get("models") or ())]
    return own or [finding]


def _label(model: dict[str, Any]) -> str:
    """The label urdf-lint gives a model (``jobs.ModelReport.label``): its entry, then its
    args as ``[k:=v ...]``."""
    label: str = model["entry"]
    if model.get("args"):
        label += " [" + " ".join(f"{k}:={v}" for k, v in sorted(model["args"].items())) + "]"
    return label


def _fail_on(path: str) -> str:
    """The ``fail-on`` of the config the command found for ``path`` (the run has succeeded,
    so the config is valid)."""
    from urdf_lint.config.schema import find_config, load_config
    return load_config(find_config(path)).fail_on


def _run(paths: list[str], rootdir: str) -> tuple[dict[str, Any] | None, str]:
    """(the JSON report, what went wrong): one ``urdf-lint check`` of ``paths``."""
    cmd = [sys.executable, "-m", "urdf_lint", "check", "--format", "json", "--exit-zero",
           "--", *paths]
    p = subprocess.run(cmd, cwd=rootdir, capture_output=True, text=True,
                       stdin=subprocess.DEVNULL)
    if p.returncode != 0:
        return None, (f"urdf-lint check exited {p.returncode}:\n{p.stderr.strip()}"
                      or "urdf-lint check failed")
    try:
        return json.loads(p.stdout), ""
    except ValueError:
        return None, f"urdf-lint check printed no JSON report:\n{p.stderr.strip()}"


def _nodeid(name: str) -> str:
    """``urdf_lint::NAME``: the items hang off the session, whose node id is empty, so pytest
    would make ``::NAME`` of them, and JUnit's classname (``--junit-prefix`` + the id's part
    before the name) would end with a dot; ``urdf_lint`` is the class every model test is in."""
    return f"urdf_lint::{name}"


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(session: pytest.Session, config: pytest.Config,
                                  items: list[pytest.Item]) -> None:
    """Add one item per model before ``-k``/``-m`` selection (which then applies to them)."""
    if not _enabled(config):
        return
    rootdir = str(config.rootpath)
    paths = list(config.getini("urdf_lint_paths")) or ["."]
    report, problem = _run(paths, rootdir)
    if report is None:
        items.append(RunItem.from_parent(session, name="urdf-lint", nodeid=_nodeid("urdf-lint"),
                                         problem=problem))
        return
    fail_on = _fail_on(os.path.join(rootdir, paths[0]))
    by_model: dict[str, list[dict[str, Any]]] = {}
    for f in report["findings"]:
        for label in f.get("models") or [""]:
            by_model.setdefault(label, []).append(f)
    for m in report["models"]:
        label = _label(m)
        items.append(ModelItem.from_parent(
            session, name=label, nodeid=_nodeid(label), label=label,
            findings=by_model.get(label, []), fail_on=fail_on,
            failed=m.get("status") == "failed"))
    if by_model.get(""):
        name = "urdf-lint (run-wide rules)"
        items.append(ModelItem.from_parent(
            session, name=name, nodeid=_nodeid(name), label="run-wide rules",
            findings=by_model[""], fail_on=fail_on, failed=False))


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line("markers", "urdf_lint: a robot model linted by urdf-lint")
