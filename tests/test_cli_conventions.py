"""The CLI conventions of issue 9 (ruff's): concise output, --show-source, --exit-zero,
--statistics, --color, -q/-v, help texts, flag typos, --changed-since, baselines, folding,
Ctrl-C, and docs/ci.md's pre-commit snippet. In process where possible."""
from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from types import SimpleNamespace

import pytest
import yaml

from conftest import CORPUS, REPO, make_package, run_cli

from urdf_lint.report import registry as report

from urdf_lint.cli import main as cli
from urdf_lint.cli.main import build_parser, main
from urdf_lint.core.findings import Problem

from test_formats import SRC, X   # a macro-made joint whose limits are swapped (UL302)

FINDING = re.compile(r"^[^\s:][^:]*:\d+:\d+: UL\d{3} ")


@pytest.fixture
def pkg(tmp_path, monkeypatch):
    p = make_package(tmp_path, "p", {"urdf/r.urdf.xacro": SRC})
    monkeypatch.chdir(p)
    for k in ("GITHUB_ACTIONS", "NO_COLOR", "FORCE_COLOR"):
        monkeypatch.delenv(k, raising=False)
    return p


def run(capsys, *args):
    rc = main(list(args))
    out, err = capsys.readouterr()
    return rc, out, err


def test_concise_is_one_parsable_line_per_finding(pkg, capsys):
    rc, out, _ = run(capsys, "check", ".", "--no-cache", "--output-format", "concise")
    assert rc == 1
    lines = out.splitlines()
    assert lines[-1].startswith("Found ")
    body = lines[:-1]
    assert body and all(FINDING.match(ln) for ln in body), body
    assert ("urdf/r.urdf.xacro:4:7: UL302 joint 'elbow': lower 1 > upper 0 (swap them?) "
            "[limit-order] (called from urdf/r.urdf.xacro:7)") in body
    # --format is an alias; -q drops the summary so every line is a finding
    rc, out, _ = run(capsys, "check", ".", "--no-cache", "--format", "concise", "-q")
    assert out.splitlines() == body


def test_show_source_frames_the_xacro_line(pkg, capsys):
    rc, out, _ = run(capsys, "check", ".", "--no-cache", "--select", "UL302", "--show-source")
    lines = out.splitlines()
    i = lines.index("urdf/r.urdf.xacro:4:7: UL302 joint 'elbow': lower 1 > upper 0 (swap them?) "
                    "[limit-order]")
    frame = lines[i + 1:i + 7]
    assert frame[0].strip() == "|"
    assert frame[1] == '  3 |     <joint name="${n}" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>'
    assert frame[2] == '  4 |       <limit lower="1" upper="0" effort="1" velocity="1"/></joint>'
    assert frame[3] == "    |       ^"          # under column 7
    assert frame[4].startswith("  5 |")
    assert lines[i + 7] == "    called from urdf/r.urdf.xacro:7"


def test_exit_zero(pkg, capsys):
    rc, out, _ = run(capsys, "check", ".", "--no-cache", "--exit-zero")
    assert rc == 0 and "UL302" in out
    (pkg / "urdf/r.urdf.xacro").write_text("<robot")
    rc, _, _ = run(capsys, "check", ".", "--no-cache", "--exit-zero", "--select", "UL001")
    assert rc == 0


def test_statistics_prints_only_the_counts(pkg, capsys):
    rc, out, _ = run(capsys, "check", ".", "--no-cache", "--statistics")
    assert rc == 1
    lines = out.splitlines()
    assert lines and all(re.match(r"^\s*\d+  UL\d{3}  \S+\s+(error|warning|info)$", ln) for ln in lines), lines
    assert any(re.match(r"^\s*1  UL302  limit-order\s+error$", ln) for ln in lines)
    rc, out, _ = run(capsys, "check", ".", "--no-cache", "--statistics", "--format", "json")
    stats = json.loads(out)
    assert {"code": "UL302", "name": "limit-order", "severity": "error", "count": 1} in stats


