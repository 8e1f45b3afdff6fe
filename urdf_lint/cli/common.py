"""What the commands share: the CLI's own messages and the notes after a run (what they do
between parsing and printing is :mod:`urdf_lint.run.check`'s, re-exported here). No
``argparse.Namespace`` goes past a command's module: each turns its arguments into a dataclass
first (:class:`ConfigOptions`, and the command's own)."""
from __future__ import annotations

import dataclasses
import os
from typing import TYPE_CHECKING, Any, TypeVar

from urdf_lint.cli.output import write_base as write_base
from urdf_lint.core.emit import say
from urdf_lint.core.errors import UsageError
# what check does between parsing and printing lives in the run room; the commands that share
# these steps import them from here
from urdf_lint.run.check import (MODEL_SUFFIXES as MODEL_SUFFIXES,
                                 ConfigOptions as ConfigOptions, Snapshots,
                                 apply_cli_values as apply_cli_values,
                                 apply_trust as apply_trust, clear_stale as clear_stale,
                                 finish_snapshots, load_cfg as load_cfg,
                                 parse_package_paths as parse_package_paths,
                                 refuse_symlinked_out as refuse_symlinked_out,
                                 through_models as through_models)

if TYPE_CHECKING:  # pragma: no cover
    from collections.abc import Iterable, Sequence

    from _typeshed import DataclassInstance

    from urdf_lint.core.jobs import LintJob, ModelReport
    from urdf_lint.config.schema import Config
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.run.pipeline import CheckResult

    Options = TypeVar("Options", bound=DataclassInstance)   # a command's options dataclass


def options_from(cls: type[Options], args: Any, **extra: Any) -> Options:
    """A command's options dataclass ``cls`` from its parsed arguments: each field from the
    argument of the same name when the command has it (else the field's default)."""
    given = vars(args)
    names = {f.name for f in dataclasses.fields(cls)} - set(extra)
    return cls(**{n: given[n] for n in names if n in given}, **extra)


def safe_text(s: object) -> str:
    from urdf_lint.core.escape import escape_text
    return escape_text(str(s))


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


def report_snapshots(result: CheckResult, out_dir: str, out: Out | None = None) -> int:
    """Finish the snapshots (:func:`urdf_lint.run.check.finish_snapshots`) and say what they
    are; returns how many requested snapshots could not be made."""
    return say_snapshots(finish_snapshots(result, out_dir), out_dir, out)


def say_snapshots(snaps: Snapshots, out_dir: str, out: Out | None = None) -> int:
    """Say (one located line each) which requested snapshot could not be made, and where the
    snapshots are; returns how many could not."""
    from urdf_lint.core.locations import display_path
    for line in snaps.missed:
        say(line)
    if snaps.no_rerun:
        no_recordings_note(snaps.no_rerun)
    msg = (f"snapshots: {snaps.written} files for {snaps.models} model(s) in "
           f"{display_path(out_dir)}/ (summary: {display_path(snaps.summary)})")
    if out is not None:
        out.note(msg)
    else:
        say(msg)
    return len(snaps.missed)


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
