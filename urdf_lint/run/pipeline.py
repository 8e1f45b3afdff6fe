"""The run pipeline of ``urdf-lint check``: discover -> lint every model (workers, cache) ->
run-scope rules -> merge -> suppress -> policy -> CheckResult.

Discovery is :mod:`urdf_lint.discovery.discover`, one model's lint :mod:`urdf_lint.engine.lint` (inside
workers, :mod:`urdf_lint.runner.pool`), what is kept and at what severity :mod:`urdf_lint.config.policy`.
"""
from __future__ import annotations

import dataclasses
import os
from dataclasses import dataclass, field
from collections.abc import Set as AbstractSet
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence

from urdf_lint.discovery.discover import discover_models
from urdf_lint.core.findings import Problem, exit_status, merge
from urdf_lint.core.jobs import DEFAULT_ENV_ALLOW, LintJob, LintSettings, ModelReport, Status
from urdf_lint.config.policy import Policy, code_matches
from urdf_lint.core.codes import RuleName

# the rules raised or consulted here, by name (core.codes: importing a rule module loads the
# rule API and what it needs, ~12 ms of every run's start-up)
ul002_xacro_error = RuleName("ul002_xacro_error")
ul006_not_a_robot = RuleName("ul006_not_a_robot")
ul103_missing_link = RuleName("ul103_missing_link")
unused_suppression = RuleName("ul009_unused_suppression")
invalid_suppression = RuleName("ul010_invalid_suppression")
ul004_unknown_package = RuleName("ul004_unknown_package")

# findings that usually mean "this file is a fragment: the model including it defines the rest"
FRAGMENT_HINT_CODES = (ul002_xacro_error.CODE, ul006_not_a_robot.CODE, ul103_missing_link.CODE)

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.run.cache import Cache
    from urdf_lint.config.schema import Config
    from urdf_lint.discovery.packages import PackageResolver

# a finding of a run-scope rule belongs to no single model; its "models" list holds this label
RUN_LABEL = ""


@dataclass
class CheckResult:
    """The outcome of a check run: findings after merging and policy, the linted models,
    the files skipped, and internal errors."""
    findings: list = field(default_factory=list)     # merged Problems, after policy
    models: list = field(default_factory=list)       # ModelReport of linted models
    skipped: list = field(default_factory=list)      # libraries etc.
    internal: list = field(default_factory=list)     # internal errors (exit 2)
    unused_files: list = field(default_factory=list)
    fragments: dict = field(default_factory=dict)    # fragment file -> the files including it
    gone: list = field(default_factory=list)         # deleted files no model reads any more
    generated: dict = field(default_factory=dict)    # generated .urdf -> the xacro it comes from
    reused: bool = False                             # the last identical run's result (runcache)


@dataclass
class RunView:
    """What a run-scope rule's ``check(run, ctx)`` sees: every linted model of the run."""
    models: list                                     # ModelReport
    generated: dict = field(default_factory=dict)    # generated .urdf -> the xacro it comes from


class RunContext:
    def __init__(self, options: dict):
        self.options = options


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


