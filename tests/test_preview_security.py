"""A red-team pass on `urdf-lint preview` and the review page of `urdf-lint diff --html`
(SECURITY.md, "The preview"): what an attacker controlling the repository, or a web page open
in the user's browser, could try that tests/test_preview.py does not already cover. Plain HTTP
(the review page's CSP in a browser: tests/test_preview_browser.py)."""
from __future__ import annotations

import socket
import time

from support.preview_robot import get, make_robot, serve

OBJ_LINK = ('<link name="shell"><visual><geometry><mesh '
            'filename="package://arm_description/meshes/shell.obj"/></geometry></visual></link>')


def _obj_robot(tmp_path, mtllib: str):
    entry = make_robot(tmp_path, OBJ_LINK)
    pkg = entry.parent.parent
    (pkg / "meshes" / "shell.obj").write_text(
        f"mtllib {mtllib}\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    return entry, pkg


def test_an_mtl_outside_the_package_roots_is_never_read(tmp_path):
    """An OBJ's ``mtllib`` climbing out of the roots: the MTL is not read, so nothing it names
    (here a file inside the roots) becomes servable through it."""
    entry, pkg = _obj_robot(tmp_path, "../../outside.mtl")
    (pkg / "meshes" / "inner.png").write_bytes(b"\x89PNG inner")
    (tmp_path / "outside.mtl").write_text(
        f"newmtl a\nmap_Kd {pkg / 'meshes' / 'inner.png'}\n")
    with serve(entry) as (server, session):
        obj = next(f for f in session.table.files if f.path.endswith("shell.obj"))
        assert obj.textures == {}, obj.textures
        i = session.table.files.index(obj)
        for name in ("inner.png", "arm_description/meshes/inner.png", "../outside.mtl",
                     "_/_/outside.mtl", "outside.mtl"):
            assert get(server, f"/{server.token}/m/{i}/{name}")[0] == 404, name


def test_an_mtl_inside_the_roots_still_gives_its_textures(tmp_path):
    entry, pkg = _obj_robot(tmp_path, "shell.mtl")
    (pkg / "meshes" / "skin.png").write_bytes(b"\x89PNG skin")
    (pkg / "meshes" / "shell.mtl").write_text("newmtl a\nmap_Kd skin.png\n")
    with serve(entry) as (server, session):
        obj = next(f for f in session.table.files if f.path.endswith("shell.obj"))
        i = session.table.files.index(obj)
        assert get(server, f"/{server.token}/m/{i}/skin.png") == (200, b"\x89PNG skin")
        status, _ = get(server, f"/{server.token}/m/{i}/shell.mtl")
        assert status == 200


def test_a_repository_file_is_never_served_as_a_page_or_a_script(tmp_path):
    """A texture named ``*.html``, ``*.js`` or ``*.svg`` (an MTL may name any file in the roots)
    is served as bytes, in a sandbox: were the user to open it, it runs nothing at the
    preview's origin (where the token and state.json are)."""
    entry, pkg = _obj_robot(tmp_path, "shell.mtl")
    for name, data in (("x.html", b"<script src='x.js'></script>"), ("x.js", b"alert(1)"),
                       ("x.svg", b"<svg xmlns='http://www.w3.org/2000/svg'><script>1</script>"
                                 b"</svg>"), ("x.xhtml", b"<html/>")):
        (pkg / "meshes" / name).write_bytes(data)
    (pkg / "meshes" / "shell.mtl").write_text(
        "newmtl a\nmap_Kd x.html\nmap_Ka x.js\nmap_Ks x.svg\nmap_Ns x.xhtml\n")
    with serve(entry) as (server, session):
        obj = next(f for f in session.table.files if f.path.endswith("shell.obj"))
        i = session.table.files.index(obj)
        for name in ("x.html", "x.js", "x.svg", "x.xhtml", "shell.obj", "shell.mtl"):
            kind, csp = _headers(server, f"/{server.token}/m/{i}/{name}")
            assert not any(t in kind for t in ("html", "javascript", "xml", "svg")), (name, kind)
            assert "sandbox" in csp, (name, csp)


def _headers(server, path):
    import http.client
    c = http.client.HTTPConnection("127.0.0.1", server.port, timeout=30)
    try:
        c.request("GET", path)
        r = c.getresponse()
        r.read()
        assert r.status == 200, (path, r.status)
        return r.getheader("Content-Type", ""), r.getheader("Content-Security-Policy", "")
    finally:
        c.close()


def test_a_slow_client_is_dropped_and_others_are_served_meanwhile(tmp_path, monkeypatch):
    """Slowloris: a connection that never finishes its request is closed after the server's
    idle timeout (a thread is not held for ever), and a well-formed request is answered while
    it hangs. (The timeout is the handler's, 10 s: made 2 s here to keep the test short.)"""
    from urdf_lint.preview import server as served
    assert served.Handler.timeout == served.IDLE_TIMEOUT_S == 10
    monkeypatch.setattr(served.Handler, "timeout", 2)
    limit = 2
    entry = make_robot(tmp_path)
    with serve(entry) as (server, _):
        slow = socket.create_connection(("127.0.0.1", server.port))
        slow.sendall(f"GET /{server.token}/state.json HTTP/1.1\r\nHost: 127.0".encode())
        try:
            assert get(server, f"/{server.token}/state.json")[0] == 200
            slow.settimeout(limit + 10)
            t0 = time.monotonic()
            assert slow.recv(1024) == b""          # closed by the server, nothing answered
            assert time.monotonic() - t0 <= limit + 5
        finally:
            slow.close()


def test_what_a_page_of_another_site_can_send_is_refused_and_learns_nothing(tmp_path):
    """Held on the first red-team pass (kept so it stays so): another port of localhost is
    same-site, not same-origin; no answer grants CORS or names the token or a path."""
    import http.client
    entry = make_robot(tmp_path)
    with serve(entry) as (server, _):
        t = server.token
        p = f"/{t}/state.json"
        for headers in ({"Sec-Fetch-Site": "same-site"}, {"Sec-Fetch-Site": "cross-site",
                                                         "Sec-Fetch-Mode": "no-cors"},
                        {"Origin": f"http://localhost:{server.port + 1}"}):
            status, body = get(server, p, headers)
            assert status == 403 and t.encode() not in body, headers
        for path in (p, f"/{t}/m/0/arm.stl", f"/{t}/nothing", f"/{t[:-1]}/state.json"):
            c = http.client.HTTPConnection("127.0.0.1", server.port, timeout=30)
            c.request("GET", path, headers={"Origin": "http://evil.example"})
            r = c.getresponse()
            body = r.read()
            c.close()
            assert r.getheader("Access-Control-Allow-Origin") is None
            assert t.encode() not in body and str(tmp_path).encode() not in body
            assert r.getheader("X-Frame-Options") == "DENY"
            assert "frame-ancestors 'none'" in r.getheader("Content-Security-Policy")


def test_the_preview_opens_nothing_outside_the_repository(tmp_path):
    """``urdf-lint preview`` under strace, its page, scene, meshes and textures fetched, with
    a repository whose DAE names an image outside it, whose OBJ names an MTL outside it, and a
    mesh symlinked out of it: every file opened (its workers' too) is the repository's, the
    cache's, the runtime's or the system's."""
    import os
    import signal
    import subprocess
    import sys

    import pytest

    from support import strace
    why = strace.available()
    if why:
        pytest.skip(why)
    root = tmp_path / "repo"
    root.mkdir()
    entry = make_robot(root, OBJ_LINK + (
        '<link name="body"><visual><geometry><mesh filename="package://arm_description/meshes/'
        'body.dae"/></geometry></visual></link><link name="leaky"><visual><geometry><mesh '
        'filename="package://arm_description/meshes/leak.stl"/></geometry></visual></link>'))
    meshes = entry.parent.parent / "meshes"
    (meshes / "shell.obj").write_text("mtllib ../../../outside.mtl\nv 0 0 0\nv 1 0 0\n"
                                      "v 0 1 0\nf 1 2 3\n")
    (meshes / "body.dae").write_text(
        "<COLLADA><library_images><image id='b'><init_from>../../../secret.png</init_from>"
        f"</image><image id='c'><init_from>file://{tmp_path}/secret2.png</init_from></image>"
        "</library_images></COLLADA>")
    (root / "secret.txt").unlink()
    for name in ("outside.mtl", "secret.png", "secret2.png", "secret.txt"):
        (tmp_path / name).write_text("map_Kd secret.png\nTOKEN=hunter2\n")
    os.symlink(tmp_path / "secret.txt", meshes / "leak.stl")
    allowed = [root, tmp_path / "cache", tmp_path / "tmp", tmp_path / "home"]
    for d in allowed[1:]:
        d.mkdir()
    env = dict(os.environ, XDG_CACHE_HOME=str(allowed[1]), TMPDIR=str(allowed[2]),
               HOME=str(allowed[3]))
    env.pop("GITHUB_ACTIONS", None)
    logs = tmp_path / "tmp" / "strace"
    p = subprocess.Popen(strace.command(logs, [sys.executable, "-m", "urdf_lint", "preview",
                                               str(entry)]),
                         cwd=root, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True, start_new_session=True)
    try:
        url = p.stdout.readline().strip()
        assert url.startswith("http://127.0.0.1:"), p.stderr.read() if p.poll() else url
        import urllib.request
        base = url

        def fetch(rel):
            try:
                with urllib.request.urlopen(base + rel, timeout=60) as r:
                    return r.read()
            except OSError:
                return b""
        import json
        state = json.loads(fetch("state.json"))
        urdf = state["variants"][0]["urdf"]
        import re
        names = re.findall(r'filename="(m/[^"]+)"', urdf)
        assert names, urdf
        for rel in ["", "static/vendor.js", "static/viewer.js", *names, "m/0/../../secret.png",
                    "m/1/secret.png", "m/2/_/_/_/secret.png", "m/1/outside.mtl"]:
            assert b"hunter2" not in fetch(rel), rel
    finally:
        os.killpg(p.pid, signal.SIGINT)
        try:
            p.wait(30)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()
    paths = {o.opened for o in strace.opens(logs) if o.opened}
    assert any(x.endswith("shell.obj") for x in paths)        # (it traced what it served)
    assert strace.outside_allowed(paths, *allowed) == []


def test_the_review_page_inlines_at_most_its_total_of_meshes(tmp_path):
    """Many distinct large meshes (cheap in git, as deltas of each other): the review page
    inlines them up to its total and refuses the rest, with a reason the page shows, instead
    of holding them all in the diff's memory and the artifact."""
    from urdf_lint.preview.review import ReviewPage
    page = ReviewPage(max_mesh_mb=1, max_total_mb=1)
    paths = []
    for i in range(4):
        p = tmp_path / f"part{i}.stl"
        p.write_bytes(bytes([i]) * 400_000)          # 0.4 MB each, all different
        paths.append(str(p))
        page.table.add(str(p), "mesh", None)
    notes = page._inline(page.table, [str(tmp_path)])
    assert len(notes) == 2 and "part2.stl" in notes[0] and "used up" in notes[0], notes
    got = [page.files[f"m/{i}/part{i}.stl"] for i in range(4)]
    assert ["data" in g for g in got] == [True, True, False, False], got
    assert all("used up" in g["refused"] for g in got[2:])
    assert page.total == 800_000
    # identical bytes cost nothing more
    same = tmp_path / "same.stl"
    same.write_bytes(bytes([0]) * 400_000)
    page2 = ReviewPage(max_mesh_mb=1, max_total_mb=1)
    for p in (paths[0], str(same), paths[1]):
        page2.table.add(p, "mesh", None)
    page2._inline(page2.table, [str(tmp_path)])
    assert page2.files["m/1/same.stl"] == {"same": "m/0/part0.stl"}
    assert "data" in page2.files["m/2/part1.stl"] and page2.total == 800_000


def test_the_servers_own_errors_are_plain_text_with_its_headers(tmp_path):
    """An unknown method or a malformed request line: http.server answered with its HTML error
    page (the request echoed, no CSP, no nosniff, no framing header)."""
    entry = make_robot(tmp_path)
    with serve(entry) as (server, _):
        for line in (f"FOO /{server.token}/<b>x</b> HTTP/1.1", "GET /<svg> x HTTP/1.1",
                     f"TRACE /{server.token}/ HTTP/1.1"):
            s = socket.create_connection(("127.0.0.1", server.port), timeout=30)
            s.sendall(f"{line}\r\nHost: 127.0.0.1:{server.port}\r\n\r\n".encode())
            reply = b""
            while chunk := s.recv(65536):
                reply += chunk
            s.close()
            head, _, body = reply.partition(b"\r\n\r\n")
            assert b"Content-Type: text/plain" in head, (line, reply)
            assert b"nosniff" in head and b"frame-ancestors 'none'" in head, (line, head)
            assert b"<" not in body and server.token.encode() not in body, (line, body)
