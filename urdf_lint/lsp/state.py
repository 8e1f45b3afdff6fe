"""The language server's view of one workspace folder, without the protocol.

It loads the config exactly as ``check`` does (``[tool.urdf-lint]``, trust rules, clamps),
discovers the models and their include graph, lints them in the runner's pool of sandboxed
workers kept alive (``runner.pool.WorkerPool``, persistent) with the unsaved buffers as the
jobs' overlay, and keeps every model's report warm. A change to a file re-lints only the
models it can reach: those whose entry it is, those whose recorded deps hold it, and those
whose entry includes it (the include graph, for a model not linted yet). The findings go
through the run pipeline's own steps (policy, merge across models, inline suppressions) so the
editor shows what ``check`` would print for the same bytes.
"""
from __future__ import annotations

import os
import re
import threading
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Callable, Iterator, Protocol

from urdf_lint.core.findings import Problem
from urdf_lint.core.jobs import LintJob, LintSettings, ModelReport, Status, job_key

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.config.schema import Config
    from urdf_lint.run.cache import Cache


class Linter(Protocol):
    """What lints the workspace's jobs: the runner's persistent :class:`WorkerPool`, or (tests
    only) :class:`InProcessLinter`."""
    closing: bool

    def start(self) -> None: ...

    def run(self, jobs: list[LintJob], stop: Callable[[], bool] | None = None
            ) -> Iterator[tuple[LintJob, ModelReport]]: ...

    def wake(self) -> None: ...

    def close(self) -> None: ...


class InProcessLinter:
    """Lints in this process, outside the sandbox and without limits: for the language
    server's unit tests only (hover, completion and diagnostics from strings, no process
    started). Only code makes one (``Workspace(root, in_process=True)``); no config key, command
    line option or environment variable reaches it (SECURITY.md, "The language server")."""

    def __init__(self, settings: LintSettings):
        self.settings = settings
        self.closing = False

    def start(self) -> None:
        pass

    def run(self, jobs: list[LintJob], stop: Callable[[], bool] | None = None
            ) -> Iterator[tuple[LintJob, ModelReport]]:
        from urdf_lint.run.worker import LINT
        for job in jobs:
            if stop is not None and stop():
                return
            yield job, LINT.run(job, self.settings)

    def wake(self) -> None:
        pass

    def close(self) -> None:
        self.closing = True


@dataclass
class ConfigProblem:
    """A config mistake, at its line of the config file (1-based; 0: line unknown)."""
    file: str
    line: int
    message: str


