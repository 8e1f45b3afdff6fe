"""Sandboxed workers kept alive between edits (the language server's lint pool).

``pool.run_jobs`` forks a pool per run; an editor re-lints after every pause in typing, and
a fork and sandbox per change would cost more than the lint. This pool keeps its workers
(forked, limited and sandboxed exactly like ``check``'s: ``urdf_lint.runner.pool._Worker``) until the
settings change, and enforces the same time limit: a model that hangs costs its worker
(killed and replaced), never the editor.
"""
from __future__ import annotations

import time

from urdf_lint.runner import forked
from urdf_lint.core.jobs import LintJob, LintSettings, ModelReport
from urdf_lint.run.worker import LINT, limit_result as _limit_result, preload
from urdf_lint.runner.pool import _Worker


class Pool:
    def __init__(self, settings: LintSettings, size: int = 2):
        """``size`` workers, each limited to ``settings.timeout`` per job and
        ``settings.memory_mb``."""
        self.settings, self.size = settings, max(1, size)
        self.timeout = settings.timeout
        self.workers: list[_Worker] = []
        self.closing = False   # set from another thread: hand out no further job

    def _spawn(self) -> _Worker:
        w = _Worker(LINT, self.settings)
        self.workers.append(w)
        return w

    def start(self) -> None:
        """Fork the workers now (they share what the parent imported)."""
        from urdf_lint.runner.sandbox import prepare
        prepare()
        preload()
        while len(self.workers) < self.size:
            self._spawn()

    def run(self, jobs: list[LintJob]) -> list[tuple[LintJob, ModelReport]]:
        """(job, report) for every job, in completion order."""
        if not self.workers:
            self.start()
        todo = list(jobs)
        out: list = []
        busy: dict = {}
        while (todo and not self.closing) or busy:
            for w in list(self.workers):
                if todo and w.conn not in busy and not self.closing:
                    w.job, w.started = todo.pop(0), time.monotonic()
                    try:
                        w.conn.send(w.job)
                    except (OSError, ValueError):
                        todo.insert(0, w.job)
                        self._drop(w)
                        self._spawn()
                        continue
                    busy[w.conn] = w
            if not busy:
                continue
            deadline = min(w.started + self.timeout for w in busy.values())
            for conn in forked.wait(list(busy), max(0.0, deadline - time.monotonic())):
                w = busy.pop(conn)
                try:
                    res = conn.recv(timeout=max(1.0, w.started + self.timeout - time.monotonic()))
                    if not isinstance(res, ModelReport):
                        raise forked.Refused(type(res).__name__)
                except (forked.Refused, EOFError, OSError) as e:
                    res = _limit_result(w.job, f"the worker linting this model stopped ({e})")
                    self._drop(w)
                    self._spawn()
                out.append((w.job, res))
            now = time.monotonic()
            for conn, w in list(busy.items()):
                if now - w.started >= self.timeout:
                    busy.pop(conn)
                    out.append((w.job, _limit_result(
                        w.job, f"expansion/lint did not finish within the time limit "
                        f"({self.timeout:g} s); a huge expression, loop or recursion?")))
                    self._drop(w)
                    self._spawn()
        return out

    def _drop(self, w: _Worker) -> None:
        if w in self.workers:
            self.workers.remove(w)
        w.kill()

    def close(self) -> None:
        self.closing = True
        for w in self.workers:
            forked.stop(w.conn, w.proc, 0.5)
        self.workers = []
