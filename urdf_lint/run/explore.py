"""Branch coverage of xacro models: the arg values that take the branches the defaults leave
out, linted as variants, and what stays out (``check --coverage``; docs/coverage.md).

After the default run, :func:`plan` reads each xacro model's sources
(:mod:`urdf_lint.discovery.branches`: lxml, nothing evaluated) and proposes assignments for the
conditions whose body the defaults did not expand and the files an arg-built path names that
the defaults did not read. :func:`select` keeps what the budget allows (round robin over the
models: every model gets its first variant before any gets a second). The variants are linted
as any job (sandboxed workers, cache); :func:`merge` adds what only a variant found to the
model's own findings, once, labelled ``(only with a:=x b:=y)``, and computes the coverage.
In ``check``, :class:`Early` plans each model and lints its first variant as soon as the
model's default reports are in, while the default pass still runs on the same workers.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable

from urdf_lint.core.jobs import LintJob, ModelReport, job_key

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.config.schema import Config
    from urdf_lint.discovery.branches import Analysis

WHY_NO_VALUE = "no value found"
WHY_BUDGET = "budget"
WHY_UNREACHABLE = "unreachable"
WHY_MACRO = "its macro is never called"
WHY_TRIED = "no value tried takes it"
WHY_FIXED = "its args are fixed"


@dataclass
class ModelPlan:
    """One model's branches and the variants proposed for the ones its defaults miss."""
    entry: str
    base: list[ModelReport]                  # the model's reports at the defaults / its listed args
    analysis: "Analysis"
    variants: list[dict[str, str]] = field(default_factory=list)   # proposed, best first
    kept: int = 0                            # how many of them the budget let run
    fixed: set[str] = field(default_factory=set)
    listed: dict[str, list[str]] = field(default_factory=dict)   # explore-args
    reports: list[ModelReport] = field(default_factory=list)    # of the kept variants

    @property
    def label(self) -> str:
        return self.base[0].label


def shown(args: dict[str, str]) -> str:
    return " ".join(f"{k}:={v}" for k, v in sorted(args.items()))


def explore_args(cfg: "Config", entry: str) -> dict[str, list[str]]:
    """The ``explore-args`` of the model ``entry``: the config's, with those of its
    ``[[models]]`` entries over them (arg by arg)."""
    out = {k: list(v) for k, v in cfg.explore_args.items()}
    for m in cfg.models:
        if m.path == entry:
            out.update({k: list(v) for k, v in m.explore_args.items()})
    return out


def explored_models(cfg: "Config", models: list[ModelReport]) -> dict[str, list[ModelReport]]:
    """entry -> its reports, for the xacro models exploration applies to (not excluded by
    ``explore-exclude`` nor by ``explore = false`` in a ``[[models]]`` entry of it)."""
    import fnmatch
    import os
    out: dict[str, list[ModelReport]] = {}
    off = {m.path for m in cfg.models if m.explore is False}
    for r in models:
        if not r.entry.endswith(".xacro") or r.entry in off:
            continue
        rel = os.path.relpath(r.entry, cfg.root)
        if any(fnmatch.fnmatch(rel, g) or fnmatch.fnmatch(r.entry, g)
               for g in cfg.explore_exclude):
            continue
        out.setdefault(r.entry, []).append(r)
    return out


def explore(cfg: "Config", models: list[ModelReport], graph: Any, resolver: Any,
            lint: Callable[[list[LintJob]], list[ModelReport]],
            early: "Early | None" = None
            ) -> tuple[list[ModelReport], dict[str, dict[str, Any]]]:
    """The one path of exploration, ``check``'s and the language server's: :func:`plan`,
    :func:`select` within ``cfg.explore_budget``, ``lint(jobs)`` (the caller's workers, cache
    or reports held), :func:`merge` into ``models``. Returns (the variants' reports, the
    coverage per model label). ``early``: the plans made during the default pass, and the
    sources they parsed."""
    plans = plan(cfg, models, graph, resolver, early)
    jobs = select(plans, cfg.explore_budget, len(models))
    reports = lint(jobs) if jobs else []
    return reports, merge(plans, reports)


