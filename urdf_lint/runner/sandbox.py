"""OS-level sandbox for the worker processes that expand and lint untrusted descriptions.

The allow-list evaluator (:mod:`urdf_lint.expansion.safe_eval`) is the first line of defence; this module
is what keeps the *next* evaluator hole harmless. :func:`enter` runs in every worker right
after fork, before the worker reads any job, and applies, each where the platform has it:

* ``PR_SET_PDEATHSIG``: the worker is killed when the urdf-lint process that forked it dies
  (and exits at once if that already happened), so no worker outlives its parent;
* closing every inherited file descriptor except the job pipe and stdio, so nothing the
  parent had open (and no sibling worker's pipe) is reachable;
* **Landlock** (Linux >= 5.13, PyPI ``landlock``): the filesystem is read-only below the
  package roots, the repository and the Python runtime, writable only below the cache and
  snapshot folders, and invisible everywhere else (``/proc`` included, so neither the
  parent's ``/proc/<pid>/environ`` nor the worker's own inherited one can be read); where
  the kernel has Landlock's scopes (ABI >= 6), no signal leaves the worker either;
* **seccomp** (PyPI ``pyseccomp`` over ``libseccomp.so.2``): ``execve``/``execveat``, socket
  creation and connection, ``ptrace``, cross-process memory access, ``io_uring``, signals
  to any other process (``kill``, ``tkill``, ``tgkill``, ``rt_sigqueueinfo``,
  ``rt_tgsigqueueinfo``) and new processes (``fork``, ``vfork``, ``clone`` without
  ``CLONE_THREAD``; ``clone3`` says ``ENOSYS`` so libc starts threads with ``clone``) fail
  with ``EPERM``: a worker has threads but never a child that could outlive it.

Filters are inherited by any thread the worker starts and cannot be lifted afterwards. A
protection the kernel lacks is reported once by the parent (:func:`note_missing`) and the run
goes on with the others. ``URDF_LINT_SANDBOX=0`` turns the OS layer off (for measuring its
cost and for debugging only; ``urdf-lint doctor`` shows it).
"""
from __future__ import annotations

import ctypes
import errno
import os
import sys
from typing import Any, Iterable

_PR_SET_PDEATHSIG = 1
_PR_SET_NO_NEW_PRIVS = 38

# syscalls a worker never needs; each fails with EPERM. socketpair() stays allowed: it makes
# an already-connected pair inside the process (rerun's runtime uses one for signals) and
# cannot reach anything outside it.
DENIED_SYSCALLS = (
    "execve", "execveat",
    "socket", "connect", "bind", "listen", "accept", "accept4",
    "ptrace", "process_vm_readv", "process_vm_writev",
    "io_uring_setup", "io_uring_enter", "io_uring_register",
    "unshare", "setns", "mount", "umount2", "pivot_root", "chroot",
    "bpf", "perf_event_open", "userfaultfd", "keyctl", "add_key", "request_key",
    "pidfd_open", "pidfd_getfd", "pidfd_send_signal",
)
# calls that signal the process or thread their first argument names: allowed only with the
# worker's own pid there
SIGNAL_SYSCALLS = ("kill", "tkill", "tgkill", "rt_sigqueueinfo", "rt_tgsigqueueinfo")
_CLONE_THREAD = 0x00010000
# read-only system folders the runtime may load shared libraries and data from
_SYSTEM_READ = ("/usr/lib", "/usr/lib64", "/usr/local/lib", "/lib", "/lib64", "/usr/share/zoneinfo",
                "/etc/ld.so.cache", "/etc/localtime", "/dev/urandom", "/dev/random",
                "/sys/devices/system/cpu")
_SYSTEM_RW = ("/dev/null",)

_noted = False
_disabled: bool | None = None


def disabled() -> bool:
    """Decided once, in the parent (the worker's environment is scrubbed)."""
    global _disabled
    if _disabled is None:
        _disabled = os.environ.get("URDF_LINT_SANDBOX", "").strip().lower() in (
            "0", "off", "no", "false")
    return _disabled


# -- probing (parent side, cheap, applies nothing) ---------------------------------------------
def _libc() -> Any:
    try:
        return ctypes.CDLL(None, use_errno=True)
    except OSError:
        return None


def _import_landlock() -> Any:
    """The ``landlock`` package, imported as it is: nothing of the standard library or of
    another package is swapped around the import (a stub for ``dataclasses``' view of
    ``inspect`` crashed every Python but 3.11)."""
    import landlock
    return landlock


