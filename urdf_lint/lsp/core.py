"""The language server's core: its documents, the lint of what a change reaches (latest
wins), and the diagnostics it publishes (the methods register in :mod:`.server`).

``urdf-lint server`` is a language server (LSP over stdio, on pygls) that knows the real
expansion. Diagnostics come from the same expansion, rules, policy and suppressions as
``check``, run in the same sandboxed workers with the same limits, on the unsaved buffers
(given to the workers as their jobs' overlay, :mod:`urdf_lint.core.overlay`).

**Latest wins.** Every change bumps :attr:`UrdfLintServer.generation`: a lint of an older
one stops (the jobs not started are dropped, the workers on the others are killed and
replaced: ``WorkerPool.run``'s ``stop``), and nothing it computed is published. After the
pause in typing (:data:`DEBOUNCE_S`) the files changed are linted, the edited file's own
model first (its diagnostics are published at once), the other models it reaches after, then
the models not linted yet.

**Explored variants** (docs/coverage.md) come last: once the models' own diagnostics are
published, the variants that take the branches their args leave out are linted through
``check``'s own path (:meth:`Workspace.explore`, within ``explore-budget``) and the
diagnostics published again, a finding only a variant has labelled ``(only with a:=x)``. A
change stops that lint like any other.
"""
from __future__ import annotations

import asyncio
from concurrent.futures import ThreadPoolExecutor
from typing import Callable, Iterable

from lsprotocol import types
from pygls.lsp.server import LanguageServer

from urdf_lint import __version__
from urdf_lint.core.jobs import LintJob
from urdf_lint.lsp.methods import diagnostics
from urdf_lint.lsp.services import Services
from urdf_lint.lsp.state import Workspace
from urdf_lint.lsp.text import Doc
from urdf_lint.lsp.uris import path_uri, uri_path

DEBOUNCE_S = 0.15        # after the last keystroke, before a change is linted

__all__ = ["DEBOUNCE_S", "UrdfLintServer", "path_uri", "uri_path"]


