"""The run pipeline of ``urdf-lint check``: discover -> lint every model (workers, cache) ->
run-scope rules -> merge -> suppress -> policy -> CheckResult.

Discovery is :mod:`urdf_lint.discovery.discover`, one model's lint :mod:`urdf_lint.engine.lint` (inside
workers, :mod:`urdf_lint.runner.pool`), what is kept and at what severity :mod:`urdf_lint.config.policy`.
"""
from __future__ import annotations

import dataclasses
import functools
import os
from dataclasses import dataclass, field
from collections.abc import Set as AbstractSet
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence

from urdf_lint.discovery.discover import discover_models
from urdf_lint.core.findings import Problem, exit_status
from urdf_lint.core.jobs import DEFAULT_ENV_ALLOW, LintJob, LintSettings, ModelReport
from urdf_lint.config.policy import Policy
from urdf_lint.core.codes import RuleName
from urdf_lint.run.finish import FRAGMENT_HINT_CODES, Scope, finish, scope, split_models

# the rules raised or consulted here, by name (core.codes: importing a rule module loads the
# rule API and what it needs, ~12 ms of every run's start-up)
ul004_unknown_package = RuleName("ul004_unknown_package")

if TYPE_CHECKING:  # pragma: no cover
    import re
    from urdf_lint.discovery.discover import Discovery, IncludeGraph
    from urdf_lint.meshes.store import FactsStore
    from urdf_lint.run.cache import Cache
    from urdf_lint.config.schema import Config
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.run.explore import Early
    from urdf_lint.run.runcache import RunMemo
    from urdf_lint.run.worker import RunPool

@dataclass
class CheckResult:
    """The outcome of a check run: findings after merging and policy, the linted models,
    the files skipped, and internal errors."""
    findings: list[Problem] = field(default_factory=list)     # merged, after policy
    models: list[ModelReport] = field(default_factory=list)   # the linted models
    skipped: list[ModelReport] = field(default_factory=list)  # libraries etc.
    internal: list[str] = field(default_factory=list)     # internal errors (exit 2)
    unused_files: list[str] = field(default_factory=list)
    fragments: dict[str, list[str]] = field(default_factory=dict)   # fragment -> its includers
    gone: list[str] = field(default_factory=list)         # deleted files no model reads any more
    generated: dict[str, str] = field(default_factory=dict)    # generated .urdf -> the xacro it comes from
    reused: bool = False                             # the last identical run's result (runcache)
    baselined: int = 0                               # findings the baseline hid (finish.scope)
    # branch coverage per model label (run.explore.coverage), when exploration ran
    coverage: dict[str, dict[str, Any]] = field(default_factory=dict)


def worker_settings(cfg: "Config", resolver: "PackageResolver", **fields: Any) -> LintSettings:
    """The settings every worker of a run starts from: the packages, the variables
    ``$(env)``/``$(optenv)`` may read and the limits of one model, from ``cfg``; ``fields``
    set the rest."""
    return LintSettings(resolver=resolver.to_dict(),
                        env_allow=tuple(sorted(set(DEFAULT_ENV_ALLOW) | set(cfg.env_allow))),
                        env_set=tuple(sorted(os.environ)),
                        timeout=cfg.timeout, memory_mb=cfg.memory_mb, **fields)


def settings_for(cfg: "Config", resolver: "PackageResolver", cache_dir: str | None,
                 policy: Policy | None = None) -> LintSettings:
    from urdf_lint.config.schema import ConfigError
    from urdf_lint.engine.registry import catalogue, load_rule
    rules = catalogue()
    policy = policy or Policy.from_config(cfg)
    options = {}
    for code, e in rules.items():
        o = cfg.options_for(code, e.name)
        if o:
            r = load_rule(code)
            assert r is not None
            unknown = set(o) - set(r.options)
            if unknown:
                raise ConfigError(f"unknown option(s) for {code} {r.name}: "
                                  f"{', '.join(sorted(unknown))} (known: "
                                  f"{', '.join(sorted(r.options)) or 'none'})")
            options[code] = o
    return worker_settings(cfg, resolver, selected=tuple(policy.selected_codes(rules)),
                           targets=tuple(policy.targets), options=options,
                           mesh_cache_dir=cache_dir)


