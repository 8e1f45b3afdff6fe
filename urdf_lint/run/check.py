"""``check`` between its command line and its output: everything the command does that is not
parsing or printing, so that the CLI room only does those two (issue 35's walk).

:func:`prepare` turns a parsed :class:`CheckRequest` into a :class:`Prepared` run (the config
with the command line's values and the trust rules applied, the paths to lint, files linted
through the models that use them, ``--changed-since``, the resolver, the result cache, the
snapshot folder checked); then one of :func:`check` (lint, write the baseline, finish the
snapshots), :func:`fix` (``--fix``/``--diff``) or :func:`add_suppressions` does the work and
returns what the command prints. What is said on the way (a config note, a file linted through
its includers) goes through the caller's :class:`Say`.
"""
from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Protocol

from urdf_lint.core.emit import say
from urdf_lint.core.errors import UsageError

if TYPE_CHECKING:
    from urdf_lint.config.schema import Config
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.run.cache import Cache
    from urdf_lint.run.pipeline import CheckResult


class Say(Protocol):
    """Where a command's own messages go (the CLI's ``Out``: stderr, filtered by -q / -v)."""
    quiet: bool

    def note(self, text: str) -> None: ...

    def info(self, text: str) -> None: ...


# -- the config a command runs with ----------------------------------------------------------
@dataclass(frozen=True)
class ConfigOptions:
    """What the command line says about the config: the file (or none), whether the
    repository's config is trusted, and what was typed for each schema key's flag."""
    values: dict[str, Any] = field(default_factory=dict)   # schema key -> as typed (None: not given)
    config: str | None = None                    # --config
    isolated: bool = False                       # --isolated: no config file at all
    trust_config: bool = False
    quiet: bool = False                          # -q: no notes

    @classmethod
    def from_args(cls, args: Any) -> "ConfigOptions":
        """From a command's parsed arguments: the flags it does not have are not given."""
        from urdf_lint.config.schema import FLAG_KEYS
        given = vars(args)
        values = {k.name: given.get((k.flag.dest if k.flag else "") or k.attr) for k in FLAG_KEYS}
        return cls(values=values, config=given.get("config"),
                   isolated=bool(given.get("isolated")),
                   trust_config=bool(given.get("trust_config")), quiet=bool(given.get("quiet")))

    def given(self) -> set[str]:
        """The schema keys set on the command line."""
        return {k for k, v in self.values.items() if v}


def parse_package_paths(items: Any) -> dict[str, str]:
    """``--package-path NAME=DIR`` (repeatable) as {name: absolute folder}."""
    out = {}
    for it in items or []:
        name, sep, d = it.partition("=")
        if not sep or not name or not d:
            raise UsageError(f"--package-path expects NAME=DIR, got {it!r}")
        out[name] = os.path.abspath(d)
    return out


def load_cfg(opts: ConfigOptions, paths: Any) -> "Config":
    """The config of a run: the repository's file (or ``--config``, or none with
    ``--isolated``), the trust rules, then the command line's values."""
    from urdf_lint.config.schema import find_config, load_config, validate_codes
    from urdf_lint.engine.registry import codes_to_names, load_rules
    known = codes_to_names()
    if opts.isolated:
        cfg = load_config(None)
    else:
        path = opts.config or find_config(paths[0] if paths else ".")
        cfg = load_config(path, known, load_rules)
    apply_trust(cfg, opts, paths)
    apply_cli_values(cfg, opts)
    validate_codes(cfg, known, rules=load_rules)
    return cfg


def apply_cli_values(cfg: "Config", opts: ConfigOptions) -> None:
    """What the user set on the command line wins (through the schema), clamped like the rest."""
    from urdf_lint.config.schema import apply_cli
    from urdf_lint.config import trust
    apply_cli(cfg, opts.values)
    trust.clamp(cfg)


def apply_trust(cfg: "Config", opts: ConfigOptions, paths: Any) -> None:
    """The repository's config may not loosen the guarantees (see urdf_lint/config/trust.py)."""
    from urdf_lint.discovery.discover import start_dir
    from urdf_lint.discovery.vcs import repo_root
    from urdf_lint.config import trust
    for n in cfg.notes + trust.apply(cfg, repo_root(start_dir(paths)),
                                     trusted=opts.trust_config, given=opts.given()):
        if not opts.quiet:
            say(f"urdf-lint: {n}")


