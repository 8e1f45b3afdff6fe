"""The ``check --fix`` / ``--diff`` / ``--add-suppressions`` side of the command line."""
from __future__ import annotations

import sys
from dataclasses import dataclass
from typing import TYPE_CHECKING

from urdf_lint.cli.output import FindingsOutput, write_findings
from urdf_lint.core.emit import report_internal, say
from urdf_lint.core.errors import UsageError
from urdf_lint.core.findings import exit_status

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.cli.common import Out
    from urdf_lint.core.findings import Problem
    from urdf_lint.run.check import Prepared
    from urdf_lint.run.fix import FixOutcome
    from urdf_lint.run.pipeline import CheckResult


@dataclass(frozen=True)
class FixRequest:
    """What ``check --fix``/``--diff``/``--add-suppressions`` was asked to do."""
    report: FindingsOutput              # how the remaining findings are written (its paths)
    write_baseline: str | None = None
    add_suppressions: bool = False
    no_cache: bool = False
    unsafe_fixes: bool = False
    diff: bool = False
    exit_zero: bool = False
    exit_non_zero_on_fix: bool = False


def _lines(fixes: "list[tuple[Problem, str]]", what: str) -> list[str]:
    """One line per fix ``what`` (not applied, rolled back) with why: a finding of many
    instances (a macro called for each finger, a YAML value every variant reads) has one fix
    at one place, named once, as the report names the finding once."""
    from urdf_lint.core.locations import display_path
    return list(dict.fromkeys(f"{display_path(p.file)}:{p.line}:{p.col}: {p.code} fix {what}: "
                              f"{reason}" for p, reason in fixes))


def _summary(outcome: FixOutcome) -> list[str]:
    """What ``--fix`` did, one message per line (each written through :func:`say`)."""
    refused = _lines(outcome.refused, "not applied")
    rolled = _lines(outcome.rolled_back, "rolled back")
    from urdf_lint.core.findings import tally
    fixed = tally(outcome.applied)
    files = len(outcome.changed_files)
    remaining = tally(outcome.result.findings).findings
    return refused + rolled + [
        f"Fixed {fixed.phrase('finding' if fixed.findings == 1 else 'findings')} "
        f"in {files} file{'s' if files != 1 else ''} ({remaining} remaining"
        + (f", {len(rolled)} fix(es) rolled back" if rolled else "")
        + (f", {len(refused)} fix(es) not applied" if refused else "") + ")."]


def _add_suppressions(req: FixRequest, prep: Prepared, out: Out, color_mode: str) -> int:
    from urdf_lint.core.locations import display_path
    from urdf_lint.run.check import add_suppressions
    done = add_suppressions(prep, out)
    result = done.result
    report_internal(result.internal)
    if done.failed:
        return 2
    if result.findings:
        write_findings(req.report, prep.cfg, result, out, color_mode, prep.resolver.roots)
    n, files = done.added, done.files
    say(f"Added {n} suppression comment{'s' if n != 1 else ''} in {len(files)} "
        f"file{'s' if len(files) != 1 else ''}")
    for f in files:
        say(f"  {display_path(f)}")
    return _exit(result, prep.cfg.fail_on)


def _exit(result: "CheckResult", fail_on: str) -> int:
    return exit_status([f.severity for f in result.findings], bool(result.internal), fail_on)


def check_fix(req: FixRequest, prep: Prepared, out: Out, color_mode: str) -> int:
    """``check --fix``/``--diff``/``--add-suppressions`` of a prepared run: the flags checked,
    the work done by :mod:`urdf_lint.run.check`, what it did printed."""
    from urdf_lint.run.check import fix
    if prep.request.render:
        raise UsageError("--fix/--diff/--add-suppressions cannot be combined with --render")
    if prep.affected_by is not None:
        raise UsageError("--fix/--diff/--add-suppressions lint every model (a fix must be right "
                         "for all of them); drop --changed-since")
    if req.write_baseline:
        raise UsageError("--fix/--diff cannot be combined with --write-baseline")
    if req.add_suppressions:
        return _add_suppressions(req, prep, out, color_mode)
    outcome = fix(prep, out, unsafe=req.unsafe_fixes, diff_only=req.diff)
    report_internal(outcome.result.internal)
    if req.diff:
        sys.stdout.write(outcome.diff)
        n = len(outcome.applied)
        for line in _lines(outcome.refused, "not applied"):
            say(line)
        say(f"Would fix {n} finding{'s' if n != 1 else ''} in "
            f"{len(outcome.changed_files)} file(s).")
        if outcome.result.internal:
            return 2
        return 1 if outcome.diff else 0
    write_findings(req.report, prep.cfg, outcome.result, out, color_mode, prep.resolver.roots)
    for line in _summary(outcome):   # also with -q: what --fix did to the sources
        say(line)
    if req.exit_zero:
        return 2 if outcome.result.internal else 0
    code = _exit(outcome.result, prep.cfg.fail_on)
    if code == 0 and req.exit_non_zero_on_fix and outcome.changed_files:
        return 1
    return code