@dataclass(frozen=True)
class RunRequest:
    """What one check run lints and how: the one argument of :func:`run_check`.

    ``paths`` and ``affected_by`` are frozen (a tuple, a frozenset) when the request is made;
    a variant of a request is ``dataclasses.replace(request, keep_models=False)``."""
    paths: Sequence[str]               # (a tuple once made)
    cfg: "Config"
    resolver: "PackageResolver"
    jobs_n: int | None = None          # workers (None: one per core, as ``run_jobs`` decides)
    cache: "Cache | None" = None
    progress: Callable[[int, int], None] | None = None   # progress(done, total) per linted model
    # changed files: report only the models whose inputs include one of them; files no
    # model uses land in ``CheckResult.unused_files``
    affected_by: AbstractSet[str] | None = None   # (a frozenset once made)
    render_dir: str | None = None      # set: the workers also draw a snapshot of each model
    render_rrd: bool = True            # ... and a recording beside it
    # lint in this process, without workers and their limits (trusted input only: tests
    # and benchmarks)
    in_process: bool = False
    # bring every expanded robot back (``ModelReport.kept_model``; ``--fix`` compares them
    # before and after)
    keep_models: bool = False
    # set: mesh facts are read from and kept in the user's facts store also when ``cache`` is
    # None (``diff`` lints the base revision with the store the working tree uses)
    mesh_cache_dir: str | None = None
    # select_jobs(jobs, discovery) keeps only the jobs worth linting (``diff``: the models a
    # change can reach through the include graph)
    select_jobs: Callable[[list[LintJob], Any], list[LintJob]] | None = None
    # set on the workers' settings (``diff --render``: the base's pictures come from its
    # lint pass)
    settings_overrides: Mapping[str, Any] | None = None
    # the end of the run that depends on who asks (run.finish.scope): the paths a fix may
    # edit, the baseline; None: the findings as the rules and the policy left them
    scope: Scope | None = None
    # explore the branches the defaults miss (run.explore; also needs cfg.explore): None, as
    # _explores decides from the rest of the request; ``diff`` sets it for both revisions alike
    explore: bool | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "paths", tuple(self.paths))
        if self.affected_by is not None:
            object.__setattr__(self, "affected_by", frozenset(self.affected_by))

    @property
    def plain(self) -> bool:
        """A run of every model with the plain settings (whose whole result the run cache
        keeps): no change set, pictures, job selection, kept models, overrides or in-process
        lint."""
        return (self.affected_by is None and not self.render_dir and self.select_jobs is None
                and not self.keep_models and not self.settings_overrides
                and not self.in_process)


def run_check(request: RunRequest) -> CheckResult:
    """Lint every model under ``request.paths`` (see :class:`RunRequest`)."""
    req = request
    paths, cfg, resolver, cache = list(req.paths), req.cfg, req.resolver, req.cache
    policy = Policy.from_config(cfg)
    facts = _facts_store(cache, req.mesh_cache_dir)
    settings = settings_for(cfg, resolver, facts.dir if facts else None, policy)
    memo = None
    if cache is not None and req.plain:
        # the whole result of the last identical run, if nothing it read changed
        from urdf_lint.run.runcache import RunMemo
        memo = RunMemo(cache, paths, cfg, resolver, settings)
        hit = memo.load()
        if hit is not None:
            return _scoped(CheckResult(reused=True, **hit), req.scope)
    found = discover_models(paths, cfg, resolver, cache.dir if cache else None)
    jobs = found.jobs if req.select_jobs is None else req.select_jobs(found.jobs, found)
    if req.keep_models:
        settings = dataclasses.replace(settings, keep_model=True)
    if req.settings_overrides:
        settings = dataclasses.replace(settings, **req.settings_overrides)
    if req.render_dir:
        settings = _render_settings(settings, req.render_dir, req.render_rrd, paths, jobs, cfg)
    # the workers of the default pass lint the explored variants too (forked once)
    from urdf_lint.run.worker import RunPool
    workers = None if req.in_process or not _explores(req, cfg) else RunPool(settings,
                                                                             req.jobs_n)
    try:
        return _run_passes(req, cfg, resolver, cache, found, jobs, settings, policy, facts,
                           memo, workers)
    finally:
        if workers is not None:
            workers.close()


