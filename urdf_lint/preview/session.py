"""A preview session: the model(s) of one path linted as ``check`` lints them (``run_check``:
sandboxed workers, the configured variants), turned into Scenes, and linted again when a file
the expansion read changes on disk."""
from __future__ import annotations

import os
import threading
from typing import Any, Callable

from urdf_lint.preview.scene import FileTable, Scene, build_scene


def _stamp(path: str) -> tuple[int, int] | None:
    try:
        st = os.stat(path)
    except OSError:
        return None
    return (st.st_mtime_ns, st.st_size)


class Session:
    """The scenes of one path and a version number that grows with each reload."""

    def __init__(self, paths: list[str], cfg: Any, resolver: Any, max_mesh_mb: int,
                 jobs_n: int | None = None) -> None:
        self.paths, self.cfg, self.resolver = list(paths), cfg, resolver
        self.jobs_n = jobs_n
        self.max_bytes = max_mesh_mb << 20
        self.table = FileTable(max_bytes=self.max_bytes)
        self.scenes: list[Scene] = []
        self.internal: list[str] = []
        self.version = 0
        self.stamps: dict[str, tuple[int, int] | None] = {}
        self.changed = threading.Condition()
        self._stop = threading.Event()

    def load(self) -> None:
        """Lint the path(s) again and replace the scenes (the file table only grows: a page
        still showing the last version may ask for its meshes)."""
        from urdf_lint.run.pipeline import RunRequest, run_check
        result = run_check(RunRequest(self.paths, self.cfg, self.resolver,
                                      jobs_n=self.jobs_n or 1, keep_models=True))
        scenes = [build_scene(m, result.findings, self.resolver, self.table,
                              self._mesh_base(m.entry)) for m in result.models]
        deps = sorted({d for s in scenes for d in s.deps} | set(_files(self.paths)))
        with self.changed:
            self.scenes = scenes
            self.internal = list(result.internal)
            self.stamps = {d: _stamp(d) for d in deps}
            self.version += 1
            self.changed.notify_all()

    def _mesh_base(self, entry: str) -> str | None:
        for spec in getattr(self.cfg, "models", None) or []:
            if spec.path == entry and spec.mesh_base:
                return str(spec.mesh_base)
        return None

    def stale(self) -> bool:
        """Has a file the last expansion read changed (or appeared, or gone) since?"""
        return any(_stamp(d) != s for d, s in list(self.stamps.items()))

    def wait_version(self, seen: int, timeout: float) -> int:
        """The version once it differs from ``seen`` (or after ``timeout`` seconds)."""
        with self.changed:
            self.changed.wait_for(lambda: self.version != seen or self._stop.is_set(), timeout)
            return self.version

    def watch(self, interval: float = 0.3,
              on_error: Callable[[BaseException], None] | None = None) -> threading.Thread:
        """Reload whenever a file the model read is saved (polled: no inotify dependency)."""
        def loop() -> None:
            while not self._stop.wait(interval):
                if self.stale():
                    try:
                        self.load()
                    except Exception as e:   # noqa: BLE001  (the page keeps the last good one)
                        if on_error is not None:
                            on_error(e)
        t = threading.Thread(target=loop, name="urdf-lint-preview-watch", daemon=True)
        t.start()
        return t

    def stop(self) -> None:
        self._stop.set()
        with self.changed:
            self.changed.notify_all()


def _files(paths: list[str]) -> list[str]:
    return [os.path.abspath(p) for p in paths if os.path.isfile(p)]