def landlock_status() -> tuple[bool, str]:
    if not sys.platform.startswith("linux"):
        return False, f"not available on {sys.platform} (Landlock is Linux-only)"
    try:
        landlock = _import_landlock()
    except ImportError:
        return False, "the 'landlock' package is not installed"
    try:
        abi = landlock.landlock_abi_version()
    except Exception as e:  # noqa: BLE001 - kernel without Landlock, or it is disabled
        reason = getattr(e, "reason", None) or str(e).splitlines()[0]
        return False, f"not available on this kernel ({reason})"
    return True, f"Landlock ABI {abi}"


def _import_pyseccomp() -> Any:
    """The ``pyseccomp`` package, imported as it is (it looks libseccomp up with the standard
    library's ``ctypes.util``; no stand-in is swapped into the standard library)."""
    import pyseccomp
    return pyseccomp


def seccomp_status() -> tuple[bool, str]:
    if not sys.platform.startswith("linux"):
        return False, f"not available on {sys.platform} (seccomp is Linux-only)"
    try:
        _import_pyseccomp()  # raises when libseccomp.so.2 is missing
    except ImportError:
        return False, "the 'pyseccomp' package is not installed"
    except Exception as e:  # noqa: BLE001 - OSError/AttributeError from the ctypes binding
        return False, f"libseccomp.so.2 could not be loaded ({e})"
    return True, "seccomp filter via libseccomp"


def pdeathsig_status() -> tuple[bool, str]:
    if not sys.platform.startswith("linux") or _libc() is None:
        return False, f"not available on {sys.platform}"
    return True, "PR_SET_PDEATHSIG"


def protections() -> dict[str, tuple[bool, str]]:
    """What the workers get on this machine, for ``urdf-lint doctor`` and ``--version``."""
    global _disabled
    _disabled = None  # parent side: read the environment afresh
    out = {}
    if disabled():
        off = (False, "turned off by URDF_LINT_SANDBOX=0")
        out = {"landlock": off, "seccomp": off}
    else:
        out = {"landlock": landlock_status(), "seccomp": seccomp_status()}
    out["pdeathsig"] = pdeathsig_status()
    out["rlimits"] = (True, "time and memory limits per model")
    out["environment"] = (True, "scrubbed to an allow-list")
    out["audit-hook"] = (True, "Python audit hook (processes, sockets, writes)")
    return out


def summary_line() -> str:
    p = protections()
    on = [k for k in ("landlock", "seccomp", "pdeathsig") if p[k][0]]
    off = [k for k in ("landlock", "seccomp", "pdeathsig") if not p[k][0]]
    return ("worker sandbox: " + (", ".join(on) or "none")
            + (f" (missing: {', '.join(off)})" if off else ""))


def note_missing(stream: Any = None) -> None:
    """Say once per process which OS protections this machine lacks."""
    global _noted
    if _noted:
        return
    _noted = True
    from urdf_lint.core.emit import say
    p = protections()
    for k in ("landlock", "seccomp"):
        ok, why = p[k]
        if not ok:
            say(f"urdf-lint: note: worker sandbox without {k}: {why}; see SECURITY.md", stream)


# -- applying (worker side) --------------------------------------------------------------------
def set_parent_death_signal(parent_pid: int) -> bool:
    libc = _libc()
    if libc is None or not sys.platform.startswith("linux"):
        return False
    import signal
    if libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0) != 0:
        return False
    if os.getppid() != parent_pid:  # the parent died before prctl: go now
        os._exit(0)
    return True


def close_inherited_fds(keep: Iterable[int]) -> None:
    keep = sorted({0, 1, 2} | {int(k) for k in keep if k is not None and k >= 0})
    try:
        fds = [int(n) for n in os.listdir("/proc/self/fd")]
    except OSError:
        fds = None
    if fds is None:
        try:
            top = os.sysconf("SC_OPEN_MAX")
        except (ValueError, OSError):
            top = 4096
        lo = 0
        for k in keep + [top]:
            if k > lo:
                os.closerange(lo, k)
            lo = k + 1
        return
    for fd in fds:
        if fd not in keep:
            try:
                os.close(fd)
            except OSError:
                pass


_runtime_paths: list[str] | None = None


def runtime_read_paths() -> list[str]:
    """Folders the Python runtime itself needs: stdlib, site-packages, urdf-lint's own code.
    Computed once, in the parent (:func:`prepare`), and inherited by the forked workers."""
    global _runtime_paths
    if _runtime_paths is None:
        _runtime_paths = _existing(_runtime_read_paths())
    return list(_runtime_paths)