def _run_passes(req: RunRequest, cfg: "Config", resolver: "PackageResolver",
                cache: "Cache | None", found: "Discovery", jobs: list[LintJob],
                settings: LintSettings, policy: Policy, facts: "FactsStore | None",
                memo: "RunMemo | None", workers: "RunPool | None") -> CheckResult:
    """The default pass, then the exploration pass (on the same ``workers``), then the end
    of the run (:func:`urdf_lint.run.finish.finish`)."""
    paths = list(req.paths)
    early = None
    if workers is not None and req.affected_by is None and _explores(req, cfg):
        from urdf_lint.run.explore import Early
        if Early.applies(cfg):   # (every model's first variant, linted as the pass runs)
            early = Early(cfg, jobs, found.graph, resolver)
    results, internal = _lint_all(jobs, settings, req.jobs_n, cache, req.progress,
                                  req.in_process, workers, early)
    if facts is not None:   # what the workers measured: stored by this process only
        facts.accept((m for r in results for m in r.mesh_facts),
                     getattr(resolver, "is_inside", None))
    out = CheckResult(internal=internal)
    out.models, out.skipped = split_models(results, {j.entry for j in jobs if j.explicit},
                                            found.fragments)
    out.fragments = dict(found.fragments)
    out.generated = dict(found.generated)
    _hint_fragments(out.models, found.graph)
    _drop_current_outputs(out.models)
    hint_packages(out.models, paths)

    if req.affected_by is not None:
        _keep_affected(out, req.affected_by, _variant_inputs(req, cfg, found, resolver))
    if _explores(req, cfg):
        more, more_internal = _explore(out, found, cfg, resolver, settings, req, workers, early)
        results += more
        out.internal += more_internal
    if workers is not None:
        workers.release()     # (no further pass: they exit while the run is finished here)
    if req.render_dir:
        _drop_snapshots([r for r in results if r not in out.models], req.render_dir)
    out.findings = finish(out.models, found.problems, settings, policy, out.generated,
                          run_rules=req.affected_by is None, internal=out.internal)
    if memo is not None:
        memo.store(out, results, found.folders)
    return _scoped(out, req.scope)


def _explores(req: RunRequest, cfg: "Config") -> bool:
    """Whether a run lints the variants that take the branches the defaults miss
    (:mod:`urdf_lint.run.explore`): a check or a hook run, not a render, ``--fix`` (which
    compares kept models) or a run with overridden settings; ``diff`` says (``req.explore``:
    its two revisions alike, or neither)."""
    if not (cfg.explore and cfg.explore_budget > 0) or req.render_dir:
        return False
    if req.explore is not None:
        return req.explore
    return not req.keep_models and not req.settings_overrides and req.select_jobs is None


def _explore(out: CheckResult, found: "Discovery", cfg: "Config", resolver: "PackageResolver",
             settings: LintSettings, req: RunRequest, workers: "RunPool | None" = None,
             early: "Early | None" = None) -> tuple[list[ModelReport], list[str]]:
    """Plan, lint (workers, cache) and merge the explored variants of ``out.models``; the
    coverage lands in ``out.coverage``. Returns (the variants' reports, internal errors).
    ``early``: the plans and reports of the first variants, made during the default pass."""
    from urdf_lint.run import explore
    internal: list[str] = []

    def lint(jobs: list[LintJob]) -> list[ModelReport]:
        done, jobs = early.take(jobs) if early is not None else ([], jobs)
        for r in done:
            internal.extend(r.internal)
        reports, errors = _lint_all(jobs, settings, req.jobs_n, req.cache, None, req.in_process,
                                    workers)
        internal.extend(errors)
        return done + reports
    reports, out.coverage = explore.explore(cfg, out.models, found.graph, resolver, lint, early)
    return reports, internal


