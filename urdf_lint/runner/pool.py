"""Run jobs in isolated worker processes with a time limit and a memory limit.

Each worker is a forked process with a scrubbed environment and an address-space limit.
The parent hands out one job at a time; a worker that exceeds the time limit is killed (and
replaced), and its job becomes the handler's limit result (a ``UL904`` finding). Other models
keep going. The pool knows neither lint nor render: it is handed a :class:`Handler` (the lint
and render one is :data:`urdf_lint.run.worker.LINT`).
"""
from __future__ import annotations

import dataclasses
import gc
import os
import signal
import sys
import time
from collections import deque
from dataclasses import dataclass
from typing import Any, Callable, Collection, Iterator, Mapping, Sequence

from urdf_lint.runner import forked, wire
from urdf_lint.runner.hardening import limit_memory
from urdf_lint.runner.hardening import inherited_data_bytes as _inherited_data_bytes
from urdf_lint.runner.hardening import install_audit_hook as _install_audit_hook
from urdf_lint.runner.hardening import scrub_environment as _scrub_environment
from urdf_lint.core.jobs import JobKey, LintJob, LintSettings, ModelReport, job_key


@dataclass(frozen=True)
class Handler:
    """What the workers run, handed to the pool (module-level functions: a worker started
    without fork receives it pickled).

    ``run(job, settings)``: a job's report, in the sandboxed worker. ``limit_result(job,
    message)``: the report of a job a limit stopped (never cached). ``allowed``: the (module,
    class) names a report may be made of besides plain data (it crosses as plain data,
    :mod:`urdf_lint.runner.wire`; the parent reads nothing else). ``setup()``: first
    thing in a new worker; ``warm()``: the imports of a worker started ahead of its settings;
    ``preload(blocks, settings, n)``: in the parent before it forks ``n`` workers (they share
    what it imports). ``share(report, settings)``: in the parent, what a report measured that
    the other workers may reuse ((name, value) pairs, checked by the parent): the pool hands
    each worker the pairs it has not had with its next job (``LintJob.shared``)."""
    run: Callable[[LintJob, LintSettings], ModelReport]
    limit_result: Callable[[LintJob, str], ModelReport]
    allowed: frozenset[tuple[str, str]]
    setup: Callable[[], None] | None = None
    warm: Callable[[], None] | None = None
    preload: "Callable[[list[Block], LintSettings, int], None] | None" = None
    share: "Callable[[ModelReport, LintSettings], list[tuple[str, Any]]] | None" = None


MAX_SHARED = 50_000   # items a pool passes between its workers (a language server's lives long)
# A worker collects its garbage after each job (the job's DOM copies, its model: cycles
# only the collector frees). Within a job it collects only every WORKER_GC_THRESHOLD
# allocations (Python's default is 700): most jobs allocate fewer, and each collection walks
# the objects still alive, the job's trees among them. A 200-link robot spent a third of its
# time in the collector at 700 (0.17 vs 0.10 s); on the corpus laid out as a workspace, young
# collections every 10,000 allocations cost each worker 0.11-0.13 s, one collection per job
# 0.07 s. A full collection frees what lived past its job: every WORKER_FULL_GC_JOBS jobs,
# and after a job that outgrew the threshold or ran out of memory.
WORKER_GC_THRESHOLD = 200_000
WORKER_FULL_GC_JOBS = 100


