"""`urdf-lint preview`'s server (SECURITY.md, "The preview"): every request needs the token,
a Host naming this server and no foreign Origin; it serves only the files the robot references,
read-only; huge meshes are refused; a saved file reaches the scene. Plain HTTP, no browser
(the browser tests are tests/test_preview_browser.py)."""
from __future__ import annotations

import json
import os
import time

import pytest

from support.preview_robot import get, make_robot, serve


def _state(server):
    status, body = get(server, f"/{server.token}/state.json")
    assert status == 200
    return json.loads(body)


def test_the_scene_is_the_expansion_with_findings_on_their_links(tmp_path):
    entry = make_robot(tmp_path)
    with serve(entry) as (server, _):
        v = _state(server)["variants"][0]
    assert sorted(v["links"]) == ["base_link", "lower", "tool", "upper"]
    assert sorted(v["joints"]) == ["lower_joint", "tool_joint", "upper_joint"]
    # the link written by the macro names the macro's line in the xacro
    assert v["links"]["upper"][1] == 5 and v["links"]["tool"][1] == 23
    targets = {(f["code"], tuple(f["target"])) for f in v["findings"] if f["target"]}
    assert ("UL801", ("link", "base_link")) in targets
    assert ("UL601", ("link", "tool")) in targets
    # the mesh is served under its own name, the package:// URI is gone
    assert 'filename="m/0/arm.stl"' in v["urdf"] and "package://" not in v["urdf"]


def test_every_request_needs_the_token(tmp_path):
    entry = make_robot(tmp_path)
    with serve(entry) as (server, _):
        t = server.token
        for path in ("/", "/index.html", "/state.json", "/m/0/arm.stl", "/static/vendor.js",
                     f"/{t[:-1]}/state.json", f"/{t}x/m/0/arm.stl", f"/x{t}/",
                     f"/{t.upper() if t.upper() != t else t.lower()}/state.json"):
            assert get(server, path)[0] == 404, path
        for path in ("", "state.json", "m/0/arm.stl", "static/vendor.js", "static/viewer.js"):
            assert get(server, f"/{t}/{path}")[0] == 200, path


def test_the_host_must_name_this_server(tmp_path):
    """DNS rebinding: a page of evil.example whose name now resolves to 127.0.0.1 sends
    Host: evil.example:<port>; refused even with the token."""
    entry = make_robot(tmp_path)
    with serve(entry) as (server, _):
        p = f"/{server.token}/state.json"
        for host in ("evil.example", f"evil.example:{server.port}", "127.0.0.1",
                     f"127.0.0.1:{server.port + 1}", "", f"localhost.evil:{server.port}"):
            assert get(server, p, host=host)[0] == 403, host
        assert get(server, p, host=f"localhost:{server.port}")[0] == 200
        assert get(server, p)[0] == 200


def test_a_foreign_origin_is_refused(tmp_path):
    entry = make_robot(tmp_path)
    with serve(entry) as (server, _):
        p = f"/{server.token}/m/0/arm.stl"
        for origin in ("http://evil.example", "null", f"http://127.0.0.1:{server.port + 1}",
                       f"https://127.0.0.1:{server.port}"):
            assert get(server, p, {"Origin": origin})[0] == 403, origin
        assert get(server, p, {"Sec-Fetch-Site": "cross-site"})[0] == 403
        assert get(server, p, {"Origin": f"http://127.0.0.1:{server.port}"})[0] == 200
        assert get(server, p, {"Sec-Fetch-Site": "same-origin"})[0] == 200


def test_only_files_the_robot_references_are_served(tmp_path):
    entry = make_robot(tmp_path)
    pkg = entry.parent.parent
    os.symlink(tmp_path / "secret.txt", pkg / "meshes" / "leak.stl")
    with serve(entry) as (server, session):
        t = server.token
        status, body = get(server, f"/{t}/m/0/arm.stl")
        assert status == 200 and body == (pkg / "meshes" / "arm.stl").read_bytes()
        for path in ("m/0/unreferenced.stl", "m/0/../unreferenced.stl", "m/0/../../../secret.txt",
                     "m/0/%2e%2e/%2e%2e/%2e%2e/secret.txt", "m/1/arm.stl", "m/0/leak.stl",
                     "m/-1/arm.stl", "m/0/", "m/0", "../secret.txt", "static/../scene.py",
                     "static/vendor/LICENSE.three.txt", "missing/0"):
            status, body = get(server, f"/{t}/{path}")
            assert status == 404 and b"hunter2" not in body, path
        assert [os.path.basename(f.path) for f in session.table.files] == ["arm.stl"]