def _scoped(out: CheckResult, how: Scope | None) -> CheckResult:
    """``out`` as ``how`` asks (:func:`urdf_lint.run.finish.scope`); the run memo keeps the
    findings before it."""
    if how is not None:
        out.findings, out.baselined = scope(out.findings, how, out.generated)
    return out


def _facts_store(cache: "Cache | None", wanted: str | None) -> "FactsStore | None":
    """The user's mesh facts store for this run: with the result cache (its key), or when the
    caller asks for mesh facts to be kept (``RunRequest.mesh_cache_dir``). ``--no-cache``: none
    (a run without caches measures every mesh)."""
    if cache is None and not wanted:
        return None
    from urdf_lint.run.cache import facts_store
    return facts_store(getattr(cache, "_secret", None))


def _render_settings(settings: LintSettings, render_dir: str, render_rrd: bool,
                     paths: Sequence[str], jobs: Sequence[LintJob],
                     cfg: "Config") -> LintSettings:
    """The workers' settings for a run that draws each model's picture into ``render_dir``."""
    from urdf_lint.core import fsbound
    fsbound.make_own_dirs(render_dir)   # checked by the CLI (check_no_symlink)
    # every picture's name is known here: one two models would share is drawn for neither
    from urdf_lint.discovery.discover import repository_root
    from urdf_lint.core.locations import clashing_names, snapshot_name
    base = repository_root(paths)
    clash = clashing_names({(j.entry, tuple(sorted(j.args.items()))):
                            snapshot_name(j.entry, j.args, base) for j in jobs})
    return dataclasses.replace(settings, render_dir=os.path.realpath(render_dir),
                               render_rrd=render_rrd, render_base=base,
                               render_refused=tuple(sorted(clash)),
                               render_views=cfg.views or "single",
                               render_forward=cfg.forward_axis)


def _variant_inputs(req: RunRequest, cfg: "Config", found: Any, resolver: "PackageResolver"
                    ) -> Callable[[list[ModelReport]], dict[str, set[str]]] | None:
    """When the run explores: what the explored variants of some models may read
    (:func:`urdf_lint.run.explore.variant_inputs`), else None."""
    if not _explores(req, cfg):
        return None
    from urdf_lint.run import explore
    return lambda models: explore.variant_inputs(cfg, models, found.graph, resolver)


def _keep_affected(out: CheckResult, affected_by: AbstractSet[str],
                   variant_inputs: Callable[[list[ModelReport]], dict[str, set[str]]] | None
                   = None) -> None:
    """Only the models whose inputs include a changed file (or, when the run explores, the
    inputs their explored variants may read: an include an arg chooses); the files no model
    uses."""
    from urdf_lint.discovery.changes import affected
    models = out.models
    out.models, out.unused_files = affected(models, affected_by)
    if variant_inputs is not None and out.unused_files:
        rest = [m for m in models if m not in out.models]
        unused = set(out.unused_files)
        reach = variant_inputs(rest)
        kept = {id(m) for m in out.models}
        used: set[str] = set()
        for m in rest:
            # (every model that may read a changed file, not only the first one)
            hit = {os.path.realpath(f) for f in reach.get(m.entry, ())} & unused
            if hit:
                kept.add(id(m))
                used |= hit
        out.models = [m for m in models if id(m) in kept]
        out.unused_files = sorted(unused - used)
    # a deleted file no model reads any more: a removed model (or an unused file) is gone
    out.gone = [f for f in out.unused_files if not os.path.exists(f)]
    out.unused_files = [f for f in out.unused_files if os.path.exists(f)]


