"""``urdf-lint.preview`` (workspace/executeCommand): the 3D preview of the current file, the
link or joint under the cursor highlighted.

Arguments: ``[uri, line?, character?]`` (0-based, as LSP positions). The preview's server
(``urdf_lint.preview.server``: 127.0.0.1, token, Host and Origin checks; SECURITY.md, "The
preview") runs in the language server's process, one per file, kept until the server exits. Its
scenes are the language server's own reports: the models the diagnostics come from, linted by
its sandboxed pool with the unsaved buffers as overlay, so an edit reaches the open page once
it is linted (no second expansion). A click on a link, joint or marker in the page shows that
element's xacro line in the editor (``window/showDocument``). The result is ``{"url": ...,
"highlight": "link:NAME" | ""}`` for the client to open; the same command on an open preview
moves its highlight."""
from __future__ import annotations

import asyncio
import operator
import re
import threading
import time
from typing import Any
from urllib.parse import quote

from lsprotocol import types

from urdf_lint.core.jobs import ModelReport, Status
from urdf_lint.lsp.methods import Refused
from urdf_lint.lsp.services import Services
from urdf_lint.lsp.uris import path_uri, uri_path
from urdf_lint.preview.session import Session

COMMAND = "urdf-lint.preview"
# moves the highlight of a preview already open to the element at [uri, line, character]
# (a client sends it as the cursor moves; it starts nothing)
HIGHLIGHT_COMMAND = "urdf-lint.previewHighlight"
START_TIMEOUT_S = 120.0
SHOW_TIMEOUT_S = 5.0
_running: dict[str, tuple[Any, EditorSession]] = {}   # path -> (PreviewServer, its session)

# an opening <link ...> or <joint ...> tag and its literal name
_OPEN = re.compile(r"<(link|joint)\b[^>]*?\bname\s*=\s*([\"'])([^\"'$]*)\2", re.S)


def element_at(text: str, line: int, character: int) -> str:
    """"link:NAME" or "joint:NAME" of the innermost <link>/<joint> whose opening tag is at or
    before the position and not closed before it (a name built by ``${...}``: "")."""
    lines = text.split("\n")
    upto = "\n".join(lines[:line]) + ("\n" if line else "") + \
        (lines[line][:character] if line < len(lines) else "")
    # the rest of the tag the cursor may be in (its name may follow the cursor)
    end = text.find(">", len(upto))
    head = text[:end + 1] if end >= 0 else text
    best = ""
    for m in _OPEN.finditer(head):
        if m.start() > len(upto):
            break
        kind, name = m.group(1), m.group(3)
        tag_end = head.find(">", m.start())
        self_closing = head[tag_end - 1] == "/" and tag_end < len(upto)
        closed = self_closing or re.search(rf"</{kind}\s*>", upto[m.start():])
        if not closed:
            best = f"{kind}:{name}"
    return best


class EditorSession(Session):
    """The preview of one file opened from the language server: the scenes of the models that
    file is the entry of (else of those that read it), built from the server's reports. Rebuilt
    in its own thread when the server has linted (``refresh``, after each publish)."""

    def __init__(self, sv: Services, path: str) -> None:
        from urdf_lint.preview.scene import DEFAULT_MAX_MESH_MB
        ws = sv.ws
        assert ws is not None
        super().__init__([path], ws.cfg, ws.resolver, DEFAULT_MAX_MESH_MB)
        self.sv, self.path = sv, path
        self.shown: list[ModelReport] = []     # the reports the scenes were built from
        self.findings_shown: Any = None
        self.loaded = threading.Event()       # the first scenes are there
        self._wanted = threading.Event()
        threading.Thread(target=self._loop, name="urdf-lint-preview-scenes",
                         daemon=True).start()

    def refresh(self) -> None:
        """The server has linted: build the scenes again if their reports changed."""
        self._wanted.set()

    def _loop(self) -> None:
        while not self._stop.is_set():
            self._wanted.wait()
            self._wanted.clear()
            if self._stop.is_set():
                return
            try:
                self.load()
            except Exception:   # noqa: BLE001 (the page keeps the last good scenes)
                pass

    def load(self) -> None:
        ws = self.sv.ws
        if ws is None:
            return
        reports, findings = _reports(ws, self.path), ws.findings
        if reports is None or (len(reports) == len(self.shown) and findings is
                               self.findings_shown and all(map(operator.is_, reports,
                                                               self.shown))):
            return   # (being linted again: the page keeps what it shows)
        self.cfg, self.resolver = ws.cfg, ws.resolver
        scenes = [self._scene(ws, r, findings) for r in reports]
        self.shown, self.findings_shown = reports, findings
        self.publish(scenes, [])
        self.loaded.set()


    def _scene(self, ws: Any, r: ModelReport, findings: list[Any]) -> Any:
        """The scene of ``r``; of the last version that expanded when ``r`` did not (a buffer
        mid-edit: the page keeps the robot, and says why it is not the latest)."""
        from urdf_lint.preview.scene import build_scene
        good = None if r.kept_model is not None else \
            ws.last_good.get((r.entry, tuple(sorted(r.args.items()))))
        scene = build_scene(good or r, findings, ws.resolver, self.table,
                            self._mesh_base(r.entry))
        if good is not None:
            errors = [p.message for p in r.problems if p.severity in ("", "error")]
            scene.notes.insert(0, "the text in the editor does not expand now ("
                               f"{errors[0] if errors else 'no robot'}): the last version "
                               "that expanded is shown")
        return scene