def test_a_symlinked_mesh_out_of_the_roots_is_not_in_the_table(tmp_path):
    entry = make_robot(tmp_path, '<link name="leaky"><visual><geometry><mesh '
                                 'filename="package://arm_description/meshes/leak.stl"/>'
                                 '</geometry></visual></link>')
    os.symlink(tmp_path / "secret.txt", entry.parent.parent / "meshes" / "leak.stl")
    with serve(entry) as (server, session):
        v = _state(server)["variants"][0]
        assert "missing/0" in v["urdf"]
        assert any("outside" in n for n in v["notes"])
        assert all(f.path != str(tmp_path / "secret.txt") and not f.path.endswith("leak.stl")
                   for f in session.table.files)
        for i in range(3):
            assert b"hunter2" not in get(server, f"/{server.token}/m/{i}/leak.stl")[1]


def test_it_is_read_only(tmp_path):
    entry = make_robot(tmp_path)
    before = entry.read_bytes()
    with serve(entry) as (server, _):
        for method in ("POST", "PUT", "DELETE", "PATCH", "OPTIONS"):
            assert get(server, f"/{server.token}/state.json", method=method)[0] == 405, method
    assert entry.read_bytes() == before


def test_the_server_listens_on_loopback_only(tmp_path):
    entry = make_robot(tmp_path)
    with serve(entry) as (server, _):
        assert server.server_address[0] == "127.0.0.1" and server.port > 0


def test_a_mesh_over_the_cap_is_refused_and_said(tmp_path):
    entry = make_robot(tmp_path)
    with serve(entry, max_mesh_mb=0) as (server, _):
        v = _state(server)["variants"][0]
        status, body = get(server, f"/{server.token}/m/0/arm.stl")
    assert status == 413 and b"cap" in body
    assert any("over the preview's 0 MB cap" in n for n in v["notes"])


def test_a_saved_file_reaches_the_scene(tmp_path):
    entry = make_robot(tmp_path)
    with serve(entry) as (server, session):
        v0 = session.version
        entry.write_text(entry.read_text().replace('name="tool"', 'name="gripper"')
                         .replace('link="tool"', 'link="gripper"'))
        deadline = time.monotonic() + 60
        while session.version == v0 and time.monotonic() < deadline:
            time.sleep(0.1)
        status, body = get(server, f"/{server.token}/version?v={v0}")
        assert status == 200 and json.loads(body)["version"] > v0
        links = _state(server)["variants"][0]["links"]
    assert "gripper" in links and "tool" not in links


def test_the_command_line_args_are_the_first_variant(tmp_path):
    entry = make_robot(tmp_path)
    with serve(entry, mappings=["len:=0.7"]) as (server, _):
        d = _state(server)
    assert d["variants"][0]["args"] == {"len": "0.7"}
    assert 'xyz="0 0 0.7"' in d["variants"][0]["urdf"]


@pytest.mark.parametrize("bad", ["noequals"])
def test_bad_args_are_a_usage_error(tmp_path, bad):
    from urdf_lint.cli.preview import PreviewOptions, start
    from urdf_lint.core.errors import UsageError
    with pytest.raises(UsageError):
        start(PreviewOptions(path=str(make_robot(tmp_path)), mappings=[bad]))


def test_a_mesh_serves_its_own_textures_even_from_a_sibling_folder(tmp_path):
    """A DAE naming ``../textures/skin.png`` is served one folder deep (``m/1/_/body.dae``), so
    the browser asks for ``m/1/textures/skin.png``; a texture it names outside the package
    roots is not served by any name."""
    entry = make_robot(tmp_path, '<link name="body"><visual><geometry><mesh '
                                 'filename="package://arm_description/meshes/body.dae"/>'
                                 '</geometry></visual></link>')
    pkg = entry.parent.parent
    (pkg / "textures").mkdir()
    (pkg / "textures" / "skin.png").write_bytes(b"\x89PNG skin")
    (tmp_path / "secret.png").write_text("TOKEN=hunter2\n")
    (pkg / "meshes" / "body.dae").write_text(
        "<COLLADA><library_images><image id='a'><init_from>../textures/skin.png</init_from>"
        "</image><image id='b'><init_from>../../secret.png</init_from></image>"
        "</library_images></COLLADA>")
    with serve(entry) as (server, _):
        v = _state(server)["variants"][0]
        assert 'filename="m/1/_/body.dae"' in v["urdf"]
        t = server.token
        assert get(server, f"/{t}/m/1/_/body.dae")[0] == 200
        assert get(server, f"/{t}/m/1/textures/skin.png") == (200, b"\x89PNG skin")
        for path in ("m/1/body.dae", "m/1/../secret.png", "m/1/secret.png", "m/1/_/../../secret.png",
                     "m/0/textures/skin.png"):
            status, body = get(server, f"/{t}/{path}")
            assert status == 404 and b"hunter2" not in body, path