def _lint_all(jobs: list[LintJob], settings: LintSettings, jobs_n: int | None,
              cache: "Cache | None", progress: Callable[[int, int], None] | None,
              in_process: bool = False, workers: "RunPool | None" = None,
              early: "Early | None" = None) -> tuple[list[ModelReport], list[str]]:
    """A ModelReport for every job: from the cache, or linted by the workers (``workers``:
    the run's, kept between its passes; else a pool for these jobs alone). ``early``: each
    report passed on as it arrives, and the jobs it gives back linted on the same workers
    (their reports kept there, not returned)."""
    results: list[ModelReport] = []
    todo = []
    # snapshots need the model itself, so a render pass expands everything once
    hits = cache.get_many(jobs, settings) if cache and not settings.render_dir else \
        [None] * len(jobs)
    for job, hit in zip(jobs, hits, strict=True):
        if hit is not None:
            results.append(hit)
            if early is not None:
                early.arrived(job, None)
        else:
            todo.append(job)
    internal: list[str] = []
    if todo:
        from urdf_lint.run.worker import process_job, run_jobs
        # what the models took when last linted plans the workers (cache.get_many read it)
        costs = cache.costs if cache else {}
        if workers is not None:
            workers.costs = costs
        done = ((job, process_job(job, settings)) for job in todo) if in_process else \
            workers.run(todo) if workers is not None else \
            run_jobs(todo, settings, jobs_n=jobs_n, costs=costs)
        n = 0
        for job, res in done:
            if cache and not res.internal and res.cacheable:
                cache.put(job, settings, res)
            if early is not None and early.done(job, res):
                continue
            internal.extend(res.internal)
            results.append(res)
            n += 1
            if progress:
                progress(n, len(todo))
            if early is not None and workers is not None:
                workers.add(early.arrived(job, res))
    return results, internal


def hint_packages(models: Sequence[ModelReport], paths: Sequence[str]) -> None:
    """An unknown package whose ``package.xml`` is in a folder beside the linted paths (a
    sibling package under the working directory, outside git): its UL004 says
    ``--package-path NAME=DIR`` (``check`` of folders and files, ``expand``). Looked for
    here, in the parent: the workers may not list folders outside the roots, and such a
    folder is never a root by itself."""
    import re
    from urdf_lint.core.locations import display_path
    from urdf_lint.discovery.workspace import beside
    found: dict[str, Any] = {}
    for r in models:
        new = []
        for p in r.problems:
            m = re.search(r"unknown package '([^']+)'", p.message) \
                if p.code == ul004_unknown_package.CODE and "pass --package-path" not in p.message \
                else None
            if m:
                name = m.group(1)
                if name not in found:
                    found[name] = beside(name, paths or ["."])
                if found[name]:
                    p = p.replace(message=f"{p.message}; {display_path(found[name])}/package.xml "
                                          f"beside the linted paths declares it: pass "
                                          f"--package-path {name}={found[name]}")
            new.append(p)
        r.problems = new


def _drop_current_outputs(models: Sequence[ModelReport]) -> None:
    """A generated URDF identical (as XML) to today's expansion of its xacro is not linted
    again: its findings are the xacro's, reported at the xacro lines (a repository that checks
    in robot.urdf next to robot.urdf.xacro got every finding twice). It stays a model."""
    current = {o for r in models for o in r.current_outputs}
    for r in models:
        if r.entry in current and not r.args:
            r.problems = []


def _drop_snapshots(reports: Sequence[ModelReport], render_dir: str) -> None:
    """Remove the snapshots the workers wrote for files that turned out not to be reported
    models (fragments, libraries, models a changed file does not affect): regular files in
    the output folder only, whatever path a worker sent back."""
    from urdf_lint.core import fsbound
    for r in reports:
        for k in ("png", "rrd"):
            f = (r.snapshot or {}).get(k)
            if isinstance(f, str) and os.path.dirname(os.path.abspath(f)) == \
                    os.path.realpath(render_dir):
                fsbound.remove(f, os.path.realpath(render_dir))
        r.snapshot = None