def plan(cfg: "Config", models: list[ModelReport], graph: Any, resolver: Any,
         early: "Early | None" = None) -> list[ModelPlan]:
    """A plan for every explored model (see the module's doc); one ``early`` made of the same
    reports (:func:`plan_key`) is taken as it is, and the sources it parsed serve the rest."""
    plans = []
    # the sources parsed for one model serve the next
    parsed: dict[Any, Any] = early.parsed if early is not None else {}
    ready = early.plans if early is not None else {}
    for entry, base in sorted(explored_models(cfg, models).items()):
        p = ready.get(plan_key(entry, base))
        plans.append(p if p is not None else plan_one(cfg, entry, base, graph, resolver, parsed))
    return plans


def plan_key(entry: str, base: list[ModelReport]) -> tuple[str, tuple[int, ...]]:
    """What a plan is made of: the model and its very reports, in order."""
    return entry, tuple(id(r) for r in base)


def plan_one(cfg: "Config", entry: str, base: list[ModelReport], graph: Any, resolver: Any,
             parsed: dict[Any, Any]) -> ModelPlan:
    """The plan of one model from its reports (``base``, in the order of the run's models)."""
    p = ModelPlan(entry, base, _analysis(entry, base, graph, resolver, parsed))
    a = p.analysis
    given = explore_args(cfg, entry)
    listed = {k: list(v) for k, v in given.items()}
    for r in base:
        for k, v in r.args.items():
            listed.setdefault(k, []).append(v)
    p.fixed = {k for k, v in given.items() if not v}
    p.listed = {k: list(v) for k, v in given.items()}
    values = {k: v for k, v in a.values(listed).items() if k not in p.fixed}
    # an arg whose values are listed takes only those
    values.update({k: [x for x in v if x != a.defaults.get(k)]
                   for k, v in given.items() if v})
    p.variants = _variants(p, values)
    return p


def variant_job(entry: str, args: dict[str, str]) -> LintJob:
    """The job of one variant of a model."""
    return LintJob(entry, dict(args), "xacro", explicit=True, mesh_base=None)


class Early:
    """Every model's first variant, linted while the default pass still runs (``check`` on
    its workers): planned as soon as the last of the model's default reports arrives, as
    :func:`plan` plans it from the same reports at the end of the pass, and linted after the
    jobs queued on the worker that linted the model (an idle worker takes it sooner). With a
    budget of at least one variant per model, :func:`select` keeps every model's first
    variant, so the end of the pass lints no job twice: it reuses these plans, the sources
    they parsed (:func:`plan`) and these reports (:meth:`take`), and lints the rest. A report
    it does not ask for (a model found to be a fragment at the end) is left out; what the run
    reports is the same either way."""

    def __init__(self, cfg: "Config", jobs: list[LintJob], graph: Any, resolver: Any) -> None:
        self.cfg, self.graph, self.resolver = cfg, graph, resolver
        self.left: dict[str, int] = {}
        for j in jobs:
            self.left[j.entry] = self.left.get(j.entry, 0) + 1
        self.base: dict[str, list[ModelReport]] = {}
        self.plans: dict[Any, ModelPlan] = {}
        self.reports: dict[Any, ModelReport] = {}
        self.jobs: dict[int, LintJob] = {}
        self.parsed: dict[Any, Any] = {}

    @staticmethod
    def applies(cfg: "Config") -> bool:
        return bool(cfg.explore) and cfg.explore_budget >= 1

    def arrived(self, job: LintJob, report: ModelReport | None) -> list[LintJob]:
        """A default report (None: one read from the cache: that model is explored at the end
        of the pass, from the cache too); the first variant of its model once all are in."""
        from urdf_lint.core.jobs import Status
        e = job.entry
        if report is None or e not in self.left:
            self.left.pop(e, None)
            return []
        self.left[e] -= 1
        self.base.setdefault(e, []).append(report)
        if self.left[e]:
            return []
        del self.left[e]
        base = sorted(self.base.pop(e), key=lambda r: sorted(r.args.items()))
        if any(r.status in (Status.LIBRARY, Status.NOT_ROBOT) for r in base) or \
                not explored_models(self.cfg, base):
            return []
        p = plan_one(self.cfg, e, base, self.graph, self.resolver, self.parsed)
        self.plans[plan_key(e, base)] = p
        if not p.variants:
            return []
        first = variant_job(e, p.variants[0])
        self.jobs[id(first)] = first
        return [first]

    def done(self, job: LintJob, report: ModelReport) -> bool:
        """Keep the report of one of :meth:`arrived`'s jobs (False: not one of them)."""
        if self.jobs.pop(id(job), None) is None:
            return False
        self.reports[job_key(job)] = report
        return True

    def take(self, jobs: list[LintJob]) -> tuple[list[ModelReport], list[LintJob]]:
        """(the reports linted already of ``jobs``, the jobs still to lint)."""
        got, rest = [], []
        for j in jobs:
            r = self.reports.pop(job_key(j), None)
            if r is None:
                rest.append(j)
            else:
                got.append(r)
        return got, rest


