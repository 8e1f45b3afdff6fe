"""``urdf-lint diff BASE [HEAD]``: what a change did to the robots, for review in CI.

1. Both revisions are materialised from git (``git archive``, extracted with tarfile's ``data``
   filter); HEAD defaults to the working tree, used in place.
2. HEAD is linted as ``check`` would (cache included); the models whose recorded inputs (every
   xacro, YAML, mesh and texture read, and every file looked for and missing) meet a changed
   path are *affected*. Deleted entry models are affected too.
3. Only the affected models are expanded at BASE; every other model costs nothing there.
4. Each affected model is expanded once more on each side in a worker (same isolation as
   ``check``) to get the robot itself, and :mod:`urdf_lint.review.robotdiff` compares the two.
5. Findings are compared by code, file (relative to the revision's root) and message: those
   only at HEAD are *introduced*, those only at BASE are *fixed*.
"""
from __future__ import annotations

import dataclasses
import functools
import io
import os
import tarfile
import tempfile
from collections import Counter
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, cast, overload

from urdf_lint.report.diff.base import DiffResult
from urdf_lint.review.robotdiff import ModelDiff, diff_models
from urdf_lint.core.codes import RuleName

if TYPE_CHECKING:  # pragma: no cover
    import threading
    from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence

    from urdf_lint.config.schema import Config
    from urdf_lint.core.jobs import LintJob, ModelReport
    from urdf_lint.core.locations import Origin
    from urdf_lint.discovery.discover import Discovery
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.engine.model import Model
    from urdf_lint.render.raster import Geometry
    from urdf_lint.render.recording import Plan, Recorder
    from urdf_lint.review.robotdiff import Change, FindingKey
    from urdf_lint.run.cache import Cache
    from urdf_lint.run.pipeline import CheckResult

    CfgLoader = Callable[[list[str]], Config]       # the config of a revision's paths
    # on_model(model_diff, head_model, base_model)
    OnModel = Callable[[ModelDiff, "Model | None", "Model | None"], object]
    # .rrd path -> (model key, its snapshot info, recording id, the revisions' plans)
    Recordings = dict[str, tuple[str, dict[str, Any], str, list[tuple[str, Plan]]]]

# the rules whose findings say a revision did not expand, by name (core.codes: importing the
# rule modules would load the rule API, which this command's parent does not need)
ul001_xml_syntax = RuleName("ul001_xml_syntax")
ul002_xacro_error = RuleName("ul002_xacro_error")
ul003_missing_include = RuleName("ul003_missing_include")
ul004_unknown_package = RuleName("ul004_unknown_package")
ul005_missing_arg = RuleName("ul005_missing_arg")
ul006_not_a_robot = RuleName("ul006_not_a_robot")
ul007_doctype = RuleName("ul007_doctype")
ul902_outside_roots = RuleName("ul902_outside_roots")
ul903_unsafe_expression = RuleName("ul903_unsafe_expression")
ul904_resource_limit = RuleName("ul904_resource_limit")

# the problems that say why a model could not be expanded or parsed
_FAILURE_RULES = (ul001_xml_syntax, ul002_xacro_error, ul003_missing_include,
                  ul004_unknown_package, ul005_missing_arg, ul006_not_a_robot, ul007_doctype,
                  ul902_outside_roots, ul903_unsafe_expression, ul904_resource_limit)



class ReviewError(Exception):
    pass


@overload
def _git(top: str, *args: str, binary: Literal[False] = False) -> str: ...


@overload
def _git(top: str, *args: str, binary: Literal[True]) -> bytes: ...


def _git(top: str, *args: str, binary: bool = False) -> str | bytes:
    """git in ``top`` (:func:`urdf_lint.discovery.vcs.git`); a failure is a ReviewError with
    git's last line."""
    from urdf_lint.discovery.vcs import GitError, git
    try:
        out: str | bytes = git(*args, cwd=top, timeout=120, binary=binary)
        return out
    except GitError as e:
        raise ReviewError(str(e).strip().splitlines()[-1]) from None


def verify_rev(top: str, rev: str) -> str:
    try:
        return _git(top, "rev-parse", "--verify", "--quiet", rev + "^{commit}").strip()
    except ReviewError:
        raise ReviewError(f"'{rev}' is not a commit in {top} (fetch it first, e.g. "
                          f"'git fetch origin {rev}')") from None


def materialize(top: str, rev: str, dest: str, only: "Iterable[str] | None" = None) -> None:
    """The tracked files of ``rev`` (or just ``only``, paths relative to the top) under
    ``dest``; links and paths that would leave ``dest`` are refused by tarfile's data filter."""
    from urdf_lint.core import fsbound
    fsbound.make_own_dirs(dest)   # a temporary folder of this run
    batches: list[list[str]]
    if only is None:
        batches = [[]]
    else:
        only = sorted(only)
        batches = [only[i:i + 400] for i in range(0, len(only), 400)]
    for batch in batches:
        if only is not None and not batch:
            continue
        spec = ["--"] + [":(literal)" + p for p in batch] if batch else []
        data = _git(top, "archive", "--format=tar", rev, *spec, binary=True)
        with tarfile.open(fileobj=io.BytesIO(data)) as tf:
            if hasattr(tarfile, "data_filter"):
                tf.extractall(dest, filter=_data_or_skip)
            else:   # a Python before 3.10.12 / 3.11.4 (Debian 12's 3.11.2): no filters
                tf.extractall(dest, members=_inside(tf, dest))


