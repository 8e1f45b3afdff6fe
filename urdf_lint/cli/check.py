"""``urdf-lint check``: find, expand and lint every robot model under the paths (and
``--fix``/``--diff``/``--add-suppressions``, :mod:`urdf_lint.cli.fix`)."""
from __future__ import annotations

import os
import sys
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from urdf_lint.cli.common import (ConfigOptions, Out, color_mode, no_models_warning,
                                  note_unused, options_from, safe_text, say_snapshots)
from urdf_lint.cli.output import FindingsOutput, write_findings
from urdf_lint.cli.parser import (add_fix, add_inputs, add_key_flags, add_limits, add_output,
                                  add_selection, add_views)
from urdf_lint.core.findings import exit_status
from urdf_lint.core.emit import report_internal, say
from urdf_lint.core.errors import UsageError
from urdf_lint.run.check import CheckRequest, Checked, Prepared, prepare
from urdf_lint.run.check import check as run_checked

if TYPE_CHECKING:  # pragma: no cover
    from collections.abc import Callable, Iterable, Sequence

    from urdf_lint.cli.parser import Formatter, SubParsers
    from urdf_lint.run.pipeline import CheckResult

NAME = "check"


def add_parser(sub: SubParsers, raw: Formatter) -> None:
    c = sub.add_parser("check", help="find, expand and lint every robot model under PATHS",
                       formatter_class=raw,
                       description="Find, expand and lint every robot model under PATHS.")
    c.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                   help="files or folders to lint (default: .)")
    add_output(c)
    c.add_argument("-o", "--output", metavar="FILE",
                   help="write the report to FILE, atomically (default: standard output)")
    add_selection(c)
    add_inputs(c)
    c.add_argument("--isolated", action="store_true", help="ignore all config files")
    c.add_argument("--render", metavar="DIR",
                   help="also write snapshots (.rrd, .png) to DIR (default: no snapshots)")
    add_views(c)
    c.add_argument("--changed-since", metavar="REF",
                   help="only the models affected by files changed since a git ref, e.g. "
                        "origin/main (default: every model)")
    c.add_argument("--write-baseline", metavar="FILE",
                   help="record the current findings in FILE and exit 0 (default: off)")
    add_limits(c)
    add_key_flags(c, "explore")
    c.add_argument("--coverage", action="store_true",
                   help="after the findings, list per model the xacro branches never taken "
                        "and why (text; a JSON document with --format json)")
    add_fix(c)


@dataclass
class CheckOptions:
    """What ``check`` (and ``hook``, which runs it) was asked to do."""
    config: ConfigOptions = field(default_factory=ConfigOptions)
    paths: list[str] = field(default_factory=lambda: ["."])
    package_path: list[str] | None = None
    output: str | None = None
    show_source: bool = False
    statistics: bool = False
    coverage: bool = False
    color: str = "auto"
    no_cache: bool = False
    quiet: bool = False
    verbose: bool = False
    exit_zero: bool = False
    render: str | None = None
    changed_since: str | None = None
    write_baseline: str | None = None
    fix: bool = False
    unsafe_fixes: bool = False
    diff: bool = False
    add_suppressions: bool = False
    exit_non_zero_on_fix: bool = False
    files: list[str] | None = None       # hook: the committed files whose models to report
    hook_summary: bool = False           # hook: one line on every run

    def report(self, paths: Iterable[str]) -> FindingsOutput:
        return FindingsOutput(paths=list(paths), output=self.output, statistics=self.statistics,
                              show_source=self.show_source, coverage=self.coverage)


def run(args: Any) -> int:
    return check(options_from(CheckOptions, args, config=ConfigOptions.from_args(args)))