def test_color(pkg, capsys, monkeypatch):
    def colored(*extra):
        return "\033[" in run(capsys, "check", ".", "--no-cache", *extra)[1]
    assert not colored()                         # captured output is not a terminal
    assert colored("--color", "always")
    assert not colored("--color", "never")
    monkeypatch.setenv("FORCE_COLOR", "1")
    assert colored() and not colored("--color", "never")
    monkeypatch.setenv("NO_COLOR", "1")
    assert not colored() and colored("--color", "always")
    rc, _, err = run(capsys, "check", ".", "--color", "sometimes")
    assert rc == 2 and "--color" in err and "auto, always or never" in err


def test_quiet_and_verbose(pkg, capsys):
    rc, out, err = run(capsys, "check", ".", "--no-cache", "-q")
    assert rc == 1 and err == ""
    assert "Found" not in out and "UL302" in out
    (pkg / "urdf/r.urdf.xacro").write_text(SRC.replace('lower="1" upper="0"', 'lower="0" upper="1"'))
    rc, out, err = run(capsys, "check", ".", "--no-cache", "-q", "--select", "UL302")
    assert (rc, out, err) == (0, "", "")
    rc, out, err = run(capsys, "check", ".", "--no-cache", "-v")
    assert "config: none (defaults)" in err
    assert "model: urdf/r.urdf.xacro (model, 0 other file(s) read)" in err
    # a model that includes a file lists it
    (pkg / "urdf/inc.xacro").write_text(f'<robot {X}><xacro:macro name="m"><link name="c"/></xacro:macro></robot>')
    (pkg / "urdf/r.urdf.xacro").write_text(SRC.replace('<link name="a"/>',
                                                       '<xacro:include filename="inc.xacro"/><link name="a"/>'))
    rc, out, err = run(capsys, "check", ".", "--no-cache", "-v")
    assert "model: urdf/r.urdf.xacro (model, 1 other file(s) read)\n    urdf/inc.xacro\n" in err, err
    assert "skipped: urdf/inc.xacro (library)" in err


def _all_parsers():
    p = build_parser()
    yield "urdf-lint", p
    for name, sp in cli.SUBPARSERS.items():
        yield name, sp


def test_every_flag_has_help_and_valued_flags_show_their_default():
    for name, p in _all_parsers():
        for a in p._actions:
            if isinstance(a, (argparse._HelpAction, argparse._SubParsersAction)):
                continue
            assert a.help and len(a.help) > 10, (name, a.dest)
            takes_value = not isinstance(a, (argparse._StoreTrueAction,))
            if takes_value and name != "urdf-lint" and not a.required:
                assert "default:" in a.help, (name, a.dest, a.help)


def test_no_rest_markup_in_help_or_rules(capsys):
    texts = [p.format_help() for _, p in _all_parsers()]
    rc, out, _ = run(capsys, "rules")
    assert rc == 0 and out.count("\n") >= 50
    texts.append(out)
    for code in sorted(re.findall(r"^(UL\d{3}) ", out, re.M)):
        rc, text, _ = run(capsys, "rule", code)
        assert rc == 0
        texts.append(text)
    rc, out, _ = run(capsys, "rule", "UL004")
    assert "`package://pkg`" in out
    for t in texts:
        assert "``" not in t, t[:300]


def test_help_lists_every_registered_format(capsys):
    build_parser()
    h = cli.SUBPARSERS["check"].format_help()
    assert "output formats:\n" in h
    for name, formatter in report.formats().items():
        assert f"\n  {name:<9} {formatter.help}\n" in h + "\n", name
    assert report.names() == _declared_formats(REPO / "urdf_lint" / "report", report.ORDER)
    # diff's formats: the same kind of registry, the same help
    from urdf_lint.report import diff as diff_formats
    h = cli.SUBPARSERS["diff"].format_help()
    for name, formatter in diff_formats.formats().items():
        assert f"\n  {name:<9} {formatter.help}" in h, name
    assert diff_formats.names() == _declared_formats(REPO / "urdf_lint" / "report" / "diff",
                                                     diff_formats.ORDER)