# -- the paths a command is given ---------------------------------------------------------------
MODEL_SUFFIXES = (".urdf", ".xacro")


def through_models(paths: Any, package_paths: dict[str, str], cfg: "Config",
                   quiet: bool = False) -> tuple[str, set[str], set[str]] | None:
    """Files that are not models themselves, linted through the models that use them, as the
    hook does: a fragment or macro library that models include, and any other file (a YAML
    file, a mesh, a texture: ``check $(git diff --name-only)``). Returns (the repository root
    to lint, the files whose models to report, the files the user named), or None when every
    path is a model or a folder. Folders named beside such files are linted whole (their
    model files join the files to report)."""
    from urdf_lint.discovery.discover import build_resolver, discover_models, repository_root
    from urdf_lint.core.escape import escape_text
    from urdf_lint.core.jobs import Status
    from urdf_lint.engine.lint import classify_xacro
    files = [os.path.realpath(p) for p in paths if os.path.isfile(p)]
    configured = {m.path for m in cfg.models}
    # (a .srdf.xacro is a robot's configuration, like its YAML: linted through that robot)
    inputs = [f for f in files if (not f.endswith(MODEL_SUFFIXES) or f.endswith(".srdf.xacro"))
              and f not in configured]
    cand = [f for f in files if f.endswith(".xacro") and not f.endswith(".srdf.xacro")
            and f not in configured]
    if not inputs and not cand:
        return None
    root = repository_root(paths)
    redirect = list(inputs)
    by: dict[str, list[str]] = {}
    if cand:
        resolver = build_resolver([root], cfg, package_paths)
        graph = discover_models([root], cfg, resolver).graph
        by = {f: graph.includers(f) for f in cand}
        redirect += [f for f in cand if by[f] or classify_xacro(f) is Status.LIBRARY]
    if not redirect:
        return None
    from urdf_lint.core.locations import display_path
    from urdf_lint.discovery.packages import iter_files
    for f in cand:
        if by.get(f) and not quiet:
            inc = by[f]
            say(f"note: {escape_text(display_path(f))} is included by "
                f"{', '.join(escape_text(display_path(g)) for g in inc[:5])}"
                f"{' ...' if len(inc) > 5 else ''}: linting the models that include it")
    report = set(files)
    for d in paths:
        if os.path.isdir(d):
            report.update(os.path.realpath(f) for f in iter_files(Path(d), MODEL_SUFFIXES))
    return root, report, set(files)


def changed_since(ref: str, first_path: str) -> set[str]:
    """The files changed since the git ref ``ref`` in the repository of ``first_path``; a
    usage error that says why when git cannot tell."""
    from urdf_lint.discovery.vcs import GitError, changed_files
    cwd = first_path if os.path.isdir(first_path) else os.path.dirname(os.path.abspath(first_path))
    try:
        return set(changed_files(ref, cwd))
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


# -- where output goes ---------------------------------------------------------------------------
def write_base(target: str, paths: Any) -> str:
    """The folder a write to ``target`` (named on the command line) is checked from
    (:func:`urdf_lint.core.fsbound.output_base`): the repository of the linted paths (their
    folder outside git) or the git work tree of the working directory when ``target`` is in
    one, else the nearest existing folder above it (the user's own, as named)."""
    from urdf_lint.core import fsbound
    from urdf_lint.discovery.discover import start_dir
    from urdf_lint.discovery.vcs import git_root, repo_root
    repos: list[str | None] = [repo_root(start_dir(paths))] if paths else []
    repos.append(git_root(os.getcwd()))
    return fsbound.output_base(target, repos)


def _why(e: OSError) -> str:
    from urdf_lint.core.escape import escape_text
    return escape_text(str(getattr(e, "why", None) or e.strerror or e))


def refuse_symlinked_out(d: str | None, paths: Any = ()) -> None:
    """Snapshots are written where the user said, never through a link a repository planted:
    no component of the folder from the repository down (the folder itself included) may be
    a symlink."""
    if not d:
        return
    from urdf_lint.core import fsbound
    from urdf_lint.core.escape import escape_text
    base = write_base(d, paths)
    try:
        if os.path.abspath(d) != os.path.abspath(base):
            fsbound.check_no_symlink(d, base)
            fsbound.make_dirs(d, base)
        elif os.path.islink(d.rstrip(os.sep) or d):
            raise fsbound.BoundaryError(d, "is a symlink; refusing to write through it")
    except OSError as e:
        raise UsageError(f"output folder {escape_text(d)}: {_why(e)}") from None