def _data_or_skip(member: tarfile.TarInfo, path: str) -> tarfile.TarInfo | None:
    """tarfile's ``data`` filter, but a member it refuses (an absolute symlink, a link out of
    the tree, a device) is left out instead of ending the run: what reads it later finds it
    missing, as the linted tree would not hold it either (inside the roots)."""
    try:
        return tarfile.data_filter(member, path)
    except tarfile.FilterError:
        return None


def _inside(tf: tarfile.TarFile, dest: str) -> "Iterator[tarfile.TarInfo]":
    """What :func:`_data_or_skip` keeps, where tarfile has no filters: folders, regular files
    and symlinks whose path, and a symlink's target, stay inside ``dest`` after symlinks (the
    members already extracted included), without setuid bits or group/other write."""
    top = os.path.realpath(dest)

    def inside(path: str) -> bool:
        return path == top or path.startswith(top + os.sep)
    for m in tf.getmembers():
        if not (m.isreg() or m.isdir() or m.issym()) or os.path.isabs(m.name):
            continue
        if not inside(os.path.realpath(os.path.join(top, m.name))):
            continue
        if m.issym() and (os.path.isabs(m.linkname) or not inside(os.path.realpath(
                os.path.join(top, os.path.dirname(m.name), m.linkname)))):
            continue
        m.mode &= 0o755
        yield m


def tracked_files(top: str, rev: str) -> set[str]:
    return {p for p in _git(top, "ls-tree", "-r", "-z", "--name-only", rev).split("\0") if p}


def name_status(top: str, base: str, head: str | None) -> list[tuple[str, str, str]]:
    """(status letter, old path, new path) relative to the top, renames detected."""
    args = ["diff", "--name-status", "-M", "-z", base] + ([head] if head else [])
    parts = _git(top, *args).split("\0")
    out, i = [], 0
    while i < len(parts) and parts[i]:
        st = parts[i]
        if st.startswith(("R", "C")):
            out.append((st[0], parts[i + 1], parts[i + 2]))
            i += 3
        else:
            out.append((st[0], parts[i + 1], parts[i + 1]))
            i += 2
    if head is None:
        for f in _git(top, "ls-files", "--others", "--exclude-standard", "-z").split("\0"):
            if f:
                out.append(("A", f, f))
    return out


@dataclass
class Side:
    """One revision of a ``diff`` run: its models, findings, robots and pictures."""
    root: str
    models: dict[str, ModelReport] = field(default_factory=dict)      # key -> ModelResult
    # key -> Counter of (code, file, message)
    findings: dict[str, Counter[FindingKey]] = field(default_factory=dict)
    # (code, file, message) -> severity
    severities: dict[FindingKey, str] = field(default_factory=dict)
    # (code, file, message) -> (line, col)
    lines: dict[FindingKey, tuple[int, int]] = field(default_factory=dict)
    # (code, file, message) -> (file relative to root, line, col) of the robot element
    related: dict[FindingKey, tuple[str, int, int]] = field(default_factory=dict)
    # (code, file, message) -> (file relative to root, line, col) its value comes from (a YAML
    # scalar, a property elsewhere: the finding's value_from)
    value_from: dict[FindingKey, tuple[str, int, int]] = field(default_factory=dict)
    robots: dict[str, Model | None] = field(default_factory=dict)      # key -> Model | None
    # key -> render.Geometry (diff --render)
    geometry: dict[str, Geometry] = field(default_factory=dict)
    rrd: dict[str, Plan] = field(default_factory=dict)    # key -> recording.Plan of this revision
    errors: dict[str, str] = field(default_factory=dict)      # key -> message
    # key -> its pictures' name (as `render`'s)
    pictures: dict[str, str] = field(default_factory=dict)


def _key(rel_entry: str, args: dict[str, str]) -> str:
    return rel_entry + ("" if not args else " [" + " ".join(
        f"{k}:={v}" for k, v in sorted(args.items())) + "]")


@functools.lru_cache(maxsize=65536)
def _realpath(path: str) -> str:
    return os.path.realpath(path)


def _rel(root: str, path: str) -> str:
    # memoised: every dependency of every model goes through here (thousands of paths)
    return os.path.relpath(_realpath(path), _realpath(root))


_SOURCE_SUFFIXES = (".xacro", ".urdf")


