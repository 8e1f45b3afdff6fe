"""The run of ``urdf-lint format [PATHS]`` (the command: :mod:`urdf_lint.cli.format`): lay out
xacro and URDF sources (:mod:`urdf_lint.formatting.layout`) and prove that no robot changes.

1. Every ``.urdf``/``.xacro`` under the paths (``exclude`` and ``[format] exclude`` honoured;
   a file named explicitly is always formatted) is read (regular files of bounded size only)
   and laid out; the guard of :func:`urdf_lint.formatting.layout.check_same` runs on each result.
2. **The proof.** A layout is proved from the file itself where xacro's rules make it one
   (:mod:`urdf_lint.formatting.inert`; the weaker of its two rules also asks every file of
   every model that reads the file). The models of the repository that read a file not
   proved so (the include graph of :mod:`urdf_lint.discovery.discover`, plus the models whose
   includes only expansion resolves, kept when their recorded inputs meet such a file;
   ``exclude`` and ``discover = false`` do not hide a model from the proof) are expanded in
   the sandboxed workers, as ``check`` and ``expand`` do, once as the files are and once with the
   new layouts in place of the files (``LintJob.overlay``: nothing is written while it
   is proved). The two robots are compared as canonical XML (comments, layout whitespace and
   attribute order ignored; every other text kept exact). A model that differs leaves every
   changed file it reads that was not proved by itself alone, and the reason is printed;
   the models those files also feed are proved again without them, until nothing more is
   refused.
   Expanding proves a layout only for the args the models are given: a file whose new
   whitespace in an ``xacro:if``/``xacro:unless`` body the file's own rules do not prove is
   left alone (:func:`urdf_lint.formatting.inert.unproven_in_branches`).
3. The rest is written atomically (:func:`urdf_lint.core.fsbound.rewrite`), only below the
   formatted paths (a named symlink out of the repository is refused), and only while the
   file still holds what was read (else skipped, exit 1); ``--check`` and ``--diff`` write
   nothing.

Exit codes as ``ruff format``: 0 formatted (or nothing to do), 1 with ``--check``/``--diff``
when a file would change, 2 on an error (a file that is not well-formed XML, a bad option).
"""
from __future__ import annotations

import dataclasses
import os
from dataclasses import dataclass
from typing import TYPE_CHECKING

from urdf_lint.formatting.layout import (FormatError, Refused, Style, format_source, normal_nodes,
                                        read_document)

if TYPE_CHECKING:  # pragma: no cover
    from collections.abc import Callable, Iterable, Sequence

    from urdf_lint.config.schema import Config
    from urdf_lint.core.fsbound import Roots
    from urdf_lint.core.jobs import LintJob, ModelReport
    from urdf_lint.discovery.discover import Discovery, IncludeGraph
    from urdf_lint.formatting.layout import Node

    Reach = Callable[[str], set[str]]
    Parsed = Callable[[bytes], list[Node]]
    Key = tuple[str, tuple[tuple[str, str], ...]]

def style_of(cfg: "Config", args: object | None = None) -> Style:
    """The layout settings: ``[tool.urdf-lint.format]``, then the command line (``args``:
    any object with the format flags as attributes, read with getattr)."""
    from urdf_lint.config.schema import FORMAT_KEYS, format_option
    opts = {k: FORMAT_KEYS[k].default for k in STYLE_KEYS}
    opts.update({k: v for k, v in cfg.format_options.items() if k in opts})
    for k in opts:
        given = getattr(args, k.replace("-", "_"), None) if args is not None else None
        if given is not None:
            opts[k] = format_option(k, given)
    return Style(**{k.replace("-", "_"): v for k, v in opts.items()})


# the [tool.urdf-lint.format] keys that are Style's fields (each also a flag of format)
STYLE_KEYS = ("indent", "line-length", "attribute-order", "self-closing")


@dataclass
class FileResult:
    """One file the formatter looked at: its bytes before and after, or why it is left alone."""
    path: str                   # real path
    shown: str                  # as messages show it
    old: bytes = b""
    new: bytes | None = None    # the new layout (None: unchanged, or left alone)
    error: str | None = None    # cannot be formatted (exit 2)
    refused: str | None = None  # left alone: why


def files_to_format(paths: "Iterable[str]", cfg: "Config") -> list[str]:
    from urdf_lint.discovery.discover import candidate_files
    excludes = list(cfg.exclude) + list(cfg.format_options.get("exclude", []))
    scoped = dataclasses.replace(cfg, exclude=excludes)
    return [f for f, _ in candidate_files(paths, scoped)]