def _reports(ws: Any, path: str) -> list[ModelReport] | None:
    """The reports the preview of ``path`` shows: of the jobs whose entry it is (every
    configured variant), else of the models that read it; None while one of them is not linted
    (yet, or again after an edit)."""
    from urdf_lint.core.jobs import job_key
    own = [ws.reports.get(job_key(j)) for j in ws.jobs if j.entry == path]
    if any(r is None for r in own):
        return None
    if any(r.status is not Status.FRAGMENT and r.status is not Status.LIBRARY for r in own):
        return own
    readers = [r for r in ws.models() if path in r.deps]
    if not readers and ws.unlinted():
        return None
    return readers or own


def _editor(ls: Any, loop: asyncio.AbstractEventLoop) -> Any:
    """``editor(file, line, col)`` for the session: ``window/showDocument`` of that start tag,
    sent from the server's loop (the page's click arrives on the preview's thread)."""
    def show(file: str, line: int, col: int) -> str:
        window = getattr(ls.client_capabilities, "window", None)
        support = getattr(getattr(window, "show_document", None), "support", False)
        if not support:
            return "the editor does not support window/showDocument"
        ws = ls.services.ws
        if ws is None or not ws.readable(file):
            return "outside the run's roots: not shown"
        params = types.ShowDocumentParams(
            uri=path_uri(file), external=False, take_focus=True,
            selection=ls.services.doc(file).element_range(line, col))
        done = asyncio.run_coroutine_threadsafe(ls.window_show_document_async(params), loop)
        try:
            result = done.result(SHOW_TIMEOUT_S)
        except Exception:   # noqa: BLE001 (no answer in time: it was asked)
            return ""
        return "" if getattr(result, "success", True) else "the editor did not show it"
    return show


def handle(sv: Services, args: list[Any], ls: Any = None) -> dict[str, str]:
    """Start (or reuse) the preview of the file ``args[0]``, highlight the element at the
    position and return its URL."""
    if not args:
        raise Refused(f"{COMMAND} needs the file's URI")
    path = uri_path(str(args[0]))
    if sv.ws is None or not sv.ws.readable(path):
        # (what the server may read: the preview lints and serves what it previews)
        raise Refused(f"{COMMAND}: the file is outside the workspace's package roots; "
                      "it is not previewed")
    line = int(args[1]) if len(args) > 1 else 0
    character = int(args[2]) if len(args) > 2 else 0
    highlight = element_at(sv.doc(path).text, line, character)
    running = _running.get(path)
    if running is None:
        from urdf_lint.preview.server import PreviewServer
        session = EditorSession(sv, path)
        if ls is not None:
            session.editor = _editor(ls, asyncio.get_running_loop())
            ls.after_publish.append(session.refresh)
        server = PreviewServer(session)
        server.start()
        running = _running[path] = (server, session)
        session.refresh()
    running[1].set_highlight(highlight)
    url = running[0].url + (f"#highlight={quote(highlight)}" if highlight else "")
    return {"url": url, "highlight": highlight}


def highlight(sv: Services, args: list[Any]) -> dict[str, str]:
    """``urdf-lint.previewHighlight``: the open previews of ``args[0]`` (the file's own, and
    those of the models that read it) highlight the element at the position; {"highlight":
    ...} ("" and nothing done when no preview shows the file)."""
    if not args:
        raise Refused(f"{HIGHLIGHT_COMMAND} needs the file's URI")
    path = uri_path(str(args[0]))
    shown = [s for _, s in list(_running.values())
             if s.path == path or any(path in sc.deps for sc in s.scenes)]
    if not shown or sv.ws is None or not sv.ws.readable(path):
        return {"highlight": ""}
    line = int(args[1]) if len(args) > 1 else 0
    character = int(args[2]) if len(args) > 2 else 0
    name = element_at(sv.doc(path).text, line, character)
    for s in shown:
        s.set_highlight(name)
    return {"highlight": name}


async def command(ls: Any, *args: Any) -> dict[str, str]:
    """The command as the server runs it: the preview started, and its URL answered once it
    shows the file's models (or after ``START_TIMEOUT_S``: the page shows them when linted)."""
    got = handle(ls.services, list(args), ls)
    session = _running[uri_path(str(args[0]))][1]
    end = time.monotonic() + START_TIMEOUT_S
    while not session.loaded.is_set() and time.monotonic() < end:
        await asyncio.sleep(0.05)
    return got


def stop_all() -> None:
    """End every preview this server started (at shutdown)."""
    for server, session in _running.values():
        session.stop()
        session.refresh()   # (its thread sees the stop)
        server.shutdown()
        server.server_close()
    _running.clear()
