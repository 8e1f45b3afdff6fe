"""The preview's HTTP server: 127.0.0.1, a random port, GET and HEAD only.

Every request must carry the session's token as the first path segment (``/<token>/...``: the
page's relative URLs, meshes' textures included, keep it), a ``Host`` naming this server by
127.0.0.1 or localhost and this port, and no ``Origin`` but this server's (DNS rebinding, a
page of another site). It answers only with the page's own files, the scene as JSON, and the
mesh and texture files the robot references (``FileTable``), read through the file boundary
(``core.fsbound``) below the package roots. See SECURITY.md, "The preview"."""
from __future__ import annotations

import hmac
import html
import json
import os
import secrets
import threading
import urllib.parse
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

from urdf_lint.core import fsbound
from urdf_lint.preview.session import Session

STATIC = os.path.join(os.path.dirname(os.path.abspath(__file__)), "static")
# the page's own files, by the name it asks for (nothing else of the package is served)
STATIC_FILES = {
    "viewer.js": "viewer.js", "viewer.css": "viewer.css",
    "vendor.js": "vendor/vendor.js",
}
TYPES = {".js": "text/javascript", ".css": "text/css", ".html": "text/html; charset=utf-8",
         ".json": "application/json", ".stl": "model/stl", ".dae": "model/vnd.collada+xml",
         ".obj": "text/plain", ".mtl": "text/plain"}
CSP = ("default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self' data: blob:; "
       "connect-src 'self' data: blob:; base-uri 'none'; form-action 'none'; "
       "frame-ancestors 'none'")
LONG_POLL_S = 20.0
MAX_POST_BYTES = 4096    # a click: {"version", "variant", "element" | "finding"}
# the review page's (a <meta>: no frame-ancestors there): its own scripts and the meshes it
# inlines, nothing from any other place, a URL a pull request's DAE names included
REVIEW_CSP = ("default-src 'none'; script-src 'self'; style-src 'self'; img-src data: blob:; "
              "connect-src data: blob:; base-uri 'none'; form-action 'none'")
# a repository's files go out as bytes of a known mesh or image type, else opaque, and in a
# sandbox: a texture named x.html or x.js, opened by the user, runs nothing at this origin
FILE_TYPES = {".stl": "model/stl", ".dae": "model/vnd.collada+xml", ".obj": "text/plain",
              ".mtl": "text/plain", ".png": "image/png", ".jpg": "image/jpeg",
              ".jpeg": "image/jpeg", ".gif": "image/gif", ".bmp": "image/bmp",
              ".tga": "image/x-tga", ".webp": "image/webp"}
FILE_CSP = "default-src 'none'; sandbox; frame-ancestors 'none'"
# a connection that has not sent its whole request by then is closed (a slow client holds
# its thread no longer); replies are on loopback, a 64 MB mesh leaves in well under a second
IDLE_TIMEOUT_S = 10