def format_files(files: "Iterable[str]", style: Style, paths: "Iterable[str]",
                 docs: "dict[bytes, list[Node]] | None" = None,
                 repo: str | None = None) -> list[FileResult]:
    """Read and lay out each file (not written); ``docs`` receives the documents read of the
    files that change, before and after (:func:`urdf_lint.formatting.layout.format_source`).
    A file is read only when its real path is below a named path's
    (:func:`urdf_lint.core.fsbound.write_roots`: a named symlink out of the repository ``repo``
    stands for nothing)."""
    from urdf_lint.core.fsbound import write_roots
    from urdf_lint.core.hashing import read_regular
    from urdf_lint.core.locations import display_path
    from urdf_lint.discovery.packages import MAX_SOURCE_BYTES
    from urdf_lint.fix.scope import inside
    real_paths = write_roots(paths, repo)
    out = []
    for f in files:
        real = os.path.realpath(f)
        res = FileResult(real, display_path(f))
        out.append(res)
        if not inside(real, real_paths, resolved=True):
            res.refused = "it resolves outside the formatted paths (a symlink?)"
            continue
        data = read_regular(real, MAX_SOURCE_BYTES)
        if data is None:
            res.error = (f"{res.shown}:1:1: not a regular file of at most "
                         f"{MAX_SOURCE_BYTES >> 20} MiB; not formatted")
            continue
        res.old = data
        try:
            new = format_source(data, style, real, docs)
        except FormatError as e:
            res.error = f"{res.shown}:{e.line}:{e.col}: {e.message}"
            continue
        except Refused as e:
            res.refused = e.reason
            continue
        if new != data:
            res.new = new
    return out


# -- the proof ------------------------------------------------------------------------------------
def canonical_robot(xml: str) -> "list[Node]":
    """An expanded robot as canonical nodes: comments and layout whitespace dropped,
    attributes sorted, all other text exact."""
    return normal_nodes([n for n in read_document(xml.encode("utf-8")) if n[0] == "el"], False,
                   comments=False)


def first_difference(a: "list[Node]", b: "list[Node]", path: str = "") -> str:
    """Where two canonical robots first differ, as ``<joint 'j1'>``."""
    for x, y in zip(a, b, strict=False):
        if x == y:
            continue
        if x[0] == y[0] == "el" and x[1] == y[1] and x[2] == y[2]:
            return first_difference(x[3], y[3], _describe(x))
        return _describe(x if x[0] == "el" else y) if (x[0] == "el" or y[0] == "el") \
            else f"the text in {path or 'the document'}"
    return f"the number of children of {path or 'the document'}"


def _describe(node: "Node") -> str:
    name = dict(node[2]).get("name")
    return f"<{node[1]}{' ' + repr(name) if name else ''}>"


def _outcome(report: "ModelReport") -> "tuple[list[Node] | None, str | None]":
    """(canonical robot or None, the failure or None) of an expansion."""
    from urdf_lint.core.jobs import Status
    xml = report.kept_model.xml if report.kept_model is not None else None
    if report.status is Status.FAILED or xml is None or report.internal:
        why = next(iter(report.problems), None)
        text = f"{why.code} {why.message}" if why is not None else "expansion failed"
        return None, text
    try:
        return canonical_robot(xml), None
    except FormatError as e:
        return None, e.message


@dataclass
class Proof:
    """What the proof of a run found."""
    refused: dict[str, str] = dataclasses.field(default_factory=dict)   # real path -> why left alone
    compared: int = 0        # models expanded before and after
    by_file: int = 0         # changed files proved from the file itself (formatting.inert)