def clear_stale(out_dir: str, paths: Any) -> None:
    """Remove the snapshots an earlier run left in ``out_dir`` (never outside it)."""
    from urdf_lint.core.escape import escape_text
    from urdf_lint.render.snapshot import clear_stale as clear
    try:
        clear(out_dir, write_base(out_dir, paths))
    except OSError as e:
        raise UsageError(f"cannot clear {escape_text(out_dir)}: {_why(e)}") from None


@dataclass
class Snapshots:
    """What finishing a run's snapshots did, for the command to say: one line per model whose
    snapshot is missing or incomplete, whether recordings were unavailable, the summary."""
    written: int = 0
    missed: list[str] = field(default_factory=list)
    no_rerun: str | None = None          # why there are no .rrd recordings (said once)
    summary: str = ""                    # summary.md
    models: int = 0


def finish_snapshots(result: "CheckResult", out_dir: str) -> Snapshots:
    """Caption and finish the snapshots with the run's final findings, write summary.md and
    the manifest; returns what to say about them."""
    from urdf_lint.core.escape import escape_text
    from urdf_lint.render.recording import NO_RERUN
    from urdf_lint.render.snapshot import finish_snapshots as finish
    from urdf_lint.render.snapshot import write_manifest, write_summary
    finish(result.models, result.findings, out_dir)
    out = Snapshots(models=len(result.models))
    files: list[str] = []
    for m in result.models:
        snap = m.snapshot or {}
        if f"rrd: {NO_RERUN}" in snap.get("problems", ()):   # optional: said once
            snap["problems"] = [p for p in snap["problems"] if p != f"rrd: {NO_RERUN}"]
            out.no_rerun = NO_RERUN
        for k in ("png", "rrd"):
            if snap.get(k):
                out.written += 1
                files.append(snap[k])
        if m.status != "model":
            out.missed.append(f"{m.label}: no snapshot: the model did not expand (see "
                              "'urdf-lint check')")
        elif snap.get("problems") or not snap.get("png"):
            why = "; ".join(snap.get("problems") or ["no picture was drawn"])
            out.missed.append(f"{escape_text(m.label)}: snapshot incomplete: {escape_text(why)}")
    out.summary = write_summary(result, out_dir)
    write_manifest(out_dir, files + [out.summary])
    return out


# -- check ------------------------------------------------------------------------------------
@dataclass(frozen=True)
class CheckRequest:
    """What ``check`` (or ``hook``) was asked, as parsed: the one argument of :func:`prepare`."""
    paths: tuple[str, ...] = (".",)
    config: ConfigOptions = field(default_factory=ConfigOptions)
    package_path: tuple[str, ...] = ()
    files: tuple[str, ...] | None = None     # hook: the committed files whose models to report
    changed_since: str | None = None
    no_cache: bool = False
    render: str | None = None                # snapshots to this folder
    write_baseline: str | None = None
    fixing: bool = False                     # --fix / --diff / --add-suppressions


@dataclass
class Prepared:
    """A check run ready to go: its config, the paths it lints (a file linted through the
    models that use it makes these the repository), the files whose models it reports
    (``affected_by``; None: all), the files the user named that are not models, the resolver
    and the result cache."""
    request: CheckRequest
    cfg: "Config"
    paths: list[str]
    affected_by: set[str] | None
    named: set[str]
    resolver: "PackageResolver"
    cache: "Cache | None"


