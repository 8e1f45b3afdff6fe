"""The language server's view of one workspace folder, without the protocol.

It loads the config exactly as ``check`` does (``[tool.urdf-lint]``, trust rules, clamps),
discovers the models and their include graph, lints them in a pool of sandboxed workers that
stays alive (:mod:`.pool`) with the unsaved buffers as the jobs' overlay, and keeps every
model's report warm. A change to a file re-lints only the models it can reach: those whose
entry it is, those whose recorded deps hold it, and those whose entry includes it (the
include graph, for a model not linted yet). The findings go through the run pipeline's own
steps (policy, merge across models, inline suppressions) so the editor shows what ``check``
would print for the same bytes.
"""
from __future__ import annotations

import os
import re
import threading
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from urdf_lint.core.findings import Problem
from urdf_lint.core.jobs import LintJob, ModelReport, Status

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.lsp.pool import Pool


def job_key(job: LintJob) -> tuple:
    return (job.entry, tuple(sorted(job.args.items())))


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
    buffers: dict = field(default_factory=dict)       # path -> bytes (open, maybe unsaved)
    reports: dict = field(default_factory=dict)       # job_key -> ModelReport
    findings: list = field(default_factory=list)      # after policy, merge, suppression
    config_problem: ConfigProblem | None = None
    pool_size: int = 2
    facts: Any = None       # the user's mesh facts store (urdf_lint.meshes.store.FactsStore)

    def __post_init__(self):
        self.root = os.path.realpath(self.root)
        self.lock = threading.RLock()
        self.pool: Pool | None = None   # made by load()
        self.cache = None
        self.jobs: list[LintJob] = []
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
        self.reports = {}
        from urdf_lint.lsp.pool import Pool
        self.pool = Pool(self.settings, self.pool_size)

    def start(self) -> None:
        """Fork the pool's workers now (from the main thread, before the lint thread exists)."""
        if self.pool is not None:
            self.pool.start()

    def stop_soon(self) -> None:
        """Hand out no further job: the lint under way ends with the jobs it has started."""
        if self.pool is not None:
            self.pool.closing = True

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
        inside it (:func:`urdf_lint.fix.sourceedit.inside`), never an installed package or a
        file a symlink leads out to."""
        from urdf_lint.fix.sourceedit import inside
        return inside(path, [self.root], resolved=True)

    # -- which models a file reaches ---------------------------------------------------------
    def affected(self, path: str) -> list[LintJob]:
        """The jobs whose result a change to ``path`` can change."""
        path = os.path.realpath(path)
        # a xacro file the include graph knows: a model not linted yet reaches it only through
        # the graph (or an include only expansion resolves); anything else (a YAML file): any
        known = path.endswith(".xacro") and path in self.graph.includes
        includers = set(self.graph.includers(path)) if known else set()
        out = []
        for job in self.jobs:
            r = self.reports.get(job_key(job))
            if job.entry == path:
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
    def lint(self, jobs: list[LintJob] | None = None) -> set:
        """Lint ``jobs`` (default: every job) with the open buffers; returns the files whose
        findings may have changed."""
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
                else:
                    todo.append(LintJob(job.entry, job.args, job.kind, job.explicit,
                                        job.display_name, job.output, job.mesh_base,
                                        overlay=overlay, configs=job.configs))
            if todo:
                assert self.pool is not None, "load() makes the pool"
                for job, rep in self.pool.run(todo):
                    self.reports[job_key(job)] = rep
                    if self.facts is not None:
                        self.facts.accept(rep.mesh_facts, self.resolver.is_inside)
                    if self.cache and not job.overlay and rep.cacheable and not rep.internal:
                        plain = LintJob(job.entry, job.args, job.kind, job.explicit,
                                        job.display_name, job.output, job.mesh_base,
                                        configs=job.configs)
                        self.cache.put(plain, self.settings, rep)
            self.findings = self._finish()
            return before | {f.file for f in self.findings}

    def _finish(self) -> list[Problem]:
        """What ``check`` would report from the reports held: the models' findings, the
        run-scope rules over every model held, and discovery's own (the config's args)."""
        from urdf_lint.core import overlay
        from urdf_lint.run.finish import Scope, finish, scope, split_models
        import copy
        reports = [copy.copy(r) for r in self.reports.values()]
        for r in reports:
            if r.status is Status.FRAGMENT:
                r.status = Status.MODEL   # (decided again below, over the reports held now)
        models, _ = split_models(reports, self.explicit, self.fragments)
        with overlay.using(self.buffers):   # suppression comments of the unsaved buffers
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
        return [r for r in self.reports.values() if r.status is Status.MODEL]


def _load_cfg(root: str):
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


def _reads_buffer(report: ModelReport, buffers: dict) -> bool:
    return any(d in buffers for d in report.deps)


def _cache_for(root: str, cfg):
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


_AT_LINE = re.compile(r"^(?P<file>[^\n]*?):(?P<line>\d+): ")


def _config_problem(message: str, root: str) -> ConfigProblem:
    """A ConfigError's message (``path:LINE: what``) as a located problem."""
    from urdf_lint.config.schema import find_config
    cfg_file = find_config(root)
    m = _AT_LINE.match(message)
    line = int(m.group("line")) if m else 0
    file = str(cfg_file) if cfg_file else os.path.join(root, "pyproject.toml")
    if m and os.path.exists(m.group("file")):
        file = m.group("file")
    text = message[m.end():] if m else message.split(": ", 1)[-1] if ": " in message else message
    return ConfigProblem(os.path.realpath(file), line, text)