def _runtime_read_paths() -> list[str]:
    import sysconfig
    out = []
    for k in ("stdlib", "platstdlib", "purelib", "platlib"):
        p = sysconfig.get_paths().get(k)
        if p:
            out.append(p)
    try:
        import site
        out += site.getsitepackages()
    except Exception:  # noqa: BLE001 - some embedded interpreters have no site
        pass
    cwd = os.getcwd()
    for p in sys.path:
        # the folder `python -m` was started in is not runtime; it is only readable when it
        # is a package root or the repository
        if p and os.path.abspath(p) != cwd:
            out.append(p)
    import urdf_lint
    out += [os.path.abspath(p) for p in urdf_lint.__path__]   # the package and every room
    try:   # (found, not imported: the runner runs no rule)
        import importlib.util
        spec = importlib.util.find_spec("urdf_lint.rules")
        out += list(spec.submodule_search_locations or ()) if spec else []
    except Exception:  # noqa: BLE001
        pass
    return out


def _existing(paths: Iterable[str | None]) -> list[str]:
    seen: set[str] = set()
    out: list[str] = []
    for p in paths:
        if not p:
            continue
        try:
            real = os.path.realpath(p)
        except (OSError, ValueError):
            continue
        if real in seen or not os.path.exists(real) or real == "/":
            continue
        seen.add(real)
        out.append(real)
    return out


def apply_landlock(read_paths: Iterable[str | None],
                   write_paths: Iterable[str | None]) -> None:
    from landlock import FSAccess, Ruleset
    handled = FSAccess.all()
    ro_file = FSAccess.READ_FILE
    ro_dir = FSAccess.READ_FILE | FSAccess.READ_DIR
    rw_file = FSAccess.READ_FILE | FSAccess.WRITE_FILE
    if FSAccess.TRUNCATE & handled:
        rw_file |= FSAccess.TRUNCATE
    rw_dir = ro_dir | rw_file | FSAccess.MAKE_REG | FSAccess.MAKE_DIR | \
        FSAccess.REMOVE_FILE | FSAccess.REMOVE_DIR
    rs = Ruleset(handled)
    try:
        for paths, fr, dr in ((read_paths, ro_file, ro_dir), (write_paths, rw_file, rw_dir)):
            for p in _existing(paths):
                rs.allow(p, rules=dr if os.path.isdir(p) else fr)
        rs.apply()
    finally:
        try:
            os.close(rs._fd)
        except OSError:
            pass


# Landlock's scopes (ABI >= 6): a domain that may not signal a process outside itself
_LANDLOCK_SCOPE_SIGNAL = 1 << 1
_SYS_LANDLOCK_CREATE_RULESET, _SYS_LANDLOCK_RESTRICT_SELF = 444, 446   # every architecture