def prepare(req: CheckRequest, out: Say) -> Prepared:
    """Load the config, settle the paths, build the resolver and the cache, check the snapshot
    folder: a usage error (exit 2) for what cannot be run."""
    from urdf_lint.core.locations import display_path
    from urdf_lint.discovery.discover import build_resolver
    for p in req.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    cfg = load_cfg(req.config, list(req.paths))
    out.info(f"config: {display_path(cfg.path) if cfg.path else 'none (defaults)'}")
    package_paths = parse_package_paths(req.package_path)
    paths, affected_by, named = list(req.paths), None, set()
    if req.files is None and not req.changed_since:
        redirect = through_models(req.paths, package_paths, cfg, out.quiet)
        if redirect is not None:
            paths, affected_by, named = [redirect[0]], redirect[1], redirect[2]
    if req.changed_since:
        affected_by = changed_since(req.changed_since, paths[0])
    if req.files is not None:
        affected_by = {os.path.abspath(f) for f in req.files}
    resolver = build_resolver(paths, cfg, package_paths)
    cache = None
    if not req.no_cache:
        from urdf_lint.run.cache import Cache
        cache = Cache.for_paths(paths, cfg)
        cache = None if cache.refused else cache   # (refused: said why on stderr)
    refuse_symlinked_out(req.render, paths)
    return Prepared(req, cfg, paths, affected_by, named, resolver, cache)


@dataclass
class Checked:
    """What a check run found, with what the command says after the findings."""
    result: "CheckResult"
    variants: dict[str, list[str]] = field(default_factory=dict)  # models left at defaults
    snapshots: Snapshots | None = None
    baseline: str | None = None          # the baseline written (--write-baseline)


def check(prep: Prepared, out: Say,
          progress: Callable[[int, int], None] | None = None) -> Checked:
    """Lint (:func:`urdf_lint.run.pipeline.run_check`), then write the baseline or finish the
    snapshots as asked."""
    from urdf_lint.run.finish import Scope
    from urdf_lint.run.pipeline import RunRequest, run_check, variant_args
    req = prep.request
    if req.render:
        clear_stale(req.render, prep.paths)
    # a fix offered in JSON / SARIF edits only the linted files; a baseline being written
    # records every finding, one being read hides its own
    how = Scope(tuple(prep.paths), None if req.write_baseline else prep.cfg.baseline, out.note)
    result = run_check(RunRequest(prep.paths, prep.cfg, prep.resolver, jobs_n=prep.cfg.jobs,
                                  cache=prep.cache, progress=progress,
                                  affected_by=prep.affected_by, render_dir=req.render,
                                  scope=how))
    done = Checked(result)
    if req.write_baseline:
        from urdf_lint.engine.baseline import write_baseline
        write_baseline(req.write_baseline, result.findings,
                       write_base(req.write_baseline, prep.paths))
        done.baseline = req.write_baseline
    else:
        explored = {c["entry"] for c in result.coverage.values()}
        done.variants = variant_args(result.models, prep.cfg, prep.resolver, skip=explored)
    if req.render:
        done.snapshots = finish_snapshots(result, req.render)
    return done


# -- fix ------------------------------------------------------------------------------------------
def fix(prep: Prepared, out: Say, unsafe: bool = False, diff_only: bool = False) -> Any:
    """``--fix``/``--diff``: :func:`urdf_lint.run.fix.run_fix` over every model of the paths,
    with the fix memo of the prepared run's result cache; returns its outcome."""
    from urdf_lint.run.fix import run_fix
    memo = None
    if prep.cache is not None:
        from urdf_lint.fix.memo import FixMemo
        memo = FixMemo(prep.cache)
    return run_fix(prep.paths, prep.cfg, prep.resolver, jobs_n=prep.cfg.jobs, unsafe=unsafe,
                   diff_only=diff_only, memo=memo, note=out.note)


@dataclass
class Suppressed:
    """What ``--add-suppressions`` did: the comments added, the files changed, and the run
    after them (or the first run, when it failed)."""
    result: "CheckResult"
    added: int = 0
    files: list[str] = field(default_factory=list)
    failed: bool = False                 # the first run failed: nothing was added


def add_suppressions(prep: Prepared, out: Say) -> Suppressed:
    """A suppression comment for every finding (the baseline's too), then the run again with
    the baseline."""
    from dataclasses import replace
    from urdf_lint.fix.addsuppress import add_suppressions as add
    from urdf_lint.run.finish import Scope
    from urdf_lint.run.pipeline import RunRequest, run_check
    request = RunRequest(prep.paths, prep.cfg, prep.resolver, jobs_n=prep.cfg.jobs)
    result = run_check(request)
    if result.internal:
        return Suppressed(result, failed=True)
    n, files, _ = add(result.findings, prep.paths)
    result = run_check(replace(request, scope=Scope(tuple(prep.paths), prep.cfg.baseline,
                                                    out.note)))
    return Suppressed(result, n, list(files))