@dataclass
class Workspace:
    """What the language server knows of one workspace: open buffers, latest reports, includes."""
    root: str
    buffers: dict[str, bytes] = field(default_factory=dict)   # open, maybe unsaved
    reports: dict[tuple[str, tuple[tuple[str, str], ...]], ModelReport] = \
        field(default_factory=dict)                   # by job_key
    findings: list[Problem] = field(default_factory=list)   # after policy, merge, suppression
    config_problem: ConfigProblem | None = None
    last_good: dict[tuple[str, tuple[tuple[str, str], ...]], ModelReport] = \
        field(default_factory=dict)   # by job_key: the last report that expanded
    pool_size: int = 2
    facts: Any = None       # the user's mesh facts store (urdf_lint.meshes.store.FactsStore)
    # tests only: lint in this process, unsandboxed (InProcessLinter); set by code, never by
    # a config, the command line or the environment
    in_process: bool = field(default=False, kw_only=True)

    def __post_init__(self) -> None:
        self.root = os.path.realpath(self.root)
        self.lock = threading.RLock()
        self.pool: Linter | None = None   # made by load()
        self.cache = None
        self.jobs: list[LintJob] = []
        # what each job was when last linted (kept when its report is forgotten)
        self.last_status: dict[tuple[str, tuple[tuple[str, str], ...]], Status] = {}
        # the explored variants' reports (run.explore, as check's), by job_key: linted after
        # the models' own (:meth:`explore`), forgotten with their model's report
        self.variants: dict[tuple[str, tuple[tuple[str, str], ...]], ModelReport] = {}
        self.load()

    # -- set-up ----------------------------------------------------------------------------
    def load(self) -> None:
        """(Re)read the config, the packages and the models (after a config change)."""
        from urdf_lint.config.schema import ConfigError, Config
        from urdf_lint.discovery.discover import build_resolver, discover_models
        from urdf_lint.run.pipeline import settings_for
        from urdf_lint.config.policy import Policy
        if self.pool is not None:
            self.pool.close()
            self.pool = None
        self.config_problem = None
        try:
            cfg = _load_cfg(self.root)
            resolver = build_resolver([self.root], cfg)
            self.policy = Policy.from_config(cfg)
            self.settings = settings_for(cfg, resolver, None, self.policy)
        except ConfigError as e:
            self.config_problem = _config_problem(str(e), self.root)
            cfg = Config(root=self.root)
            resolver = build_resolver([self.root], cfg)
            self.policy = Policy.from_config(cfg)
            self.settings = settings_for(cfg, resolver, None, self.policy)
        self.cfg, self.resolver = cfg, resolver
        self.read_roots = tuple(resolver.read_paths())   # (frozen with the resolver)
        # the workers send each robot back (navigation and hover read it through its source
        # map): results are kept in memory, not taken from check's cache (it holds no robot);
        # its mesh facts are used
        import dataclasses
        cache = _cache_for(self.root, cfg)
        # the user's mesh facts store, shared with check and every other workspace (the
        # workers read it; this process stores what they measured)
        from urdf_lint.run.cache import facts_store
        self.facts = facts_store(repo_dirs=[self.root])
        self.settings = dataclasses.replace(self.settings, keep_model=True,
                                            mesh_cache_dir=self.facts.dir if self.facts
                                            else None)
        self.cache = None
        found = discover_models([self.root], cfg, resolver, cache.dir if cache else None)
        self.jobs, self.graph, self.fragments = found.jobs, found.graph, found.fragments
        self.generated, self.discovery_problems = dict(found.generated), list(found.problems)
        self.explicit = {j.entry for j in self.jobs if j.explicit}
        self.reports, self.last_good, self.variants = {}, {}, {}
        self.pool = self._linter()

    def _linter(self) -> Linter:
        """The runner's pool of sandboxed workers, kept alive between edits (forked, limited
        and sandboxed exactly like ``check``'s)."""
        if self.in_process:
            return InProcessLinter(self.settings)
        from urdf_lint.run.worker import LINT
        from urdf_lint.runner.pool import WorkerPool
        return WorkerPool(self.settings, LINT, self.pool_size, persistent=True)

    def start(self) -> None:
        """Fork the pool's workers now (from the main thread, before the lint thread exists)."""
        if self.pool is not None:
            self.pool.start()

    def stop_soon(self) -> None:
        """Hand out no further job: the lint under way ends with the jobs it has started."""
        if self.pool is not None:
            self.pool.closing = True

    def interrupt(self) -> None:
        """Make the lint under way look at its ``stop()`` now (from the server's thread)."""
        if self.pool is not None:
            self.pool.wake()

    def forget(self, jobs: list[LintJob]) -> None:
        """Drop the reports of ``jobs`` (made from older text): until they are linted again,
        their findings are not shown (a partial result holds only what is current)."""
        with self.lock:
            entries = set()
            for job in jobs:
                self.reports.pop(job_key(job), None)
                entries.add(job.entry)
            for k in [k for k, r in self.variants.items() if r.entry in entries]:
                del self.variants[k]

    def close(self) -> None:
        if self.pool is not None:
            self.pool.close()

    def contains(self, path: str) -> bool:
        return os.path.realpath(path).startswith(self.root + os.sep)

    # -- what the server process may read and offer to write -----------------------------------
    def readable(self, path: str) -> bool:
        """May the server read ``path``? Exactly what ``check``'s own process may: inside the
        run's roots after symlinks (the packages, repository and colcon workspace holding the
        workspace folder, and the environment's packages: ``PackageResolver.is_inside``)."""
        return self.resolver.is_inside(path)

    def read(self, path: str) -> bytes:
        """The bytes of ``path`` through the boundary with the run's roots (regular files only,
        bounded); raises ``BoundaryError`` (an ``OSError``) for a file outside them."""
        from urdf_lint.core import fsbound
        if not self.readable(path):
            raise fsbound.BoundaryError(path, "resolves outside the package roots and the "
                                        "workspace; it was not read")
        return fsbound.read_bytes(path, roots=self.read_roots)

    def writable(self, path: str) -> bool:
        """May a code action edit ``path``? The rule of ``check --fix`` and
        ``--add-suppressions`` for the linted path (the workspace folder): its real path is
        inside it (:func:`urdf_lint.fix.scope.inside`), never an installed package or a
        file a symlink leads out to."""
        from urdf_lint.fix.scope import inside
        return inside(path, [self.root], resolved=True)

    # -- which models a file reaches ---------------------------------------------------------
    def affected(self, path: str) -> list[LintJob]:
        """The jobs whose result a change to ``path`` can change."""
        path = os.path.realpath(path)
        # a xacro file the include graph knows: a model not linted yet reaches it only through
        # the graph (or an include only expansion resolves); anything else (a YAML file): any
        known = path.endswith(".xacro") and path in self.graph.includes
        includers = set(self.graph.includers(path)) if known else set()
        # a file only an explored variant reads (an include an arg chooses)
        explored = {r.entry for r in list(self.variants.values())
                    if path in r.deps or path in r.missing}
        out = []
        for job in self.jobs:
            r = self.reports.get(job_key(job))
            if job.entry == path or job.entry in explored:
                out.append(job)
            elif r is None:
                if not known or job.entry in includers or \
                        self.graph.unresolved_below(job.entry):
                    out.append(job)
            elif r.status in (Status.LIBRARY, Status.NOT_ROBOT):
                continue   # decided by its own text alone
            elif job.entry in includers or path in r.deps or path in r.missing:
                out.append(job)
        return out

    def unlinted(self) -> list[LintJob]:
        return [j for j in self.jobs if job_key(j) not in self.reports]

    # -- linting -------------------------------------------------------------------------------
    def lint(self, jobs: list[LintJob] | None = None,
             stop: Callable[[], bool] | None = None) -> set[str] | None:
        """Lint ``jobs`` (default: every job, in their order) with the open buffers; returns
        the files whose findings may have changed, or None when ``stop()`` turned true first
        (the jobs under way were stopped; the findings are left as they were)."""
        with self.lock:
            jobs = self.jobs if jobs is None else jobs
            overlay = tuple(sorted(self.buffers.items()))
            before = {f.file for f in self.findings}
            todo = []
            hits = self.cache.get_many(jobs, self.settings) if self.cache and not overlay \
                else [None] * len(jobs)
            for job, hit in zip(jobs, hits, strict=True):
                if hit is not None and not _reads_buffer(hit, self.buffers):
                    self.reports[job_key(job)] = hit
                    self.last_status[job_key(job)] = hit.status
                else:
                    todo.append(replace(job, overlay=overlay))
            if todo:
                assert self.pool is not None, "load() makes the pool"
                for job, rep in self.pool.run(todo, stop):
                    self.reports[job_key(job)] = rep
                    self.last_status[job_key(job)] = rep.status
                    if rep.status is Status.MODEL and rep.kept_model is not None:
                        self.last_good[job_key(job)] = rep   # (completion while mid-edit)
                    if self.facts is not None:
                        self.facts.accept(rep.mesh_facts, self.resolver.is_inside)
                    if self.cache and not job.overlay and rep.cacheable and not rep.internal:
                        plain = replace(job, overlay=())
                        self.cache.put(plain, self.settings, rep)
            if stop is not None and stop():
                return None
            self.findings = self._finish()
            return before | {f.file for f in self.findings}

    def explores(self) -> bool:
        """Whether the models' variants are explored (``explore``, ``explore-budget``: the
        config as ``check`` reads it)."""
        return bool(self.cfg.explore and self.cfg.explore_budget > 0)

    def explore(self, stop: Callable[[], bool] | None = None) -> set[str] | None:
        """Lint the variants that take the branches the models held leave out, through
        ``check``'s own path (:func:`urdf_lint.run.explore.explore`: plan, budget, merge), the
        variants not held yet in the pool with the open buffers. Returns the files whose
        findings may have changed (empty: nothing new to lint), or None when ``stop()``
        turned true first."""
        if not self.explores():
            return set()
        from urdf_lint.core import overlay
        from urdf_lint.run.explore import explore
        with self.lock:
            buffers = tuple(sorted(self.buffers.items()))
            linted: list[ModelReport] = []

            def lint(jobs: list[LintJob]) -> list[ModelReport]:
                todo = [replace(j, overlay=buffers) for j in jobs
                        if job_key(j) not in self.variants]
                assert self.pool is not None, "load() makes the pool"
                for job, rep in self.pool.run(todo, stop) if todo else ():
                    self.variants[job_key(job)] = rep
                    linted.append(rep)
                return []   # (merged by _finish, into the reports it holds)
            with overlay.using(self.buffers):
                explore(self.cfg, self._models(), self.graph, self.resolver, lint)
            if stop is not None and stop():
                return None
            if not linted:
                return set()
            before = {f.file for f in self.findings}
            self.findings = self._finish()
            return before | {f.file for f in self.findings}

    def _models(self) -> list[ModelReport]:
        """Copies of the models' reports held (a fragment decided again over them), which
        :meth:`_finish` may add to (the explored variants' findings and files)."""
        from urdf_lint.run.finish import split_models
        import copy
        reports = []
        for r in list(self.reports.values()):
            r = copy.copy(r)
            r.problems, r.deps = list(r.problems), list(r.deps)
            if r.directive_files is not None:
                r.directive_files = list(r.directive_files)
            if r.status is Status.FRAGMENT:
                r.status = Status.MODEL   # (decided again below, over the reports held now)
            reports.append(r)
        models, _ = split_models(reports, self.explicit, self.fragments)
        return models

    def _finish(self) -> list[Problem]:
        """What ``check`` would report from the reports held: the models' findings, the
        run-scope rules over every model held, and discovery's own (the config's args)."""
        from urdf_lint.core import overlay
        from urdf_lint.run.finish import Scope, finish, scope
        models = self._models()
        with overlay.using(self.buffers):   # suppression comments of the unsaved buffers
            if self.variants and self.explores():
                # what only a variant found, labelled once (check's merge); a variant not
                # held (not linted yet, or forgotten) adds nothing
                from urdf_lint.run.explore import explore
                held = self.variants
                explore(self.cfg, models, self.graph, self.resolver,
                        lambda jobs: [held[k] for j in jobs for k in [job_key(j)] if k in held])
            final = finish(models, self.discovery_problems, self.settings, self.policy,
                           self.generated)
        # the end check gives: the fixes check --fix would refuse (an edit outside the
        # workspace folder, of a generated URDF) are refused here too, so no code action offers
        # them; the configured baseline's findings are not shown (docs/editors: as check)
        final, _ = scope(final, Scope((self.root,), self.cfg.baseline), self.generated)
        return final

    def findings_in(self, path: str) -> list[Problem]:
        path = os.path.realpath(path)
        return [f for f in self.findings if f.file == path]

    def findings_valued_in(self, path: str) -> list[Problem]:
        """The findings elsewhere whose value comes from ``path`` (a YAML file read by
        ``xacro.load_yaml``, a property file): ``Problem.value_from`` points into it."""
        path = os.path.realpath(path)
        return [f for f in self.findings if f.value_from and f.file != path
                and os.path.realpath(f.value_from[0]) == path]

    def models(self) -> list[ModelReport]:
        # (a copy first: the lint thread adds reports while a request reads them)
        return [r for r in list(self.reports.values()) if r.status is Status.MODEL]


