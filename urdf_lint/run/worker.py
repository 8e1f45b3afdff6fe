"""What a worker runs: the job handler the pool (:mod:`urdf_lint.runner.pool`) is handed. A job
is expanded and linted and, on a render run, its model drawn; the parent imports beforehand
what the workers will share, and a job stopped by a limit is a ``UL904`` finding."""
from __future__ import annotations

import sys
import time
from typing import TYPE_CHECKING, Any

from urdf_lint.core.findings import Problem
from urdf_lint.core.jobs import LintJob, LintSettings, ModelReport
from urdf_lint.core.codes import RuleName
from urdf_lint.runner import pool
from urdf_lint.runner.pool import Block, Handler, mesh_facts_cached

if TYPE_CHECKING:  # pragma: no cover
    from collections.abc import Iterator, Mapping

    from urdf_lint.core.jobs import JobKey
    from urdf_lint.engine.lint import Context
    from urdf_lint.engine.model import Model
    from urdf_lint.render.raster import Geometry
    from urdf_lint.render.recording import Plan

resource_limit = RuleName("ul904_resource_limit")   # (by name: no rule module in the parent)


def process_job(job: LintJob, settings: LintSettings) -> ModelReport:
    """Lint one job; on a render run, hand the linted model to the renderer too."""
    from urdf_lint.engine.lint import lint_model
    from urdf_lint.core import overlay
    started = time.perf_counter()
    if job.shared:   # what the run's other workers measured (share): not measured again here
        from urdf_lint.meshes.resolve import remember
        remember(job.shared)
    from urdf_lint.core.tree import paths_fixed
    # unsaved editor buffers, read in place of the files; the job's real paths asked once
    with overlay.using(job.overlay), paths_fixed():
        report, model, ctx = lint_model(job, settings)
    if ctx.meshes.env_failures or job.overlay:
        # e.g. a mesh refused by the memory limit: not the file's fault; or it read buffers
        report.cacheable = False
    # (an editor's unsaved mesh is measured under its buffer's digest: never stored)
    report.mesh_facts = ctx.meshes.measured
    if settings.diff_render and model is not None and report.kept_model is not None:
        report.diff_geometry, report.diff_rrd = _diff_snapshot(model, ctx, settings)
    if settings.render_dir and model is not None:
        # drawn here (meshes are read only in the sandbox); captioned and given its findings
        # by the parent once the run's policy and baseline are applied
        from urdf_lint.render.snapshot import render_model
        report.snapshot = render_model(model, ctx, [], settings.render_dir,
                                       settings.render_base, rrd=settings.render_rrd,
                                       views=settings.render_views,
                                       forward=settings.render_forward,
                                       refused=settings.render_refused)
    report.seconds = time.perf_counter() - started
    return report


def _diff_snapshot(model: "Model", ctx: "Context", settings: LintSettings
                   ) -> tuple["Geometry", "Plan | None"]:
    """``urdf-lint diff --render``: the picture's geometry (drawn by the parent with the other
    revision's framing) and the plan of this revision's part of the shared recording
    (written with the other revision's by the parent's recorder: no rerun import here)."""
    from urdf_lint.render.raster import scene_geometry
    from urdf_lint.render.scene import build_scene
    scene = build_scene(model, ctx)
    geometry = scene_geometry(scene, ctx)
    plan = None
    if settings.diff_rrd:
        from urdf_lint.core.locations import label_base
        from urdf_lint.render.recording import plan_rrd
        plan = plan_rrd(scene, ctx, model, label_base(model.entry))
    return geometry, plan


# Optional accelerators trimesh probes for when it is imported (~0.4 s per process). urdf-lint
# uses none of them (its convex hulls come from manifold3d); they arrive with yourdfpy's
# ``trimesh[easy]`` (the ``render`` extra). A worker runs only urdf-lint's code, so it skips them.
UNUSED_TRIMESH_EXTRAS = ("scipy", "networkx", "shapely", "rtree", "embreex")


def _skip_unused_imports() -> None:
    for name in UNUSED_TRIMESH_EXTRAS:
        # None in sys.modules: "import fails" (ImportError), so trimesh skips them
        sys.modules.setdefault(name, None)  # type: ignore[arg-type]


def limit_result(job: LintJob, message: str) -> ModelReport:
    """A limit stopped the job: the finding depends on the machine (its load, its memory) and
    its deps are unknown (an included file that loops is not in them), so it is never cached."""
    out = ModelReport.failed(job, [Problem.at(resource_limit.CODE, message, (job.entry, 1, 1))])
    out.cacheable = False
    return out