@pytest.mark.parametrize("env", [{}, {"COLUMNS": "50"}, {"COLUMNS": "0"}, {"COLUMNS": "wide"},
                                 {"COLUMNS": "-3"}, {"COLUMNS": "300"}])
def test_help_is_as_wide_as_argparses_own(env, monkeypatch):
    """The parser's formatter takes its width as argparse's own does (through ``shutil``,
    which urdf-lint no longer imports on every run): ``COLUMNS``, else the terminal, else 80."""
    from urdf_lint.cli.parser import Parser, RawDescriptionHelpFormatter, columns
    monkeypatch.delenv("COLUMNS", raising=False)
    for k, v in env.items():
        monkeypatch.setenv(k, v)
    assert columns() == shutil.get_terminal_size().columns
    for ours, theirs in ((Parser, None), (RawDescriptionHelpFormatter,
                                          argparse.RawDescriptionHelpFormatter)):
        made = []
        for cls, kw in ((Parser, {} if theirs is None else {"formatter_class": ours}),
                        (argparse.ArgumentParser, {} if theirs is None else
                         {"formatter_class": theirs})):
            p = cls(prog="x", description="word " * 40 + "\n  a kept line " * 3, **kw)
            p.add_argument("--flag", metavar="VALUE", help="what it does " * 20)
            made.append(p.format_help())
        assert made[0] == made[1], env
        if theirs is None:     # (the raw one keeps the description's lines as they are)
            assert max(map(len, made[0].splitlines())) <= max(columns() - 2, 40), env


def _declared_formats(folder, order) -> tuple:
    """The format names the modules of ``folder`` declare (read as text, not imported), in
    the registry's order: those in ``order`` first, then by name."""
    found = set()
    for f in folder.glob("*.py"):
        found |= set(re.findall(r'^    name = "([a-z0-9-]+)"$', f.read_text(), re.M))
    assert found, folder
    return tuple(sorted(found, key=lambda n: (order.index(n) if n in order else len(order), n)))


def test_flag_typo_gets_one_line_with_did_you_mean(pkg, capsys):
    # one line naming the subcommand and the closest flag (issue 22: the whole usage came
    # first and buried the suggestion)
    rc, out, err = run(capsys, "check", ".", "--selct", "UL1")
    assert rc == 2
    assert err == ("urdf-lint check: error: unrecognized arguments: --selct UL1 (did you mean "
                   "--select?); see 'urdf-lint check --help'\n"), err
    rc, _, err = run(capsys, "hook", "--extnd-select", "UL1")
    assert rc == 2 and err.startswith("urdf-lint hook: error:") and "did you mean --extend-select?" in err
    assert len(err.splitlines()) == 1


def git(*args, cwd):
    subprocess.run(["git", "-c", "user.email=t@t", "-c", "user.name=t", *args], cwd=cwd,
                   check=True, capture_output=True)


@pytest.mark.skipif(shutil.which("git") is None, reason="needs git")
def test_bad_changed_since_ref_is_one_clear_line(pkg, capsys):
    rc, _, err = run(capsys, "check", ".", "--changed-since", "main")
    assert rc == 2 and err.count("\n") == 1 and "not inside a git repository" in err, err
    git("init", "-q", cwd=pkg)
    git("add", "-A", cwd=pkg)
    git("commit", "-qm", "init", cwd=pkg)
    rc, _, err = run(capsys, "check", ".", "--changed-since", "no-such-ref")
    assert rc == 2
    assert err == ("urdf-lint: error: --changed-since no-such-ref: no commit, branch or tag named "
                   "'no-such-ref' (try e.g. origin/main or HEAD~1)\n"), err
    rc, out, err = run(capsys, "check", ".", "--changed-since", "HEAD", "--format", "json")
    assert rc == 0 and json.loads(out)["models"] == []


