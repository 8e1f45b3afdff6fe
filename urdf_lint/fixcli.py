"""The ``check --fix`` / ``--diff`` / ``--add-suppressions`` side of the command line."""
from __future__ import annotations

import os
import sys

from .errors import UsageError


def _summary(outcome) -> str:
    from .locations import display_path
    lines = []
    for p, reason in outcome.refused:
        lines.append(f"{display_path(p.file)}:{p.line}:{p.col}: {p.code} fix not applied: "
                     f"{reason}\n")
    for p, reason in outcome.rolled_back:
        lines.append(f"{display_path(p.file)}:{p.line}:{p.col}: {p.code} fix rolled back: "
                     f"{reason}\n")
    n = len(outcome.applied)
    files = len(outcome.changed_files)
    remaining = len(outcome.result.findings)
    lines.append(f"Fixed {n} finding{'s' if n != 1 else ''} in {files} "
                 f"file{'s' if files != 1 else ''} ({remaining} remaining"
                 + (f", {len(outcome.rolled_back)} fix(es) rolled back" if outcome.rolled_back
                    else "")
                 + (f", {len(outcome.refused)} fix(es) not applied" if outcome.refused else "")
                 + ").\n")
    return "".join(lines)


def _add_suppressions(args, cfg, resolver) -> int:
    from . import report
    from .addsuppress import add_suppressions
    from .locations import display_path
    from .pipeline import exit_code, run_check
    result = run_check(args.paths, cfg, resolver, jobs_n=args.jobs or cfg.jobs)
    if result.internal:
        for msg in result.internal:
            sys.stderr.write(f"urdf-lint: internal error (please report): {msg}\n")
        return 2
    n, files, _ = add_suppressions(result.findings, args.paths)
    result = run_check(args.paths, cfg, resolver, jobs_n=args.jobs or cfg.jobs)
    if result.findings:
        report.write(result, args.format or "text", sys.stdout)
    sys.stderr.write(f"Added {n} suppression comment{'s' if n != 1 else ''} in {len(files)} "
                     f"file{'s' if len(files) != 1 else ''}"
                     + "".join(f"\n  {display_path(f)}" for f in files) + "\n")
    return exit_code(result, cfg.fail_on)


def check_fix(args, cfg, resolver, affected_by, render_dir) -> int:
    from . import report
    from .fixrun import run_fix
    from .pipeline import exit_code
    if render_dir:
        raise UsageError("--fix/--diff/--add-suppressions cannot be combined with --render")
    if affected_by is not None:
        raise UsageError("--fix/--diff/--add-suppressions lint every model (a fix must be right for all of them); "
                         "drop --changed-since")
    if args.write_baseline:
        raise UsageError("--fix/--diff cannot be combined with --write-baseline")
    if args.add_suppressions:
        return _add_suppressions(args, cfg, resolver)
    outcome = run_fix(args.paths, cfg, resolver, jobs_n=args.jobs or cfg.jobs,
                      unsafe=args.unsafe_fixes, diff_only=args.diff)
    for msg in outcome.result.internal:
        sys.stderr.write(f"urdf-lint: internal error (please report): {msg}\n")
    if args.diff:
        sys.stdout.write(outcome.diff)
        n = len(outcome.applied)
        sys.stderr.write(f"Would fix {n} finding{'s' if n != 1 else ''} in "
                         f"{len(outcome.changed_files)} file(s).\n")
        if outcome.result.internal:
            return 2
        return 1 if outcome.diff else 0
    result = outcome.result
    if args.baseline:
        from .baseline import filter_baseline
        result.findings = filter_baseline(args.baseline, result.findings)
    fmt = args.format or cfg.format or ("github" if os.environ.get("GITHUB_ACTIONS") else "text")
    if args.output:
        from .sourceedit import write_atomic
        import io
        buf = io.StringIO()
        report.write(result, fmt, buf, statistics=args.statistics, color=False)
        write_atomic(args.output, buf.getvalue().encode("utf-8"))
    elif not (args.quiet and not result.findings):
        report.write(result, fmt, sys.stdout, statistics=args.statistics)
    sys.stderr.write(_summary(outcome))
    code = exit_code(result, cfg.fail_on)
    if code == 0 and getattr(args, "exit_non_zero_on_fix", False) and outcome.changed_files:
        return 1
    return code
