"""Run lint jobs in isolated worker processes with a time limit and a memory limit.

Each worker is a forked process with a scrubbed environment and an address-space limit.
The parent hands out one job at a time; a worker that exceeds the time limit is killed (and
replaced), and its job becomes a ``UL904`` finding. Other models keep going.
"""
from __future__ import annotations

import multiprocessing as mp
import os
import signal
import sys
import time
from multiprocessing.connection import wait
from typing import Any

from .findings import Problem
from .jobs import LintJob, LintSettings, ModelReport
from .rules import ul904_resource_limit as resource_limit

# importing rerun reserves ~1.2 GB of writable address space (its Rust runtime) before any
# data is logged; workers that write recordings get this on top of the memory limit
RERUN_RESERVE_MB = 1536

_KEEP_ENV = {"PATH", "HOME", "LANG", "LANGUAGE", "TMPDIR", "TMP", "TEMP", "PYTHONHASHSEED",
             "SYSTEMROOT"}


def _scrub_environment(allow):
    for k in list(os.environ):
        if k in _KEEP_ENV or k.startswith("LC_") or k in allow:
            continue
        del os.environ[k]


_DENIED_EVENTS = {"os.system", "subprocess.Popen", "os.exec", "os.posix_spawn", "os.spawn",
                  "os.fork", "os.forkpty", "pty.spawn", "socket.connect", "socket.bind",
                  "os.kill", "webbrowser.open", "shutil.rmtree", "os.remove",
                  "os.rename", "os.rmdir", "os.chmod", "os.chown", "os.symlink", "os.link"}


def _install_audit_hook(*writable):
    """Second line of defence: even if an expression escaped the evaluator, the worker may not
    start processes, open sockets or write files outside the cache and snapshot folders."""
    dirs = tuple(os.path.realpath(d) + os.sep for d in writable if d)

    def ok(path):
        return bool(dirs) and os.path.realpath(os.fsdecode(path)).startswith(dirs)
    flags_w = os.O_WRONLY | os.O_RDWR | os.O_CREAT | os.O_APPEND | os.O_TRUNC

    def hook(event, args):
        if event in _DENIED_EVENTS:
            if event in ("os.rename", "os.remove") and args and ok(args[0]):
                return  # atomic cache / snapshot writes
            raise PermissionError(f"urdf-lint worker: {event} is not allowed")
        if event == "open" and len(args) >= 3:
            path, mode, flags = args[0], args[1], args[2]
            writing = (isinstance(mode, str) and any(c in mode for c in "wax+")) or \
                (isinstance(flags, int) and flags & flags_w)
            if writing and isinstance(path, (str, bytes, os.PathLike)) and not ok(path):
                raise PermissionError(f"urdf-lint worker: writing {os.fsdecode(path)} is not allowed")
    sys.addaudithook(hook)


def process_job(job: LintJob, settings: LintSettings) -> ModelReport:
    """Lint one job; on a render run, hand the linted model to the renderer too."""
    from .lint import lint_model
    report, model, ctx = lint_model(job, settings)
    if settings.diff_render_dir and model is not None and report.kept_model is not None:
        report.diff_geometry, report.diff_rrd = _diff_snapshot(model, ctx, job, settings)
    if settings.render_dir and model is not None:
        from .render import render_model
        from .registry import load_rules
        rules = load_rules()
        shown = [p.replace(severity=p.severity or (rules[p.code].severity if p.code in rules
                                                   else "error"))
                 for p in report.problems]
        report.snapshot = render_model(model, ctx, shown, settings.render_dir,
                                       settings.render_base, rrd=settings.render_rrd)
    return report


def _diff_snapshot(model, ctx, job: LintJob, settings: LintSettings):
    """``urdf-lint diff --render``: the picture's geometry (drawn by the parent with the other
    revision's framing) and this revision's half of the shared recording."""
    from . import render
    scene = render.build_scene(model, ctx)
    geometry = render.scene_geometry(scene, ctx)
    rrd = None
    if settings.diff_rrd:
        try:
            import rerun  # noqa: F401
        except ImportError:
            return geometry, None
        stem = os.path.join(settings.diff_render_dir or "", job.diff_stem or "")
        rrd = f"{stem}.{settings.diff_side}.rrd"
        render.record_rrd(scene, ctx, [], rrd, recording_id=f"urdf-lint-diff/{job.diff_stem}",
                          prefix=f"{settings.diff_side}/", model=model,
                          blueprint=("base/", "head/"))
    return geometry, rrd


# Optional accelerators trimesh probes for when it is imported (~0.4 s per process). urdf-lint
# uses none of them (its convex hulls come from manifold3d); they arrive with yourdfpy's
# ``trimesh[easy]`` (the ``render`` extra). A worker runs only urdf-lint's code, so it skips them.
UNUSED_TRIMESH_EXTRAS = ("scipy", "networkx", "shapely", "rtree", "embreex")