def _with_policy(problems, label: str, policy: Policy) -> list[Problem]:
    """Problems with their rule name, effective severity and model label. The severity is the
    configured override, else the highest the selected targets give (:mod:`urdf_lint.core.targets`:
    the finding's own target table, else the rule's ``TARGETS``, over the severity the rule
    chose for it, else the rule's); a finding no selected target keeps is dropped."""
    from urdf_lint.engine.registry import catalogue
    from urdf_lint.core.targets import resolve
    rules = catalogue()
    out = []
    for p in problems:
        r = rules.get(p.code)
        name = r.name if r else p.code
        base = p.severity or (r.severity if r else "error")
        table = dict(p.consumers) if p.consumers is not None else (r.targets if r else {})
        sev, by = resolve(table, base, policy.targets) if table else (base, ())
        if sev is None:
            continue
        over = policy.override_of(p.code, name)
        if over is not None:
            sev, by = over, ()
        out.append(p.replace(name=name, severity=sev, models=(label,), severity_from=by))
    return out


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
            return CheckResult(reused=True, **hit)
    found = discover_models(paths, cfg, resolver, cache.dir if cache else None)
    jobs = found.jobs if req.select_jobs is None else req.select_jobs(found.jobs, found)
    if req.keep_models:
        settings = dataclasses.replace(settings, keep_model=True)
    if req.settings_overrides:
        settings = dataclasses.replace(settings, **req.settings_overrides)
    if req.render_dir:
        settings = _render_settings(settings, req.render_dir, req.render_rrd, paths, jobs, cfg)
    results, internal = _lint_all(jobs, settings, req.jobs_n, cache, req.progress,
                                  req.in_process)
    if facts is not None:   # what the workers measured: stored by this process only
        facts.accept((m for r in results for m in r.mesh_facts),
                     getattr(resolver, "is_inside", None))
    out = CheckResult(internal=internal)
    out.models, out.skipped = _split_models(results, {j.entry for j in jobs if j.explicit},
                                            found.fragments)
    out.fragments = dict(found.fragments)
    out.generated = dict(found.generated)
    _hint_fragments(out.models, found.graph)
    _drop_current_outputs(out.models)
    hint_packages(out.models, paths)

    if req.affected_by is not None:
        _keep_affected(out, req.affected_by)
    if req.render_dir:
        _drop_snapshots([r for r in results if r not in out.models], req.render_dir)
    out.findings = _findings(out, found.problems, settings, policy,
                             run_rules=req.affected_by is None)
    if memo is not None:
        memo.store(out, results, found.folders)
    return out


def _facts_store(cache, wanted: str | None):
    """The user's mesh facts store for this run: with the result cache (its key), or when the
    caller asks for mesh facts to be kept (``RunRequest.mesh_cache_dir``). ``--no-cache``: none
    (a run without caches measures every mesh)."""
    if cache is None and not wanted:
        return None
    from urdf_lint.run.cache import facts_store
    return facts_store(getattr(cache, "_secret", None))