def _worker_main(conn: Any, handler: Handler, settings: LintSettings | None) -> None:
    if handler.setup is not None:
        handler.setup()
    gc.set_threshold(WORKER_GC_THRESHOLD, *gc.get_threshold()[1:])
    # what the fork shares with the parent, measured before this worker imports anything (a
    # prestarted worker's own imports count against its limit like any job's allocations)
    inherited = _inherited_data_bytes()
    # the parent turns SIGTERM into KeyboardInterrupt; a worker just dies of it (also when
    # it was forked from a thread, where Worker could not set the signals around the fork)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if settings is None:
        # started ahead of its settings (prestart): import the expansion while the parent
        # reads the config and finds the packages, then wait for what to run with
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        try:
            if handler.warm is not None:
                handler.warm()
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
        settings = first
    assert settings is not None
    memory_mb = settings.memory_mb
    # (render --out / check --render: the worker writes recordings itself)
    limit_memory(memory_mb, inherited, bool(settings.render_dir and settings.render_rrd))
    _scrub_environment(set(settings.env_allow))
    from urdf_lint.runner.sandbox import enter_worker
    enter_worker(conn, settings)  # Landlock, seccomp, pdeathsig, inherited fds closed
    sys.setrecursionlimit(4000)
    sys.dont_write_bytecode = True
    _install_audit_hook(settings.render_dir)   # (the mesh facts store: read only)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    for done, job in enumerate(forked.messages(conn), 1):
        young = gc.get_stats()[0]["collections"]
        ran_out = _run_and_send(conn, handler, job, settings, memory_mb)
        # (sent: the parent goes on meanwhile) after a job that ran out of memory, or whose
        # own collections (past WORKER_GC_THRESHOLD allocations) moved some of its garbage to
        # the oldest generation, a full collection: what it left must not count against the
        # next job's memory limit
        full = ran_out or gc.get_stats()[0]["collections"] != young \
            or done % WORKER_FULL_GC_JOBS == 0
        gc.collect(2 if full else 1)


def _run_and_send(conn: Any, handler: Handler, job: Any, settings: LintSettings,
                  memory_mb: int) -> bool:
    """Run one job and send its result; whether it ran out of memory."""
    ran_out = False
    try:
        result = handler.run(job, settings)
    except MemoryError:
        ran_out = True
        result = handler.limit_result(job, "expansion ran out of memory (memory-mb limit "
                                      f"{memory_mb} MiB)")
    except BaseException as e:  # noqa: BLE001
        import traceback
        result = ModelReport.failed(
            job, internal=[f"{type(e).__name__}: {e}\n{traceback.format_exc()}"])
    try:
        conn.send(result)
    except MemoryError:
        ran_out = True
        conn.send(handler.limit_result(job, "result too large for the memory limit"))
    except wire.Unencodable as e:   # (a bug: the parent reads only plain data)
        unsent = ModelReport.failed(job, internal=[f"the result could not be sent: {e}"])
        unsent.cacheable = False
        conn.send(unsent)
    return ran_out


_prestarted: "Worker | None" = None


def prestart(handler: Handler) -> None:
    """Fork one worker now, before the run's settings are known, so that its imports overlap
    with the parent's config and package discovery (``urdf-lint expand``: a single small job
    whose latency is mostly start-up). The next :func:`run_jobs` hands it the settings; it
    enters the sandbox then, before it reads a job, exactly like a worker started there."""
    global _prestarted
    if _prestarted is None:
        from urdf_lint.runner.sandbox import disabled
        disabled()   # decided from the parent's environment before the fork (the worker's is scrubbed)
        try:
            _prestarted = Worker(handler, None)
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


def _take_prestarted(settings: LintSettings) -> "Worker | None":
    global _prestarted
    w, _prestarted = _prestarted, None
    if w is None:
        return None
    try:
        w.conn.send(settings)
    except (OSError, ValueError):
        w.kill()
        return None
    return w


# -- scheduling: the models of one package go to one worker ---------------------------------
def max_workers(jobs_n: int | None) -> int:
    """The workers a pass may run at most: ``-j`` (``jobs_n``), else one per core."""
    return jobs_n or os.cpu_count() or 1