@pytest.mark.skipif(shutil.which("git") is None, reason="needs git")
def test_baseline_in_hook_and_as_config_key(pkg, capsys):
    git("init", "-q", cwd=pkg)
    rc, _, err = run(capsys, "check", ".", "--write-baseline", "known.json")
    assert rc == 0 and "wrote" in err and "known.json" in err
    assert json.loads((pkg / "known.json").read_text())["findings"]
    rc, out, _ = run(capsys, "hook", "urdf/r.urdf.xacro")
    assert rc == 1 and "UL302" in out
    rc, out, _ = run(capsys, "hook", "--baseline", "known.json", "urdf/r.urdf.xacro")
    assert (rc, out) == (0, "")
    (pkg / "urdf-lint.toml").write_text('baseline = "known.json"\n')
    rc, out, _ = run(capsys, "hook", "urdf/r.urdf.xacro")
    assert (rc, out) == (0, "")
    rc, out, _ = run(capsys, "check", ".", "--format", "json")
    assert rc == 0 and json.loads(out)["findings"] == []
    rc, _, err = run(capsys, "check", ".", "--baseline", "nope.json")
    assert rc == 2 and "cannot read baseline nope.json" in err


def test_in_n_models_is_folded():
    f = Problem.at("UL302", "m", ("a.xacro", 1, 1)).replace(
        name="limit-order", severity="error", models=tuple(f"m{i}.xacro" for i in range(7)))
    result = SimpleNamespace(findings=[f], models=[object()] * 7)
    import io
    s = io.StringIO()
    report.write(result, "text", s, color=False)
    assert "    in 7 models: m0.xacro, m1.xacro, m2.xacro and 4 more\n" in s.getvalue()
    result.findings = [f.replace(models=f.models[:3])]
    s = io.StringIO()
    report.write(result, "text", s, color=False)
    assert "    in 3 models: m0.xacro, m1.xacro, m2.xacro\n" in s.getvalue()


def test_ctrl_c_in_process_exits_130(pkg, capsys, monkeypatch):
    import urdf_lint.run.pipeline as pipeline

    def interrupted(*a, **k):
        raise KeyboardInterrupt
    monkeypatch.setattr(pipeline, "run_check", interrupted)
    rc, _, err = run(capsys, "check", ".", "--no-cache")
    assert rc == 130 and "interrupted" in err


def test_ctrl_c_during_a_real_run_exits_130(corpus, tmp_path):
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    p = subprocess.Popen([sys.executable, "-m", "urdf_lint", "check", str(CORPUS), "--no-cache",
                          "-j", "2", "--format", "json"], cwd=tmp_path, env=env,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True)
    time.sleep(4)
    assert p.poll() is None, "the corpus run ended before it could be interrupted"
    os.killpg(p.pid, signal.SIGINT)          # like Ctrl-C: the whole process group
    out, err = p.communicate(timeout=60)
    assert p.returncode == 130, err
    assert "Traceback" not in err and "interrupted" in err


def documented_precommit_config(kind: str = "remote") -> str:
    """docs/ci.md's ``.pre-commit-config.yaml`` of ``kind``: "local" (a repository where
    urdf-lint is installed) or "remote" (pre-commit installs it from its repository)."""
    text = (REPO / "docs" / "ci.md").read_text()
    blocks = re.findall(r"```yaml\n(.*?)```", text, re.S)
    found = [b for b in blocks if b.startswith("repos:")]
    assert len(found) == 2, blocks
    local = [b for b in found if yaml.safe_load(b)["repos"][0]["repo"] == "local"]
    assert len(local) == 1, found
    return local[0] if kind == "local" else next(b for b in found if b is not local[0])