def fix_mode(o: CheckOptions) -> bool:
    """Whether ``check`` writes or proposes fixes; the flags that need each other are checked."""
    if o.unsafe_fixes and not (o.fix or o.diff):
        raise UsageError("--unsafe-fixes needs --fix or --diff")
    if o.exit_non_zero_on_fix and not o.fix:
        raise UsageError("--exit-non-zero-on-fix needs --fix")
    if o.add_suppressions and (o.fix or o.diff):
        raise UsageError("--add-suppressions cannot be combined with --fix or --diff")
    return bool(o.fix or o.diff or o.add_suppressions)


def _progress(out: Out) -> Callable[[int, int], None] | None:
    """The progress counter on a terminal (not in CI, not with -q), or None."""
    if not sys.stderr.isatty() or os.environ.get("CI") or out.quiet:
        return None

    def progress(n: int, total: int) -> None:
        sys.stderr.write(f"\rlinting {n}/{total} models" + (" " * 10))
        if n == total:
            sys.stderr.write("\r" + " " * 40 + "\r")
        sys.stderr.flush()
    return progress


def request(o: CheckOptions) -> CheckRequest:
    """The run's request, parsed from the options (the flags that need each other checked)."""
    return CheckRequest(paths=tuple(o.paths), config=o.config,
                        package_path=tuple(o.package_path or ()),
                        files=None if o.files is None else tuple(o.files),
                        changed_since=o.changed_since, no_cache=o.no_cache, render=o.render,
                        write_baseline=o.write_baseline, fixing=fix_mode(o))


def check(o: CheckOptions) -> int:
    """Parse (:func:`request`), run (:mod:`urdf_lint.run.check`), print."""
    out = Out(o.quiet, o.verbose)
    mode = color_mode(o.color)
    req = request(o)
    prep = prepare(req, out)
    if req.fixing:
        return _fix(o, prep, out, mode)
    done = run_checked(prep, out, _progress(out))
    result = done.result
    if result.reused:
        out.info("nothing changed since the last identical run: showing its result")
    if out.verbose:
        list_models(result, out)
    report_internal(result.internal)
    if done.baseline is not None:
        return _baseline_written(o, done, out)
    write_findings(o.report(prep.paths), prep.cfg, result, out, mode, prep.resolver.roots)
    if o.coverage and (prep.cfg.output_format or "text") not in ("json",):
        from urdf_lint.core.emit import tell
        from urdf_lint.report.base import coverage_text
        for line in coverage_text(result):
            tell(line)
    if o.hook_summary:
        hook_summary(result, o.files or [])
    note_unused(result, out, prep.named)
    if o.files is None and not o.changed_since:
        no_models_warning(o.paths, result, out)
    note_variants(result, done.variants, out)
    if done.snapshots is not None:
        say_snapshots(done.snapshots, o.render or "", out)
    if o.exit_zero:
        return 2 if result.internal else 0
    status = exit_status([f.severity for f in result.findings], bool(result.internal),
                         prep.cfg.fail_on)
    note_fail_on(result, prep.cfg, status, out)
    return status


def note_fail_on(result: CheckResult, cfg: Any, status: int, out: Out) -> None:
    """A run that a config file's ``fail-on = "never"`` makes exit 0 despite errors says so,
    naming the file: one found by looking up from the linted paths can sit in a folder above
    the repository (``--fail-on never`` typed on the command line is not repeated back)."""
    if status != 0 or cfg.fail_on != "never" or not cfg.path \
            or cfg.raw.get("fail-on") != "never" or \
            not any(f.severity == "error" for f in result.findings):
        return
    from urdf_lint.core.locations import display_path
    out.note(f"note: exit 0 although errors were found: fail-on = \"never\" is set in "
             f"{safe_text(display_path(cfg.path))}")