def test_the_wheel_ships_every_file_of_the_page():
    """Each file under urdf_lint/preview/static (the vendored bundle and its licences too)
    matches pyproject's package data: the installed page has all its scripts."""
    import fnmatch
    from conftest import REPO
    from pyproject import pyproject
    data = pyproject()["tool"]["setuptools"]
    globs = data["package-data"]["urdf_lint.preview"]
    assert "urdf_lint.preview" in data["packages"]
    static = REPO / "urdf_lint" / "preview"
    files = [p.relative_to(static).as_posix() for p in (static / "static").rglob("*")
             if p.is_file()]
    assert {"static/vendor/vendor.js", "static/vendor/LICENSE.three.txt",
            "static/vendor/LICENSE.urdf-loader.txt", "static/viewer.js"} <= set(files)
    for f in files:
        assert any(fnmatch.fnmatch(f, g) for g in globs), f


PADS = """
  <xacro:macro name="pad" params="n">
    <link name="pad${n}"/>
    <joint name="pad${n}_joint" type="revolute"><parent link="tool"/><child link="pad${n}"/>
      <axis xyz="0 0 1"/><limit lower="2" upper="1" effort="1" velocity="1"/></joint>
  </xacro:macro>
  <xacro:pad n="1"/>
  <xacro:pad n="2"/>
"""


def test_the_summary_counts_problems_as_check_does(tmp_path, capsys):
    # one macro line wrong in two joints: two markers on the page, one problem, as `check`
    # says (the summary said "N findings", counting each instance)
    from urdf_lint.cli.check import CheckOptions, check
    from urdf_lint.cli.common import ConfigOptions
    from urdf_lint.cli.preview import scene_summary
    entry = make_robot(tmp_path, PADS)
    with serve(entry) as (_, session):
        scene = session.scenes[0]
    assert len([f for f in scene.findings if f["code"] == "UL302"]) == 2
    capsys.readouterr()
    check(CheckOptions(config=ConfigOptions(isolated=True, values={"output-format": "json"}),
                       paths=[str(entry)], quiet=True, no_cache=True))
    report = json.loads(capsys.readouterr().out)
    n = len(report["findings"])
    assert n == scene.problems < len(scene.findings)
    assert f" {n} problem(s) ({len(scene.findings)} marker(s))" in scene_summary(scene)


def test_a_click_names_an_element_and_never_a_line_outside_the_roots(tmp_path):
    """``Session.jump`` (the page's POST jump, when the language server opened the preview):
    the line comes from the scene, and one outside the run's roots is never shown."""
    from types import SimpleNamespace

    from urdf_lint.preview.scene import Scene
    from urdf_lint.preview.session import Session
    inside = str(tmp_path / "pkg" / "a.urdf.xacro")
    resolver = SimpleNamespace(is_inside=lambda p: p.startswith(str(tmp_path / "pkg")))
    session = Session([inside], None, resolver, 1)
    scene = Scene("a", inside, {}, sources={"link:a": (inside, 3, 3),
                                            "link:b": ("/etc/passwd", 1, 1)},
                  finding_sources=[("/etc/shadow", 1, 1), (inside, 9, 5)])
    session.publish([scene], [])
    assert session.jump({"variant": 0, "element": "link:a"})[0] == 404   # no editor: no jump
    shown = []
    session.editor = lambda f, line, col: shown.append((f, line, col)) or ""
    v = session.version
    assert session.jump({"variant": 0, "element": "link:a"}) == (200, "shown")
    assert session.jump({"version": v, "variant": 0, "finding": 1})[0] == 200
    assert shown == [(inside, 3, 3), (inside, 9, 5)]
    for asked in ({"variant": 0, "element": "link:b"},
                  {"version": v, "variant": 0, "finding": 0}):
        assert session.jump(asked)[0] == 403, asked
    for asked in ({"variant": 0, "file": "/etc/passwd", "line": 1}, [], "link:a",
                  {"variant": "0", "element": "link:a"}, {"variant": 0, "finding": True},
                  {"version": v, "variant": 0, "finding": 2}):
        assert session.jump(asked)[0] == 400, asked
    assert session.jump({"version": v - 1, "variant": 0, "finding": 1})[0] == 409
    session.set_highlight("link:a")   # (the cursor moved: the scenes, their indexes, did not)
    assert session.version > v and session.jump({"version": v, "variant": 0, "finding": 1})[0] \
        == 200
    assert len(shown) == 3


def test_the_cli_preview_takes_no_click(tmp_path):
    entry = make_robot(tmp_path)
    with serve(entry) as (server, _):
        status, _ = get(server, f"/{server.token}/jump", {
            "Origin": f"http://127.0.0.1:{server.port}", "Content-Type": "application/json"},
            method="POST", body=b'{"variant": 0, "element": "link:base_link"}')
    assert status == 405