class _Reach:
    """Which models a change can reach without expanding them: when every changed path is a
    xacro or URDF file, a model is skipped (not linted at HEAD) when its include closure,
    read from the include graph, is complete (no include only expansion can resolve) and
    holds none of them. Any other change (YAML, meshes, manifests, configs) lints every
    model, whose recorded inputs then say which are affected."""

    def __init__(self, changed_abs: "Iterable[str]") -> None:
        self.changed = {os.path.realpath(p) for p in changed_abs}
        self.active = bool(self.changed) and all(p.endswith(_SOURCE_SUFFIXES)
                                                 for p in self.changed)
        self.skipped = 0   # models not linted (counted in the total)

    def __call__(self, jobs: "list[LintJob]", found: "Discovery") -> "list[LintJob]":
        if not self.active:
            return jobs
        keep = []
        for job in jobs:
            if self._may_reach(job, found):
                keep.append(job)
            elif job.entry not in found.fragments:
                self.skipped += 1
        return keep

    def _may_reach(self, job: "LintJob", found: "Discovery") -> bool:
        graph = found.graph
        # a xacro with generated outputs reads those files too (UL011 compares them); a
        # generated URDF is a model of its own, whose only source is itself
        todo = [job.entry] + ([job.output] if job.output else []) + list(job.outputs)
        seen: set[str] = set()
        while todo:
            f = todo.pop()
            real = _realpath(f)
            if real in seen:
                continue
            seen.add(real)
            if real in self.changed:
                return True
            if f.endswith(".xacro"):
                if f not in graph.includes or graph.unresolved.get(f):
                    return True   # not read, or an include only expansion can resolve
                todo.extend(graph.includes.get(f, ()))
        return False


def _lint_side(side: Side, paths: "Sequence[str]", cfg: "Config",
               package_paths: dict[str, str] | None, jobs_n: int | None,
               cache: "Cache | None", keep_models: bool = False,
               mesh_cache_dir: str | None = None,
               select_jobs: "Callable[[list[LintJob], Any], list[LintJob]] | None" = None,
               settings_overrides: "Mapping[str, Any] | None" = None, explore: bool = False
               ) -> "tuple[PackageResolver, CheckResult]":
    """Lint one revision as ``check`` would; with ``keep_models`` the robots come back from
    the same expansion (no second pass in :func:`_load_robots`). Packages resolve from the
    whole revision (``side.root``), as they do at HEAD, even when only a few entries are
    linted."""
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.core.locations import picture_name
    from urdf_lint.run.pipeline import RunRequest, run_check
    resolver = build_resolver(list(dict.fromkeys([side.root, *paths])), cfg, package_paths)
    result = run_check(RunRequest(paths, cfg, resolver, jobs_n=jobs_n or cfg.jobs, cache=cache,
                                  keep_models=keep_models, mesh_cache_dir=mesh_cache_dir,
                                  select_jobs=select_jobs,
                                  settings_overrides=settings_overrides, explore=explore))
    labels: dict[str, str] = {}
    for m in result.models:
        k = _key(_rel(side.root, m.entry), m.args)
        side.models[k] = m
        side.pictures[k] = picture_name(_rel(side.root, m.entry), m.args)
        labels[m.label] = k
        side.findings[k] = Counter()
    # one entry per finding and model, as every command counts (core.findings.group): a macro
    # line that makes two joints of one model wrong is one finding there, named by its first
    # instance in that model, with how many more it stands for
    from urdf_lint.core.findings import group
    for g in group(result.findings):
        for label in g.models:
            if label not in labels:
                continue
            own = [i for i in g.each() if label in i.models] or [g]
            more = f" (and {len(own) - 1} more like it)" if len(own) > 1 else ""
            fk = (g.code, _rel(side.root, g.file), _unrooted(side.root, own[0].message) + more)
            side.severities[fk] = g.severity
            side.lines.setdefault(fk, (own[0].line, own[0].col))
            if own[0].related:     # an SRDF or YAML finding's robot element (its xacro line)
                side.related.setdefault(fk, (_rel(side.root, own[0].related[0]),
                                             *own[0].related[1:3]))
            if own[0].value_from:  # the YAML line (or property) its value comes from
                side.value_from.setdefault(fk, (_rel(side.root, own[0].value_from[0]),
                                                *own[0].value_from[1:3]))
            side.findings[labels[label]][fk] += 1
    return resolver, result


def _unrooted(root: str, message: str) -> str:
    """A message naming files relative to the revision's root (a temporary copy)."""
    return message.replace(_realpath(root) + os.sep, "").replace(root + os.sep, "")