def _analysis(entry: str, base: list[ModelReport], graph: Any, resolver: Any,
              parsed: dict[Any, Any] | None = None) -> "Analysis":
    """The branches of the model ``entry``, from its sources: the include graph's files from
    it, and what its reports read (``parsed``: the run's parsed sources)."""
    from urdf_lint.discovery import branches as br
    files = [entry] + _closure(entry, graph) + [d for r in base for d in r.deps]
    return br.analyse(files, resolver, parsed=parsed)


def variant_inputs(cfg: "Config", models: list[ModelReport], graph: Any,
                   resolver: Any) -> dict[str, set[str]]:
    """entry -> the files an explored variant of the model may read (``--changed-since``, the
    hook: a change to one of them re-lints the model): every file the include graph reaches
    from it (an include inside a branch its args leave out), every file a path built from an
    arg not fixed by ``explore-args`` may name, and what those include. Read from the sources,
    as :func:`plan` reads them; a superset of what the variants will read. The YAML files a
    ``load_yaml`` of those sources names (a literal path, or a property holding one, as
    ``$(find pkg)/config/inertial.yaml``: :func:`urdf_lint.discovery.branches.yaml_reads`)
    are among them: a call in a macro only a branch calls is read by no default pass."""
    from urdf_lint.discovery import branches as br
    out = {}
    sources: dict[str, br.YamlSources] = {}    # file -> its load_yaml calls and properties
    parsed: dict[Any, Any] = {}
    for entry, base in explored_models(cfg, models).items():
        a = _analysis(entry, base, graph, resolver, parsed)
        fixed = {k for k, v in explore_args(cfg, entry).items() if not v}
        files = set(_closure(entry, graph))
        for ch in a.choices:
            if ch.arg not in fixed:
                for path in ch.values.values():
                    files.add(path)
                    files.update(_closure(path, graph))
        read = dict.fromkeys([entry, *sorted(files), *a.files, *(d for r in base for d in r.deps)])
        for f in read:
            if f not in sources:
                sources[f] = br.yaml_sources(f, resolver, parsed)
        files |= br.yaml_reads((sources[f] for f in read), resolver)
        out[entry] = files
    return out


def _closure(entry: str, graph: Any) -> list[str]:
    if graph is None:
        return []
    out, todo = [], [entry]
    seen = {entry}
    while todo:
        f = todo.pop()
        for g in graph.includes.get(f, ()):
            if g not in seen:
                seen.add(g)
                out.append(g)
                todo.append(g)
    return out


def taken(reports: list[ModelReport]) -> set[tuple[str, int]]:
    """(file, line) of every condition whose body one of ``reports`` expanded."""
    return {(b[0], b[1]) for r in reports for b in r.branches if b[3]}


