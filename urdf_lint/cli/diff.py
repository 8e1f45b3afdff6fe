"""``urdf-lint diff BASE [HEAD]``: what a change did to the robots (:mod:`urdf_lint.review`),
in any of diff's output formats (:mod:`urdf_lint.report.diff`)."""
from __future__ import annotations

import os
import sys
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from urdf_lint.cli.common import (ConfigOptions, load_cfg, no_recordings_note, options_from,
                                  parse_package_paths, refuse_symlinked_out, safe_text,
                                  write_base)
from urdf_lint.cli.parser import add_target, add_views
from urdf_lint.core.emit import say
from urdf_lint.core.errors import UsageError

if TYPE_CHECKING:  # pragma: no cover
    from argparse import Namespace
    from collections.abc import Sequence

    from urdf_lint.cli.parser import Formatter, SubParsers
    from urdf_lint.config.schema import Config
    from urdf_lint.preview.review import ReviewPage
    from urdf_lint.report.diff.base import DiffResult


NAME = "diff"


def add_parser(sub: SubParsers, raw: Formatter) -> None:
    df = sub.add_parser("diff", help="what a change did to the robots: a semantic diff of "
                        "every affected model between two git revisions", formatter_class=raw,
                        description="Compare every model a change affects between two git "
                                    "revisions: links, joints, limits, inertials, geometry, "
                                    "poses and findings, at their xacro lines.")
    df.add_argument("base", help="the base revision (e.g. origin/main)")
    df.add_argument("head", nargs="?", help="the head revision (default: the working tree)")
    df.add_argument("--path", action="append", dest="paths", metavar="PATH",
                    help="limit to models under PATH (default: the whole repository)")
    from urdf_lint.report import diff as diff_formats
    fmts = diff_formats.formats()
    df.add_argument("--format", choices=list(fmts), default="text", metavar="FORMAT",
                    help="output format: " + ", ".join(fmts) + " (see below; default: text)")
    df.epilog = "output formats:\n" + "\n".join(f"  {n:<9} {c.help}" for n, c in fmts.items())
    df.add_argument("-o", "--output", metavar="FILE",
                    help="write the report to FILE, atomically (default: standard output)")
    df.add_argument("--image-base-url", metavar="URL",
                    help="where the --render images will be served from, for the markdown "
                         "(default: none, no images in the markdown)")
    df.add_argument("--fail-on", choices=["error", "warning", "info", "never"],
                    help="exit 1 when the change introduces findings at or above this "
                         "severity (default: error)")
    add_target(df)
    df.add_argument("--package-path", action="append", metavar="NAME=DIR",
                    help="where a package lives (default: found from package.xml files)")
    df.add_argument("-j", "--jobs", metavar="N",
                    help="parallel workers (default: from the work, at most the CPU count)")
    df.add_argument("--no-cache", action="store_true", help="do not read or write the cache")
    df.add_argument("--render", metavar="DIR", help="write before/after/difference PNGs with "
                    "identical framing and one .rrd holding both revisions per affected model "
                    "(default: no snapshots)")
    df.add_argument("--no-rrd", action="store_true", help="with --render: PNGs only")
    df.add_argument("--html", metavar="DIR",
                    help="write an interactive review page (DIR/index.html: both robots "
                         "overlaid in 3D, changed links highlighted; opens from file://; default: none)")
    add_views(df)
    df.add_argument("--trust-config", action="store_true",
                    help="let each revision's config set env-allow, package-paths outside the "
                         "repository, cache-dir, jobs and looser limits (default: off)")


@dataclass
class ReviewOptions:
    """What ``diff`` was asked to do (from the command line, or the MCP server's ``diff``
    tool: the same typed options, no command line in between)."""
    base: str
    head: str | None = None
    paths: list[str] | None = None
    format: str = "text"
    output: str | None = None
    image_base_url: str | None = None
    fail_on: str | None = None
    package_path: list[str] | None = None
    no_cache: bool = False
    render: str | None = None
    no_rrd: bool = False
    html: str | None = None
    config: ConfigOptions = field(default_factory=ConfigOptions)


def _write_page(page: ReviewPage, out_dir: str, paths: Sequence[str], result: DiffResult) -> None:
    title = f"urdf-lint review: {result.base} .. {result.head}"
    try:
        page.write(out_dir, write_base(os.path.join(out_dir, "index.html"), paths), title)
    except OSError as e:
        raise UsageError(f"cannot write {safe_text(out_dir)}: "
                         f"{safe_text(getattr(e, 'why', None) or e.strerror or e)}") from None


def run(args: Namespace) -> int:
    return diff(options_from(ReviewOptions, args, config=ConfigOptions.from_args(args)))


def diff(o: ReviewOptions) -> int:
    from urdf_lint.report import diff as diff_report
    from urdf_lint.review import run as review
    paths = o.paths or ["."]
    for p in paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    # the config comes from each revision's own tree; the CLI adds only its flags' keys
    refuse_symlinked_out(o.render, paths)
    refuse_symlinked_out(o.html, paths)
    page = None
    if o.html:
        from urdf_lint.preview.review import ReviewPage
        page = ReviewPage()
    cfgs: list[Config] = []

    def load(ps: list[str]) -> Config:
        cfgs.append(load_cfg(o.config, ps))
        return cfgs[-1]
    try:
        result = review.run_diff(o.base, o.head, paths, load,
                                 parse_package_paths(o.package_path), jobs_n=None,
                                 use_cache=not o.no_cache, render_dir=o.render,
                                 rrd=not o.no_rrd,
                                 on_model=page.collect if page is not None else None)
    except review.ReviewError as e:
        raise UsageError(str(e)) from None
    if page is not None and o.html:
        _write_page(page, o.html, paths, result)
    options = diff_report.DiffOptions(image_base_url=o.image_base_url)
    if o.output:
        try:
            diff_report.write_file(result, o.format, o.output,
                                   write_base(o.output, paths), options)
        except OSError as e:
            raise UsageError(f"cannot write {safe_text(o.output)}: "
                             f"{safe_text(getattr(e, 'why', None) or e.strerror or e)}") from None
    else:
        diff_report.write(result, o.format, sys.stdout, options)
    for model, why in result.snapshot_problems:
        say(f"{safe_text(model)}: snapshot incomplete: {safe_text(why)}")
    if result.no_recordings:
        no_recordings_note(result.no_recordings)
    from urdf_lint.core.emit import report_internal
    report_internal(result.internal)
    return review.exit_code(result, cfgs[0].fail_on if cfgs else (o.fail_on or "error"))
