"""Run lint jobs in isolated worker processes with a time limit and a memory limit.

Each worker is a forked process with a scrubbed environment and an address-space limit.
The parent hands out one job at a time; a worker that exceeds the time limit is killed (and
replaced), and its job becomes a ``UL904`` finding. Other models keep going.
"""
from __future__ import annotations

import gc
import os
import signal
import sys
import time
from collections import deque
from dataclasses import dataclass
from typing import Any

from urdf_lint.runner import forked
from urdf_lint.core.findings import Problem
from urdf_lint.runner.hardening import limit_memory
from urdf_lint.runner.hardening import inherited_data_bytes as _inherited_data_bytes
from urdf_lint.runner.hardening import install_audit_hook as _install_audit_hook
from urdf_lint.runner.hardening import scrub_environment as _scrub_environment
from urdf_lint.core.jobs import LintJob, LintSettings, ModelReport
from urdf_lint.rules import ul904_resource_limit as resource_limit

def process_job(job: LintJob, settings: LintSettings) -> ModelReport:
    """Lint one job; on a render run, hand the linted model to the renderer too."""
    from urdf_lint.engine.lint import lint_model
    from urdf_lint.core import overlay
    with overlay.using(job.overlay):   # unsaved editor buffers, read in place of the files
        report, model, ctx = lint_model(job, settings)
    if ctx.meshes.env_failures or job.overlay:
        # e.g. a mesh refused by the memory limit: not the file's fault; or it read buffers
        report.cacheable = False
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
    return report


def _diff_snapshot(model, ctx, settings: LintSettings):
    """``urdf-lint diff --render``: the picture's geometry (drawn by the parent with the other
    revision's framing) and the plan of this revision's part of the shared recording
    (written with the other revision's by the parent's recorder: no rerun import here)."""
    from urdf_lint.render import snapshot as render
    scene = render.build_scene(model, ctx)
    geometry = render.scene_geometry(scene, ctx)
    plan = None
    if settings.diff_rrd:
        from urdf_lint.render.recording import label_base, plan_rrd
        plan = plan_rrd(scene, ctx, model, label_base(model.entry))
    return geometry, plan


# Optional accelerators trimesh probes for when it is imported (~0.4 s per process). urdf-lint
# uses none of them (its convex hulls come from manifold3d); they arrive with yourdfpy's
# ``trimesh[easy]`` (the ``render`` extra). A worker runs only urdf-lint's code, so it skips them.
UNUSED_TRIMESH_EXTRAS = ("scipy", "networkx", "shapely", "rtree", "embreex")


def _skip_unused_imports():
    for name in UNUSED_TRIMESH_EXTRAS:
        # None in sys.modules: "import fails" (ImportError), so trimesh skips them
        sys.modules.setdefault(name, None)  # type: ignore[arg-type]


WORKER_GC_THRESHOLD = 10_000   # allocations between young collections (Python's default: 700)