def _hint_fragments(models: Sequence[ModelReport], graph: "IncludeGraph") -> None:
    """A model whose entry other files include (a fragment linted on its own, because it was
    named or configured): say which model to lint instead where a finding suggests it."""
    from urdf_lint.core.locations import display_path
    for r in models:
        if not r.entry.endswith(".xacro"):
            continue
        by = graph.includers(r.entry)
        if not by:
            continue
        top = [f for f in by if not graph.included_by().get(f)] or by
        names = ", ".join(display_path(f) for f in top[:3]) + (" ..." if len(top) > 3 else "")
        hint = (f" (this file is included by {names}; lint {display_path(top[0])} instead, "
                "or list it under models)")
        r.problems = [p.replace(message=p.message + hint)
                      if p.code in FRAGMENT_HINT_CODES and p.file == r.entry else p
                      for p in r.problems]


def variant_args(models: Sequence[ModelReport], cfg: "Config",
                 resolver: "PackageResolver", skip: AbstractSet[str] = frozenset()
                 ) -> dict[str, Any]:
    """{entry: [arg, ...]} for the models linted with every arg at its default although args
    select variants there (an arg with a true/false default, or one read in a condition,
    ``if=``/``unless=``/``<xacro:if value=...>``, or an include's ``filename``: a hand, a
    simulation mode, an arm type), and no ``[[models]]`` entry lists the file; not for the
    entries in ``skip`` (explored). Each source is read and scanned once, however many
    models include it."""
    configured = {m.path for m in cfg.models}
    out: dict[str, Any] = {}
    scanned: dict[str, list[str]] = {}
    for r in models:
        if r.args or r.entry in configured or r.entry in skip or not r.entry.endswith(".xacro"):
            continue
        names: dict[str, Any] = {}
        for f in r.deps:
            if f.endswith(".xacro"):
                if f not in scanned:
                    scanned[f] = _variant_names(f, resolver)
                names.update(dict.fromkeys(scanned[f]))
        if names:
            out[r.entry] = list(names)
    return out


def _variant_names(f: str, resolver: "PackageResolver") -> list[str]:
    """The args one xacro source may select variants with (:func:`variant_args`), read
    through the boundary."""
    from urdf_lint.core import fsbound
    from urdf_lint.discovery.packages import MAX_SOURCE_BYTES
    if not resolver.readable(f, MAX_SOURCE_BYTES):
        return []
    data = fsbound.read_regular(f, MAX_SOURCE_BYTES)
    if data is None:
        return []
    bool_arg, variant_use, condition_before = _variant_patterns()
    names: dict[str, Any] = {}
    for m in bool_arg.finditer(data):
        names[m.group(1).decode("utf-8", "replace")] = None
    for m in variant_use.finditer(data):
        if not data.startswith(b"value", m.start()) or \
                condition_before.search(data[max(0, m.start() - 20):m.start()]):
            names[m.group(2).decode("utf-8", "replace")] = None
    return list(names)


@functools.lru_cache(maxsize=1)
def _variant_patterns() -> tuple["re.Pattern[bytes]", "re.Pattern[bytes]", "re.Pattern[bytes]"]:
    """(an arg with a true/false default; an arg read in a condition, a value or an include's
    filename; a ``value=`` that belongs to ``<xacro:if>``/``<xacro:unless>``), compiled when
    a run first asks."""
    import re
    return (re.compile(rb"""<xacro:arg\s+name\s*=\s*["']([A-Za-z_][\w-]*)["']\s+"""
                       rb"""default\s*=\s*["'](?:true|false|True|False)["']"""),
            re.compile(rb"""\b(?:if|unless|filename|value)\s*=\s*(["'])[^"']*?"""
                       rb"""\$\(\s*arg\s+([A-Za-z_][\w-]*)\s*\)"""),
            re.compile(rb"xacro:(?:if|unless)\s+$"))


def exit_code(result: CheckResult, fail_on: str) -> int:
    return exit_status((f.severity for f in result.findings), bool(result.internal), fail_on)