def _render_settings(settings: LintSettings, render_dir: str, render_rrd: bool, paths, jobs,
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


def _keep_affected(out: CheckResult, affected_by: AbstractSet[str]) -> None:
    """Only the models whose inputs include a changed file; the files no model uses."""
    from urdf_lint.discovery.changes import affected
    out.models, out.unused_files = affected(out.models, affected_by)
    # a deleted file no model reads any more: a removed model (or an unused file) is gone
    out.gone = [f for f in out.unused_files if not os.path.exists(f)]
    out.unused_files = [f for f in out.unused_files if os.path.exists(f)]


def _findings(out: CheckResult, run_problems, settings: LintSettings, policy: Policy,
              run_rules: bool) -> list[Problem]:
    """The findings of the run: the models', the run-scope rules' (``run_rules``) and
    discovery's, with the policy's severities, suppressions and selection applied, sorted."""
    problems: list[Problem] = []
    for r in out.models:
        problems.extend(_with_policy(r.problems, r.label, policy))
    if run_rules:
        problems.extend(_with_policy(_run_rules(out, settings), RUN_LABEL, policy))
    problems.extend(_with_policy(run_problems, RUN_LABEL, policy))
    kept = _suppress(merge(problems), out.models, settings, policy)
    final = [f for f in kept if policy.is_selected(f.code, f.name)
             and not policy.ignored_for_file(f.code, f.name, f.file)]
    from urdf_lint.fix.fixes import not_in_generated
    return sorted(not_in_generated(final, out.generated),
                  key=lambda f: (f.file, f.line, f.col, f.code))


def _lint_all(jobs: list[LintJob], settings: LintSettings, jobs_n, cache,
              progress, in_process=False) -> tuple[list[ModelReport], list[str]]:
    """A ModelReport for every job: from the cache, or linted by the workers."""
    results: list[ModelReport] = []
    todo = []
    # snapshots need the model itself, so a render pass expands everything once
    hits = cache.get_many(jobs, settings) if cache and not settings.render_dir else \
        [None] * len(jobs)
    for job, hit in zip(jobs, hits, strict=True):
        if hit is not None:
            results.append(hit)
        else:
            todo.append(job)
    internal: list[str] = []
    if todo:
        from urdf_lint.run.worker import process_job, run_jobs
        done = ((job, process_job(job, settings)) for job in todo) if in_process else \
            run_jobs(todo, settings, jobs_n=jobs_n)
        for n, (job, res) in enumerate(done, 1):
            internal.extend(res.internal)
            results.append(res)
            if cache and not res.internal and res.cacheable:
                cache.put(job, settings, res)
            if progress:
                progress(n, len(todo))
    return results, internal


def _split_models(results: list[ModelReport], explicit: "set | frozenset" = frozenset(),
                  fragments: dict | None = None):
    """(models, skipped): macro-only files and XML that is not a robot are skipped. A file
    other files include (``fragments``, from the include graph, or a file a model's expansion
    read, for includes only expansion resolves such as ``${prefix}.xacro``) is kept as a model
    of its own only when it is a complete robot by itself; otherwise it is a fragment, linted
    through the models that include it. A file named explicitly is always a model."""
    used = set(fragments or ())
    for r in results:
        if r.status is Status.MODEL:   # (a generated .urdf output is an input, not an include)
            used.update(d for d in r.deps[1:] if d != r.entry and d.endswith(".xacro"))
    models, skipped = [], []
    for r in sorted(results, key=lambda r: (r.entry, sorted(r.args.items()))):
        if r.status in (Status.LIBRARY, Status.NOT_ROBOT):
            skipped.append(r)
        elif r.entry in used and not r.args and r.entry not in explicit \
                and not _complete_robot(r):
            r.status = Status.FRAGMENT
            skipped.append(r)
        else:
            models.append(r)
    return models, skipped


def _complete_robot(r: ModelReport) -> bool:
    """Does an included file also stand alone as a robot (a named robot with links, no
    undefined link or name)?"""
    return r.status is Status.MODEL and r.links > 0 and bool(r.name) and not any(
        p.code in FRAGMENT_HINT_CODES for p in r.problems)


def hint_packages(models, paths) -> None:
    """An unknown package whose ``package.xml`` is in a folder beside the linted paths (a
    sibling package under the working directory, outside git): its UL004 says
    ``--package-path NAME=DIR`` (``check`` of folders and files, ``expand``). Looked for
    here, in the parent: the workers may not list folders outside the roots, and such a
    folder is never a root by itself."""
    import re
    from urdf_lint.core.locations import display_path
    from urdf_lint.discovery.workspace import beside
    found: dict = {}
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


def _drop_current_outputs(models) -> None:
    """A generated URDF identical (as XML) to today's expansion of its xacro is not linted
    again: its findings are the xacro's, reported at the xacro lines (a repository that checks
    in robot.urdf next to robot.urdf.xacro got every finding twice). It stays a model."""
    current = {o for r in models for o in r.current_outputs}
    for r in models:
        if r.entry in current and not r.args:
            r.problems = []


def _drop_snapshots(reports, render_dir) -> None:
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


def _hint_fragments(models, graph) -> None:
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


def _run_rules(out: CheckResult, settings: LintSettings) -> list[Problem]:
    """The run-scope rules (``SCOPE = "run"``) over every linted model."""
    from urdf_lint.engine.registry import run_rules
    run = RunView(models=list(out.models), generated=dict(out.generated))
    return [Problem.at(rule.code, msg, loc, severity=sev, consumers=table)
            for rule, loc, msg, sev, table in run_rules("run", settings.selected,
                                                        settings.options, run, RunContext({}),
                                                        out.internal, with_table=True)]


def _suppress(merged: list[Problem], models, settings: LintSettings,
              policy: Policy) -> list[Problem]:
    """Drop what inline comments suppress; add a finding for each unused suppression."""
    from urdf_lint.engine import suppress
    from urdf_lint.engine.registry import catalogue
    rules = catalogue()
    files: set[str] = set()
    # a generated URDF that is today's expansion is not linted: the comments xacro copied
    # into it suppress nothing there (they are the xacro's)
    current = {o for r in models for o in r.current_outputs}
    for r in models:
        sources = [d for d in r.deps if d.endswith(suppress.SOURCE_SUFFIXES)
                   and d not in current]
        # the worker said which sources hold urdf-lint comments (kept in the cache with the
        # result, valid while the deps are); otherwise every source is read
        known = None if r.directive_files is None else set(r.directive_files)
        files.update(d for d in sources if known is None or d in known)
    from urdf_lint.discovery.packages import MAX_SOURCE_BYTES, PackageResolver
    resolver = PackageResolver.from_dict(settings.resolver)
    # the parent reads only what the workers could: inside the roots, regular, bounded
    directives = {f: suppress.parse_directives(f) for f in sorted(files)
                  if resolver.readable(f, MAX_SOURCE_BYTES)}
    selected = settings.selected
    kept, unused, invalid = suppress.apply(
        merged, directives,
        is_selected=lambda c: any(code_matches(c, s, rules[s].name) for s in selected))
    from urdf_lint.fix.fixes import remove_comment
    about_comments = [Problem.at(unused_suppression.CODE, msg, loc, fix=remove_comment(loc))
                      for loc, msg in unused]
    about_comments += [Problem.at(invalid_suppression.CODE, msg, loc) for loc, msg in invalid]
    kept += [p.replace(models=()) for p in _with_policy(about_comments, RUN_LABEL, policy)]
    return kept


_VARIANT_USE = None
_BOOL_ARG = None


def variant_args(models, cfg: "Config", resolver: "PackageResolver") -> dict:
    """{entry: [arg, ...]} for the models linted with every arg at its default although args
    select variants there (an arg with a true/false default, or one read in a condition,
    ``if=``/``unless=``/``<xacro:if value=...>``, or an include's ``filename``: a hand, a
    simulation mode, an arm type), and no ``[[models]]`` entry lists the file."""
    import re
    from urdf_lint.discovery.packages import MAX_SOURCE_BYTES
    global _VARIANT_USE, _BOOL_ARG
    if _VARIANT_USE is None:
        _VARIANT_USE = re.compile(rb"""\b(?:if|unless|filename|value)\s*=\s*(["'])[^"']*?"""
                                  rb"""\$\(\s*arg\s+([A-Za-z_][\w-]*)\s*\)""")
        _BOOL_ARG = re.compile(rb"""<xacro:arg\s+name\s*=\s*["']([A-Za-z_][\w-]*)["']\s+"""
                               rb"""default\s*=\s*["'](?:true|false|True|False)["']""")
    configured = {m.path for m in cfg.models}
    out: dict = {}
    for r in models:
        if r.args or r.entry in configured or not r.entry.endswith(".xacro"):
            continue
        names: dict = {}
        for f in r.deps:
            if f.endswith(".xacro") and resolver.readable(f, MAX_SOURCE_BYTES):
                from urdf_lint.core import fsbound
                data = fsbound.read_regular(f, MAX_SOURCE_BYTES)
                if data is None:
                    continue
                for m in _BOOL_ARG.finditer(data):
                    names[m.group(1).decode("utf-8", "replace")] = None
                for m in _VARIANT_USE.finditer(data):
                    if not data.startswith(b"value", m.start()) or re.search(
                            rb"xacro:(?:if|unless)\s+$", data[max(0, m.start() - 20):m.start()]):
                        names[m.group(2).decode("utf-8", "replace")] = None
        if names:
            out[r.entry] = list(names)
    return out


def exit_code(result: CheckResult, fail_on: str) -> int:
    return exit_status((f.severity for f in result.findings), bool(result.internal), fail_on)