def prove(changed: dict[str, bytes], paths: "Sequence[str]", cfg: "Config",
          package_paths: dict[str, str] | None, jobs_n: int | None = None,
          old: dict[str, bytes] | None = None, docs: "dict[bytes, list[Node]] | None" = None,
          held: dict[str, bytes] | None = None,
          runner: "Callable[[list[LintJob]], Iterable[tuple[LintJob, ModelReport]]] | None"
          = None) -> Proof:
    """The proof for the new layouts ``changed`` ({real path: bytes}); ``old`` ({real path:
    bytes}, the files as they are) lets a file be proved from itself
    (:mod:`urdf_lint.formatting.inert`): the models are expanded for the others only;
    ``docs`` ({bytes: read_document}) holds the documents already read. The language
    server gives ``held`` ({real path: bytes}, its unsaved buffers: read in place of the
    files both before and after) and ``runner`` (jobs -> [(job, report)]: its warm pool of
    sandboxed workers; default a pool of ``jobs_n`` forked for the proof)."""
    from urdf_lint.discovery.discover import build_resolver, discover_models, repository_root
    from urdf_lint.core.jobs import LintJob
    from urdf_lint.discovery.packages import inside
    from urdf_lint.run.pipeline import worker_settings
    from urdf_lint.run.worker import run_jobs
    proof = Proof()
    if not changed:
        return proof
    root = repository_root(paths)
    scan = [root] + [p for p in paths if not inside(os.path.realpath(p), os.path.realpath(root))]
    resolver = build_resolver(scan, cfg, package_paths)
    # every model that may read a changed file, also those the config leaves out of linting
    every = dataclasses.replace(cfg, exclude=[], discover=True)
    disc = discover_models(scan, every, resolver)
    graph = disc.graph
    reach = _reach(graph)
    unproven, relaxed, quiet_test = _by_file(changed, old, docs, disc, reach, resolver.roots)

    def is_quiet(f: str) -> bool:
        # (asked only where a file of ``relaxed`` is read: then _by_file gave the test)
        assert quiet_test is not None
        return quiet_test(f)
    proof.by_file = len(changed) - len(unproven)
    # expanding proves only the branches the models' args take: a file whose changed
    # whitespace in an xacro:if/unless body the file's own rules do not prove is left alone
    branches = _in_branches(unproven, old, docs, changed)
    proof.refused.update(branches)
    unproven -= branches.keys()
    if not unproven and not relaxed:
        return proof

    def needed(files_read: set[str]) -> bool:
        """Must a model that reads these files be expanded before and after?"""
        return bool(files_read & unproven) or bool(files_read & relaxed) and not all(
            is_quiet(f) for f in sorted(files_read))
    jobs: "dict[Key, LintJob]" = {}
    for job in disc.jobs:
        if job.kind != "xacro":   # a .urdf model is the file itself: the guard compared it
            continue
        if needed(reach(job.entry)) or graph.unresolved_below(job.entry):
            key = (job.entry, tuple(sorted(job.args.items())))
            jobs[key] = LintJob(job.entry, dict(job.args), "expand", explicit=True)
    base = worker_settings(cfg, resolver)

    def expand(keys: "Iterable[Key]", overlay: dict[str, bytes]) -> "dict[Key, ModelReport]":
        """Each model of ``keys`` expanded with the new layouts ``overlay`` read in place of
        the files (the job's overlay, as the language server's unsaved buffers: nothing is
        written while it is proved)."""
        pairs = tuple(sorted({**(held or {}), **overlay}.items()))
        todo = {k: dataclasses.replace(jobs[k], overlay=pairs) for k in keys}
        by_job = {id(j): k for k, j in todo.items()}
        ran = runner(list(todo.values())) if runner is not None else \
            run_jobs(list(todo.values()), base, jobs_n=jobs_n)
        return {by_job[id(j)]: r for j, r in ran}
    before = expand(list(jobs), {})
    deps = {k: {os.path.realpath(d) for d in r.deps} for k, r in before.items()}
    # (a file proved where every file reads quietly, read by a model whose files do not)
    loud = {f for k in jobs for f in deps[k] & relaxed
            if not all(is_quiet(g) for g in sorted(deps[k]))}
    branches = _in_branches(loud, old, docs, changed)
    proof.refused.update(branches)
    proof.by_file -= len(branches)
    overlay = {f: v for f, v in changed.items() if f not in proof.refused}
    refused = proof.refused
    pending = [k for k in jobs if needed(deps[k])]
    proof.compared = len(pending)
    while pending:
        after = expand(pending, overlay)
        removed: set[str] = set()
        for k in pending:
            deps[k] |= {os.path.realpath(d) for d in after[k].deps}
            why = _difference(before[k], after[k])
            if why is None:
                continue
            label = before[k].label
            # the files not proved by themselves (all it reads, should those not do)
            culprits = deps[k] & overlay.keys() & (unproven | relaxed) or deps[k] & overlay.keys()
            for f in sorted(culprits):
                refused.setdefault(f, f"formatting would change the robot {label}: {why}")
                removed.add(f)
        for f in removed:
            overlay.pop(f, None)
        pending = [k for k in jobs if deps[k] & removed and deps[k] & overlay.keys()]
    return proof


def _reach(graph: "IncludeGraph") -> Reach:
    """The files a model's entry reads by the static include graph (itself included)."""
    def reach(entry: str) -> set[str]:
        seen, todo = {entry}, [entry]
        while todo:
            for g in graph.includes.get(todo.pop(), ()):
                if g not in seen:
                    seen.add(g)
                    todo.append(g)
        return seen
    return reach