def _worker_main(conn, settings: LintSettings | None, memory_mb):
    _skip_unused_imports()
    # an expansion allocates a DOM node per element: collected every 700 allocations, a
    # 200-link robot spends a third of its time in the collector (0.17 vs 0.10 s)
    gc.set_threshold(WORKER_GC_THRESHOLD, *gc.get_threshold()[1:])
    # what the fork shares with the parent, measured before this worker imports anything (a
    # prestarted worker's own imports count against its limit like any job's allocations)
    inherited = _inherited_data_bytes()
    # the parent turns SIGTERM into KeyboardInterrupt; a worker just dies of it (also when
    # it was forked from a thread, where _Worker could not set the signals around the fork)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if settings is None:
        # started ahead of its settings (prestart): import the expansion while the parent
        # reads the config and finds the packages, then wait for what to run with
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        try:
            from urdf_lint.engine import lint  # noqa: F401
            from urdf_lint.expansion import expand  # noqa: F401
            from urdf_lint.runner.sandbox import warm
            warm()
        except Exception:  # noqa: BLE001 - the job imports them again and reports the failure
            pass
        try:
            first = conn.recv()
        except (EOFError, OSError):
            return
        if first is None:
            return
        settings, memory_mb = first
    assert settings is not None
    # (render --out / check --render: the worker writes recordings itself)
    limit_memory(memory_mb, inherited, bool(settings.render_dir and settings.render_rrd))
    _scrub_environment(set(settings.env_allow))
    from urdf_lint.runner.sandbox import enter_worker
    enter_worker(conn, settings)  # Landlock, seccomp, pdeathsig, inherited fds closed
    sys.setrecursionlimit(4000)
    sys.dont_write_bytecode = True
    _install_audit_hook(settings.mesh_cache_dir, settings.render_dir)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    for job in forked.messages(conn):
        try:
            result = process_job(job, settings)
        except MemoryError:
            result = _limit_result(job, "expansion ran out of memory (memory-mb limit "
                                   f"{memory_mb} MiB)")
        except BaseException as e:  # noqa: BLE001
            import traceback
            result = ModelReport.failed(
                job, internal=[f"{type(e).__name__}: {e}\n{traceback.format_exc()}"])
        try:
            conn.send(result)
        except MemoryError:
            conn.send(_limit_result(job, "result too large for the memory limit"))


def _limit_result(job: LintJob, message: str) -> ModelReport:
    """A limit stopped the job: the finding depends on the machine (its load, its memory) and
    its deps are unknown (an included file that loops is not in them), so it is never cached."""
    out = ModelReport.failed(job, [Problem.at(resource_limit.CODE, message, (job.entry, 1, 1))])
    out.cacheable = False
    return out


# What a worker's result may be made of (with plain data: str, numbers, lists, dicts, tuples,
# sets, bytes): the parent reads nothing else from a worker. Were code to escape the evaluator
# and the sandbox, a pickle naming any other function would run it in the parent, which holds
# the secrets (test_sandbox.py::test_a_worker_cannot_run_code_in_the_parent_through_its_result).
RESULT_CLASSES = frozenset({
    ("urdf_lint.core.jobs", "ModelReport"), ("urdf_lint.core.jobs", "Status"),
    ("urdf_lint.core.jobs", "KeptModel"), ("urdf_lint.core.findings", "Problem"),
    ("urdf_lint.core.locations", "Origin"), ("urdf_lint.core.locations", "Loc"),
    ("urdf_lint.fix.fixes", "Fix"), ("urdf_lint.fix.sourceedit", "Edit"),
    ("urdf_lint.expansion.sourcemap", "SourceMap"), ("urdf_lint.render.raster", "Geometry"),
    ("urdf_lint.render.recording", "Plan"),
    # numpy arrays (numpy 1 and 2 name their reconstructors differently)
    ("numpy", "ndarray"), ("numpy", "dtype"),
    ("numpy.core.multiarray", "_reconstruct"), ("numpy._core.multiarray", "_reconstruct"),
    ("numpy.core.numeric", "_frombuffer"), ("numpy._core.numeric", "_frombuffer"),
})


def preload() -> None:
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


_prestarted: "_Worker | None" = None


def prestart() -> None:
    """Fork one worker now, before the run's settings are known, so that its imports overlap
    with the parent's config and package discovery (``urdf-lint expand``: a single small job
    whose latency is mostly start-up). The next :func:`run_jobs` hands it the settings; it
    enters the sandbox then, before it reads a job, exactly like a worker started there."""
    global _prestarted
    if _prestarted is None:
        from urdf_lint.runner.sandbox import disabled
        disabled()   # decided from the parent's environment before the fork (the worker's is scrubbed)
        try:
            _prestarted = _Worker(None, None)
        except OSError:   # no fork here, or no process to spare: start later
            _prestarted = None
            return
        import atexit
        atexit.register(_drop_prestarted)   # a run that stopped before it needed the worker