def apply_signal_scope() -> bool:
    """Landlock ABI >= 6: no signal leaves the worker's domain (the kernel's own check, under
    seccomp's argument filter). False when the kernel's ABI has no scopes."""
    from landlock import landlock_abi_version
    if landlock_abi_version() < 6:
        return False
    libc = _libc()
    if libc is None:
        return False
    libc.syscall.restype = ctypes.c_long
    attr = (ctypes.c_uint64 * 3)(0, 0, _LANDLOCK_SCOPE_SIGNAL)   # fs, net, scoped
    fd = libc.syscall(_SYS_LANDLOCK_CREATE_RULESET, ctypes.byref(attr),
                      ctypes.c_size_t(ctypes.sizeof(attr)), ctypes.c_uint32(0))
    if fd < 0:
        raise OSError(ctypes.get_errno(), "landlock_create_ruleset (signal scope)")
    try:
        if libc.prctl(_PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0:
            raise OSError(ctypes.get_errno(), "prctl(PR_SET_NO_NEW_PRIVS)")
        if libc.syscall(_SYS_LANDLOCK_RESTRICT_SELF, ctypes.c_int(fd), ctypes.c_uint32(0)) != 0:
            raise OSError(ctypes.get_errno(), "landlock_restrict_self (signal scope)")
    finally:
        os.close(fd)
    return True


def apply_seccomp() -> None:
    sc = _import_pyseccomp()
    f = sc.SyscallFilter(defaction=sc.ALLOW)
    for name in DENIED_SYSCALLS:
        try:
            f.add_rule(sc.ERRNO(errno.EPERM), name)
        except Exception:  # noqa: BLE001 - a syscall this architecture does not have
            continue
    me = os.getpid()
    # signals only to itself (its own threads included): every call that names a target
    # process or thread by its first argument (a thread of the worker is reached through
    # tgkill(me, tid), which glibc's pthread_kill and raise use)
    for name in SIGNAL_SYSCALLS:
        try:
            f.add_rule(sc.ERRNO(errno.EPERM), name, sc.Arg(0, sc.NE, me))
        except Exception:  # noqa: BLE001 - a syscall this architecture does not have
            continue
    # no child process: fork/vfork, and clone without CLONE_THREAD, fail (a thread shares the
    # worker's life: it dies with it). clone3 passes its flags in memory a filter cannot
    # read: it says ENOSYS, and libc falls back to clone, which is filtered
    for name in ("fork", "vfork"):
        try:
            f.add_rule(sc.ERRNO(errno.EPERM), name)
        except Exception:  # noqa: BLE001 - aarch64 has neither
            continue
    # clone(flags, ...): the flags are the first argument everywhere but s390 (the second)
    flags_arg = 1 if os.uname().machine.startswith("s390") else 0
    f.add_rule(sc.ERRNO(errno.EPERM), "clone", sc.Arg(flags_arg, sc.MASKED_EQ, _CLONE_THREAD, 0))
    try:
        f.add_rule(sc.ERRNO(errno.ENOSYS), "clone3")
    except Exception:  # noqa: BLE001 - a libseccomp that predates clone3 (the kernel's
        pass           # filter then allows it: no worse than before)
    f.load()


def enter(parent_pid: int, read_paths: Iterable[str | None],
          write_paths: Iterable[str | None], keep_fds: Iterable[int] = ()) -> dict[str, Any]:
    """Lock this (worker) process down. Returns {protection: "on" | reason it is off}."""
    status = {}
    status["pdeathsig"] = "on" if set_parent_death_signal(parent_pid) else "unavailable"
    close_inherited_fds(keep_fds)
    if disabled():
        status["landlock"] = status["seccomp"] = "off (URDF_LINT_SANDBOX=0)"
        return status
    if landlock_status()[0]:
        try:
            apply_landlock(list(read_paths) + runtime_read_paths() + list(_SYSTEM_READ),
                           list(write_paths) + list(_SYSTEM_RW))
            status["landlock"] = "on"
        except Exception as e:  # noqa: BLE001 - report and go on with what remains
            status["landlock"] = f"failed: {e}"
        try:
            status["signal-scope"] = "on" if apply_signal_scope() else "unavailable (ABI < 6)"
        except Exception as e:  # noqa: BLE001
            status["signal-scope"] = f"failed: {e}"
    else:
        status["landlock"] = "unavailable"
    if seccomp_status()[0]:
        try:
            apply_seccomp()
            status["seccomp"] = "on"
        except Exception as e:  # noqa: BLE001
            status["seccomp"] = f"failed: {e}"
    else:
        status["seccomp"] = "unavailable"
    return status


def enter_worker(conn: Any, settings: Any) -> dict[str, Any]:
    """The one call a worker makes at start-up, before it reads its first job (``settings`` is
    the run's :class:`urdf_lint.core.jobs.LintSettings`)."""
    import signal
    from urdf_lint.runner import forked
    # the parent turns SIGTERM into KeyboardInterrupt; a worker just dies of it (a Python
    # handler would never run while a C-level loop holds the interpreter)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    parent_pid = forked.parent_pid or os.getppid()
    from urdf_lint.discovery.packages import PackageResolver
    read = PackageResolver.from_dict(settings.resolver).read_paths() if settings.resolver else []
    write = []
    # the mesh facts store is read here, written by the parent only (urdf_lint.meshes.store)
    if settings.mesh_cache_dir and os.path.isdir(settings.mesh_cache_dir):
        read = [*read, settings.mesh_cache_dir]
    # snapshots: check --render / render --out (a diff --render worker writes nothing: its
    # pictures and recording plan go back through the pipe)
    if settings.render_dir:
        try:
            from urdf_lint.core import fsbound
            fsbound.make_own_dirs(settings.render_dir)   # the snapshot folder
            write.append(settings.render_dir)
        except OSError:
            pass
    keep = list(getattr(conn, "fds", None) or (conn.fileno(),))
    status = enter(parent_pid, read, write, keep_fds=keep)
    bad = {k: v for k, v in status.items() if v.startswith("failed")}
    if bad:  # the parent's probe said it would work: say why it did not
        os.write(2, ("urdf-lint: note: worker sandbox: " + "; ".join(
            f"{k} {v}" for k, v in bad.items()) + "\n").encode("utf-8", "replace"))
    return status


def warm() -> None:
    """A worker forked ahead of its settings: import what :func:`enter` uses and find the
    runtime's folders while it waits (applies nothing, says nothing)."""
    if disabled():
        return
    if landlock_status()[0]:
        _import_landlock()
    seccomp_status()
    runtime_read_paths()


def prepare() -> None:
    """Parent side, before forking workers: warm the imports and say what is missing, once."""
    global _disabled
    _disabled = None
    if disabled():
        return
    if landlock_status()[0]:
        _import_landlock()   # imported once, shared by the forked workers
    seccomp_status()
    runtime_read_paths()
    note_missing()