def _by_file(changed: dict[str, bytes], old: dict[str, bytes] | None,
             docs: "dict[bytes, list[Node]] | None", disc: "Discovery", reach: Reach,
             roots: "Roots" = None
             ) -> "tuple[set[str], set[str], Callable[[str], bool] | None]":
    """(the changed files not proved from the file itself, those proved only where every
    file of their models reads quietly, the per-file quiet test) (:mod:`urdf_lint.formatting.inert`)."""
    unproven = set(changed)
    if not old:
        return unproven, set(), None
    from functools import lru_cache

    from urdf_lint.formatting.inert import proven
    read = lru_cache(maxsize=None)(read_document)

    def parsed(data: bytes) -> "list[Node]":   # (each layout read once: format_files read most)
        return (docs or {}).get(data) or read(data)
    for f in sorted(changed):
        if f in old and proven(parsed(old[f]), parsed(changed[f])) is None:
            unproven.discard(f)
    relaxed, is_quiet = _proven_quietly(unproven, changed, old, disc, reach, parsed, roots)
    return unproven - relaxed, relaxed, is_quiet


def _in_branches(files: set[str], old: dict[str, bytes] | None,
                 docs: "dict[bytes, list[Node]] | None",
                 changed: dict[str, bytes]) -> dict[str, str]:
    """{file: why} for the changed files whose new whitespace inside an xacro:if/unless body
    the rules of :mod:`urdf_lint.formatting.inert` do not prove: expanding the models proves
    only the branches their args take, so they are left alone."""
    from urdf_lint.formatting.inert import unproven_in_branches
    out = {}
    for f in sorted(files):
        if old is None or f not in old:
            continue
        try:
            why = unproven_in_branches(*((docs or {}).get(d) or read_document(d)
                                         for d in (old[f], changed[f])))
        except FormatError as e:
            why = e.message
        if why is not None:
            out[f] = f"formatting it cannot be proved for every value of the args: {why}"
    return out


def _difference(before: "ModelReport", after: "ModelReport") -> str | None:
    """None when a model's expansion before and after the new layouts is the same robot
    (or fails the same way); else how they differ."""
    (a, why_a), (b, why_b) = _outcome(before), _outcome(after)
    if a is not None and b is not None:
        return None if a == b else f"{first_difference(a, b)} differs"
    if a is None and b is None:
        # it does not expand either way: the guard is the proof
        return None if why_a == why_b else f"the expansion fails differently ({why_b})"
    return f"the expansion {'fails' if b is None else 'succeeds'} once formatted" + \
        (f" ({why_b})" if why_b else "")


def _proven_quietly(files: set[str], changed: dict[str, bytes], old: dict[str, bytes],
                    disc: "Discovery", reach: Reach, parsed: Parsed, roots: "Roots" = None
                    ) -> "tuple[set[str], Callable[[str], bool]]":
    """Those of ``files`` :func:`urdf_lint.formatting.inert.proven` holds for when xacro's
    reading of whitespace is quiet in every model that reads them: every file of those models
    (as it is and as it will be) :func:`~urdf_lint.formatting.inert.reads_quietly`; and the
    test of that per file. A model with an include only expansion resolves is not asked here:
    :func:`prove` expands it and asks once it knows what the model read."""
    from urdf_lint.core.fsbound import read_regular
    from urdf_lint.discovery.packages import MAX_SOURCE_BYTES
    from urdf_lint.formatting.inert import proven, reads_quietly
    ok = {f for f in files if f in old and proven(parsed(old[f]), parsed(changed[f]),
                                                 True) is None}
    quiet: dict[str, bool] = {}

    def is_quiet(f: str) -> bool:
        if f not in quiet:
            # (a file outside the roots is not read: it does not count as quiet)
            data = [old[f], changed[f]] if f in changed else [
                read_regular(f, MAX_SOURCE_BYTES, roots)]
            try:
                quiet[f] = all(d is not None and reads_quietly(parsed(d)) for d in data)
            except FormatError:
                quiet[f] = False
        return quiet[f]
    for job in disc.jobs:
        if job.kind != "xacro" or disc.graph.unresolved_below(job.entry):
            continue   # (what it reads is known once it is expanded: prove() checks it then)
        files_read = reach(job.entry)
        hit = files_read & ok
        if hit and not all(is_quiet(g) for g in sorted(files_read)):
            ok -= hit
    return ok, is_quiet
