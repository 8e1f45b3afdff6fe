"""Write the findings of a run as ``check`` reports them (baseline, format, ``-o``, ``-q``):
shared by ``check`` and ``check --fix``."""
from __future__ import annotations

import os
import sys

from .errors import UsageError


def safe_lines(s) -> str:
    """Text from a model or a traceback, each line escaped for the terminal."""
    from .report.escape import escape_text
    return "\n".join(escape_text(line) for line in str(s).split("\n"))


def report_internal(messages) -> bool:
    """Each internal error on stderr (they make the exit code 2); whether there was one."""
    for msg in messages:
        sys.stderr.write(f"urdf-lint: internal error (please report): {safe_lines(msg)}\n")
    return bool(messages)


def write_findings(args, cfg, result, out, color_mode) -> None:
    """The findings of a run as ``check`` reports them: baseline, format, ``-o`` (atomic), ``-q``.
    ``check --fix`` reports what remains through the same function."""
    from . import report
    from .locations import display_path
    if cfg.baseline:
        from .baseline import filter_baseline
        before = len(result.findings)
        result.findings = filter_baseline(cfg.baseline, result.findings, out.note)
        out.info(f"baseline: {before - len(result.findings)} known finding(s) hidden "
                 f"({display_path(cfg.baseline)})")
    fmt = cfg.format or ("github" if os.environ.get("GITHUB_ACTIONS") else "text")
    options = dict(statistics=args.statistics, show_source=args.show_source, quiet=out.quiet)
    if getattr(args, "output", None):
        from .atomic import atomic_open
        try:
            with atomic_open(args.output) as f:
                report.write(result, fmt, f, color=color_mode == "always", **options)
        except OSError as e:
            raise UsageError(f"cannot write {args.output}: {e.strerror or e}") from None
    elif not (out.quiet and not result.findings and fmt in ("text", "concise", "github")
              and not args.statistics):
        report.write(result, fmt, sys.stdout, color=report.use_color(color_mode, sys.stdout),
                     **options)
