"""What the commands share: typed options for loading the config, the CLI's own messages, the
checks on where output goes, and the notes after a run. No ``argparse.Namespace`` goes past
a command's module: each turns its arguments into a dataclass first (:class:`ConfigOptions`
here, and the command's own)."""
from __future__ import annotations

import dataclasses
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

from urdf_lint.cli.output import write_base as write_base   # (re-exported: the commands use it)
from urdf_lint.core.emit import say
from urdf_lint.core.errors import UsageError

if TYPE_CHECKING:  # pragma: no cover
    from collections.abc import Iterable, Sequence

    from _typeshed import DataclassInstance

    from urdf_lint.config.schema import Config
    from urdf_lint.core.jobs import LintJob, ModelReport
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.run.pipeline import CheckResult

    Options = TypeVar("Options", bound=DataclassInstance)   # a command's options dataclass


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


def options_from(cls: type[Options], args: Any, **extra: Any) -> Options:
    """A command's options dataclass ``cls`` from its parsed arguments: each field from the
    argument of the same name when the command has it (else the field's default)."""
    given = vars(args)
    names = {f.name for f in dataclasses.fields(cls)} - set(extra)
    return cls(**{n: given[n] for n in names if n in given}, **extra)


def parse_package_paths(items: Iterable[str] | None) -> dict[str, str]:
    out = {}
    for it in items or []:
        name, sep, d = it.partition("=")
        if not sep or not name or not d:
            raise UsageError(f"--package-path expects NAME=DIR, got {it!r}")
        out[name] = os.path.abspath(d)
    return out


# -- config -----------------------------------------------------------------------------------
def load_cfg(opts: ConfigOptions, paths: Sequence[str]) -> Config:
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


def apply_cli_values(cfg: Config, opts: ConfigOptions) -> None:
    """What the user set on the command line wins (through the schema), clamped like the rest."""
    from urdf_lint.config.schema import apply_cli
    from urdf_lint.config import trust
    apply_cli(cfg, opts.values)
    trust.clamp(cfg)


def apply_trust(cfg: Config, opts: ConfigOptions, paths: Sequence[str]) -> None:
    """The repository's config may not loosen the guarantees (see urdf_lint/config/trust.py)."""
    from urdf_lint.discovery.discover import start_dir
    from urdf_lint.discovery.vcs import repo_root
    from urdf_lint.config import trust
    for n in cfg.notes + trust.apply(cfg, repo_root(start_dir(paths)),
                                     trusted=opts.trust_config, given=opts.given()):
        if not opts.quiet:
            say(f"urdf-lint: {n}")


def safe_text(s: object) -> str:
    from urdf_lint.core.escape import escape_text
    return escape_text(str(s))


def refuse_symlinked_out(d: str | None, paths: Sequence[str] = ()) -> None:
    """Snapshots are written where the user said, never through a link a repository planted:
    no component of the folder from the repository down (the folder itself included) may be
    a symlink."""
    if not d:
        return
    from urdf_lint.core import fsbound
    base = write_base(d, paths)
    try:
        if os.path.abspath(d) != os.path.abspath(base):
            fsbound.check_no_symlink(d, base)
            fsbound.make_dirs(d, base)
        elif os.path.islink(d.rstrip(os.sep) or d):
            raise fsbound.BoundaryError(d, "is a symlink; refusing to write through it")
    except OSError as e:
        raise UsageError(f"output folder {safe_text(d)}: "
                         f"{safe_text(getattr(e, 'why', None) or e.strerror or e)}") from None


class Out:
    """Where the CLI's own messages go: stderr, filtered by -q / -v."""

    def __init__(self, quiet: bool = False, verbose: bool = False) -> None:
        self.quiet, self.verbose = quiet, verbose

    def note(self, text: str) -> None:
        if not self.quiet:
            say(text)

    def info(self, text: str) -> None:
        if self.verbose:
            say(text)


def color_mode(mode: str | None) -> str:
    """``--color``: auto, always or never."""
    mode = mode or "auto"
    if mode not in ("auto", "always", "never"):
        from urdf_lint.core.suggest import did_you_mean
        raise UsageError(f"--color: invalid value {mode!r} (expected auto, always or never"
                         f"{did_you_mean(mode, ('auto', 'always', 'never'))})")
    return mode


# -- the paths a command is given ---------------------------------------------------------------
MODEL_SUFFIXES = (".urdf", ".xacro")


def through_models(paths: Sequence[str], package_paths: dict[str, str], cfg: Config,
                   quiet: bool = False) -> tuple[str, set[str], set[str]] | None:
    """Files that are not models themselves, linted through the models that use them, as the
    hook does: a fragment or macro library that models include, and any other file (a YAML
    file, a mesh, a texture: ``check $(git diff --name-only)``). Returns (the repository root
    to lint, the files whose models to report, the files the user named), or None when every
    path is a model or a folder. Folders named beside such files are linted whole (their
    model files join the files to report)."""
    from urdf_lint.discovery.discover import build_resolver, discover_models, repository_root
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
            say(f"note: {safe_text(display_path(f))} is included by "
                f"{', '.join(safe_text(display_path(g)) for g in inc[:5])}"
                f"{' ...' if len(inc) > 5 else ''}: linting the models that include it")
    report = set(files)
    for d in paths:
        if os.path.isdir(d):
            report.update(os.path.realpath(f) for f in iter_files(Path(d), MODEL_SUFFIXES))
    return root, report, set(files)