def _load_cfg(root: str) -> Config:
    """The config ``check`` would use for ``root`` (no command line): the repository's own
    config may not loosen the guarantees (``trust.py``), limits are clamped."""
    from urdf_lint.config import trust
    from urdf_lint.config.schema import find_config, load_config, validate_codes
    from urdf_lint.engine.registry import codes_to_names, load_rules
    from urdf_lint.discovery.vcs import repo_root
    known = codes_to_names()
    cfg = load_config(find_config(root), known, load_rules)
    from urdf_lint.core.emit import say
    for note in trust.apply(cfg, repo_root(root), trusted=False):
        say(f"urdf-lint: {note}")   # on stderr (stdout is the protocol), escaped
    trust.clamp(cfg)
    validate_codes(cfg, known, rules=load_rules)
    return cfg


def _reads_buffer(report: ModelReport, buffers: dict[str, bytes]) -> bool:
    return any(d in buffers for d in report.deps)


def _cache_for(root: str, cfg: Config) -> Cache | None:
    """The on-disk cache of ``check`` (results of unchanged files, mesh facts), where
    ``check`` would keep it; none outside git without a configured folder (the server's
    working directory is wherever the editor started it)."""
    from urdf_lint.run.cache import Cache
    from urdf_lint.discovery.vcs import git_root
    if not (os.environ.get("URDF_LINT_CACHE_DIR") or cfg.cache_dir or git_root(root)):
        return None
    try:
        c = Cache.for_paths([root], cfg)
    except OSError:
        return None
    return None if c.refused else c


_AT_LINE = re.compile(r"^(?P<file>[^\n]*?):(?P<line>\d+)(?::\d+)?: ")
_AT_FILE = re.compile(r"^(?P<file>[^\n]*?\.toml)(?::\d+)*: ")


def _config_problem(message: str, root: str) -> ConfigProblem:
    """A ConfigError's message (``path:LINE[:COL]: what``) as a located problem. The config
    file is the one the message names; else the one found from ``root``, which is not looked
    for again when finding it is what failed (a ``pyproject.toml`` that does not parse raises
    the same error again)."""
    from urdf_lint.config.schema import ConfigError, find_config
    m = _AT_LINE.match(message)
    line = int(m.group("line")) if m else 0
    named = m or _AT_FILE.match(message)
    if named and os.path.isfile(named.group("file")):
        file = named.group("file")
    else:
        try:
            cfg_file = find_config(root)
        except ConfigError:
            cfg_file = None
        file = str(cfg_file) if cfg_file else os.path.join(root, "pyproject.toml")
    text = message[m.end():] if m else message.split(": ", 1)[-1] if ": " in message else message
    return ConfigProblem(os.path.realpath(file), line, text)