MESH_SUFFIXES = (".stl", ".dae", ".obj", ".ply", ".glb", ".gltf")
# first-time estimates, fitted to the time each package took (one worker, cold) on the corpus
# and on bench/heavy_repo.py's repository (bench/fit_costs.py); checked on the corpus laid out
# as a workspace. The costliest package starts first: a large one started late runs alone
# at the end while the other workers idle (0.04 s a model ranked a package of 31 small models
# above one of 6 large ones, and the corpus's -j 2 run ended 0.1 s later)
# (refitted 2026-11-28: the STL fit is ~0 now that a visual STL's volume is not measured, and
# the heavy repository's arm packages, estimated at 0.22 s for their 20 MB of STL, took
# 0.05-0.08 s: its 200-link robot, 0.13 s, ranked below them and ran last)
JOB_COST_S = 0.0074          # expanding and checking a small model, meshes aside
XACRO_ELEMENT_COST_S = 0.0006  # each xacro element of the entry file (a macro call: links, joints)
STL_COST_S_PER_MB = 0.001    # numpy reads binary STL (hash, bounds)
MESH_COST_S_PER_MB = 0.047   # COLLADA / OBJ go through their parsers
# a second worker's fork, sandbox and what it measures again (it shares what the parent
# preloaded), on the estimates' scale: two workers from 0.16 s of estimated work. Measured:
# descriptions/ (0.4 s estimated) takes 0.43 s on two workers and 0.50 s on one, the corpus's
# turtlebot3_description (0.19 s) 0.275 s and 0.300 s; urdf_tutorial (0.1 s) the same on both
WORKER_COST_S = 0.04
WARM_WORKER_COST_S = 0.035   # the same when the mesh facts are cached (few meshes are read)
MAX_WALK = 20000             # files looked at per package to estimate its meshes


@dataclass
class Block:
    """The jobs of one package (or of one folder outside any package), with a cost estimate."""
    key: str
    jobs: list[LintJob]
    cost: float = 0.0
    formats: frozenset[str] = frozenset()   # the mesh suffixes found in the package


def package_roots(settings: LintSettings) -> list[str]:
    """The package roots of the run's resolver, the deepest first."""
    r = settings.resolver or {}
    return sorted({str(v) for k in ("explicit", "scanned") for v in (r.get(k) or {}).values()},
                  key=len, reverse=True)


def package_of(job: LintJob, roots: list[str]) -> str | None:
    """The deepest of ``roots`` (:func:`package_roots`) holding the job's entry file."""
    return next((root for root in roots if job.entry.startswith(root.rstrip(os.sep) + os.sep)),
                None)


def block_key(job: LintJob, roots: list[str]) -> str:
    """The block a job goes in: its package (:func:`package_of`), else its entry's folder."""
    return package_of(job, roots) or os.path.dirname(job.entry)


def package_blocks(jobs: list[LintJob], settings: LintSettings, meshes: bool = True,
                   costs: Mapping[JobKey, float] | None = None) -> list[Block]:
    """Jobs grouped by the package holding their entry file (the deepest package root), each
    block sorted by entry and args so models that share meshes are neighbours; a block's cost
    is its models plus the mesh bytes of its package (what its first worker will load).
    ``costs``: the seconds a model took when it was last linted (the result cache keeps them),
    used in place of its first-time estimate; a block whose models all have one gets no mesh
    estimate (their seconds include the meshes they measured)."""
    costs = costs or {}
    r = settings.resolver or {}
    roots = package_roots(settings)
    blocks: dict[str, Block] = {}
    for job in jobs:
        key = package_of(job, roots)
        b = blocks.setdefault(block_key(job, roots), Block(key or "", []))
        b.jobs.append(job)
    out = []
    for b in blocks.values():
        b.jobs.sort(key=lambda j: (j.entry, sorted(j.args.items())))
        # (``meshes=False``: the mesh facts are cached, the packages' meshes cost nothing)
        mesh_cost, b.formats = _mesh_cost(b.key) if b.key and meshes else (0.0, frozenset())
        known = [costs.get(job_key(j)) for j in b.jobs]
        if all(c is not None for c in known):
            mesh_cost = 0.0
        b.cost = sum(job_cost(j, r.get("roots")) if c is None else c
                     for j, c in zip(b.jobs, known, strict=True)) + mesh_cost
        out.append(b)
    return sorted(out, key=lambda b: -b.cost)


def job_cost(job: LintJob, roots: Sequence[str] | None = None) -> float:
    """A first-time estimate of one model's expansion and checks, its meshes aside: every
    xacro element of its entry file adds to it (a 200-link robot written as 200 macro calls
    takes ~0.25 s, a model of a few includes ~0.03 s). Scheduled costliest first, such a
    model does not start last and leave the other workers idle. Read only inside the run's
    ``roots`` (an entry symlinked out of them is not read: it costs the base estimate)."""
    from urdf_lint.core import fsbound
    # (a FIFO named as a model: not read)
    text = fsbound.read_regular(job.entry, MAX_ENTRY_READ, roots)
    return JOB_COST_S + (XACRO_ELEMENT_COST_S * text.count(b"<xacro:") if text else 0.0)