def _drop_prestarted() -> None:
    global _prestarted
    w, _prestarted = _prestarted, None
    if w is not None:
        forked.stop(w.conn, w.proc, 0.5)


def _take_prestarted(settings, memory_mb) -> "_Worker | None":
    global _prestarted
    w, _prestarted = _prestarted, None
    if w is None:
        return None
    try:
        w.conn.send((settings, memory_mb))
    except (OSError, ValueError):
        w.kill()
        return None
    return w


# -- scheduling: the models of one package go to one worker ---------------------------------
MESH_SUFFIXES = (".stl", ".dae", ".obj", ".ply", ".glb", ".gltf")
JOB_COST_S = 0.04            # expanding and checking a small model, meshes aside
XACRO_ELEMENT_COST_S = 0.001 # each xacro element of the entry file (a macro call: links, joints)
STL_COST_S_PER_MB = 0.003    # numpy reads binary STL (hash, bounds, volume)
MESH_COST_S_PER_MB = 0.025   # COLLADA / OBJ go through their parsers
WORKER_COST_S = 0.15         # a worker's fork and sandbox (it shares what the parent preloaded)
WARM_WORKER_COST_S = 0.1     # the same when the mesh facts are cached (few meshes are read)
MAX_WALK = 20000             # files looked at per package to estimate its meshes


@dataclass
class Block:
    """The jobs of one package (or of one folder outside any package), with a cost estimate."""
    key: str
    jobs: list
    cost: float = 0.0
    formats: frozenset = frozenset()   # the mesh suffixes found in the package


def package_blocks(jobs: list[LintJob], settings: LintSettings,
                   meshes: bool = True) -> list[Block]:
    """Jobs grouped by the package holding their entry file (the deepest package root), each
    block sorted by entry and args so models that share meshes are neighbours; a block's cost
    is its models plus the mesh bytes of its package (what its first worker will load)."""
    r = settings.resolver or {}
    roots = sorted({str(v) for k in ("explicit", "scanned") for v in (r.get(k) or {}).values()},
                   key=len, reverse=True)
    blocks: dict[str, Block] = {}
    for job in jobs:
        key = next((root for root in roots
                    if job.entry.startswith(root.rstrip(os.sep) + os.sep)), None)
        b = blocks.setdefault(key or os.path.dirname(job.entry), Block(key or "", []))
        b.jobs.append(job)
    out = []
    for b in blocks.values():
        b.jobs.sort(key=lambda j: (j.entry, sorted(j.args.items())))
        # (``meshes=False``: the mesh facts are cached, the packages' meshes cost nothing)
        mesh_cost, b.formats = _mesh_cost(b.key) if b.key and meshes else (0.0, frozenset())
        b.cost = sum(map(job_cost, b.jobs)) + mesh_cost
        out.append(b)
    return sorted(out, key=lambda b: -b.cost)


def job_cost(job: LintJob) -> float:
    """A first-time estimate of one model's expansion and checks, its meshes aside: every
    xacro element of its entry file adds to it (a 200-link robot written as 200 macro calls
    takes ~0.25 s, a model of a few includes ~0.03 s). Scheduled costliest first, such a
    model does not start last and leave the other workers idle."""
    from urdf_lint.core.hashing import read_regular
    text = read_regular(job.entry, MAX_ENTRY_READ)    # (a FIFO named as a model: not read)
    return JOB_COST_S + (XACRO_ELEMENT_COST_S * text.count(b"<xacro:") if text else 0.0)


MAX_ENTRY_READ = 4 << 20