class UrdfLintServer(LanguageServer):
    def __init__(self) -> None:
        super().__init__("urdf-lint", __version__)
        self.services = Services()
        self.executor = ThreadPoolExecutor(max_workers=1)   # one lint at a time, in order
        self.published: set[str] = set()
        self.generation = 0      # bumped by every change: a lint of an older one stops
        self.dirty: dict[str, None] = {}   # files changed and not linted since (oldest first)
        self.timer: asyncio.TimerHandle | None = None   # the pause in typing under way
        self.task: asyncio.Task[None] | None = None      # the lint loop
        # called after each publish (an open preview builds its scenes from the new reports)
        self.after_publish: list[Callable[[], None]] = []

    @property
    def ws(self) -> Workspace | None:
        return self.services.ws

    @ws.setter
    def ws(self, ws: Workspace | None) -> None:
        self.services.ws = ws

    # -- documents -------------------------------------------------------------------------
    def doc(self, path: str) -> Doc:
        return self.services.doc(path)

    def set_buffer(self, uri: str) -> str:
        path = uri_path(uri)
        if self.ws is not None:
            text = self.workspace.get_text_document(uri).source
            self.ws.buffers[path] = text.encode("utf-8")
        return path

    def versions(self) -> dict[str, int | None]:
        """path -> the version of each open document."""
        out = {}
        for uri, doc in list(self.workspace.text_documents.items()):
            out[uri_path(uri)] = doc.version
        return out

    # -- linting: latest wins ------------------------------------------------------------------
    def schedule(self, path: str, delay: float, newer: bool = True) -> None:
        """``path`` changed: stop the lint under way (it read older text), and lint what the
        change reaches ``delay`` seconds from now (a newer change restarts the wait).
        ``newer=False`` (a file opened): the lint under way goes on."""
        self.dirty.pop(path, None)
        self.dirty[path] = None          # (the last changed, last: its model goes first)
        if newer:
            self.generation += 1
            if self.ws is not None:
                self.ws.interrupt()
        if self.timer is not None:
            self.timer.cancel()
        self.timer = asyncio.get_running_loop().call_later(delay, self._kick)

    def _kick(self) -> None:
        self.timer = None
        if self.task is None or self.task.done():
            self.task = asyncio.get_running_loop().create_task(self._lint_loop())

    async def _lint_loop(self) -> None:
        """Lint the files changed, then the models not linted yet, until a newer change waits
        for its pause (its timer starts the loop again) or nothing is left."""
        while self.ws is not None and self.timer is None:
            if self.dirty:
                paths = list(self.dirty)
                self.dirty.clear()
                if not await self._lint_changed(paths):   # a newer change: its text first
                    again = dict.fromkeys(p for p in paths if p not in self.dirty)
                    again.update(self.dirty)
                    self.dirty = again
                continue
            rest = self.ws.unlinted()
            if rest:
                versions = self.versions()
                files = await self._run(rest, self.generation)
                if files is None:
                    continue
                self.publish(files | set(self.ws.buffers), versions)
            if await self._explore():
                return

    async def _explore(self) -> bool:
        """Lint the explored variants not held yet and publish what they change; False when a
        change newer than the models' lint came first (nothing of it was published)."""
        ws = self.ws
        if ws is None or not ws.explores():
            return True
        gen, versions = self.generation, self.versions()
        files = await asyncio.get_running_loop().run_in_executor(
            self.executor, ws.explore, lambda: self.generation != gen)
        if files is None or self.generation != gen:
            return False
        if files:
            self.publish(files | set(ws.buffers), versions)
        return True

    async def _lint_changed(self, paths: list[str]) -> bool:
        """Lint what ``paths`` reach, the last one's own model first; False when a newer
        change stopped it (nothing of it was published then)."""
        ws = self.ws
        assert ws is not None
        gen, versions = self.generation, self.versions()
        outside = {p for p in paths if not ws.readable(p)}
        if outside:   # not linted: each gets the diagnostic saying so
            self.publish(outside, versions)
        inside = [p for p in paths if p not in outside]
        if not inside:
            return True
        jobs = _ordered(ws, inside)
        ws.forget(jobs)   # their reports are of older text: not shown until linted again
        for batch in (jobs[:1], jobs[1:]):   # the edited file's model, then the others
            files = await self._run(batch, gen)
            if files is None:
                return False
            self.publish(files | set(inside) | set(ws.buffers), versions)
        return True

    async def _run(self, jobs: list[LintJob] | None, gen: int) -> set[str] | None:
        """Lint ``jobs`` in the lint thread; None when a change newer than ``gen`` came
        first (the lint stopped, or its result is of older text)."""
        ws = self.ws
        if ws is None or self.generation != gen:
            return None
        if jobs is not None and not jobs:
            return set()
        loop = asyncio.get_running_loop()
        files = await loop.run_in_executor(self.executor, ws.lint, jobs,
                                           lambda: self.generation != gen)
        return None if self.generation != gen else files

    async def reload(self, extra: Iterable[str] = ()) -> None:
        """Read the config, the packages and the models again, then lint every model."""
        ws = self.ws
        if ws is None:
            return
        self.generation += 1
        ws.interrupt()
        gen = self.generation
        await asyncio.get_running_loop().run_in_executor(self.executor, ws.load)
        ws.start()   # (forks from the server's thread, not the lint thread)
        versions = self.versions()
        files = await self._run(None, gen)
        if files is not None:
            self.publish(files | set(extra) | set(ws.buffers), versions)
            await self._explore()

    # -- publishing ------------------------------------------------------------------------
    def publish(self, files: Iterable[str], versions: dict[str, int | None] | None = None
                ) -> None:
        ws = self.ws
        if ws is None:
            return
        versions = versions or {}
        for f in sorted(set(files) | self.published):
            diags = self.diagnostics(f)
            if not diags and f not in self.published and f not in ws.buffers:
                continue   # (an open file always gets its diagnostics, none included)
            self.text_document_publish_diagnostics(types.PublishDiagnosticsParams(
                uri=path_uri(f), diagnostics=diags, version=versions.get(f)))
            (self.published.add if diags else self.published.discard)(f)
        for hook in list(self.after_publish):
            hook()

    def diagnostics(self, path: str) -> list[types.Diagnostic]:
        return diagnostics.handle(self.services, path)


def _ordered(ws: Workspace, paths: list[str]) -> list[LintJob]:
    """The jobs the changes to ``paths`` reach: first a model of the file changed last (the
    model it is the entry of, else the first model that reaches it), then the other models,
    then the files that were no model when last linted (a macro library's own job)."""
    from urdf_lint.core.jobs import Status
    from urdf_lint.core.jobs import job_key

    def rank(job: LintJob, path: str) -> int:
        status = ws.last_status.get(job_key(job))
        model = status is None or status in (Status.MODEL, Status.FRAGMENT)
        return 2 if not model else 0 if job.entry == path else 1
    seen: dict[tuple[object, ...], LintJob] = {}
    for p in reversed(paths):
        for j in sorted(ws.affected(p), key=lambda j: rank(j, p)):
            seen.setdefault(job_key(j), j)
    return list(seen.values())