# What a worker's result may be made of besides plain data (str, numbers, lists, dicts, tuples,
# sets, bytes): it crosses the pipe as plain data (urdf_lint/runner/wire.py), each object a
# dataclass, enum or named tuple by name, and the parent rebuilds no other class and calls
# nothing (test_sandbox.py::test_a_worker_cannot_run_code_in_the_parent_through_its_result).
RESULT_CLASSES = frozenset({
    ("urdf_lint.core.jobs", "ModelReport"), ("urdf_lint.core.jobs", "Status"),
    ("urdf_lint.core.jobs", "KeptModel"), ("urdf_lint.core.findings", "Problem"),
    ("urdf_lint.core.locations", "Origin"), ("urdf_lint.core.locations", "Loc"),
    ("urdf_lint.core.edits", "Fix"), ("urdf_lint.core.edits", "Edit"),
    ("urdf_lint.expansion.sourcemap", "SourceMap"), ("urdf_lint.render.raster", "Geometry"),
    ("urdf_lint.render.recording", "Plan"),
    ("numpy", "ndarray"),   # arrays of numbers (render: geometry, recordings)
})


def preload(blocks: list[Block] | None = None, settings: LintSettings | None = None,
            n: int = 1) -> None:
    """Import in the parent what every lint job uses (the expansion, xacro, the rules, lxml)
    before it forks workers, so that they share it instead of each importing it again (~60 ms
    per worker). Not PyYAML (~20 ms): only models that load YAML files need it, and a worker
    imports it for the first of them. Not for ``expand``'s worker, forked before the parent
    knew."""
    from urdf_lint.engine import lint  # noqa: F401
    from urdf_lint.engine import model  # noqa: F401
    from urdf_lint.engine import suppress  # noqa: F401
    from urdf_lint.expansion import expand  # noqa: F401
    from urdf_lint.engine.registry import load_rules
    load_rules()
    if n > 1 and blocks is not None and settings is not None:
        _preload_mesh_modules(blocks, settings)


MESH_MODULES = ("numpy", "manifold3d", "blake3",    # STL facts, volumes, hulls, mesh hashes
                "urdf_lint.meshes.resolve", "urdf_lint.meshes.readers")
# (COLLADA: meshio.collada_arrays_lean reads it with lxml; pycollada, ~30 ms to import with
# its dateutil and Pillow, only for a document the lean reader leaves to it: the worker that
# meets one imports it then, so it is not preloaded)
TRIMESH_MODULES = ("PIL.Image", "collada", "trimesh", "trimesh.exchange.load",
                   "trimesh.exchange.dae", "trimesh.exchange.obj")   # any other format
LEAN_FORMATS = (".stl", ".dae", ".obj")      # read without trimesh (unusual files aside)


def _mesh_modules(blocks: list[Block]) -> tuple[str, ...]:
    """The loaders the packages' meshes need: trimesh (~0.35 s to import) only for formats
    urdf-lint does not read itself."""
    formats = set().union(*(b.formats for b in blocks)) if blocks else set()
    return MESH_MODULES + (TRIMESH_MODULES if formats - set(LEAN_FORMATS) else ())


def _preload_mesh_modules(blocks: list[Block], settings: LintSettings) -> None:
    """Import the mesh loaders once in the parent before forking several workers, when the
    selected rules read meshes and the packages hold some: the workers share the imported
    modules instead of each importing them again. numpy whenever those rules are selected:
    they compute with it on primitive shapes and stored facts too (each worker of a re-lint
    imported it again, ~0.1 s of CPU)."""
    from urdf_lint.engine.registry import load_rules
    rules = load_rules()
    if not any("meshes" in getattr(rules.get(c), "needs", ()) for c in settings.selected):
        return
    import numpy  # noqa: F401
    if not any(b.formats for b in blocks):
        return
    if mesh_facts_cached(settings):
        return   # a run after the first: the workers find the facts and seldom load a mesh
    import importlib
    # without trimesh's optional accelerators, like the workers (~0.4 s of scipy & co. the
    # parent would import for nothing); the markers are removed again afterwards, so the
    # parent's own later imports are untouched
    marked = [n for n in UNUSED_TRIMESH_EXTRAS if n not in sys.modules]
    for n in marked:
        sys.modules[n] = None  # type: ignore[assignment]
    try:
        from urdf_lint.core import lazy
        for name in _mesh_modules(blocks):
            try:
                importlib.import_module(name)
                lazy.load(name)    # (Pillow, deferred by meshio: trimesh's formats use it)
            except ImportError:
                pass
    finally:
        for n in marked:
            if n in sys.modules and sys.modules[n] is None:
                del sys.modules[n]


