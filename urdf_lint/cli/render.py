"""``urdf-lint render``: a .rrd recording and a PNG snapshot per model."""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from urdf_lint.cli.common import (ConfigOptions, Out, clear_stale, load_cfg, no_models_warning,
                                  note_unused, options_from, parse_package_paths,
                                  refuse_symlinked_out, report_snapshots, through_models)
from urdf_lint.cli.parser import add_inputs, add_limits, add_target, add_views
from urdf_lint.core.emit import tell
from urdf_lint.core.errors import UsageError

if TYPE_CHECKING:  # pragma: no cover
    from argparse import Namespace

    from urdf_lint.cli.parser import Formatter, SubParsers


NAME = "render"


def add_parser(sub: SubParsers, raw: Formatter) -> None:
    rd = sub.add_parser("render", help="write .rrd recordings and PNG snapshots",
                        description="Write a .rrd recording and a PNG snapshot per model.")
    rd.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                    help="files or folders (default: .)")
    rd.add_argument("--out", default="snapshots", metavar="DIR",
                    help="output folder (default: snapshots)")
    add_inputs(rd)
    add_limits(rd)
    rd.add_argument("--no-rrd", action="store_true", help="PNG only, no rerun recording")
    add_views(rd)
    add_target(rd)


@dataclass
class RenderOptions:
    """What ``render`` was asked to do (from the command line, or the MCP server's ``render``
    tool: the same typed options, no command line in between)."""
    paths: list[str] = field(default_factory=lambda: ["."])
    out: str = "snapshots"
    no_rrd: bool = False
    package_path: list[str] | None = None
    config: ConfigOptions = field(default_factory=ConfigOptions)


def run(args: Namespace) -> int:
    return render(options_from(RenderOptions, args, config=ConfigOptions.from_args(args)))


def render(o: RenderOptions) -> int:
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import RunRequest, run_check
    for p in o.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    refuse_symlinked_out(o.out, o.paths)
    cfg = load_cfg(o.config, o.paths)
    package_paths = parse_package_paths(o.package_path)
    paths, affected_by, named = list(o.paths), None, set()
    redirect = through_models(o.paths, package_paths, cfg)
    if redirect is not None:
        paths, affected_by, named = [redirect[0]], redirect[1], redirect[2]
    resolver = build_resolver(paths, cfg, package_paths)
    clear_stale(o.out, paths)
    from urdf_lint.run.finish import Scope
    # the pictures and summary.md count what 'check' would report (the baseline too)
    result = run_check(RunRequest(paths, cfg, resolver, jobs_n=cfg.jobs,
                                  render_dir=o.out, render_rrd=not o.no_rrd,
                                  affected_by=affected_by,
                                  scope=Scope(tuple(paths), cfg.baseline, Out().note)))
    note_unused(result, Out(), named)
    no_models_warning(o.paths, result, Out())
    missed = report_snapshots(result, o.out)
    for m in result.models:
        snap = m.snapshot or {}
        for k in ("png", "rrd"):
            if snap.get(k):
                from urdf_lint.core.locations import display_path
                tell(display_path(snap[k]))
    from urdf_lint.core.emit import report_internal
    if report_internal(result.internal):
        return 2
    # a requested model that could not be snapshotted is a failure, not a blank image
    return 1 if missed else 0