def no_models_warning(paths: Sequence[str], result: CheckResult, out: Out) -> None:
    """A folder the user named that holds no robot model: said, like ruff's "No Python files
    found" (the run still exits 0: nothing failed)."""
    entries = [os.path.realpath(m.entry) for m in [*result.models, *result.skipped]]
    for p in paths:
        if not os.path.isdir(p):
            continue
        top = os.path.realpath(p)
        if not any(e == top or e.startswith(top.rstrip(os.sep) + os.sep) for e in entries):
            out.note(f"warning: no robot models found in {safe_text(p)} (no .urdf file and no "
                     ".xacro file that expands to a robot)")


def note_unused(result: CheckResult, out: Out, named: Iterable[str] = ()) -> None:
    """Deleted files no remaining model reads (always said), unused files (under -v, or always
    when the user named the file)."""
    from urdf_lint.core.locations import display_path
    for f in getattr(result, "gone", ()):
        if f.endswith((".xacro", ".urdf")):
            out.note(f"note: {safe_text(display_path(f))} was deleted and no remaining model "
                     "reads it; if it was a model, it is gone")
    named = {os.path.realpath(f) for f in named}
    for f in result.unused_files:
        if os.path.realpath(f) in named:   # the user named it: always said
            out.note(f"note: {safe_text(display_path(f))} is not used by any model")
        elif f.endswith((".xacro", ".urdf", ".yaml", ".yml", ".stl", ".dae", ".obj")):
            out.info(f"note: {safe_text(display_path(f))} is not used by any model")


def clear_stale(out_dir: str, paths: Sequence[str]) -> None:
    from urdf_lint.render.snapshot import clear_stale
    try:
        clear_stale(out_dir, write_base(out_dir, paths))
    except OSError as e:
        raise UsageError(f"cannot clear {safe_text(out_dir)}: "
                         f"{safe_text(getattr(e, 'why', None) or e.strerror or e)}") from None


def report_snapshots(result: CheckResult, out_dir: str, out: Out | None = None) -> int:
    """Caption and finish the snapshots with the run's final findings, write summary.md and
    the manifest, and say (one located line each) which requested snapshot could not be
    made; returns how many could not."""
    from urdf_lint.render.snapshot import finish_snapshots, write_manifest, write_summary
    from urdf_lint.core.locations import display_path
    from urdf_lint.render.recording import NO_RERUN
    finish_snapshots(result.models, result.findings, out_dir)
    written, missed = 0, 0
    files: list[str] = []
    no_rerun = False
    for m in result.models:
        snap = m.snapshot or {}
        if f"rrd: {NO_RERUN}" in snap.get("problems", ()):   # optional: said once, below
            snap["problems"] = [p for p in snap["problems"] if p != f"rrd: {NO_RERUN}"]
            no_rerun = True
        for k in ("png", "rrd"):
            if snap.get(k):
                written += 1
                files.append(snap[k])
        if m.status != "model":
            say(f"{m.label}: no snapshot: the model did not expand (see 'urdf-lint check')")
            missed += 1
        elif snap.get("problems") or not snap.get("png"):
            why = "; ".join(snap.get("problems") or ["no picture was drawn"])
            say(f"{safe_text(m.label)}: snapshot incomplete: {safe_text(why)}")
            missed += 1
    if no_rerun:
        no_recordings_note(NO_RERUN)
    summary = write_summary(result, out_dir)
    write_manifest(out_dir, files + [summary])
    msg = (f"snapshots: {written} files for {len(result.models)} model(s) in "
           f"{display_path(out_dir)}/ (summary: {display_path(summary)})")
    if out is not None:
        out.note(msg)
    else:
        say(msg)
    return missed


def no_recordings_note(why: str) -> None:
    """The .rrd recordings are optional (rerun-sdk, the ``render`` extra): without them the
    pictures are still made and the run does not fail; said once (``render`` and
    ``diff --render`` alike)."""
    say(f"note: no .rrd recordings: {safe_text(why)}; the PNG pictures are written "
        "(--no-rrd: no recordings, no note)")


def expand_in_workers(jobs: list[LintJob], resolver: PackageResolver, cfg: Config
                      ) -> list[ModelReport]:
    """The ModelReport of each ``expand`` job, in the jobs' order: expanded in sandboxed
    workers (time and memory limits, scrubbed environment, Landlock, seccomp) with the run's
    one snapshot of the roots; the XML comes back as data (``kept_model.xml``)."""
    from urdf_lint.run.pipeline import worker_settings
    from urdf_lint.run.worker import run_jobs
    done = {id(job): res for job, res in run_jobs(jobs, worker_settings(cfg, resolver),
                                                  jobs_n=cfg.jobs)}
    return [done[id(job)] for job in jobs]