def page_html(title: str, scripts: tuple[str, ...] = ("static/vendor.js", "static/viewer.js"),
              css: str = "static/viewer.css", csp: str = "") -> str:
    """The page; ``csp``: its policy in a <meta> too (the review page, opened from file://, has
    no server to send the header)."""
    from urdf_lint.core.escape import escape_html as html_text
    tags = "\n".join(f'<script src="{s}"></script>' for s in scripts)
    meta = f'\n<meta http-equiv="Content-Security-Policy" content="{html.escape(csp)}">' \
        if csp else ""
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="referrer" content="no-referrer">{meta}
<title>{html_text(title)}</title>
<link rel="stylesheet" href="{css}">
</head><body>
<div id="panel"><h1 id="title">{html_text(title)}</h1><div id="controls"></div>
<div id="info"></div><div id="findings"></div></div>
<div id="view"></div>
{tags}
</body></html>
"""


class PreviewServer(ThreadingHTTPServer):
    daemon_threads = True
    allow_reuse_address = False

    def __init__(self, session: Session, host: str = "127.0.0.1", port: int = 0) -> None:
        self.session = session
        self.token = secrets.token_urlsafe(24)
        super().__init__((host, port), Handler)
        self.port = self.server_address[1]
        self.hosts = {f"127.0.0.1:{self.port}", f"localhost:{self.port}"}
        self.origins = {f"http://{h}" for h in self.hosts}

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}/{self.token}/"

    def start(self) -> threading.Thread:
        t = threading.Thread(target=self.serve_forever, name="urdf-lint-preview", daemon=True)
        t.start()
        return t


class Handler(BaseHTTPRequestHandler):
    server: PreviewServer
    server_version = "urdf-lint-preview"
    timeout = IDLE_TIMEOUT_S
    sys_version = ""

    def log_message(self, format: str, *args: Any) -> None:   # noqa: A002
        pass   # (quiet: the terminal shows the URL and the reloads)

    # -- read-only (but for the one click a page opened from the editor sends) -------------
    def _refuse_method(self) -> None:
        self._send(405, b"read-only\n", "text/plain", {"Allow": "GET, HEAD"})

    do_PUT = do_DELETE = do_PATCH = do_OPTIONS = _refuse_method

    def do_POST(self) -> None:
        """``POST /<token>/jump`` (only when the language server opened the preview): the page's
        click, a small JSON object, shows that element's line in the editor
        (``Session.jump``). Token, Host and Origin as every request; the Origin must be sent
        (a browser's POST always sends it) and be this server's; the body is JSON."""
        self._head = False
        path = urllib.parse.urlsplit(self.path).path
        if path.split("/", 2)[2:] != ["jump"] or self.server.session.editor is None:
            self._refuse_method()
            return
        why = self._refused()
        if not why and self.headers.get("Origin") not in self.server.origins:
            why = "origin"
        if why:
            self._send(403 if why != "token" else 404,
                       b"not found\n" if why == "token" else f"refused: {why}\n".encode(),
                       "text/plain")
            return
        self.close_connection = True   # (the body is not read when refused below)
        if self.headers.get_content_type() != "application/json":
            self._send(415, b"expected application/json\n", "text/plain")
            return
        n = _int(self.headers.get("Content-Length", ""))
        if not 0 <= n <= MAX_POST_BYTES:
            self._send(413, b"too large\n", "text/plain")
            return
        try:
            asked = json.loads(self.rfile.read(n))
        except ValueError:
            self._send(400, b"not JSON\n", "text/plain")
            return
        code, what = self.server.session.jump(asked)
        self._send(code, json.dumps({"result": what}).encode(), TYPES[".json"])

    def send_error(self, code: int, message: str | None = None,
                   explain: str | None = None) -> None:
        """http.server's own errors (an unknown method, a malformed request line, a slow
        client's timeout) as plain text with this server's headers: never its HTML page, which
        echoes the request and goes out without CSP, nosniff or framing headers."""
        self.close_connection = True
        self._send(code, f"{code}\n".encode(), "text/plain")

    def do_HEAD(self) -> None:
        self._serve(head=True)

    def do_GET(self) -> None:
        self._serve(head=False)

    # -- the checks, then the routes ------------------------------------------------------
    def _serve(self, head: bool) -> None:
        self._head = head
        why = self._refused()
        if why:
            self._send(403 if why != "token" else 404,
                       b"not found\n" if why == "token" else f"refused: {why}\n".encode(),
                       "text/plain")
            return
        url = urllib.parse.urlsplit(self.path)
        rest = url.path.split("/", 2)[2] if url.path.count("/") >= 2 else ""
        query = urllib.parse.parse_qs(url.query)
        try:
            self._route(urllib.parse.unquote(rest), query)
        except BrokenPipeError:
            pass

    def _refused(self) -> str:
        """Why this request is refused ("" if it is not): a wrong Host, a foreign Origin (or
        Sec-Fetch-Site), a missing or wrong token."""
        s = self.server
        if self.headers.get("Host", "") not in s.hosts:
            return "host"
        origin = self.headers.get("Origin")
        if origin is not None and origin not in s.origins:
            return "origin"
        if self.headers.get("Sec-Fetch-Site", "same-origin") not in ("same-origin", "none"):
            return "origin"
        path = urllib.parse.urlsplit(self.path).path
        parts = path.split("/", 2)
        given = parts[1] if len(parts) > 1 else ""
        if not hmac.compare_digest(given.encode(), s.token.encode()):
            return "token"
        return ""

    def _route(self, rest: str, query: dict[str, list[str]]) -> None:
        if rest in ("", "index.html"):
            body = page_html("urdf-lint preview").encode()
            self._send(200, body, TYPES[".html"])
        elif rest.startswith("static/") and rest[7:] in STATIC_FILES:
            self._static(STATIC_FILES[rest[7:]])
        elif rest == "state.json":
            self._state()
        elif rest == "version":
            seen = _int(query.get("v", ["-1"])[0])
            v = self.server.session.wait_version(seen, LONG_POLL_S if seen >= 0 else 0)
            self._send(200, json.dumps({"version": v}).encode(), TYPES[".json"])
        elif rest.startswith("m/"):
            self._file(rest[2:])
        else:
            self._send(404, b"not found\n", "text/plain")

    def _static(self, rel: str) -> None:
        data = fsbound.read_bytes(os.path.join(STATIC, rel), [STATIC], max_bytes=8 << 20)
        self._send(200, data, TYPES[os.path.splitext(rel)[1]])

    def _state(self) -> None:
        s = self.server.session
        with s.changed:
            scenes, version, internal = list(s.scenes), s.version, list(s.internal)
            scene_version = s.scene_version
        body = {"version": version, "scene_version": scene_version, "internal": internal,
                "highlight": s.highlight,
                "editor": s.editor is not None,
                "variants": [sc.to_json() for sc in scenes]}
        self._send(200, json.dumps(body).encode(), TYPES[".json"])

    def _file(self, rest: str) -> None:
        """``m/<index>/<name>``: a file of the table, or a texture its mesh names."""
        i, _, name = rest.partition("/")
        table = self.server.session.table
        found = table.lookup(_int(i), name) if i.isdigit() else None
        if found is None:
            self._send(404, b"not found\n", "text/plain")
            return
        if isinstance(found, str):
            path, refused = found, ""
        else:
            path, refused = found.path, found.refused
        if refused:
            self._send(413, refused.encode() + b"\n", "text/plain")
            return
        roots = self.server.session.resolver.read_paths()
        try:
            data = fsbound.read_bytes(path, roots, max_bytes=table.max_bytes)
        except OSError as e:
            self._send(404, f"cannot read: {e.strerror or e}\n".encode(), "text/plain")
            return
        kind = FILE_TYPES.get(os.path.splitext(path)[1].lower(), "application/octet-stream")
        self._send(200, data, kind, csp=FILE_CSP)

    def _send(self, code: int, body: bytes, kind: str, extra: dict[str, str] | None = None,
              csp: str = CSP) -> None:
        self.send_response(code)
        self.send_header("Content-Type", kind)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "no-store")
        self.send_header("X-Content-Type-Options", "nosniff")
        self.send_header("Referrer-Policy", "no-referrer")
        self.send_header("Cross-Origin-Resource-Policy", "same-origin")
        self.send_header("X-Frame-Options", "DENY")
        self.send_header("Content-Security-Policy", csp)
        for k, v in (extra or {}).items():
            self.send_header(k, v)
        self.end_headers()
        if not getattr(self, "_head", False):
            self.wfile.write(body)


def _int(s: str) -> int:
    try:
        return int(s)
    except ValueError:
        return -1
