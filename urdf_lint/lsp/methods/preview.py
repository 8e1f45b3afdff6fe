"""``urdf-lint.preview`` (workspace/executeCommand): the 3D preview of the current file, the
link or joint under the cursor highlighted.

Arguments: ``[uri, line?, character?]`` (0-based, as LSP positions). The preview runs as its own
``urdf-lint preview FILE`` process (its own sandboxed workers and server; SECURITY.md, "The
preview"), one per file, kept until the language server exits; the result is
``{"url": ..., "highlight": "link:NAME" | ""}`` for the client to open."""
from __future__ import annotations

import atexit
import os
import re
import select
import subprocess
import sys
import time
from typing import Any
from urllib.parse import quote

from urdf_lint.lsp.methods import Refused
from urdf_lint.lsp.services import Services
from urdf_lint.lsp.uris import uri_path

COMMAND = "urdf-lint.preview"
START_TIMEOUT_S = 120.0
_running: dict[str, tuple[subprocess.Popen[str], str]] = {}

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


def _start(path: str) -> tuple[subprocess.Popen[str], str]:
    proc = subprocess.Popen([sys.executable, "-m", "urdf_lint", "preview", path],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                            stdin=subprocess.DEVNULL, cwd=os.path.dirname(path) or None,
                            text=True)
    assert proc.stdout is not None
    end = time.monotonic() + START_TIMEOUT_S
    while time.monotonic() < end:
        ready, _, _ = select.select([proc.stdout], [], [], 0.5)
        if ready:
            line = proc.stdout.readline()
            if not line:
                break
            if line.startswith("http://127.0.0.1:"):
                return proc, line.strip()
        elif proc.poll() is not None:
            break
    proc.kill()
    proc.wait()
    raise RuntimeError(f"the preview of {path} did not start")


def handle(sv: Services, args: list[Any]) -> dict[str, str]:
    """Start (or reuse) the preview of the file ``args[0]`` and return its URL."""
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
    if running is None or running[0].poll() is not None:
        if not _running:
            atexit.register(stop_all)   # (once: stop_all empties the table)
        running = _running[path] = _start(path)
    url = running[1] + (f"#highlight={quote(highlight)}" if highlight else "")
    return {"url": url, "highlight": highlight}


def stop_all() -> None:
    """End every preview this server started (at shutdown)."""
    for proc, _ in _running.values():
        if proc.poll() is None:
            proc.terminate()
    for proc, _ in _running.values():
        try:
            proc.wait(5)
        except subprocess.TimeoutExpired:
            proc.kill()
    _running.clear()
