"""``urdf-lint check``: find, expand and lint every robot model under the paths (and
``--fix``/``--diff``/``--add-suppressions``, :mod:`urdf_lint.cli.fix`)."""
from __future__ import annotations

import os
import re
import sys
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from urdf_lint.cli.common import (ConfigOptions, Out, clear_stale, color_mode, load_cfg,
                                  no_models_warning, note_unused, options_from,
                                  parse_package_paths, refuse_symlinked_out, report_snapshots,
                                  safe_text, through_models)
from urdf_lint.cli.output import FindingsOutput, write_base
from urdf_lint.cli.parser import (add_fix, add_inputs, add_key_flags, add_limits, add_output,
                                  add_selection, add_views)
from urdf_lint.core.emit import say
from urdf_lint.core.errors import UsageError

if TYPE_CHECKING:  # pragma: no cover
    from collections.abc import Callable, Iterable, Sequence

    from urdf_lint.cli.parser import Formatter, SubParsers
    from urdf_lint.config.schema import Config
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.run.cache import Cache
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


def _scope(o: CheckOptions, cfg: Config) -> tuple[list[str], set[str] | None, set[str]]:
    """(the paths to lint, the files whose models to report or None for all, the files the
    user named that are not models)."""
    paths, named = list(o.paths), set()
    affected_by: set[str] | None = None
    if o.files is None and not o.changed_since:
        redirect = through_models(o.paths, parse_package_paths(o.package_path), cfg, o.quiet)
        if redirect is not None:
            paths, affected_by, named = [redirect[0]], redirect[1], redirect[2]
    if o.changed_since:
        affected_by = changed_since(o.changed_since, paths[0])
    if o.files is not None:
        affected_by = {os.path.abspath(f) for f in o.files}
    return paths, affected_by, named


def _cache(o: CheckOptions, paths: Sequence[str], cfg: Config) -> Cache | None:
    if o.no_cache:
        return None
    from urdf_lint.run.cache import Cache
    cache = Cache.for_paths(paths, cfg)
    return None if cache.refused else cache   # (refused: said why on stderr)


def check(o: CheckOptions) -> int:
    from urdf_lint.core.locations import display_path
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import RunRequest, run_check
    out = Out(o.quiet, o.verbose)
    mode = color_mode(o.color)
    for p in o.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    cfg = load_cfg(o.config, o.paths)
    out.info(f"config: {display_path(cfg.path) if cfg.path else 'none (defaults)'}")
    paths, affected_by, named = _scope(o, cfg)
    resolver = build_resolver(paths, cfg, parse_package_paths(o.package_path))
    cache = _cache(o, paths, cfg)
    refuse_symlinked_out(o.render, paths)
    if fix_mode(o):
        return _fix(o, paths, named, cfg, resolver, affected_by, out, mode)
    if o.render:
        clear_stale(o.render, paths)
    from urdf_lint.run.finish import Scope
    # a fix offered in JSON / SARIF edits only the linted files; a baseline being written
    # records every finding, one being read hides its own
    how = Scope(tuple(paths), None if o.write_baseline else cfg.baseline, out.note)
    result = run_check(RunRequest(paths, cfg, resolver, jobs_n=cfg.jobs, cache=cache,
                                  progress=_progress(out), affected_by=affected_by,
                                  render_dir=o.render, scope=how))
    if result.reused:
        out.info("nothing changed since the last identical run: showing its result")
    if out.verbose:
        list_models(result, out)
    from urdf_lint.core.emit import report_internal
    report_internal(result.internal)
    if o.write_baseline:
        return _write_baseline(o, paths, result, out)
    from urdf_lint.cli.output import write_findings
    write_findings(o.report(paths), cfg, result, out, mode, resolver.roots)
    if o.coverage and (cfg.output_format or "text") not in ("json",):
        from urdf_lint.core.emit import tell
        from urdf_lint.report.base import coverage_text
        for line in coverage_text(result):
            tell(line)
    _notes_after(o, result, cfg, resolver, out, named)
    if o.exit_zero:
        return 2 if result.internal else 0
    from urdf_lint.run.pipeline import exit_code
    return exit_code(result, cfg.fail_on)