def _mesh_cost(root: str) -> tuple[float, frozenset]:
    """(seconds to measure the meshes under a package root (a first-time estimate), the mesh
    suffixes found)."""
    cost, seen, formats = 0.0, 0, set()
    from urdf_lint.core import fsbound
    for folder, files in fsbound.walk(root, skip=lambda d: d.startswith(".")):
        for f in files:
            seen += 1
            low = f.lower()
            if low.endswith(MESH_SUFFIXES):
                try:
                    mb = os.stat(os.path.join(folder, f)).st_size / 2**20
                except OSError:
                    continue
                formats.add(os.path.splitext(low)[1])
                cost += mb * (STL_COST_S_PER_MB if low.endswith(".stl") else MESH_COST_S_PER_MB)
        if seen > MAX_WALK:
            break
    return cost, frozenset(formats)


def default_workers(blocks: list[Block], cores: int, load: float | None = None,
                    worker_cost: float = WORKER_COST_S) -> int:
    """How many workers the work is worth: one for little work (a second process costs more
    than it saves), else as many as the idle cores (the cores less the load average: on a
    busy machine another worker only adds CPU), the jobs and the cost allow."""
    total = sum(b.cost for b in blocks)
    jobs = sum(len(b.jobs) for b in blocks)
    if load is None:
        load = busy_cores()
    idle = max(1, cores - int(load))   # only cores kept wholly busy count as taken
    n = min(cores, idle, jobs, max(1, int(total / (2 * worker_cost))))
    return max(1, n)


def busy_cores() -> float:
    """Cores other processes keep busy: the 1-minute load average, but no more than the
    processes running right now (less this one). The average alone still counts a burst that
    just ended (a build step, the previous command of a script) for a minute after it, and
    made a run on an idle machine use one worker."""
    try:
        load = os.getloadavg()[0]
    except (OSError, AttributeError):
        return 0.0
    running = _procs_running()
    return load if running is None else min(load, max(0, running - 1))


def _procs_running() -> int | None:
    """Processes running or runnable now, this one included (Linux), else None."""
    try:
        with open("/proc/stat", "rb") as f:
            for line in f:
                if line.startswith(b"procs_running "):
                    return int(line.split()[1])
    except (OSError, ValueError, IndexError):
        pass
    return None


def assign(blocks: list[Block], n: int) -> list[deque]:
    """n queues of jobs: whole blocks, the costliest first, each to the least loaded queue."""
    queues: list[deque] = [deque() for _ in range(n)]
    load = [0.0] * n
    for b in blocks:
        i = min(range(n), key=lambda k: (load[k], k))
        queues[i].extend(b.jobs)
        load[i] += b.cost
    return queues


MESH_MODULES = ("numpy", "manifold3d", "_hashlib",    # STL facts, volumes, hulls, mesh hashes
                "urdf_lint.meshes.resolve", "urdf_lint.meshes.readers")
DAE_MODULES = ("collada",)                   # COLLADA facts (meshio.collada_arrays)
TRIMESH_MODULES = ("PIL.Image", "collada", "trimesh", "trimesh.exchange.load",
                   "trimesh.exchange.dae", "trimesh.exchange.obj")   # any other format
LEAN_FORMATS = (".stl", ".dae", ".obj")      # read without trimesh (unusual files aside)


def _mesh_modules(blocks: list[Block]) -> tuple:
    """The loaders the packages' meshes need: trimesh (~0.35 s to import) only for formats
    urdf-lint does not read itself."""
    formats = set().union(*(b.formats for b in blocks)) if blocks else set()
    out = MESH_MODULES + (DAE_MODULES if ".dae" in formats else ())
    return out + (TRIMESH_MODULES if formats - set(LEAN_FORMATS) else ())


def _preload_mesh_modules(blocks: list[Block], settings: LintSettings) -> None:
    """Import the mesh loaders once in the parent before forking several workers, when the
    selected rules read meshes and the packages hold some: the workers share the imported
    modules instead of each importing them again."""
    if not any(b.formats for b in blocks):
        return
    if _mesh_facts_cached(settings):
        return   # a run after the first: the workers find the facts and seldom load a mesh
    from urdf_lint.engine.registry import load_rules
    rules = load_rules()
    if not any("meshes" in getattr(rules.get(c), "needs", ()) for c in settings.selected):
        return
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