def test_documented_precommit_snippets_are_complete_configs():
    hooks = {h["id"]: h for h in yaml.safe_load((REPO / ".pre-commit-hooks.yaml").read_text())}
    doc = yaml.safe_load(documented_precommit_config("remote"))
    assert list(doc) == ["repos"]
    (repo,) = doc["repos"]
    assert repo["repo"].endswith("/urdf-lint") and repo["rev"] == "v0.1.0"
    assert [h["id"] for h in repo["hooks"]] == ["urdf-lint"] and "urdf-lint" in hooks
    # the local form runs the same hook as the published one
    (local,) = yaml.safe_load(documented_precommit_config("local"))["repos"]
    (hook,) = local["hooks"]
    published = hooks["urdf-lint"]
    for key in ("entry", "args", "files", "always_run", "require_serial", "verbose"):
        assert hook.get(key) == published.get(key), key
    assert hook["language"] == "system"


def test_output_file_is_written_atomically_and_never_half(pkg, capsys, monkeypatch):
    target = pkg / "report.json"
    target.write_text("old")
    from urdf_lint.report import json as json_format

    def broken(self, result):
        self.stream.write("{ half")
        raise RuntimeError("disk full")
    monkeypatch.setattr(json_format.JsonFormatter, "write", broken)
    rc, _, err = run(capsys, "check", ".", "--no-cache", "--format", "json", "-o", str(target))
    assert rc == 2 and "internal error" in err
    assert target.read_text() == "old"
    assert [p.name for p in pkg.iterdir() if ".tmp" in p.name] == []


def test_one_atomic_write_helper():
    """No module writes a temporary file and renames it by itself: they use urdf_lint.core.fsbound
    (the file-system boundary; it replaced urdf_lint.atomic)."""
    offenders = []
    for path in sorted((REPO / "urdf_lint").rglob("*.py")):
        if path.name == "fsbound.py":
            continue
        text = path.read_text()
        if "os.replace(" in text or "os.rename(" in text or ".tmp" in text:
            offenders.append(str(path.relative_to(REPO)))
    assert offenders == []


def test_adding_a_diff_format_is_adding_one_file(monkeypatch, tmp_path):
    """A module with a DiffFormatter subclass in urdf_lint/report/diff/ is a format of
    ``urdf-lint diff``: its --format choices and help come from that registry."""
    import io
    from urdf_lint.report import diff as diff_formats
    from urdf_lint.review.run import DiffResult
    extra = tmp_path / "diff_formats"
    extra.mkdir()
    (extra / "count_only.py").write_text(
        "from urdf_lint.report.diff.base import DiffFormatter\n\n\n"
        "class CountOnly(DiffFormatter):\n"
        "    name = 'count'\n"
        "    help = 'only the number of models'\n\n"
        "    def render(self, result):\n"
        "        return f'{len(result.models)}\\n'\n")
    monkeypatch.setattr(diff_formats, "__path__", [*diff_formats.__path__, str(extra)])
    monkeypatch.setattr(diff_formats, "_FORMATS", None)
    monkeypatch.delitem(sys.modules, "urdf_lint.report.diff.count_only", raising=False)
    try:
        assert "count" in diff_formats.names()
        args = build_parser().parse_args(["diff", "HEAD", "--format", "count"])
        assert args.format == "count"
        assert "  count     only the number of models" in cli.SUBPARSERS["diff"].format_help()
        out = io.StringIO()
        diff_formats.write(DiffResult("a", "b"), "count", out)
        assert out.getvalue() == "0\n"
    finally:
        sys.modules.pop("urdf_lint.report.diff.count_only", None)
    monkeypatch.setattr(diff_formats, "_FORMATS", None)