def _load_robots(side: Side, keys: "Iterable[str]", resolver: "PackageResolver", cfg: "Config",
                 jobs_n: int | None, render: bool = False, rrd: bool = True) -> None:
    """Expand the given models once more in workers and build the Model of each (and, for
    ``--render``, the geometry of its picture and its half of the shared recording)."""
    from urdf_lint.core.jobs import LintJob
    from urdf_lint.run.pipeline import settings_for
    from urdf_lint.run.worker import run_jobs
    jobs: list[LintJob] = []
    key_of: dict[int, str] = {}
    for k in keys:
        m = side.models.get(k)
        if m is None:
            continue
        kind = "urdf" if m.entry.endswith(".urdf") else "xacro"
        job = LintJob(m.entry, dict(m.args), kind, explicit=True)
        jobs.append(job)
        key_of[id(job)] = k
    settings = dataclasses.replace(settings_for(cfg, resolver, None), selected=(),
                                   keep_model=True)
    if render:
        settings = dataclasses.replace(settings, diff_render=True, diff_rrd=rrd)
    for job, res in run_jobs(jobs, settings, jobs_n=jobs_n or cfg.jobs):
        k = key_of[id(job)]
        if res.diff_geometry is not None:
            side.geometry[k] = cast("Geometry", res.diff_geometry)
        if res.diff_rrd:
            side.rrd[k] = cast("Plan", res.diff_rrd)
        _keep_robot(side, k, job.entry, job.args, res, resolver)


def _keep_robot(side: Side, k: str, entry: str, args: dict[str, str], res: "ModelReport",
                resolver: "PackageResolver | None") -> None:
    """The Model of a report that kept its robot (``LintSettings.keep_model``), or why not."""
    from urdf_lint.engine.model import Model, model_from_xml, parse_urdf_bytes
    kept = res.kept_model
    if kept is None:
        failures = {r.CODE for r in _FAILURE_RULES}
        msgs = [p.message for p in res.problems if p.code in failures]
        side.robots[k] = None
        side.errors[k] = (_unrooted(side.root, msgs[0]) if msgs
                          else "the model could not be expanded")
        return
    if kept.xml is not None:
        side.robots[k] = model_from_xml(entry, args, kept.xml, kept.origins, res.deps, resolver,
                                        kept.values)
    else:
        from urdf_lint.core import fsbound
        try:
            data = fsbound.read_bytes(entry, resolver.roots if resolver is not None else None)
        except OSError:
            data = b""
        root, origins, _ = parse_urdf_bytes(entry, data)
        side.robots[k] = (Model(entry=entry, args={}, root=root, origins=origins,
                                deps=[entry], resolver=resolver)
                          if root is not None else None)


