"""The hardening every forked process of urdf-lint that handles repository data gets: the
workers (``pool.py``) and the ``diff --render`` recorder (``recording.py``): a scrubbed
environment, a memory limit, the audit hook, and for a process that only writes, the OS
sandbox of :mod:`urdf_lint.runner.sandbox` with nothing of the repository readable."""
from __future__ import annotations

import os
import sys
from typing import Any, Collection

from urdf_lint.runner import forked

# importing rerun reserves ~1.2 GB of writable address space (its Rust runtime) before any
# data is logged; workers that write recordings get this on top of the memory limit
RERUN_RESERVE_MB = 1536

_KEEP_ENV = {"PATH", "HOME", "LANG", "LANGUAGE", "TMPDIR", "TMP", "TEMP", "PYTHONHASHSEED",
             "SYSTEMROOT", "OPENBLAS_NUM_THREADS"}   # (the last: set by the command, cli.entry)


def scrub_environment(allow: Collection[str]) -> None:
    for k in list(os.environ):
        if k in _KEEP_ENV or k.startswith("LC_") or k in allow:
            continue
        del os.environ[k]


_DENIED_EVENTS = {"os.system", "subprocess.Popen", "os.exec", "os.posix_spawn", "os.spawn",
                  "os.fork", "os.forkpty", "pty.spawn", "socket.connect", "socket.bind",
                  "os.kill", "webbrowser.open", "shutil.rmtree", "os.remove",
                  "os.rename", "os.rmdir", "os.chmod", "os.chown", "os.symlink", "os.link"}


def install_audit_hook(*writable: str | None) -> None:
    """Second line of defence: even if an expression escaped the evaluator, the worker may not
    start processes, open sockets or write files outside the cache and snapshot folders."""
    dirs = tuple(os.path.realpath(d) + os.sep for d in writable if d)

    def ok(path: Any) -> bool:
        return bool(dirs) and os.path.realpath(os.fsdecode(path)).startswith(dirs)
    flags_w = os.O_WRONLY | os.O_RDWR | os.O_CREAT | os.O_APPEND | os.O_TRUNC

    def hook(event: str, args: tuple[Any, ...]) -> None:
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


def inherited_data_bytes() -> int:
    """The data segment (VmData) this freshly forked worker shares with its parent."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmData:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return 0


def limit_memory(memory_mb: int | float, inherited: int, rerun: bool = False) -> None:
    """The memory limit of a worker (or the recorder): memory-mb is what the job may allocate;
    what the forked process inherited from its parent (a test process that imported rerun, a
    library user's process) is on top, and so is rerun's reserve when it writes recordings."""
    try:
        import resource
        limit = int(memory_mb) * 1024 * 1024 + inherited
        if rerun:
            limit += RERUN_RESERVE_MB * 1024 * 1024
        # RLIMIT_DATA counts memory a process can actually write (heap and private mappings);
        # RLIMIT_AS would also count the address space that native thread arenas only reserve.
        which = getattr(resource, "RLIMIT_DATA", resource.RLIMIT_AS)
        resource.setrlimit(which, (limit, limit))
    except (ImportError, ValueError, OSError):
        pass


def confine_writer(write_dir: str) -> dict[str, Any]:
    """The worker hardening for a process that reads nothing and writes only below
    ``write_dir`` (the ``diff --render`` recorder): Landlock (the Python runtime readable,
    nothing of the repository or the home folder; writable only ``write_dir``), seccomp and
    the audit hook. Its inherited descriptors were closed when it started (those open now are
    its own, rerun's among them). Returns what :func:`sandbox.enter` did."""
    from urdf_lint.runner.sandbox import enter
    try:
        keep = [int(n) for n in os.listdir("/proc/self/fd")]
    except OSError:
        keep = list(range(os.sysconf("SC_OPEN_MAX")))
    status = enter(forked.parent_pid or os.getppid(), [], [write_dir], keep_fds=keep)
    install_audit_hook(write_dir)
    return status