def _variants(p: ModelPlan, values: dict[str, list[str]]) -> list[dict[str, str]]:
    """The assignments that may take what the defaults miss, those serving more first."""
    from urdf_lint.discovery.branches import guesses, merged
    a = p.analysis
    done = taken(p.base)
    read = {d for r in p.base for d in r.deps}
    by_key = {(c.file, c.line): c for c in a.conds}
    serves: dict[tuple[tuple[str, str], ...], int] = {}

    listed = {k: v for k, v in p.listed.items() if v}

    def want(g: dict[str, str]) -> None:
        if any(k in listed and v not in listed[k] for k, v in g.items()):
            return   # an arg whose values are listed takes only those
        if g and not (set(g) & p.fixed):
            k = tuple(sorted(g.items()))
            serves[k] = serves.get(k, 0) + 1
    for c in a.conds:
        if (c.file, c.line) in done or c.constant is not None:
            continue
        gs = guesses(c, a.defaults, values)[:2]
        # a nested condition: the enclosing ones must be taken too (their first guess)
        parent = by_key.get(c.parent[:2]) if c.parent else None
        depth = 0
        while parent is not None and depth < 4:
            if (parent.file, parent.line) not in done:
                pg = guesses(parent, a.defaults, values)[:1]
                gs = [m for g in gs for m in [merged(g, pg[0]) if pg else None] if m]
            parent = by_key.get(parent.parent[:2]) if parent.parent else None
            depth += 1
        for g in gs:
            want(g)
    for ch in a.choices:
        if ch.arg in p.fixed:
            continue
        for v, path in ch.values.items():
            if path not in read and v in values.get(ch.arg, [v]):
                want({ch.arg: v})
    base_args = dict(p.base[0].args)
    ranked = sorted(serves, key=lambda k: (-serves[k], len(k), k))
    out = []
    for k in ranked:
        args = {**base_args, **dict(k)}
        if args != base_args and args not in out:
            out.append(args)
    return out


# a run of few models explores as if it had this many (a single model gets 8 variants at 1.0)
MIN_MODELS = 8


def select(plans: list[ModelPlan], budget: float, n_models: int) -> list[LintJob]:
    """The variant jobs the budget allows: at most ``budget`` times the models of the run
    (at least :data:`MIN_MODELS`), round robin (every model's first variant before any
    model's second)."""
    allowed = math.ceil(budget * max(n_models, MIN_MODELS)) if budget > 0 else 0
    jobs: list[LintJob] = []
    rnd = 0
    while len(jobs) < allowed and any(rnd < len(p.variants) for p in plans):
        for p in plans:
            if rnd < len(p.variants) and len(jobs) < allowed:
                jobs.append(variant_job(p.entry, p.variants[rnd]))
                p.kept = rnd + 1
        rnd += 1
    return jobs


def merge(plans: list[ModelPlan], reports: list[ModelReport]) -> dict[str, dict[str, Any]]:
    """Add to each model what only its variants found (labelled, once, at its source line);
    returns the coverage per model label (:func:`coverage`)."""
    by = {(r.entry, tuple(sorted(r.args.items()))): r for r in reports}
    out = {}
    for p in plans:
        p.reports = [r for v in p.variants[:p.kept]
                     for r in [by.get((p.entry, tuple(sorted(v.items()))))] if r is not None]
        _add_findings(p)
        out[p.label] = coverage(p)
    return out


def _add_findings(p: ModelPlan) -> None:
    base_args = p.base[0].args
    seen = {q.key() for r in p.base for q in r.problems}
    added = []
    for r in sorted(p.reports, key=lambda r: (len(r.args), sorted(r.args.items()))):
        extra = {k: v for k, v in r.args.items() if base_args.get(k) != v}
        for q in r.problems:
            if q.key() in seen:
                continue
            seen.add(q.key())
            added.append(q.replace(message=f"{q.message} (only with {shown(extra)})"))
    p.base[0].problems = list(p.base[0].problems) + added
    # what the variants read is the model's too: suppression comments there apply, and
    # ``diff`` materialises those files in the base revision
    base = p.base[0]
    for r in p.reports:
        base.deps += [d for d in r.deps if d not in base.deps]
        # (with what was read of them: the run memo keeps a run only when it knows every
        # input's stat, and a file only a variant reads kept every such run from it)
        base.digests.update({d: r.digests[d] for d in r.deps
                             if d in r.digests and d not in base.digests})
        if base.directive_files is not None:
            if r.directive_files is None:
                base.directive_files = None
            else:
                base.directive_files += [d for d in r.directive_files
                                         if d not in base.directive_files]