def _inherited_data_bytes() -> int:
    """The data segment (VmData) this freshly forked worker shares with its parent."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmData:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return 0


def _skip_unused_imports():
    for name in UNUSED_TRIMESH_EXTRAS:
        sys.modules.setdefault(name, None)  # type: ignore[arg-type] - "import fails" marker


def _worker_main(conn, settings: LintSettings | None, memory_mb):
    _skip_unused_imports()
    # the parent turns SIGTERM into KeyboardInterrupt; a worker just dies of it
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if settings is None:
        # started ahead of its settings (prestart): import the expansion while the parent
        # reads the config and finds the packages, then wait for what to run with
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        try:
            from . import lint  # noqa: F401
            from .expansion import expand  # noqa: F401
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
    try:
        import resource
        # memory-mb is what the job may allocate: what the forked worker inherited from its
        # parent (a test process that imported rerun, a library user's process) is on top
        limit = int(memory_mb) * 1024 * 1024 + _inherited_data_bytes()
        if (settings.render_dir and settings.render_rrd) or \
                (settings.diff_render_dir and settings.diff_rrd):
            limit += RERUN_RESERVE_MB * 1024 * 1024
        # RLIMIT_DATA counts memory a process can actually write (heap and private mappings);
        # RLIMIT_AS would also count the address space that native thread arenas only reserve.
        which = getattr(resource, "RLIMIT_DATA", resource.RLIMIT_AS)
        resource.setrlimit(which, (limit, limit))
    except (ImportError, ValueError, OSError):
        pass
    _scrub_environment(set(settings.env_allow))
    from .sandbox import enter_worker
    enter_worker(conn, settings)  # Landlock, seccomp, pdeathsig, inherited fds closed
    sys.setrecursionlimit(4000)
    sys.dont_write_bytecode = True
    _install_audit_hook(settings.mesh_cache_dir, settings.render_dir, settings.diff_render_dir)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    while True:
        try:
            job = conn.recv()
        except (EOFError, OSError):
            return
        if job is None:
            return
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
    return ModelReport.failed(job, [Problem.at(resource_limit.CODE, message, (job.entry, 1, 1))])


_prestarted: "_Worker | None" = None


def prestart() -> None:
    """Fork one worker now, before the run's settings are known, so that its imports overlap
    with the parent's config and package discovery (``urdf-lint expand``: a single small job
    whose latency is mostly start-up). The next :func:`run_jobs` hands it the settings; it
    enters the sandbox then, before it reads a job, exactly like a worker started there."""
    global _prestarted
    if _prestarted is None:
        from .sandbox import disabled
        disabled()   # decided from the parent's environment before the fork (the worker's is scrubbed)
        try:
            _prestarted = _Worker(mp.get_context("fork"), None, None)
        except (ValueError, OSError):   # no fork here, or no process to spare: start later
            _prestarted = None
            return
        import atexit
        atexit.register(_drop_prestarted)   # a run that stopped before it needed the worker


def _drop_prestarted() -> None:
    global _prestarted
    w, _prestarted = _prestarted, None
    if w is not None:
        try:
            w.conn.send(None)
            w.proc.join(0.5)
        except (OSError, ValueError):
            pass
        if w.proc.is_alive():
            w.kill()


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


class _Worker:
    def __init__(self, ctx, settings, memory_mb):
        self.conn, child = ctx.Pipe()
        self.proc = ctx.Process(target=_worker_main, args=(child, settings, memory_mb),
                                daemon=True)
        # the child ignores Ctrl-C and dies of SIGTERM from its first instruction (the parent
        # exits 130 for both; its SIGTERM handler must not run in the child)
        try:
            old = signal.signal(signal.SIGINT, signal.SIG_IGN)
            old_term = signal.signal(signal.SIGTERM, signal.SIG_DFL)
        except ValueError:          # not the main thread: signals are not ours to change
            old = old_term = None
        try:
            self.proc.start()
        finally:
            if old is not None:
                signal.signal(signal.SIGINT, old)
                signal.signal(signal.SIGTERM, old_term)
        child.close()
        self.job = None
        self.started = 0.0

    def kill(self):
        try:
            self.proc.kill()
        except Exception:
            pass
        self.proc.join(1)
        self.conn.close()


def run_jobs(jobs: list[LintJob], settings: LintSettings, jobs_n=None, timeout=30.0,
             memory_mb=2048):
    """Yield (job, ModelReport) for every job; results arrive in completion order."""
    jobs = list(jobs)
    if not jobs:
        return
    from .sandbox import prepare
    prepare()
    try:
        ctx: Any = mp.get_context("fork")
    except ValueError:  # pragma: no cover - no fork on this platform
        ctx = mp.get_context()
    n = max(1, min(jobs_n or os.cpu_count() or 1, len(jobs)))
    pending = list(reversed(jobs))
    pre = _take_prestarted(settings, memory_mb)
    workers = [pre] if pre is not None else []
    workers += [_Worker(ctx, settings, memory_mb) for _ in range(n - len(workers))]
    try:
        busy: dict = {}
        while pending or busy:
            for w in workers:
                if w.job is None and pending:
                    w.job = pending.pop()
                    w.started = time.monotonic()
                    w.conn.send(w.job)
                    busy[w.conn] = w
            now = time.monotonic()
            next_deadline = min(w.started + timeout for w in busy.values())
            ready = wait(list(busy), timeout=max(0.0, next_deadline - now))
            for conn in ready:
                w = busy.pop(conn)
                job = w.job
                try:
                    result = w.conn.recv()
                except (EOFError, OSError):
                    code = w.proc.exitcode
                    result = _limit_result(job, "the expansion worker died (exit code "
                                           f"{code}); likely the memory limit ({memory_mb} MiB)")
                    workers.remove(w)
                    w.kill()
                    workers.append(_Worker(ctx, settings, memory_mb))
                else:
                    w.job = None
                yield job, result
            now = time.monotonic()
            for conn, w in list(busy.items()):
                if now - w.started >= timeout:
                    busy.pop(conn)
                    job = w.job
                    workers.remove(w)
                    w.kill()
                    if pending or busy:
                        workers.append(_Worker(ctx, settings, memory_mb))
                    yield job, _limit_result(job, f"expansion/lint did not finish within the "
                                             f"time limit ({timeout:g} s); a huge expression, "
                                             "loop or recursion?")
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
