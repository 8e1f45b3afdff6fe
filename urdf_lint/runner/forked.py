"""Forked worker processes and the pipes to them, without :mod:`multiprocessing`.

A worker is ``os.fork()`` plus two pipes carrying length-prefixed messages. ``multiprocessing``
does the same through a fork context, but importing it (connection, reduction, socket,
tempfile, subprocess) costs ~22 ms before the first fork, on the critical path of every run
that starts a worker, ``urdf-lint expand`` of one small file above all. The worker needs none
of it: only ``pickle``, the plain-data encoding and the job modules.

The parent sends pickles (the child is a fork of the same interpreter and trusts its parent);
a child whose parent restricts what it reads (``allowed``: a sandboxed worker) sends plain data
(:mod:`urdf_lint.runner.wire`), never a pickle: what the parent accepts then depends neither on
how a Python release pickles an object nor on guessing which calls a pickle may make.

Where ``os.fork`` does not exist (Windows), :func:`start` falls back to ``multiprocessing``'s
default context, which offers the same ``send``/``recv``/``fileno`` and process methods.
"""
from __future__ import annotations

import gc
import os
import pickle
import signal
import struct
import sys
import time
from typing import Any, Callable, Iterator, Sequence

from urdf_lint import runner
from urdf_lint.runner import wire
from urdf_lint.runner.wire import Refused

_HEADER = struct.Struct("!Q")
_live: set[Process] = set()
Allowed = frozenset[tuple[str, str]]   # (module, class) names a message may be made of
# in a forked child: the pid of the process that forked it (read before the fork, so a parent
# that dies at once is still known by its pid: the sandbox checks it after PR_SET_PDEATHSIG)
parent_pid: int | None = None


__all__ = ["Conn", "Process", "Refused", "Wake", "active_children", "messages", "pipe",
           "start", "stop", "wait"]
MAX_MESSAGE = 1 << 30    # bytes of one message from an untrusted end


def _readable(fd: int, timeout: float) -> bool:
    import select
    p = select.poll()
    p.register(fd, select.POLLIN | select.POLLHUP | select.POLLERR)
    return bool(p.poll(max(0.0, timeout) * 1000))


class Conn:
    """One end of a duplex channel: reads from ``rfd``, writes to ``wfd``. With ``allowed``
    (``(module, name)`` pairs), it reads only plain-data messages (:mod:`~urdf_lint.runner.wire`)
    made of those classes, never a pickle (which can call any importable function while it
    is read: ``os.system``); with ``plain``, it writes such messages (the other end's)."""

    def __init__(self, rfd: int, wfd: int, allowed: Allowed | None = None,
                 plain: bool = False):
        self.rfd, self.wfd = rfd, wfd
        self.allowed = allowed
        self.plain = plain

    def fileno(self) -> int:
        return self.rfd

    @property
    def fds(self) -> tuple[int, int]:
        return self.rfd, self.wfd

    def send(self, obj: Any) -> None:
        """Write ``obj`` (a plain-data end: :class:`~urdf_lint.runner.wire.Unencodable` when
        it has no such form; nothing is written then)."""
        data = (wire.encode(obj) if self.plain
                else pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL))
        view = memoryview(_HEADER.pack(len(data)) + data)
        while view:
            view = view[os.write(self.wfd, view):]

    def _read(self, n: int, deadline: float | None = None) -> bytearray:
        buf = bytearray(n)
        view = memoryview(buf)
        got = 0
        while got < n:
            if deadline is not None and not _readable(self.rfd, deadline - time.monotonic()):
                raise Refused(f"a message not finished in time ({got} of {n} bytes)")
            k = os.readv(self.rfd, [view[got:]])
            if k == 0:
                raise EOFError("the other end closed the channel")
            got += k
        return buf

    def recv(self, timeout: float | None = None) -> Any:
        """The next message. On an end with ``allowed``, anything but a whole, readable
        message of at most ``MAX_MESSAGE`` bytes made of those classes, within ``timeout``
        seconds, is :class:`Refused`: the other end is not trusted to keep to the protocol."""
        deadline = None if timeout is None else time.monotonic() + timeout
        (n,) = _HEADER.unpack(self._read(_HEADER.size, deadline))
        if self.allowed is None:
            return pickle.loads(self._read(n))
        if n > MAX_MESSAGE:
            raise Refused(f"a message of {n} bytes")
        return wire.decode(self._read(n, deadline), self.allowed)

    def close(self) -> None:
        for fd in (self.rfd, self.wfd):
            try:
                os.close(fd)
            except OSError:
                pass
        self.rfd = self.wfd = -1