def _half(jobs_n: int | None, cfg: "Config") -> int:
    """Workers for one of two revisions that are linted / drawn at the same time."""
    return max(1, (jobs_n or cfg.jobs or os.cpu_count() or 2) // 2)


class _Background:
    """``fn(*args)`` in a thread (its workers are processes: the thread only waits on
    them); :meth:`join` raises what it raised."""

    def __init__(self, fn: "Callable[..., object]", *args: Any) -> None:
        import threading
        self.error: BaseException | None = None
        self.thread: threading.Thread | None = None
        if args and not args[1]:   # no keys: nothing to do
            return

        def run() -> None:
            try:
                fn(*args)
            except BaseException as e:  # noqa: BLE001 - raised again by join()
                self.error = e
        self.thread = threading.Thread(target=run, name="urdf-lint-diff", daemon=True)
        self.thread.start()

    def join(self) -> None:
        if self.thread is not None:
            self.thread.join()
        if self.error is not None:
            raise self.error


def run_diff(base_rev: str, head_rev: str | None, paths: "Sequence[str]",
             cfg_loader: CfgLoader, package_paths: dict[str, str] | None = None,
             jobs_n: int | None = None, use_cache: bool = True, render_dir: str | None = None,
             rrd: bool = True, on_model: OnModel | None = None) -> DiffResult:
    """``on_model(model_diff, head_model, base_model)``, when given, is called for each model
    diff at the end, while both revisions are still on disk (``diff --html`` reads the
    meshes then); it may change the models."""
    from urdf_lint.discovery.discover import start_dir
    from urdf_lint.discovery.vcs import git_root
    top = git_root(start_dir(paths))
    if top is None:
        raise ReviewError("diff compares git revisions: run it inside a git repository")
    base_sha = verify_rev(top, base_rev)
    head_sha = verify_rev(top, head_rev) if head_rev else None
    result = DiffResult(base=base_rev, head=head_rev or "working tree")
    # the recordings' writer imports rerun while the revisions are linted (forked now, before
    # any worker or thread)
    recorder = _start_recorder(render_dir) if render_dir and rrd else None
    try:
        with tempfile.TemporaryDirectory(prefix="urdf-lint-diff-") as tmp:
            return _run_diff(result, top, base_sha, head_sha, paths, cfg_loader, package_paths,
                             jobs_n, use_cache, render_dir, rrd, recorder, tmp, on_model)
    finally:
        if recorder is not None:
            recorder.close()


def _start_recorder(render_dir: str) -> "Recorder | None":
    from urdf_lint.render.recording import Recorder
    try:
        return Recorder(render_dir)
    except OSError:   # no process to spare: the recordings are written here
        return None


@dataclass
class _Changes:
    """What git says changed between the revisions (paths relative to the top)."""
    entries: list[tuple[str, str, str]]   # (status letter, old path, new path)
    head: set[str]                # paths present at HEAD that changed
    base: set[str]                # paths present at BASE that changed
    renamed: dict[str, str]       # new path -> old path

    @classmethod
    def between(cls, top: str, base_sha: str, head_sha: str | None) -> _Changes:
        changes = name_status(top, base_sha, head_sha)
        return cls(changes, {new for st, _, new in changes if st != "D"},
                   {old for st, old, _ in changes if st != "A"},
                   {new: old for st, old, new in changes if st == "R"})

    def at_base(self, rel: str) -> str:
        """Where a HEAD path was at BASE (through a rename)."""
        return self.renamed.get(rel, rel)


def _inputs(root: str, m: "ModelReport") -> list[str]:
    """Every path (relative to ``root``) model result ``m`` read or looked for, entry included."""
    return [_rel(root, d) for d in list(m.deps) + list(getattr(m, "missing", [])) + [m.entry]]


def _run_diff(result: DiffResult, top: str, base_sha: str, head_sha: str | None,
              paths: "Sequence[str]", cfg_loader: CfgLoader,
              package_paths: dict[str, str] | None, jobs_n: int | None, use_cache: bool,
              render_dir: str | None, rrd: bool, recorder: "Recorder | None", tmp: str,
              on_model: OnModel | None = None) -> DiffResult:
    changed = _Changes.between(top, base_sha, head_sha)
    head_root = top
    if head_sha:
        head_root = os.path.join(tmp, "head")
        materialize(top, head_sha, head_root)
    base_root = os.path.join(tmp, "base")
    rel_paths = [os.path.relpath(os.path.abspath(p), top) for p in (paths or ["."])]

    head = Side(head_root)
    head_paths = [os.path.normpath(os.path.join(head_root, p)) for p in rel_paths]
    head_paths = [p for p in head_paths if os.path.exists(p)] or [head_root]
    cfg = cfg_loader(head_paths)
    cache = _head_cache(head_paths, cfg) if use_cache and head_sha is None else None
    # models linted now (not from the cache) bring their robot back: no second expansion
    # models the change cannot reach (include graph) are not even linted
    reach = _Reach([os.path.join(head_root, p) for p in changed.head] +
                   [os.path.join(head_root, p) for p in changed.base])
    # both revisions explore the branches their defaults miss, or neither (a picture run)
    head_resolver, head_result = _lint_side(head, head_paths, cfg, package_paths, jobs_n,
                                            cache, keep_models=not render_dir,
                                            select_jobs=reach, explore=not render_dir)
    result.internal += head_result.internal
    result.total_models = len(head.models) + reach.skipped

    touched = changed.head | changed.base
    affected = [k for k, m in head.models.items() if set(_inputs(head_root, m)) & touched]
    if render_dir:
        _clear_snapshots(render_dir)
    again = _keep_affected_robots(head, affected, head_resolver, render_dir)
    # the head's robots (and pictures) are made while the base is materialised and linted
    head_load = _Background(_load_robots, head, again, head_resolver, cfg,
                            _half(jobs_n, cfg), bool(render_dir), rrd)
    # (an exception from here on leaves it: its workers die with this process)
    base_jobs = _half(jobs_n, cfg) if head_load.thread is not None else jobs_n
    _materialize_base(top, base_sha, base_root, head, affected, changed)
    base_entries = _base_entries(base_root, head, affected, changed, rel_paths)
    base = Side(base_root)
    at_base = {k: _key(changed.at_base(_rel(head_root, m.entry)), m.args)
               for k, m in head.models.items()}
    if base_entries:
        # the affected variants of an entry, not its others (the change does not reach
        # them: unchanged, never "removed"), and every variant of a deleted entry
        select = _BaseSelect(base_root, {at_base[k] for k in affected},
                             {changed.at_base(_rel(head_root, head.models[k].entry))
                              for k in affected})
        _lint_base(result, base, base_entries, cfg_loader, package_paths, base_jobs,
                   cache.dir if cache else None, render_dir, rrd, select)
    result.base_expanded = len(base.models)

    base_keys = {k: at_base[k] for k in affected if at_base[k] in base.models}
    present = set(at_base.values())
    deleted = [k for k in base.models if k not in base_keys.values() and k not in present]
    head_load.join()

    shown = top if head_sha else None
    for k in sorted(affected):
        result.models.append(_model_diff(k, head, base, base_keys.get(k), top=shown))
    for dk in sorted(deleted):
        result.models.append(_model_diff(dk, head, base, dk, removed=True, top=shown))
    if render_dir:
        _render_snapshots(result, head, base, base_keys, render_dir, cfg, recorder)
    _hand_robots(on_model, result, head, base, base_keys, affected, deleted)
    return result


def _hand_robots(on_model: OnModel | None, result: DiffResult, head: Side, base: Side,
                 base_keys: dict[str, str], affected: list[str], deleted: list[str]) -> None:
    """``on_model(model_diff, head_model, base_model)`` for each model diff (in the order
    ``_run_diff`` appended them), when ``on_model`` is given."""
    if on_model is None:
        return
    robots = [(head.robots.get(k), base.robots.get(base_keys[k]) if k in base_keys else None)
              for k in sorted(affected)]
    robots += [(None, base.robots.get(dk)) for dk in sorted(deleted)]
    for md, (hm, bm) in zip(result.models, robots, strict=True):
        on_model(md, hm, bm)


def _head_cache(head_paths: "Sequence[str]", cfg: "Config") -> "Cache | None":
    """The working tree's cache, or None when it is refused (said why on stderr)."""
    from urdf_lint.run.cache import Cache
    cache = Cache.for_paths(head_paths, cfg)
    return None if cache.refused else cache


def _keep_affected_robots(head: Side, affected: list[str], resolver: "PackageResolver",
                          render_dir: str | None) -> list[str]:
    """Keep the robots the head's lint brought back for the affected models; the keys of
    those that must be expanded again (all of them with ``render_dir``: pictures are drawn
    from a fresh expansion) are returned. Every other kept model is dropped."""
    again = []
    for k in affected:
        m = head.models[k]
        if m.kept_model is not None and not render_dir:
            _keep_robot(head, k, m.entry, m.args, m, resolver)
        else:
            again.append(k)
    for m in head.models.values():
        m.kept_model = None  # only the affected robots are needed from here on
    return again


_BASE_MANIFESTS = ("package.xml", "pyproject.toml", "urdf-lint.toml", "COLCON_IGNORE",
                   "CATKIN_IGNORE")


def _materialize_base(top: str, base_sha: str, base_root: str, head: Side, affected: list[str],
                      changed: _Changes) -> None:
    """The base needs only what the affected models can read there: their inputs at HEAD
    (through renames), every changed path, and the package manifests and configs."""
    base_files = tracked_files(top, base_sha)
    need = set(changed.base)
    for k in affected:
        need.update(changed.at_base(rel) for rel in _inputs(head.root, head.models[k]))
    need |= {f for f in base_files if os.path.basename(f) in _BASE_MANIFESTS}
    materialize(top, base_sha, base_root, only=need & base_files)
    # and what the base's config names (its models must exist to validate it there)
    from urdf_lint.config.schema import find_config, named_files
    from urdf_lint.core.tree import inside
    conf = find_config(base_root)
    if conf is not None and inside(str(conf), os.path.realpath(base_root)):
        named = {os.path.relpath(f, os.path.realpath(base_root)) for f in named_files(conf)}
        if (named & base_files) - need:
            materialize(top, base_sha, base_root, only=(named & base_files) - need)


def _base_entries(base_root: str, head: Side, affected: list[str], changed: _Changes,
                  rel_paths: list[str]) -> set[str]:
    """The models to expand at BASE: the affected ones (through renames) and the deleted
    model files under the paths asked for."""
    from urdf_lint.engine.lint import classify_xacro
    base_entries: set[str] = set()
    for k in affected:
        rel = changed.at_base(_rel(head.root, head.models[k].entry))
        if os.path.exists(os.path.join(base_root, rel)):
            base_entries.add(rel)
    for st, old, _new in changed.entries:
        if st in ("D", "R") and old.endswith((".urdf", ".xacro")) and \
                any(old == p or old.startswith(p.rstrip("/") + "/") or p == "."
                    for p in rel_paths):
            f = os.path.join(base_root, old)
            if os.path.isfile(f) and (old.endswith(".urdf") or classify_xacro(f) is None):
                base_entries.add(old)
    return base_entries


@dataclass
class _BaseSelect:
    """The base's jobs worth linting: the wanted variants (keys) of the affected entries,
    every job of any other entry (a deleted one)."""
    root: str
    wanted: set[str]
    entries: set[str]

    def __call__(self, jobs: "list[LintJob]", found: Any) -> "list[LintJob]":
        keep = []
        for j in jobs:
            rel = _rel(self.root, j.entry)
            if rel not in self.entries or _key(rel, j.args) in self.wanted:
                keep.append(j)
        return keep


def _lint_base(result: DiffResult, base: Side, base_entries: set[str], cfg_loader: CfgLoader,
               package_paths: dict[str, str] | None, jobs_n: int | None,
               mesh_cache_dir: str | None, render_dir: str | None, rrd: bool,
               select: _BaseSelect | None = None) -> None:
    """Lint the base entries and keep their robots (and with --render their pictures'
    geometry and half recordings): all from this one expansion; mesh facts (keyed by
    content) are shared with the working tree's cache."""
    base_paths = [os.path.join(base.root, e) for e in sorted(base_entries)]
    base_cfg = cfg_loader([base.root])
    overrides = {"diff_render": True, "diff_rrd": rrd} if render_dir else None
    base_resolver, base_result = _lint_side(
        base, base_paths, base_cfg, package_paths, jobs_n, None, keep_models=True,
        mesh_cache_dir=mesh_cache_dir, settings_overrides=overrides, select_jobs=select,
        explore=not render_dir)
    result.internal += base_result.internal
    for k, m in base.models.items():
        _keep_robot(base, k, m.entry, m.args, m, base_resolver)
        if m.diff_geometry is not None:
            base.geometry[k] = cast("Geometry", m.diff_geometry)
        if m.diff_rrd:
            base.rrd[k] = cast("Plan", m.diff_rrd)


def _render_snapshots(result: DiffResult, head: Side, base: Side, base_keys: dict[str, str],
                      render_dir: str, cfg: "Config", recorder: "Recorder | None") -> None:
    """Draw each model's before/after pictures (and recordings) and write the manifest; two
    models whose pictures would share a name are not drawn (a snapshot problem)."""
    from urdf_lint.core.locations import clashing_names
    from urdf_lint.render.snapshot import write_manifest
    recordings: Recordings = {}
    clash = clashing_names({md.model: md.picture for md in result.models})
    for name, models in clash.items():
        result.snapshot_problems += [(k, f"another model ({', '.join(o for o in models if o != k)}) "
                                         f"has the picture name {name}: neither is drawn")
                                     for k in models]
    for md in result.models:
        if md.picture in clash:
            md.snapshot = {}
            continue
        removed = md.status == "removed"
        md.snapshot = _snapshot(md.model, head, base, None if removed else md.model,
                                md.model if removed else base_keys.get(md.model),
                                render_dir, result, cfg, recorder, recordings)
    _finish_recordings(result, recorder, recordings)
    files = [v for md in result.models for k, v in md.snapshot.items()
             if k in ("before", "after", "diff", "rrd") and v]
    write_manifest(render_dir, files)


def _clear_snapshots(render_dir: str) -> None:
    """Remove what an earlier diff --render wrote here (its manifest), so no stale picture
    survives; files this tool did not write stay."""
    from urdf_lint.render.snapshot import clear_stale
    from urdf_lint.core import fsbound
    fsbound.make_own_dirs(render_dir)   # checked by the CLI (check_no_symlink)
    if os.path.islink(render_dir):
        raise ReviewError(f"--render {render_dir} is a symbolic link; refusing to write there")
    clear_stale(render_dir)


def _snapshot(key: str, head: Side, base: Side, hk: str | None, bk: str | None, render_dir: str,
              result: DiffResult, cfg: "Config | None" = None, recorder: "Recorder | None" = None,
              recordings: "Recordings | None" = None) -> dict[str, Any]:
    from urdf_lint.render import snapshot as render
    md = next(m for m in result.models if m.model == key)
    stem = os.path.join(render_dir, md.picture)
    before = base.geometry.get(bk) if bk else None
    after = head.geometry.get(hk) if hk else None
    info: dict[str, Any] = {}
    lost = [side for side, g, wanted in (("base", before, md.status != "added"),
                                         ("head", after, md.status != "removed"))
            if wanted and g is None]
    if lost:
        result.snapshot_problems.append(
            (key, f"no picture of the {' and '.join(lost)} revision (it did not expand; see "
                  "'urdf-lint check')"))
    if before is None and after is None:
        return info
    changed = {name for name, _, _ in md.moved}
    changed |= {c.name for c in md.changes if c.kind == "link"}
    whole = after if after is not None else before
    if md.status in ("added", "removed") and whole is not None:
        changed |= set(whole.part_links) | set(whole.wire_links)
    views = (cfg.views if cfg is not None else None) or "sheet"
    forward = cfg.forward_axis if cfg is not None else "+x"
    plans = [(prefix, p) for prefix, p in (("base/", base.rrd.get(bk) if bk else None),
                                           ("head/", head.rrd.get(hk) if hk else None)) if p]
    if plans and recordings is not None:
        # both revisions in one recording, written by the recorder while the pictures are
        # drawn (collected by _finish_recordings)
        path, rid = stem + ".rrd", f"urdf-lint-diff/{md.picture}"
        recordings[path] = (key, info, rid, plans)
        if recorder is not None:
            recorder.write(path, rid, plans, blueprint=("base/", "head/"))
    info.update(render.render_pair(before, after, stem, frozenset(changed), views=views,
                                   forward=forward, unseen=_unseen(md)))
    return info


_DRAWN = ("origin", "axis", "parent", "child", "visual", "collision", "geometry")


def _unseen(md: ModelDiff, most: int = 3) -> str:
    """What changed in a model that its pictures do not show: joint limits, masses and
    inertia, materials, mimic and dynamics (``joint 'elbow' limit.lower, limit.upper``), and the
    findings the change introduced, so a picture never reads 'changed: nothing' beside a
    table of changes."""
    fields: dict[str, list[str]] = {}
    for c in md.changes:
        if c.change == "changed" and c.field and not c.field.startswith(_DRAWN):
            fields.setdefault(f"{c.kind} '{c.name}'", []).append(c.field)
    parts = [f"{what} {', '.join(fs)}" for what, fs in list(fields.items())[:most]]
    if len(fields) > most:
        parts.append(f"{len(fields) - most} more")
    if md.findings_introduced:
        parts.append(f"{len(md.findings_introduced)} new finding(s)")
    return "; ".join(parts)


def _finish_recordings(result: DiffResult, recorder: "Recorder | None",
                       recordings: "Recordings") -> None:
    """Wait for the recorder (or write here without one); a recording that could not be
    written is a snapshot problem, except when rerun is not installed (no .rrd then, as
    ``--no-rrd``, and ``result.no_recordings`` says why once)."""
    from urdf_lint.render.recording import NO_RERUN, write_recording
    if not recordings:
        return
    if recorder is not None:
        done = recorder.results()
    else:
        done = {path: write_recording(path, rid, plans, blueprint=("base/", "head/"))
                for path, (_k, _i, rid, plans) in recordings.items()}
    for path, (key, info, _rid, _plans) in recordings.items():
        why = done.get(path, "not written")
        if why is None:
            info["rrd"] = path
        elif why == NO_RERUN:   # an optional part: the pictures are made, said once
            result.no_recordings = why
        else:
            result.snapshot_problems.append((key, f"no recording: {why}"))


def _model_diff(k: str, head: Side, base: Side, bk: str | None, removed: bool = False,
                top: str | None = None) -> ModelDiff:
    """``top``: the repository, where locations are shown when HEAD is a revision (its
    files are in a temporary folder)."""
    hm = None if removed else head.robots.get(k)
    bm = base.robots.get(bk) if bk else None
    if removed:
        status = "removed"
    elif bk is None:
        status = "added"
    else:
        status = "changed"
    shown = base.pictures.get(bk, "") if bk is not None else ""
    md = ModelDiff(model=k, status=status,
                   picture=shown if removed else head.pictures.get(k, ""))
    if not removed and hm is None:
        md.status, md.error = "failed", head.errors.get(k, "")
    elif bk is not None and bm is None and not removed:
        md.error = "at base: " + base.errors.get(bk, "")
    try:
        changes, md.moved = diff_models(bm, hm)
        md.changes = [_rebase(c, base.root, head.root, top) for c in changes]
    except Exception as e:  # noqa: BLE001 - a malformed model still gets its findings diff
        md.error = f"could not compare: {type(e).__name__}: {e}"
    _findings_diff(md, head.findings.get(k, Counter()) if not removed else Counter(),
                   base.findings.get(bk, Counter()) if bk else Counter(), head, base)
    if status == "changed" and not md.changes and not md.moved and not md.findings_introduced \
            and not md.findings_fixed and not md.error:
        md.status = "unchanged"
    return md


def _findings_diff(md: ModelDiff, hf: "Counter[FindingKey]", bf: "Counter[FindingKey]",
                   head: Side, base: Side) -> None:
    """The findings only HEAD has (introduced) and only BASE has (fixed), with where each is
    in its revision (the key has no line: an edit above it moves it), the robot element
    an SRDF or YAML finding is about and where its value comes from (a YAML line)."""
    md.findings_introduced = [(fk, head.severities.get(fk, "error"))
                              for fk in sorted((hf - bf).elements())]
    md.findings_fixed = [(fk, base.severities.get(fk, "error"))
                         for fk in sorted((bf - hf).elements())]
    for side, items in ((base, md.findings_fixed), (head, md.findings_introduced)):
        md.finding_lines.update({fk: side.lines[fk] for fk, _ in items if fk in side.lines})
        md.finding_related.update({fk: side.related[fk] for fk, _ in items
                                   if fk in side.related})
        md.finding_value_from.update({fk: side.value_from[fk] for fk, _ in items
                                      if fk in side.value_from})


def _rebase(c: "Change", base_root: str, head_root: str, top: str | None = None) -> "Change":
    """Locations name the file where it is in the repository (``top``), not in a temporary
    copy of a revision: base-side ones always, head-side ones too when HEAD is a revision."""
    from dataclasses import replace

    from urdf_lint.core.locations import Origin
    moves = [(root, to) for root, to in [(base_root, top or head_root)]
             + ([(head_root, top)] if top else []) for root in (root, _realpath(root))]

    def move(p: str) -> str:
        for root, to in moves:
            rel = os.path.relpath(p, root)
            if not rel.startswith(".."):
                return os.path.join(to, rel)
        return p

    def origin(o: "Origin | None") -> "Origin | None":
        return o if o is None else Origin(move(o.file), o.line, o.col,
                                          tuple((move(x[0]),) + tuple(x[1:]) for x in o.chain))
    return replace(c, base=origin(c.base), head=origin(c.head),
                   value_from=(move(c.value_from[0]), *c.value_from[1:]) if c.value_from
                   else ())


def exit_code(result: DiffResult, fail_on: str) -> int:
    from urdf_lint.core.findings import exit_status
    code = exit_status((sev for m in result.models for _, sev in m.findings_introduced),
                       bool(result.internal), fail_on)
    # a requested snapshot that could not be made fails the run (said on stderr by the CLI)
    return max(code, 1) if result.snapshot_problems else code