def _mesh_facts_cached(settings: LintSettings) -> bool:
    """Whether the mesh-facts cache holds entries already (then preloading the mesh readers in
    the parent costs ~0.1 s of a re-lint that will probably read no mesh)."""
    d = os.path.join(settings.mesh_cache_dir, "meshes") if settings.mesh_cache_dir else None
    from urdf_lint.core import fsbound
    return bool(d) and fsbound.has_entries(d)


def _next_job(mine, queues, block_of=None, running=()):
    """The next job of a worker: the front of its own queue, else from the far end of the
    longest other queue (the models least likely to share meshes with what that worker is
    on): the whole last package block there when no worker has started it (its meshes are
    then loaded by one worker only), else its last job, but not the only job left of a block
    being linted (its worker has its meshes loaded and takes it next: another worker would
    load them again for nothing). None: nothing to take. ``block_of`` maps ``id(job)`` to its
    block, ``running`` holds the blocks of the jobs being linted."""
    if mine:
        return mine.popleft()
    other = max(queues, key=len)
    if not other:
        return None
    block_of = block_of or {}
    block = block_of.get(id(other[-1]))
    if block is None:
        return other.pop()
    if block in running:
        return other.pop() if len(other) > 1 else None
    taken = []
    while other and block_of.get(id(other[-1])) == block:
        taken.append(other.pop())
    mine.extend(reversed(taken[:-1]))      # (the block's own order: neighbours share meshes)
    return taken[-1]


class _Worker:
    def __init__(self, settings, memory_mb):
        # the child ignores Ctrl-C and dies of SIGTERM from its first instruction (the parent
        # exits 130 for both; its SIGTERM handler must not run in the child)
        try:
            old = signal.signal(signal.SIGINT, signal.SIG_IGN)
            old_term = signal.signal(signal.SIGTERM, signal.SIG_DFL)
        except ValueError:          # not the main thread: signals are not ours to change
            old = old_term = None
        try:
            self.conn, self.proc = forked.start(_worker_main, (settings, memory_mb),
                                                allowed=RESULT_CLASSES)
        finally:
            if old is not None:
                signal.signal(signal.SIGINT, old)
                signal.signal(signal.SIGTERM, old_term)
        self.job = None
        self.started = 0.0
        self.cpu0: float | None = None   # the worker's CPU time when its job started
        self.queue: Any = None

    def kill(self):
        try:
            self.proc.kill()
        except Exception:
            pass
        self.proc.join(1)
        self.conn.close()


WALL_FACTOR = 4      # the wall-clock limit of a job: this many times its CPU-time limit
POLL_S = 0.25        # how often the parent looks at the CPU time of busy workers