class Wake(Conn):
    """A pipe another thread writes a byte to (:meth:`set`), to end a :func:`wait` on it at
    once (a newer edit stops the language server's lint under way)."""

    def __init__(self) -> None:
        r, w = os.pipe()
        os.set_blocking(r, False)
        os.set_blocking(w, False)
        super().__init__(r, w)

    def set(self) -> None:
        try:
            os.write(self.wfd, b"x")
        except OSError:   # full (woken already) or closed
            pass

    def clear(self) -> None:
        try:
            while os.read(self.rfd, 512):
                pass
        except OSError:
            pass


def pipe(allowed: Allowed | None = None) -> tuple[Conn, Conn]:
    """Two connected ends (parent's, child's); with ``allowed``, the child's sends plain data
    and the parent's accepts only that, made of ``allowed``."""
    r1, w1 = os.pipe()   # parent -> child
    r2, w2 = os.pipe()   # child -> parent
    return Conn(r2, w1, allowed), Conn(r1, w2, plain=allowed is not None)


class Process:
    """A forked child running ``target(*args)``; the subset of ``multiprocessing.Process``
    the worker pool uses (pid, exitcode, is_alive, join, kill)."""

    def __init__(self, target: Callable[..., Any], args: Sequence[Any] = (),
                 close_in_child: Sequence[Conn] = ()) -> None:
        self.pid = 0
        self._status: int | None = None
        self._target, self._args = target, args
        self._close_in_child = close_in_child

    def start(self) -> None:
        sys.stdout.flush()
        sys.stderr.flush()
        me = os.getpid()
        # the child's garbage collector leaves what it inherits alone (the preloaded modules:
        # ~100k objects a full collection would walk, and write to, page by page); the
        # parent's collects its own objects again once the child is forked, unless it is a
        # one-shot command's (urdf_lint.runner.ONE_SHOT)
        gc.freeze()
        try:
            pid = os.fork()
        finally:
            if os.getpid() == me and not runner.ONE_SHOT:
                gc.unfreeze()
        if pid == 0:   # the child: never returns
            global parent_pid
            parent_pid = me
            code = 1
            try:
                for c in self._close_in_child:
                    c.close()
                _live.clear()
                _quiet_stdin()
                self._target(*self._args)
                code = 0
            except SystemExit as e:
                code = e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
            except BaseException:   # noqa: BLE001 - a worker's crash is shown, then it exits
                import traceback
                traceback.print_exc()
            finally:
                try:
                    sys.stdout.flush()
                    sys.stderr.flush()
                finally:
                    os._exit(code)
        self.pid = pid
        _live.add(self)

    def _reap(self, flags: int) -> bool:
        if self._status is not None:
            return True
        try:
            pid, status = os.waitpid(self.pid, flags)
        except ChildProcessError:
            self._status = 255   # reaped elsewhere: gone, cause unknown
        else:
            if pid == 0:
                return False
            self._status = os.waitstatus_to_exitcode(status)
        _live.discard(self)
        return True

    @property
    def exitcode(self) -> int | None:
        """None while running; the exit status, or ``-signal`` when a signal ended it."""
        return self._status if self.pid and self._reap(os.WNOHANG) else None

    def is_alive(self) -> bool:
        return bool(self.pid) and not self._reap(os.WNOHANG)

    def join(self, timeout: float | None = None) -> None:
        if not self.pid:
            return
        if timeout is None:
            self._reap(0)
            return
        if self._reap(os.WNOHANG):
            return
        if _ended_within(self.pid, timeout) is not None:   # (woken at its exit, or timed out)
            self._reap(os.WNOHANG)
            return
        deadline = time.monotonic() + timeout
        pause = 0.0005
        while not self._reap(os.WNOHANG) and time.monotonic() < deadline:
            time.sleep(min(pause, max(0.0, deadline - time.monotonic())))
            pause = min(pause * 2, 0.02)

    def kill(self) -> None:
        if self.pid and self._status is None:
            try:
                os.kill(self.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass


def _ended_within(pid: int, timeout: float) -> bool | None:
    """Whether child ``pid`` (not reaped) ended within ``timeout`` seconds, waited for on a
    pidfd, which wakes at its exit; None where there is no pidfd (then the caller polls)."""
    import select
    try:
        fd = os.pidfd_open(pid)
    except (AttributeError, OSError):
        return None
    try:
        p = select.poll()
        p.register(fd, select.POLLIN)
        return bool(p.poll(int(max(0.0, timeout) * 1000) + 1))
    finally:
        os.close(fd)


def _quiet_stdin() -> None:
    """The child must not read the parent's stdin: descriptor 0 becomes /dev/null."""
    from urdf_lint.core.fsbound import null_onto
    try:
        null_onto(0, write=False)
    except OSError:
        pass


def start(target: Callable[..., Any], args: Sequence[Any] = (),
          allowed: Allowed | None = None) -> tuple[Any, Any]:
    """Fork a child running ``target(conn, *args)``; returns (parent's conn, process). With
    ``allowed``, the child sends plain data and the parent's end reads only messages made of
    those classes (a child that runs untrusted code; ``frozenset()``: plain data only)."""
    if not hasattr(os, "fork"):   # pragma: no cover - Windows (no OS sandbox there either)
        import multiprocessing as mp
        mp_parent, mp_child = mp.Pipe()
        mp_proc = mp.get_context().Process(target=target, args=(mp_child, *args), daemon=True)
        mp_proc.start()
        mp_child.close()
        return mp_parent, mp_proc
    parent, child = pipe(allowed)
    proc = Process(target, (child, *args), close_in_child=(parent,))
    try:
        proc.start()
    except BaseException:
        parent.close()
        raise
    finally:
        child.close()
    return parent, proc


def messages(conn: Any) -> Iterator[Any]:
    """A child's messages from its parent, until the parent sends ``None`` or goes away."""
    while True:
        try:
            msg = conn.recv()
        except (EOFError, OSError):
            return
        if msg is None:
            return
        yield msg


def stop(conn: Any, proc: Any, wait: float) -> None:
    """Ask a child to end (a ``None`` message), give it ``wait`` seconds, then kill it; the
    channel is closed either way."""
    try:
        conn.send(None)
        proc.join(wait)
    except (OSError, ValueError):
        pass
    if proc.is_alive():
        proc.kill()
        proc.join(1)
    conn.close()


def active_children() -> list[Process]:
    """The forked children still running (reaps those that ended)."""
    return [p for p in list(_live) if p.is_alive()]


def wait(conns: Sequence[Any], timeout: float | None = None) -> list[Any]:
    """The conns with data (or end of file) to read, after at most ``timeout`` seconds."""
    import select
    if not hasattr(os, "fork"):   # pragma: no cover - Windows: multiprocessing's connections
        from multiprocessing.connection import wait as mp_wait
        return mp_wait(conns, timeout)
    by_fd = {c.fileno(): c for c in conns}
    if hasattr(select, "poll"):
        poller = select.poll()
        for fd in by_fd:
            poller.register(fd, select.POLLIN)
        ms = None if timeout is None else max(0, int(timeout * 1000 + 0.999))
        return [by_fd[fd] for fd, _ in poller.poll(ms)]
    ready, _, _ = select.select(list(by_fd), [], [], timeout)   # pragma: no cover
    return [by_fd[fd] for fd in ready]
