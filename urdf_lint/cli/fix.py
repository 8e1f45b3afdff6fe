"""The ``check --fix`` / ``--diff`` / ``--add-suppressions`` side of the command line."""
from __future__ import annotations

import sys
from dataclasses import dataclass
from typing import TYPE_CHECKING

from urdf_lint.cli.output import FindingsOutput, write_findings
from urdf_lint.core.emit import report_internal, say
from urdf_lint.core.errors import UsageError

if TYPE_CHECKING:  # pragma: no cover
    from collections.abc import Set as AbstractSet

    from urdf_lint.cli.common import Out
    from urdf_lint.config.schema import Config
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.run.fix import FixOutcome


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


def _summary(outcome: FixOutcome) -> list[str]:
    """What ``--fix`` did, one message per line (each written through :func:`say`)."""
    from urdf_lint.core.locations import display_path
    lines = []
    for p, reason in outcome.refused:
        lines.append(f"{display_path(p.file)}:{p.line}:{p.col}: {p.code} fix not applied: "
                     f"{reason}")
    for p, reason in outcome.rolled_back:
        lines.append(f"{display_path(p.file)}:{p.line}:{p.col}: {p.code} fix rolled back: "
                     f"{reason}")
    from urdf_lint.core.findings import tally
    fixed = tally(outcome.applied)
    files = len(outcome.changed_files)
    remaining = tally(outcome.result.findings).findings
    lines.append(f"Fixed {fixed.phrase('finding' if fixed.findings == 1 else 'findings')} "
                 f"in {files} file{'s' if files != 1 else ''} ({remaining} remaining"
                 + (f", {len(outcome.rolled_back)} fix(es) rolled back" if outcome.rolled_back
                    else "")
                 + (f", {len(outcome.refused)} fix(es) not applied" if outcome.refused else "")
                 + ").")
    return lines


def _add_suppressions(req: FixRequest, cfg: Config, resolver: PackageResolver, out: Out,
                      color_mode: str) -> int:
    from urdf_lint.fix.addsuppress import add_suppressions
    from urdf_lint.core.locations import display_path
    from urdf_lint.run.pipeline import RunRequest, exit_code, run_check
    from dataclasses import replace
    from urdf_lint.run.finish import Scope
    paths = req.report.paths
    request = RunRequest(paths, cfg, resolver, jobs_n=cfg.jobs)
    result = run_check(request)   # every finding gets its comment, the baseline's too
    if result.internal:
        report_internal(result.internal)
        return 2
    n, files, _ = add_suppressions(result.findings, paths)
    result = run_check(replace(request, scope=Scope(tuple(paths), cfg.baseline, out.note)))
    report_internal(result.internal)
    if result.findings:
        write_findings(req.report, cfg, result, out, color_mode, resolver.roots)
    say(f"Added {n} suppression comment{'s' if n != 1 else ''} in {len(files)} "
        f"file{'s' if len(files) != 1 else ''}")
    for f in files:
        say(f"  {display_path(f)}")
    return exit_code(result, cfg.fail_on)


def check_fix(req: FixRequest, cfg: Config, resolver: PackageResolver,
              affected_by: AbstractSet[str] | None, render_dir: str | None, out: Out,
              color_mode: str) -> int:
    from urdf_lint.run.fix import run_fix
    from urdf_lint.run.pipeline import exit_code
    if render_dir:
        raise UsageError("--fix/--diff/--add-suppressions cannot be combined with --render")
    if affected_by is not None:
        raise UsageError("--fix/--diff/--add-suppressions lint every model (a fix must be right "
                         "for all of them); drop --changed-since")
    if req.write_baseline:
        raise UsageError("--fix/--diff cannot be combined with --write-baseline")
    if req.add_suppressions:
        return _add_suppressions(req, cfg, resolver, out, color_mode)
    memo = None
    paths = req.report.paths
    if not req.no_cache:
        from urdf_lint.run.cache import Cache
        from urdf_lint.fix.memo import FixMemo
        cache = Cache.for_paths(paths, cfg)
        memo = FixMemo(cache) if not cache.refused else None
    outcome = run_fix(paths, cfg, resolver, jobs_n=cfg.jobs,
                      unsafe=req.unsafe_fixes, diff_only=req.diff, memo=memo, note=out.note)
    report_internal(outcome.result.internal)
    if req.diff:
        sys.stdout.write(outcome.diff)
        n = len(outcome.applied)
        say(f"Would fix {n} finding{'s' if n != 1 else ''} in "
            f"{len(outcome.changed_files)} file(s).")
        if outcome.result.internal:
            return 2
        return 1 if outcome.diff else 0
    write_findings(req.report, cfg, outcome.result, out, color_mode, resolver.roots)
    for line in _summary(outcome):   # also with -q: what --fix did to the sources
        say(line)
    if req.exit_zero:
        return 2 if outcome.result.internal else 0
    code = exit_code(outcome.result, cfg.fail_on)
    if code == 0 and req.exit_non_zero_on_fix and outcome.changed_files:
        return 1
    return code