def _cpu_seconds(pid: int) -> float | None:
    """The CPU time (user + system) process ``pid`` has used, from ``/proc`` (None where
    there is none: the time limit is then wall-clock time)."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            stat = f.read()
        fields = stat[stat.rindex(b")") + 2:].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return None


def _used(w) -> float | None:
    """CPU seconds worker ``w`` spent on its current job (None: not measurable)."""
    now = _cpu_seconds(w.proc.pid)
    return None if now is None or w.cpu0 is None else now - w.cpu0


def run_jobs(jobs: list[LintJob], settings: LintSettings, jobs_n=None, timeout=30.0,
             memory_mb=2048):
    """Yield (job, ModelReport) for every job; results arrive in completion order.

    ``timeout`` limits the CPU time a job uses (a loaded CI machine does not make a model that
    lints in 2 s hit it), and ``WALL_FACTOR`` times it the wall-clock time (a job waiting on
    I/O); where CPU time cannot be measured, ``timeout`` is wall-clock time."""
    wall = timeout * WALL_FACTOR
    jobs = list(jobs)
    if not jobs:
        return
    # a worker forked ahead (prestart) gets its settings first: it enters the sandbox while
    # the parent probes the protections and plans the pool
    pre = _take_prestarted(settings, memory_mb)
    from urdf_lint.runner.sandbox import prepare
    prepare()
    warm_meshes = _mesh_facts_cached(settings)
    blocks = package_blocks(jobs, settings, meshes=not warm_meshes)
    cores = os.cpu_count() or 1
    n = max(1, min(jobs_n or default_workers(
        blocks, cores, worker_cost=WARM_WORKER_COST_S if warm_meshes else WORKER_COST_S),
        len(jobs)))
    queues = assign(blocks, n)
    block_of = {id(j): k for k, b in enumerate(blocks) for j in b.jobs}
    if pre is None or n > 1:   # workers forked from here on share what the parent imports
        preload()
    if n > 1:   # (the prestarted worker was forked before the mesh modules)
        _preload_mesh_modules(blocks, settings)
    workers = [pre] if pre is not None else []
    workers += [_Worker(settings, memory_mb) for _ in range(n - len(workers))]
    for w, q in zip(workers, queues, strict=True):
        w.queue = q

    def pending():
        return any(queues)

    def replace(old):
        new = _Worker(settings, memory_mb)
        new.queue = old.queue
        workers.append(new)
    try:
        busy: dict = {}
        while pending() or busy:
            for w in workers:
                if w.job is None and pending():
                    w.job = _next_job(w.queue, queues, block_of,
                                      {block_of.get(id(o.job)) for o in workers if o.job})
                    if w.job is None:
                        continue
                    w.started = time.monotonic()
                    w.cpu0 = _cpu_seconds(w.proc.pid)
                    w.conn.send(w.job)
                    busy[w.conn] = w
            now = time.monotonic()
            next_deadline = min(w.started + (wall if w.cpu0 is not None else timeout)
                                for w in busy.values())
            if any(w.cpu0 is not None for w in busy.values()):
                next_deadline = min(next_deadline, now + POLL_S)
            ready = forked.wait(list(busy), timeout=max(0.0, next_deadline - now))
            for conn in ready:
                w = busy.pop(conn)
                job = w.job
                try:
                    limit = wall if w.cpu0 is not None else timeout
                    result = w.conn.recv(timeout=max(1.0, w.started + limit - time.monotonic()))
                    if not isinstance(result, ModelReport):
                        raise forked.Refused(f"a {type(result).__name__}")
                except forked.Refused as e:
                    # not a lint result: the worker ran something that is not urdf-lint's
                    result = ModelReport.failed(job, internal=[
                        f"the worker linting this model sent back something that is not a lint "
                        f"result ({e}); it was not read, and the worker was stopped"])
                    result.cacheable = False
                    workers.remove(w)
                    w.kill()
                    replace(w)
                except (EOFError, OSError):
                    code = w.proc.exitcode
                    result = _limit_result(job, "the expansion worker died (exit code "
                                           f"{code}); likely the memory limit ({memory_mb} MiB)")
                    workers.remove(w)
                    w.kill()
                    replace(w)
                else:
                    w.job = None
                yield job, result
            now = time.monotonic()
            for conn, w in list(busy.items()):
                if w.cpu0 is not None:
                    cpu = _used(w)
                    over = (cpu is not None and cpu >= timeout) or now - w.started >= wall
                    what = (f"the time limit ({timeout:g} s of CPU time, {wall:g} s of "
                            "wall-clock time)")
                else:
                    over = now - w.started >= timeout
                    what = f"the time limit ({timeout:g} s)"
                if over:
                    busy.pop(conn)
                    job = w.job
                    workers.remove(w)
                    w.kill()
                    if pending() or busy:
                        replace(w)
                    yield job, _limit_result(job, f"expansion/lint did not finish within "
                                             f"{what}; a huge expression, loop or recursion?")
    finally:
        for w in workers:
            try:
                w.conn.send(None)
            except Exception:
                pass
        for w in workers:
            w.proc.join(0.5)
            if w.proc.is_alive():
                w.kill()
            else:
                w.conn.close()