def coverage(p: ModelPlan) -> dict[str, Any]:
    """What :func:`merge` records per model: the branches, how many the defaults and the
    exploration took, the variants linted, and every branch never taken with why."""
    rows: list[dict[str, Any]] = []
    takers: dict[str, list[str]] = {}
    t1, a1, b1 = _cond_rows(p, rows, takers)
    t2, a2, b2 = _choice_rows(p, rows)
    return {"model": p.label, "entry": p.entry, "branches": t1 + t2,
            "taken_at_defaults": a1 + a2, "taken": b1 + b2,
            "variants": [dict(r.args) for r in p.reports],
            "cut_by_budget": len(p.variants) - p.kept, "not_taken": rows, "takers": takers}


def _why(p: ModelPlan, c: Any, seen_any: set[tuple[str, int]], cut_args: set[str],
         tried: set[str]) -> str:
    """Why the condition ``c`` never kept its body."""
    from urdf_lint.discovery.branches import guesses
    if c.constant is not None:
        return WHY_UNREACHABLE
    if c.in_macro and (c.file, c.line) not in seen_any:
        return WHY_MACRO
    if c.args and set(c.args) <= p.fixed:
        return WHY_FIXED
    if set(c.args) & cut_args:
        return WHY_BUDGET
    if set(c.args) & tried or guesses(c, p.analysis.defaults, p.analysis.values()):
        return WHY_TRIED
    return WHY_NO_VALUE


def _cond_rows(p: ModelPlan, rows: list[dict[str, Any]],
               takers: dict[str, list[str]]) -> tuple[int, int, int]:
    """(conditions, kept at the defaults, kept by a run); ``rows`` hears the others."""
    at_default = taken(p.base)
    explored = taken(p.base + p.reports)
    seen_any = {(b[0], b[1]) for r in p.base + p.reports for b in r.branches}
    cut_args = {k for v in p.variants[p.kept:] for k in v}
    tried = {k for r in p.reports for k in r.args}
    n0 = n1 = 0
    for c in p.analysis.conds:
        key = (c.file, c.line)
        n0 += key in at_default
        if key in explored:
            n1 += 1
            takers[f"{c.file}:{c.line}"] = (["defaults"] if key in at_default else []) + [
                shown(r.args) for r in p.reports if key in taken([r])]
            continue
        rows.append({"file": c.file, "line": c.line, "kind": f"xacro:{c.kind}",
                     "value": c.text, "why": _why(p, c, seen_any, cut_args, tried)})
    return len(p.analysis.conds), n0, n1


def _choice_rows(p: ModelPlan, rows: list[dict[str, Any]]) -> tuple[int, int, int]:
    """(files an arg-built path may name, read at the defaults, read by a run)."""
    read0 = {d for r in p.base for d in r.deps}
    read = read0 | {d for r in p.reports for d in r.deps}
    cut = p.variants[p.kept:]
    total = n0 = n1 = 0
    for ch in p.analysis.choices:
        if not ch.values:
            total += 1
            rows.append({"file": ch.file, "line": ch.line, "kind": ch.kind, "value": ch.text,
                         "arg": ch.arg, "choice": "", "why": WHY_NO_VALUE})
        for v, path in ch.values.items():
            total += 1
            n0 += path in read0
            n1 += path in read
            if path in read:
                continue
            why = WHY_FIXED if ch.arg in p.fixed else WHY_BUDGET if any(
                x.get(ch.arg) == v for x in cut) else WHY_TRIED
            rows.append({"file": ch.file, "line": ch.line, "kind": ch.kind, "value": ch.text,
                         "arg": ch.arg, "choice": v, "why": why})
    return total, n0, n1
