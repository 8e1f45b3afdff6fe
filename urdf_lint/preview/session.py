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
        self.scene_version = 0     # the version of the last scenes (a highlight bumps version only)
        self.stamps: dict[str, tuple[int, int] | None] = {}
        self.changed = threading.Condition()
        self._stop = threading.Event()
        # the editor the page's clicks jump (set by the language server: ``editor(file, line,
        # col)`` shows that line, returns "" or why not); None: the page only shows the line
        self.editor: Callable[[str, int, int], str] | None = None
        self.highlight = ""     # "link:NAME" | "joint:NAME": tinted on the page

    def load(self) -> None:
        """Lint the path(s) again and replace the scenes (the file table only grows: a page
        still showing the last version may ask for its meshes)."""
        from urdf_lint.run.pipeline import RunRequest, run_check
        result = run_check(RunRequest(self.paths, self.cfg, self.resolver,
                                      jobs_n=self.jobs_n or 1, keep_models=True))
        scenes = [build_scene(m, result.findings, self.resolver, self.table,
                              self._mesh_base(m.entry)) for m in result.models]
        self.publish(scenes, list(result.internal))

    def publish(self, scenes: list[Scene], internal: list[str]) -> None:
        """Show ``scenes`` from now on (a new version: open pages fetch them)."""
        deps = sorted({d for s in scenes for d in s.deps} | set(_files(self.paths)))
        with self.changed:
            self.scenes = scenes
            self.internal = internal
            self.stamps = {d: _stamp(d) for d in deps}
            self.version += 1
            self.scene_version = self.version
            self.changed.notify_all()

    def set_highlight(self, highlight: str) -> None:
        with self.changed:
            if highlight != self.highlight:
                self.highlight = highlight
                self.version += 1
                self.changed.notify_all()

    def jump(self, asked: Any) -> tuple[int, str]:
        """The page's click: ``{"version", "variant", "element": "link:NAME"}`` or ``{...,
        "finding": i}`` (``version``: the scenes' ``scene_version``) shows that element's (or
        finding's) xacro line in the editor, found here from the scene (the page names no
        file). (HTTP status, what happened)."""
        if self.editor is None:
            return 404, "no editor: this preview was not opened from the language server"
        if not isinstance(asked, dict):
            return 400, "expected a JSON object"
        with self.changed:
            scenes, version = list(self.scenes), self.scene_version
        variant = asked.get("variant")
        if not isinstance(variant, int) or not 0 <= variant < len(scenes):
            return 400, "no such variant"
        scene = scenes[variant]
        element, finding = asked.get("element"), asked.get("finding")
        if isinstance(element, str) and element in scene.sources:
            file, line, col = scene.sources[element]
        elif isinstance(finding, int) and not isinstance(finding, bool):
            if asked.get("version") != version:
                return 409, "the scene changed since: reload"
            if not 0 <= finding < len(scene.finding_sources):
                return 400, "no such finding"
            file, line, col = scene.finding_sources[finding]
        else:
            return 400, "no such element"
        # (a source map names only files the expansion read; still, never outside the roots)
        if self.resolver is None or not self.resolver.is_inside(file):
            return 403, "outside the run's roots: not shown"
        why = self.editor(file, line, col)
        return (409, why) if why else (200, "shown")

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