def test_adding_a_format_is_adding_one_file(pkg, capsys, monkeypatch, tmp_path):
    """A module with a BaseFormatter subclass in urdf_lint/report/ is a format: the CLI's
    choices, help and config key all come from the registry."""
    extra = tmp_path / "formats"
    extra.mkdir()
    (extra / "codes_only.py").write_text(
        "from urdf_lint.report.base import BaseFormatter\n\n\n"
        "class CodesOnly(BaseFormatter):\n"
        "    name = 'codes'\n"
        "    help = 'only the codes'\n\n"
        "    def handle(self, f):\n"
        "        self.stream.write(f.code + '\\n')\n")
    import urdf_lint.report as package
    monkeypatch.setattr(package, "__path__", [*package.__path__, str(extra)])
    monkeypatch.setattr(report, "_FORMATS", None)
    monkeypatch.delitem(sys.modules, "urdf_lint.report.codes_only", raising=False)
    try:
        assert "codes" in report.names()
        rc, out, _ = run(capsys, "check", ".", "--no-cache", "--output-format", "codes",
                         "--select", "UL302")
        assert (rc, out) == (1, "UL302\n")
        (pkg / "urdf-lint.toml").write_text('format = "codes"\n')
        rc, out, _ = run(capsys, "check", ".", "--no-cache", "--select", "UL302")
        assert (rc, out) == (1, "UL302\n")
        build_parser()
        assert "  codes     only the codes" in cli.SUBPARSERS["check"].format_help()
    finally:
        sys.modules.pop("urdf_lint.report.codes_only", None)
    monkeypatch.setattr(report, "_FORMATS", None)


def test_each_command_is_one_module_and_argparse_stays_in_cli():
    """cli/<command>.py per command (its parser and its run); argparse is imported only
    inside urdf_lint/cli/, and nothing builds an argparse.Namespace by hand (commands hand
    typed options to the layers below)."""
    import ast
    from urdf_lint.cli.main import COMMANDS, command_module
    for name in COMMANDS:
        mod = command_module(name)
        assert mod.__name__ == f"urdf_lint.cli.{name}"
        assert callable(mod.add_parser), name
        assert callable(getattr(mod, "run", None) or getattr(mod, f"cmd_{name}", None)), name
    offenders = []
    for path in sorted((REPO / "urdf_lint").rglob("*.py")):
        rel = path.relative_to(REPO / "urdf_lint").as_posix()
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                names = [node.module or ""]
            else:
                names = []
            if "argparse" in names and not rel.startswith("cli/"):
                offenders.append(f"{rel}:{node.lineno}: imports argparse")
            if (isinstance(node, ast.Attribute) and node.attr == "Namespace"
                    and isinstance(node.value, ast.Name) and node.value.id == "argparse"):
                offenders.append(f"{rel}:{node.lineno}: argparse.Namespace")
    assert offenders == []


def test_a_run_that_exits_0_with_errors_says_where_fail_on_never_was_set(tmp_path):
    """A config file found by looking up from the linted folder may sit above the repository:
    a run it makes exit 0 despite errors says so, naming the file."""
    (tmp_path / "pyproject.toml").write_text('[tool.urdf-lint]\nfail-on = "never"\n')
    pkg = make_package(tmp_path / "repo", "p", {"urdf/r.urdf": (
        '<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="revolute">'
        '<parent link="a"/><child link="b"/><limit lower="2" upper="-2" effort="1" '
        'velocity="1"/></joint></robot>\n')})
    p = run_cli("check", ".", "--no-cache", cwd=pkg)
    assert p.returncode == 0 and "UL302" in p.stdout, p.stdout + p.stderr
    assert 'fail-on = "never" is set in' in p.stderr and "pyproject.toml" in p.stderr, p.stderr
    p = run_cli("check", ".", "--no-cache", "--fail-on", "error", cwd=pkg)
    assert p.returncode == 1 and "fail-on" not in p.stderr, p.stderr
    (tmp_path / "pyproject.toml").unlink()
    p = run_cli("check", ".", "--no-cache", "--fail-on", "never", cwd=pkg)   # typed: not echoed
    assert p.returncode == 0 and "fail-on" not in p.stderr, p.stderr