def warm() -> None:
    """A worker started ahead of its settings (prestart) imports the expansion meanwhile."""
    from urdf_lint.engine import lint  # noqa: F401
    from urdf_lint.expansion import expand  # noqa: F401


def _run(job: LintJob, settings: LintSettings) -> ModelReport:
    return process_job(job, settings)   # (looked up when called: a test may replace it)


def share(report: ModelReport, settings: LintSettings) -> list[tuple[str, Any]]:
    """In the parent: the mesh facts ``report``'s worker measured, for the run's other workers
    (a model's variant or a stolen job on another worker then measures none of them again).
    Kept only under the digest this process computes of the file (inside the run's roots),
    as the facts store keeps them (:meth:`urdf_lint.meshes.store.FactsStore.accept`): a
    worker cannot file facts under content it did not measure."""
    from urdf_lint.meshes.store import verified
    roots = (settings.resolver or {}).get("roots")
    if not roots:        # (nothing to confine the paths a worker names to: nothing shared)
        return []
    from urdf_lint.core import fsbound, hashing
    out: list[tuple[str, Any]] = []
    files: set[str] = set()
    for name, path, record in verified(report.mesh_facts, lambda p: fsbound.within(p, roots)):
        out.append((name, record))
        if path not in files:
            # and the digest this process computed of the file, at its version: the worker
            # handed these facts finds them without reading and hashing the file again
            files.add(path)
            entry = hashing.memo_entry(path)
            if entry is not None:
                out.append((f"at-{entry[1]}-{path}", entry[0]))
    return out


LINT = Handler(run=_run, limit_result=limit_result, allowed=RESULT_CLASSES,
               setup=_skip_unused_imports, warm=warm, preload=preload, share=share)


def run_jobs(jobs: list[LintJob], settings: LintSettings, jobs_n: int | None = None,
             costs: Mapping[JobKey, float] | None = None
             ) -> Iterator[tuple[LintJob, ModelReport]]:
    """:func:`urdf_lint.runner.pool.run_jobs` with the lint handler (the limits are the
    settings'; ``costs``: the seconds models took before, which plan the workers)."""
    return pool.run_jobs(jobs, settings, LINT, jobs_n=jobs_n, costs=costs)


class RunPool:
    """The lint workers of one check run, kept from its default pass for its exploration
    pass: forked, preloaded and sandboxed once (:meth:`urdf_lint.runner.pool.WorkerPool.more`).
    :meth:`close` ends them. ``costs``: the seconds models took when last linted, which
    plan the workers of the first pass (:func:`urdf_lint.runner.pool.package_blocks`)."""

    def __init__(self, settings: LintSettings, jobs_n: int | None = None) -> None:
        self.settings, self.jobs_n = settings, jobs_n
        self.pool: pool.WorkerPool | None = None
        self.costs: dict[JobKey, float] = {}

    def run(self, jobs: list[LintJob]) -> Iterator[tuple[LintJob, ModelReport]]:
        """(job, report) for ``jobs``, in completion order, on the run's workers."""
        if not jobs:
            return
        if self.pool is None:
            self.pool = pool.start_pool(jobs, self.settings, LINT, self.jobs_n, self.costs)
            yield from self.pool.drain()
        else:
            yield from self.pool.more(jobs, self.jobs_n)

    def add(self, jobs: list[LintJob]) -> None:
        """More jobs for the pass under way (:meth:`urdf_lint.runner.pool.WorkerPool.add`),
        when it runs on as many workers as a further pass would: a pass the work gave one
        worker leaves them to the next pass, which may start more (:meth:`WorkerPool.more`)."""
        want = pool.max_workers(self.jobs_n)
        if jobs and self.pool is not None and len(self.pool.workers) >= want:
            self.pool.add(jobs)

    def release(self) -> None:
        """The run's last pass is done: the idle workers exit while the run finishes
        (:meth:`urdf_lint.runner.pool.WorkerPool.release`); :meth:`close` reaps them."""
        if self.pool is not None:
            self.pool.release()

    def close(self) -> None:
        if self.pool is not None:
            self.pool.close()
            self.pool = None


def prestart() -> None:
    """:func:`urdf_lint.runner.pool.prestart` with the lint handler."""
    pool.prestart(LINT)