def _fix(o: CheckOptions, prep: Prepared, out: Out, mode: str) -> int:
    from urdf_lint.core.locations import display_path
    from urdf_lint.cli.fix import FixRequest, check_fix
    if prep.named:
        raise UsageError(
            "--fix/--diff/--add-suppressions on a file that models include: run it on "
            f"the folder ({safe_text(display_path(prep.paths[0]))}), so that every fix "
            "is checked against every model that uses the file")
    fix_request = FixRequest(report=o.report(prep.paths), write_baseline=o.write_baseline,
                             add_suppressions=o.add_suppressions, no_cache=o.no_cache,
                             unsafe_fixes=o.unsafe_fixes, diff=o.diff, exit_zero=o.exit_zero,
                             exit_non_zero_on_fix=o.exit_non_zero_on_fix)
    return check_fix(fix_request, prep, out, mode)


def _baseline_written(o: CheckOptions, done: Checked, out: Out) -> int:
    from urdf_lint.core.findings import tally
    from urdf_lint.core.locations import display_path
    assert done.baseline is not None
    result = done.result
    files = len({f.file for f in result.findings})
    out.note(f"urdf-lint: wrote {tally(result.findings).phrase()} in {files} file(s) to "
             f"{display_path(os.path.abspath(done.baseline))}; "
             f"lint with --baseline {done.baseline} to report only new ones")
    if done.snapshots is not None:
        say_snapshots(done.snapshots, o.render or "", out)
    return 2 if result.internal else 0


def list_models(result: CheckResult, out: Out) -> None:
    from urdf_lint.core.locations import display_path
    for m in result.models:
        state = "cached" if m.cached else m.status
        reads = [d for d in m.deps if d != m.entry]
        out.info(f"model: {safe_text(m.label)} ({state}, {len(reads)} other file(s) read)")
        for d in reads:
            out.info(f"    {safe_text(display_path(d))}")
    for m in result.skipped:
        out.info(f"skipped: {safe_text(display_path(m.entry))} ({m.status})")


def note_variants(result: CheckResult, variants: dict[str, list[str]], out: Out) -> None:
    """One info line: the models linted with args left at defaults that select variants
    (``variants``, :attr:`urdf_lint.run.check.Checked.variants`), and how to lint the variants
    (``[[models]] args``); and when the explore budget cut exploration short."""
    from urdf_lint.core.locations import display_path
    cut = [c for c in result.coverage.values() if c["cut_by_budget"]]
    if cut:
        n = sum(c["cut_by_budget"] for c in cut)
        out.note(f"note: the explore budget cut exploration short: {n} variant(s) of "
                 f"{len(cut)} model(s) not linted (raise --explore-budget, or see --coverage)")
    if not variants:
        return
    entry, names = next(iter(variants.items()))
    shown = ", ".join(names[:4]) + (" ..." if len(names) > 4 else "")
    more = f" and {len(variants) - 1} more model(s)" if len(variants) > 1 else ""
    out.note(f"note: {safe_text(display_path(entry))}{more} linted with args at their defaults "
             f"that select variants ({safe_text(shown)}); to lint the variants, list them: "
             f"[[tool.urdf-lint.models]] path = \"{safe_text(display_path(entry))}\" "
             f"args = [{{{safe_text(names[0])} = \"...\"}}, ...]")


def hook_summary(result: CheckResult, files: Sequence[str]) -> None:
    """``hook``: one line on every run, passed or failed, with the warnings and infos that do
    not fail it (pre-commit shows it with ``verbose: true``, set in .pre-commit-hooks.yaml)."""
    from urdf_lint.core.findings import group, tally
    named = {os.path.realpath(f) for f in files}
    t = tally(result.findings)
    # a finding is in the committed files when it is, or when its value comes from one (a
    # limit the commit changed in a YAML file is reported at the xacro line that reads it)
    mine = sum(1 for f in group(result.findings)
               if any(os.path.realpath(i.file) in named or
                      (i.value_from and os.path.realpath(i.value_from[0]) in named)
                      for i in f.each()))
    n = len(result.models)
    line = (f"urdf-lint: {n} model(s) affected by {len(files)} file(s): {t.errors} error(s), "
            f"{t.warnings} warning(s), {t.infos} info")
    if result.findings:
        line += f" ({mine} in the committed files)"
    say(line)