MAX_ENTRY_READ = 4 << 20


def _mesh_cost(root: str) -> tuple[float, frozenset[str]]:
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
    made a run on an idle machine use one worker. A process runnable for an instant (one
    exiting, a kernel thread) is no busy core either: when another seems to run, the count
    is taken RUNNING_SAMPLES times RUNNING_GAP_S apart and the least counts (one sample made
    one of five benchmark runs on an idle machine use one worker, 1.7 times slower)."""
    try:
        load = os.getloadavg()[0]
    except (OSError, AttributeError):
        return 0.0
    running = _procs_running()
    for _ in range(RUNNING_SAMPLES - 1):
        if running is None or running <= 1 or load < 1:
            break
        time.sleep(RUNNING_GAP_S)
        again = _procs_running()
        running = running if again is None else min(running, again)
    return load if running is None else min(load, max(0, running - 1))


RUNNING_SAMPLES = 3
RUNNING_GAP_S = 0.001


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


def assign(blocks: list[Block], n: int) -> list[deque[LintJob]]:
    """n queues of jobs: whole blocks, the costliest first, each to the least loaded queue."""
    queues: list[deque[LintJob]] = [deque() for _ in range(n)]
    load = [0.0] * n
    for b in blocks:
        i = min(range(n), key=lambda k: (load[k], k))
        queues[i].extend(b.jobs)
        load[i] += b.cost
    return queues


def mesh_facts_cached(settings: LintSettings) -> bool:
    """Whether the mesh-facts cache holds entries already (then preloading the mesh readers in
    the parent costs ~0.1 s of a re-lint that will probably read no mesh)."""
    d = settings.mesh_cache_dir     # the user's mesh facts store (urdf_lint.meshes.store)
    from urdf_lint.core import fsbound
    return d is not None and fsbound.has_entries(d)


def _next_job(mine: deque[LintJob], queues: list[deque[LintJob]],
              block_of: dict[int, int] | None = None,
              running: Collection[int | None] = ()) -> LintJob | None:
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


class Worker:
    """One forked, limited, sandboxed worker (:func:`_worker_main`) and the job it is on."""

    def __init__(self, handler: Handler, settings: LintSettings | None):
        # the child ignores Ctrl-C and dies of SIGTERM from its first instruction (the parent
        # exits 130 for both; its SIGTERM handler must not run in the child)
        old: Any = None
        old_term: Any = None
        try:
            old = signal.signal(signal.SIGINT, signal.SIG_IGN)
            old_term = signal.signal(signal.SIGTERM, signal.SIG_DFL)
        except ValueError:          # not the main thread: signals are not ours to change
            old = old_term = None
        try:
            self.conn, self.proc = forked.start(_worker_main, (handler, settings),
                                                allowed=handler.allowed)
        finally:
            if old is not None:
                signal.signal(signal.SIGINT, old)
                signal.signal(signal.SIGTERM, old_term)
        self.job: Any = None
        self.started = 0.0
        self.cpu0: float | None = None   # the worker's CPU time when its job started
        self.queue: Any = None
        self.told = 0     # how much of the pool's shared list this worker has been handed
        self.released = False   # sent the end of its jobs

    def kill(self) -> None:
        try:
            self.proc.kill()
        except Exception:  # noqa: BLE001 - already gone
            pass
        self.proc.join(1)
        self.conn.close()


def _tell_end(w: Worker) -> None:
    """Send worker ``w`` the end of its jobs (once)."""
    if not w.released:
        w.released = True
        try:
            w.conn.send(None)
        except Exception:  # noqa: BLE001 - a dead worker: killed by close
            pass


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


def _used(w: Worker) -> float | None:
    """CPU seconds worker ``w`` spent on its current job (None: not measurable)."""
    now = _cpu_seconds(w.proc.pid)
    return None if now is None or w.cpu0 is None else now - w.cpu0


def run_jobs(jobs: list[LintJob], settings: LintSettings, handler: Handler,
             jobs_n: int | None = None, costs: Mapping[JobKey, float] | None = None
             ) -> Iterator[tuple[LintJob, ModelReport]]:
    """Yield (job, ModelReport) for every job, run by ``handler``; results arrive in
    completion order.

    ``settings.timeout`` limits the CPU time a job uses (a loaded CI machine does not make a
    model that lints in 2 s hit it), and ``WALL_FACTOR`` times it the wall-clock time (a job
    waiting on I/O); where CPU time cannot be measured, it is wall-clock time.
    ``settings.memory_mb`` limits each worker's memory. ``costs``: :func:`package_blocks`'."""
    jobs = list(jobs)
    if not jobs:
        return
    pool = start_pool(jobs, settings, handler, jobs_n, costs)
    try:
        yield from pool.drain()
    finally:
        pool.close()


def start_pool(jobs: list[LintJob], settings: LintSettings, handler: Handler,
               jobs_n: int | None, costs: Mapping[JobKey, float] | None = None
               ) -> "WorkerPool":
    """Plan the pool for ``jobs`` (package blocks, worker count, queues; ``costs``: the
    seconds models took before, :func:`package_blocks`) and start its workers;
    :meth:`WorkerPool.drain` runs them, :meth:`WorkerPool.more` a further batch on the same
    workers, :meth:`WorkerPool.close` ends them."""
    # a worker forked ahead (prestart) gets its settings first: it enters the sandbox while
    # the parent probes the protections and plans the pool
    pre = _take_prestarted(settings)
    from urdf_lint.runner.sandbox import prepare
    prepare()
    warm_meshes = mesh_facts_cached(settings)
    blocks = package_blocks(jobs, settings, meshes=not warm_meshes, costs=costs)
    cores = os.cpu_count() or 1
    n = max(1, min(jobs_n or default_workers(
        blocks, cores, worker_cost=WARM_WORKER_COST_S if warm_meshes else WORKER_COST_S),
        len(jobs)))
    queues = assign(blocks, n)
    if handler.preload is not None and (pre is None or n > 1):
        # workers forked from here on share what the parent imports (the prestarted one was
        # forked before)
        handler.preload(blocks, settings, n)
    pool = WorkerPool(settings, handler, n)
    pool.queues = queues
    pool.block_of = {id(j): k for k, b in enumerate(blocks) for j in b.jobs}
    pool.workers = [pre] if pre is not None else []
    pool.workers += [Worker(handler, settings) for _ in range(n - len(pool.workers))]
    for w, q in zip(pool.workers, queues, strict=True):
        w.queue = q
    return pool


def affine_queues(jobs: list[LintJob], workers: list[int], home: dict[str, int],
                  took: dict[str, float]) -> dict[int, deque[LintJob]]:
    """A queue per worker (``workers``: their keys) for a batch whose entries were linted
    before (``home``: entry -> the key of the worker that did, ``took``: entry -> the seconds
    it took): the costliest job first, each where it ends soonest, on its entry's worker at
    that cost, elsewhere at twice it (its meshes measured and its sources parsed again); so
    the cheap jobs are last, at the far end where an idle worker steals (:func:`_next_job`)."""
    queues: dict[int, deque[LintJob]] = {k: deque() for k in workers}
    load = dict.fromkeys(queues, 0.0)
    for job in sorted(jobs, key=lambda j: -took.get(j.entry, JOB_COST_S)):
        d = took.get(job.entry, JOB_COST_S)
        mine = home.get(job.entry)
        mine = mine if mine in queues else None     # (its worker is gone: anywhere alike)
        cost = {k: d if mine in (None, k) else 2 * d for k in queues}
        key = min(queues, key=lambda k: load[k] + cost[k])
        load[key] += cost[key]
        queues[key].append(job)
    return queues


class WorkerPool:
    """Forked, limited, sandboxed workers (:class:`Worker`) and their scheduling, with the time
    and memory limits of ``settings``: a job over its limit costs its worker (killed and
    replaced) and becomes the handler's limit result.

    :func:`run_jobs` makes one per run (package blocks on per-worker queues, work stealing).
    ``persistent=True`` keeps the workers between runs (the language server: a fork and
    sandbox per edit would cost more than the lint): :meth:`run` takes a batch of jobs in
    priority order, and stops early, killing the workers on jobs that no longer matter, when
    its ``stop()`` turns true (:meth:`wake` makes the pool look at once)."""

    def __init__(self, settings: LintSettings, handler: Handler, size: int = 1,
                 persistent: bool = False):
        self.settings, self.handler = settings, handler
        self.size, self.persistent = max(1, size), persistent
        self.timeout, self.memory_mb = settings.timeout, settings.memory_mb
        self.wall = self.timeout * WALL_FACTOR
        self.queues: list[deque[LintJob]] = []
        self.block_of: dict[int, int] = {}
        self.workers: list[Worker] = []
        self.busy: dict[Any, Worker] = {}   # connection -> its worker, busy with a job
        self.closing = False   # set from another thread: hand out no further job
        self.stopped = 0       # jobs stopped under way by a stop() (their workers killed)
        self.linted: dict[str, Worker] = {}   # entry -> the worker that linted it last
        self.took: dict[str, float] = {}      # entry -> the seconds that took
        # what the workers measured that the others may reuse (Handler.share): (worker, name,
        # value), in the order learnt, and the names in it
        self.shared: list[tuple[Worker, str, Any]] = []
        self.shared_names: set[str] = set()
        # a run without a facts store (whose parent would hash every measured mesh anyway, to
        # store its facts) checks a report's facts only when another worker is handed a job of
        # the same package (a stolen job, a variant): {package: [(worker, report)]}; a
        # persistent pool (the language server's) checks them as they come
        self.lazy_share = settings.mesh_cache_dir is None and not persistent
        self.unshared: dict[str, list[tuple[Worker, ModelReport]]] = {}
        self._roots: list[str] | None = None
        self._wake = forked.Wake() if persistent else None

    # -- the persistent form -------------------------------------------------------------------
    def start(self) -> None:
        """Fork the workers now (they share what the parent imported; from the main thread,
        where the signals around the fork are ours to set)."""
        from urdf_lint.runner.sandbox import prepare
        prepare()
        if self.handler.preload is not None:
            self.handler.preload([], self.settings, self.size)
        while len(self.workers) < self.size:
            self.workers.append(Worker(self.handler, self.settings))

    def run(self, jobs: list[LintJob],
            stop: Callable[[], bool] | None = None) -> Iterator[tuple[LintJob, ModelReport]]:
        """(job, report) for the jobs, handed out in their order, in completion order. When
        ``stop()`` turns true (looked at between results, and at once after :meth:`wake`),
        the jobs not started are dropped and the workers on the others are killed and
        replaced: nothing more is yielded."""
        if not self.workers:
            self.start()
        shared: deque[LintJob] = deque(jobs)
        self.queues, self.block_of = [shared], {}
        for w in self.workers:
            w.queue = shared
        yield from self.drain(stop)

    def more(self, jobs: list[LintJob], jobs_n: int | None = None
             ) -> Iterator[tuple[LintJob, ModelReport]]:
        """A further batch on the workers of a :func:`start_pool` whose jobs are done (check's
        exploration after its default pass: no second fork, preload and sandbox set-up);
        workers are added up to ``jobs_n`` (default: one per core), never more than the jobs.
        A job whose entry a worker linted before goes to that worker's queue (a variant of a
        model: its meshes are measured and its sources parsed there already; on another
        worker they were measured again, and ``-j 2`` gained nothing on exploration), the
        others to the least loaded; an idle worker takes from the far end of the longest
        queue (:func:`_next_job`)."""
        want = min(max_workers(jobs_n), len(jobs))
        while len(self.workers) < want:
            self.workers.append(Worker(self.handler, self.settings))
        homes = {e: id(w) for e, w in self.linted.items()}
        queues = affine_queues(jobs, [id(w) for w in self.workers], homes, self.took)
        for w in self.workers:
            w.queue = queues[id(w)]
        self.queues, self.block_of = list(queues.values()), {}
        yield from self.drain()

    def add(self, jobs: list[LintJob]) -> None:
        """More jobs for the :meth:`drain` under way: each at the end of the queue of the
        worker that linted its entry (its sources parsed, its meshes measured there), else of
        the shortest queue; an idle worker takes them from there (:func:`_next_job`)."""
        for job in jobs:
            w = self.linted.get(job.entry)
            if w is None or w not in self.workers or w.queue is None:
                queued = [o for o in self.workers if o.queue is not None]
                if not queued:
                    continue
                w = min(queued, key=lambda o: len(o.queue))
            w.queue.append(job)

    def wake(self) -> None:
        """Make a :meth:`run` under way look at its ``stop()`` now (from any thread)."""
        if self._wake is not None:
            self._wake.set()

    def abandon(self) -> None:
        """Drop the jobs not started and stop the workers on the others."""
        for q in self.queues:
            q.clear()
        for conn, w in list(self.busy.items()):
            self.busy.pop(conn)
            self.stopped += 1
            self.replace(w)

    # -- scheduling ----------------------------------------------------------------------------
    def drain(self, stop: Callable[[], bool] | None = None
              ) -> Iterator[tuple[LintJob, ModelReport]]:
        """Run the queued jobs to the end (or until ``stop()``), yielding their results."""
        while (self.pending() and not self.closing) or self.busy:
            if stop is not None and stop():
                self.abandon()
                return
            self.dispatch()
            for conn in self.wait():
                if conn is self._wake:
                    self._wake.clear()
                    continue
                # the worker that sent a result gets its next job as soon as the result is
                # read: not after the parent has hashed its meshes, cached it and planned its
                # variants (~15 ms a job it stood idle)
                yield self.collect(conn, then=lambda: None if stop is not None and stop()
                                   else self.dispatch())
            yield from self.expire()

    def pending(self) -> bool:
        return any(self.queues)

    def replace(self, old: Worker) -> None:
        """Stop worker ``old`` and start another on its queue."""
        self.retire(old)
        new = Worker(self.handler, self.settings)
        new.queue = old.queue
        self.workers.append(new)

    def retire(self, w: Worker) -> None:
        if w in self.workers:
            self.workers.remove(w)
        w.kill()

    def _limit(self, w: Worker) -> float:
        return self.wall if w.cpu0 is not None else self.timeout

    def dispatch(self) -> None:
        """Send each idle worker its next job."""
        for w in list(self.workers):
            if w.job is None and self.pending() and not self.closing:
                w.job = _next_job(w.queue, self.queues, self.block_of,
                                  {self.block_of.get(id(o.job)) for o in self.workers if o.job})
                if w.job is None:
                    continue
                w.started = time.monotonic()
                w.cpu0 = _cpu_seconds(w.proc.pid)
                try:
                    w.conn.send(self._with_shared(w, w.job))
                except (OSError, ValueError):   # a worker gone meanwhile: another takes it
                    w.queue.appendleft(w.job)
                    w.job = None
                    self.replace(w)
                    continue
                self.busy[w.conn] = w

    def _with_shared(self, w: Worker, job: LintJob) -> LintJob:
        """``job`` with what the other workers measured since ``w`` was last handed a job."""
        if self.unshared:
            self._share_package(w, self._package(job))
        new = [(name, value) for by, name, value in self.shared[w.told:] if by is not w]
        w.told = len(self.shared)
        return dataclasses.replace(job, shared=tuple(new)) if new else job

    def _learn(self, w: Worker, job: LintJob, result: ModelReport) -> None:
        """Keep what ``w``'s result measured for the other workers (when there are others)."""
        if self.handler.share is None or len(self.workers) < 2 and self.size < 2 \
                or len(self.shared) >= MAX_SHARED:
            return
        if self.lazy_share:
            if result.mesh_facts:
                self.unshared.setdefault(self._package(job), []).append((w, result))
            return
        self._keep_shared(w, self.handler.share(result, self.settings))

    def _keep_shared(self, w: Worker, pairs: list[tuple[str, Any]]) -> None:
        for name, value in pairs:
            if name not in self.shared_names:
                self.shared_names.add(name)
                self.shared.append((w, name, value))

    def _package(self, job: LintJob) -> str:
        if self._roots is None:
            self._roots = package_roots(self.settings)
        return block_key(job, self._roots)

    def _share_package(self, w: Worker, package: str) -> None:
        """Check and keep, for ``w``'s job of ``package``, what the other workers measured
        for that package's models."""
        waiting = self.unshared.pop(package, [])
        mine = [(by, r) for by, r in waiting if by is w]
        if mine:
            self.unshared[package] = mine
        assert self.handler.share is not None
        for by, result in waiting:
            if by is not w and len(self.shared) < MAX_SHARED:
                self._keep_shared(by, self.handler.share(result, self.settings))

    def wait(self) -> list[Any]:
        """The connections of busy workers that sent something, by the next deadline (or the
        next look at CPU times); the wake pipe too when another thread set it."""
        now = time.monotonic()
        next_deadline = min((w.started + self._limit(w) for w in self.busy.values()),
                            default=now + POLL_S)
        if any(w.cpu0 is not None for w in self.busy.values()):
            next_deadline = min(next_deadline, now + POLL_S)
        conns: list[Any] = list(self.busy)
        if self._wake is not None:
            conns.append(self._wake)
        return forked.wait(conns, timeout=max(0.0, next_deadline - now))

    def collect(self, conn: Any, then: Callable[[], None] | None = None
                ) -> tuple[LintJob, ModelReport]:
        """(job, result) from the worker on ``conn``; a worker that sent something else or
        died is replaced. ``then()`` runs once the result is read, before what this process
        keeps of it (the facts it measured) is worked out."""
        w = self.busy.pop(conn)
        job = w.job
        try:
            result = w.conn.recv(timeout=max(1.0, w.started + self._limit(w) - time.monotonic()))
            if not isinstance(result, ModelReport):
                raise forked.Refused(f"a {type(result).__name__}")
        except forked.Refused as e:
            # not a lint result: the worker ran something that is not urdf-lint's (the run's
            # internal errors are listed without their models: the message names it)
            result = ModelReport.failed(job)
            result.internal.append(
                f"the worker linting {result.label} sent back something that is not a lint "
                f"result ({e}); it was not read, and the worker was stopped")
            result.cacheable = False
            self.replace(w)
        except (EOFError, OSError):
            w.proc.join(1)    # (reaped: its exit code, not None while it is still exiting)
            code = w.proc.exitcode
            result = self.handler.limit_result(
                job, f"the expansion worker died (exit code {code}); likely the memory limit "
                f"({self.memory_mb} MiB)")
            self.replace(w)
        else:
            w.job = None
            self.linted[job.entry] = w
            self.took[job.entry] = time.monotonic() - w.started
            if then is not None:
                then()
            self._learn(w, job, result)
            return job, result
        if then is not None:
            then()
        return job, result

    def _over(self, w: Worker, now: float) -> tuple[bool, str]:
        """(whether busy worker ``w`` is over its time limit, the limit in words)."""
        timeout, wall = self.timeout, self.wall
        if w.cpu0 is not None:
            cpu = _used(w)
            over = (cpu is not None and cpu >= timeout) or now - w.started >= wall
            return over, (f"the time limit ({timeout:g} s of CPU time, {wall:g} s of "
                          "wall-clock time)")
        return now - w.started >= timeout, f"the time limit ({timeout:g} s)"

    def expire(self) -> Iterator[tuple[LintJob, ModelReport]]:
        """Yield (job, limit result) for each busy worker over its time limit, stopped."""
        now = time.monotonic()
        for conn, w in list(self.busy.items()):
            over, what = self._over(w, now)
            if over:
                self.busy.pop(conn)
                job = w.job
                if self.persistent or self.pending() or self.busy:
                    self.replace(w)
                else:
                    self.retire(w)
                yield job, self.handler.limit_result(
                    job, f"expansion/lint did not finish within {what}; a huge expression, "
                    "loop or recursion?")

    def release(self) -> None:
        """Tell the idle workers that no job will follow (the pool takes none after this):
        they exit while the caller finishes its run, and :meth:`close` finds them gone."""
        self.closing = True
        for w in self.workers:
            if w.job is None:
                _tell_end(w)

    def close(self) -> None:
        self.closing = True
        for w in self.workers:
            _tell_end(w)
        for w in self.workers:
            w.proc.join(0.5)
            if w.proc.is_alive():
                w.kill()
            else:
                w.conn.close()
        self.workers = []
        if self._wake is not None:
            self._wake.close()
            self._wake = None