def _fix(o: CheckOptions, paths: list[str], named: set[str], cfg: Config,
         resolver: PackageResolver, affected_by: set[str] | None, out: Out, mode: str) -> int:
    from urdf_lint.core.locations import display_path
    from urdf_lint.cli.fix import FixRequest, check_fix
    if named:
        raise UsageError(
            "--fix/--diff/--add-suppressions on a file that models include: run it on "
            f"the folder ({safe_text(display_path(paths[0]))}), so that every fix "
            "is checked against every model that uses the file")
    request = FixRequest(report=o.report(paths), write_baseline=o.write_baseline,
                         add_suppressions=o.add_suppressions, no_cache=o.no_cache,
                         unsafe_fixes=o.unsafe_fixes, diff=o.diff, exit_zero=o.exit_zero,
                         exit_non_zero_on_fix=o.exit_non_zero_on_fix)
    return check_fix(request, cfg, resolver, affected_by, o.render, out, mode)


def _write_baseline(o: CheckOptions, paths: Sequence[str], result: CheckResult, out: Out) -> int:
    from urdf_lint.core.locations import display_path
    from urdf_lint.engine.baseline import write_baseline
    assert o.write_baseline is not None
    from urdf_lint.core.findings import tally
    write_baseline(o.write_baseline, result.findings, write_base(o.write_baseline, paths))
    files = len({f.file for f in result.findings})
    out.note(f"urdf-lint: wrote {tally(result.findings).phrase()} in {files} file(s) to "
             f"{display_path(os.path.abspath(o.write_baseline))}; "
             f"lint with --baseline {o.write_baseline} to report only new ones")
    if o.render:
        report_snapshots(result, o.render, out)
    return 2 if result.internal else 0


def _notes_after(o: CheckOptions, result: CheckResult, cfg: Config, resolver: PackageResolver,
                 out: Out, named: set[str]) -> None:
    """What is said after the findings: the hook's line, unused files, folders without
    models, variants left at their defaults, the snapshots."""
    if o.hook_summary:
        hook_summary(result, o.files or [])
    note_unused(result, out, named)
    if o.files is None and not o.changed_since:
        no_models_warning(o.paths, result, out)
    note_variants(result, cfg, resolver, out)
    if o.render:
        report_snapshots(result, o.render, out)


def changed_since(ref: str, first_path: str) -> set[str]:
    from urdf_lint.discovery.vcs import GitError, changed_files
    cwd = first_path if os.path.isdir(first_path) else os.path.dirname(os.path.abspath(first_path))
    try:
        return changed_files(ref, cwd)
    except (GitError, OSError) as e:
        lines = [ln.strip() for ln in str(e).splitlines() if ln.strip()]
        text = " ".join(lines).lower()
        if "not a git repository" in text:
            why = f"{os.path.abspath(cwd)} is not inside a git repository"
        elif "unknown revision" in text or "bad revision" in text or "ambiguous argument" in text:
            why = f"no commit, branch or tag named {ref!r} (try e.g. origin/main or HEAD~1)"
        elif isinstance(e, OSError):
            why = f"cannot run git: {e.strerror or e}"
        else:
            why = re.sub(r"^(fatal|error): ", "", lines[0]) if lines else "git failed"
        raise UsageError(f"--changed-since {ref}: {why}") from None


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


def note_variants(result: CheckResult, cfg: Config, resolver: PackageResolver, out: Out) -> None:
    """One info line: the models linted with args left at defaults that select variants, and
    how to lint the variants (``[[models]] args``)."""
    from urdf_lint.core.locations import display_path
    from urdf_lint.run.pipeline import variant_args
    explored = {c["entry"] for c in result.coverage.values()}
    cut = [c for c in result.coverage.values() if c["cut_by_budget"]]
    if cut:
        n = sum(c["cut_by_budget"] for c in cut)
        out.note(f"note: the explore budget cut exploration short: {n} variant(s) of "
                 f"{len(cut)} model(s) not linted (raise --explore-budget, or see --coverage)")
    found = {e: v for e, v in variant_args(result.models, cfg, resolver).items()
             if e not in explored}
    if not found:
        return
    entry, names = next(iter(found.items()))
    shown = ", ".join(names[:4]) + (" ..." if len(names) > 4 else "")
    more = f" and {len(found) - 1} more model(s)" if len(found) > 1 else ""
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
