"""Write the findings of a run as ``check`` reports them (baseline, format, ``-o``, ``-q``):
shared by ``check`` and ``check --fix``."""
from __future__ import annotations

import os
import sys
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from urdf_lint.core.emit import safe_lines
from urdf_lint.core.errors import UsageError
from urdf_lint.run.check import write_base as write_base

if TYPE_CHECKING:  # pragma: no cover
    from collections.abc import Iterable

    from urdf_lint.cli.common import Out
    from urdf_lint.config.schema import Config
    from urdf_lint.core.fsbound import StrPath
    from urdf_lint.run.pipeline import CheckResult


@dataclass(frozen=True)
class FindingsOutput:
    """Where and how ``check`` writes its findings."""
    paths: list[str] = field(default_factory=list)   # the linted paths (-o is checked from there)
    output: str | None = None                   # -o FILE
    statistics: bool = False
    show_source: bool = False
    coverage: bool = False          # --coverage (JSON: in the document; text: after it)


def write_findings(opts: FindingsOutput, cfg: Config, result: CheckResult, out: Out,
                   color_mode: str, roots: Iterable[StrPath] | None = None) -> None:
    """The findings of a run as ``check`` reports them: baseline, format, ``-o`` (atomic), ``-q``.
    ``check --fix`` reports what remains through the same function."""
    from urdf_lint.report import registry as report
    from urdf_lint.core.locations import display_path
    if cfg.baseline:   # (hidden by the run's end: urdf_lint.run.finish.scope)
        out.info(f"baseline: {getattr(result, 'baselined', 0)} known finding(s) hidden "
                 f"({display_path(cfg.baseline)})")
    fmt = cfg.output_format or ("github" if os.environ.get("GITHUB_ACTIONS") else "text")
    from urdf_lint.engine.registry import load_rules
    options: dict[str, Any] = dict(
        statistics=opts.statistics, show_source=opts.show_source, quiet=out.quiet,
        roots=None if roots is None else tuple(str(r) for r in roots),
        rules=load_rules() if fmt == "sarif" else None, coverage=opts.coverage)
    if opts.output:
        from urdf_lint.core import fsbound
        try:
            with fsbound.open_write(opts.output, write_base(opts.output, opts.paths)) as f:
                report.write(result, fmt, f, color=color_mode == "always", **options)
        except OSError as e:
            why = getattr(e, "why", None) or e.strerror or e
            raise UsageError(f"cannot write {safe_lines(opts.output)}: {safe_lines(why)}") from None
    elif not (out.quiet and not result.findings and fmt in ("text", "concise", "github")
              and not opts.statistics):
        try:
            report.write(result, fmt, sys.stdout,
                         color=report.use_color(color_mode, sys.stdout), **options)
            sys.stdout.flush()
        except BrokenPipeError:
            from urdf_lint.core.emit import reader_left
            reader_left()     # (the exit status is still the findings')
        except OSError as e:
            from urdf_lint.core.emit import stdout_failed, drop_stdout
            if not stdout_failed(e, certain=True):
                raise
            raise UsageError(drop_stdout(e)) from None
