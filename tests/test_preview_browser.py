"""The preview and the review page in a real browser: Debian's Chromium (/usr/bin/chromium),
driven by Playwright for Python with ``executable_path`` set (never ``playwright install``).
Skipped without either (``.ci/run`` installs both: apt's chromium, the ``browser`` extra).

Set URDF_LINT_DOCS_IMG=1 to (re)write the pictures of docs/img/ from these tests."""
from __future__ import annotations

import io
import json
import os
import time
import urllib.parse
from pathlib import Path

import pytest

from conftest import REPO
from support.preview_robot import make_robot, serve

CHROMIUM = "/usr/bin/chromium"
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
        "--disable-component-update", "--disable-sync", "--no-first-run"]
DOCS_IMG = Path(REPO) / "docs" / "img"

pytestmark = [
    pytest.mark.skipif(not os.access(CHROMIUM, os.X_OK), reason="no /usr/bin/chromium"),
]


@pytest.fixture(scope="module")
def browser():
    sync_api = pytest.importorskip("playwright.sync_api")
    with sync_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        yield b
        b.close()


class Page:
    """One tab that may reach only ``allowed`` (a URL prefix, or file://): every other request
    is aborted and recorded in ``.external``; console errors and page errors are kept."""

    def __init__(self, browser, allowed: str):
        self.page = browser.new_page(viewport={"width": 1000, "height": 700})
        self.external: list[str] = []
        self.errors: list[str] = []
        self.page.on("pageerror", lambda e: self.errors.append(str(e)))

        def route(r):
            if r.request.url.startswith(allowed):
                r.continue_()
            else:
                self.external.append(r.request.url)
                r.abort()
        self.page.route("**/*", route)

    def js(self, expr: str):
        # page.evaluate goes through the DevTools protocol: the page's CSP (no eval) holds
        return self.page.evaluate(expr)

    def until(self, expr: str, timeout: float = 60.0):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            v = self.js(expr)
            if v:
                return v
            time.sleep(0.1)
        raise AssertionError(f"timed out waiting for {expr}; errors: {self.errors}")

    def ready(self):
        self.until("!!(window.preview && window.preview.ready)")

    def png(self):
        from PIL import Image
        return Image.open(io.BytesIO(self.page.screenshot())).convert("RGB")

    def screen_of(self, link: str) -> tuple[float, float]:
        """Where the origin of ``link`` is drawn, in CSS pixels of the page."""
        return tuple(self.js(f"""(() => {{
            const V = window.URDFV, p = window.preview;
            const o = p.robot.links[{json.dumps(link)}];
            const v = new V.Vector3(); o.getWorldPosition(v);
            const c = document.querySelector('#view canvas');
            const r = c.getBoundingClientRect();
            // the camera the page draws with: the scene's only PerspectiveCamera
            v.project(p.camera);
            return [r.left + (v.x + 1) / 2 * r.width, r.top + (1 - v.y) / 2 * r.height];
        }})()"""))

    def world_of(self, link: str):
        return self.js(f"""(() => {{ const v = new window.URDFV.Vector3();
            window.preview.robot.links[{json.dumps(link)}].getWorldPosition(v);
            return [v.x, v.y, v.z]; }})()""")

    def slide(self, joint: str, value: float):
        self.js(f"""(() => {{ const s = document.querySelector(
            'input[data-joint={json.dumps(joint)}]');
            s.value = {value}; s.dispatchEvent(new Event('input')); }})()""")
        self.page.wait_for_timeout(150)   # two frames drawn

    def close(self):
        self.page.close()


@pytest.fixture
def arm(tmp_path, browser):
    entry = make_robot(tmp_path)
    with serve(entry) as (server, session):
        page = Page(browser, f"http://127.0.0.1:{server.port}/")
        page.page.goto(server.url)
        page.ready()
        yield page, server, session, entry
        page.close()


def test_the_page_loads_offline_and_shows_the_expansion(arm):
    page, server, session, _ = arm
    assert page.external == [] and page.errors == []
    scene = session.scenes[0]
    assert page.js("Object.keys(preview.robot.links).length") == len(scene.links) == 4
    assert page.js("Object.keys(preview.robot.joints).length") == len(scene.joints) == 3
    assert page.js("preview.loadErrors") == []
    # the mesh arrived: the link drawn from arm.stl has geometry
    assert page.js("""(() => { let n = 0; preview.robot.links.upper.traverse(c => {
        if (c.isMesh && c.userData.link === 'upper' && !c.userData.collision)
            n += c.geometry.attributes.position.count; });
        return n; })()""") == 36


def test_moving_a_slider_moves_the_child_and_the_mimic_follows(arm):
    page, *_ = arm
    before = page.world_of("tool")
    page.slide("lower_joint", 0.8)
    after = page.world_of("tool")
    assert max(abs(a - b) for a, b in zip(before, after, strict=True)) > 0.1
    lower = page.js("preview.robot.joints.lower_joint.angle")
    assert lower == pytest.approx(0.8, abs=0.01)   # (the slider's step)
    assert page.js("preview.robot.joints.tool_joint.angle") == lower   # the mimic follows
    # the mimic joint has no slider of its own; the base link did not move
    assert page.js("document.querySelector('input[data-joint=\"tool_joint\"]')") is None
    assert page.world_of("base_link") == [0, 0, 0]


def test_each_marker_is_on_the_element_of_its_finding(arm):
    page, _, session, _ = arm
    markers = page.js("""preview.markers.map(m => [m.kind, m.name, m.code,
        m.object.parent.name, m.object.parent.isURDFLink ? 'link' : 'joint'])""")
    expected = sorted((f["target"][0], f["target"][1], f["code"])
                      for f in session.scenes[0].findings if f["target"])
    assert sorted(tuple(m[:3]) for m in markers) == expected
    assert ("link", "tool", "UL601") in {tuple(m[:3]) for m in markers}
    for kind, name, _, parent, parent_kind in markers:
        assert (parent_kind, parent) == (kind, name)
    # clicking the finding shows its message and its xacro line
    page.js("document.querySelectorAll('#findings .finding')[0].click()")
    info = page.js("document.getElementById('info').textContent")
    f = session.scenes[0].findings[0]
    assert f["message"] in info and f"{f['file']}:{f['line']}" in info


def test_screenshots_at_two_slider_positions_differ_where_the_link_moved(arm):
    from PIL import ImageChops
    page, *_ = arm
    a = page.png()
    tool_before = page.screen_of("tool")
    page.slide("upper_joint", 1.0)
    b = page.png()
    tool_after = page.screen_of("tool")
    box = ImageChops.difference(a, b).getbbox()
    assert box is not None
    x0, y0, x1, y1 = box
    panel = page.js("document.getElementById('panel').getBoundingClientRect().right")
    for x, y in (tool_before, tool_after):
        assert x0 - 5 <= x <= x1 + 5 and y0 - 5 <= y <= y1 + 5, (box, x, y)
    # the base link, which did not move, is drawn the same (a patch around its origin)
    bx, by = page.screen_of("base_link")
    patch = (int(bx) - 4, int(by) + 6, int(bx) + 4, int(by) + 14)
    assert ImageChops.difference(a.crop(patch), b.crop(patch)).getbbox() is None
    assert x1 > panel   # the change is in the 3D view, not only the slider
    if os.environ.get("URDF_LINT_DOCS_IMG"):
        DOCS_IMG.mkdir(parents=True, exist_ok=True)
        b.save(DOCS_IMG / "preview-arm.png")


def test_a_saved_change_reaches_the_open_page(arm):
    page, _, session, entry = arm
    v0 = page.js("preview.version")
    entry.write_text(entry.read_text().replace('name="tool"', 'name="gripper"')
                     .replace('link="tool"', 'link="gripper"'))
    page.until(f"preview.version > {v0} && preview.ready && !!preview.robot.links.gripper")
    assert page.js("'tool' in preview.robot.links") is False
    assert page.errors == []


def test_the_highlighted_link_is_tinted(tmp_path, browser):
    entry = make_robot(tmp_path)
    with serve(entry) as (server, _):
        page = Page(browser, f"http://127.0.0.1:{server.port}/")
        page.page.goto(server.url + "#highlight=" + urllib.parse.quote("link:upper"))
        page.ready()
        tints = page.js("""(() => { const out = {}; for (const [n, l] of
            Object.entries(preview.robot.links)) l.traverse(c => { if (c.isMesh &&
            c.userData.link === n && !c.userData.collision && c.material.emissive) out[n] =
            c.material.emissive.getHex(); }); return out; })()""")
        page.close()
    assert tints["upper"] == 0x0077ff and tints["lower"] != 0x0077ff


def _tints(page):
    return page.js("""(() => { const out = {}; for (const [n, l] of
        Object.entries(preview.robot.links)) l.traverse(c => { if (c.isMesh &&
        c.userData.link === n && !c.userData.collision && c.material.emissive) out[n] =
        c.material.emissive.getHex(); }); return out; })()""")


def test_clicks_in_a_page_opened_from_the_editor_jump_there(tmp_path, browser):
    """The page of a preview the language server opened (``session.editor`` set, as
    lsp/methods/preview.py sets it): clicking a link in the 3D view, a marker and a joint's
    name POSTs the element, and the editor is asked for its xacro line; the highlight the
    server sets (the command again, the cursor elsewhere) is the link tinted."""
    entry = make_robot(tmp_path)
    with serve(entry) as (server, session):
        asked = []
        session.editor = lambda f, line, col: asked.append((f, line, col)) or ""
        page = Page(browser, f"http://127.0.0.1:{server.port}/")
        page.page.goto(server.url)
        page.ready()
        assert page.js("preview.data.editor") is True
        src = session.scenes[0].sources
        # a link's mesh in the 3D view: the middle of "upper"'s segment
        x, y = page.js("""(() => { const V = window.URDFV, p = window.preview;
            const v = new V.Vector3(0, 0, 0.1); p.robot.links.upper.localToWorld(v);
            v.project(p.camera); const r = document.querySelector('#view canvas')
            .getBoundingClientRect();
            return [r.left + (v.x + 1) / 2 * r.width, r.top + (1 - v.y) / 2 * r.height]; })()""")
        page.page.mouse.click(x, y)
        page.until("preview.jumps.length === 1")
        assert page.js("preview.picked") == {"link": "upper"}
        assert asked == [src["link:upper"]] and page.js("preview.jumps[0][0]") == 200
        # the marker on base_link (drawn over it): that finding's line
        bx, by = page.screen_of("base_link")
        page.page.mouse.click(bx, by)
        page.until("preview.jumps.length === 2")
        i = page.js("preview.picked.finding")
        f = session.scenes[0].findings[i]
        assert f["target"] == ["link", "base_link"]
        assert asked[1] == session.scenes[0].finding_sources[i]
        assert asked[1][1] == f["line"]
        # a joint's name in the panel
        page.js("[...document.querySelectorAll('.joint-name')].find(e => e.textContent === "
                "'lower_joint').click()")
        page.until("preview.jumps.length === 3")
        assert asked[2] == src["joint:lower_joint"]
        # the server moves the highlight (the cursor moved in the editor): the page tints that
        # link, a joint's child link, without building the robot again
        assert "upper" not in {n for n, t in _tints(page).items() if t == 0x0077ff}
        page.js("preview.robot.userData.same = true")
        for name, tinted in (("link:upper", "upper"), ("joint:lower_joint", "lower"),
                             ("", None)):
            v0 = page.js("preview.version")
            session.set_highlight(name)
            page.until(f"preview.version > {v0} && preview.highlight === {json.dumps(name)}")
            page.page.wait_for_timeout(100)
            blue = {n for n, t in _tints(page).items() if t == 0x0077ff}
            assert blue == ({tinted} if tinted else set()), name
        assert page.js("preview.robot.userData.same") is True
        # a finding of the list, clicked after the highlight moved (the scenes did not change)
        page.js("document.querySelectorAll('#findings .finding')[1].click()")
        page.until("preview.jumps.length === 4")
        assert page.js("preview.jumps[3][0]") == 200
        assert asked[3] == session.scenes[0].finding_sources[1]
        assert page.errors == [] and page.external == []
        page.close()


def test_a_request_without_the_token_gets_no_page(tmp_path, browser):
    entry = make_robot(tmp_path)
    with serve(entry) as (server, _):
        page = Page(browser, "http://")
        r = page.page.goto(f"http://127.0.0.1:{server.port}/")
        assert r.status == 404
        r = page.page.goto(f"http://localhost:{server.port}/{server.token}/")
        assert r.status == 200
        page.close()


CORPUS = Path(REPO).parent / "shared" / "corpus"


@pytest.mark.skipif(not os.environ.get("URDF_LINT_DOCS_IMG"),
                    reason="writes docs/img (URDF_LINT_DOCS_IMG=1)")
def test_docs_picture_of_r2d2(browser):
    entry = Path(REPO) / "descriptions" / "r2d2_description" / "urdf" / "r2d2.urdf.xacro"
    with serve(entry) as (server, _):
        page = Page(browser, f"http://127.0.0.1:{server.port}/")
        page.page.goto(server.url)
        page.ready()
        page.js("document.getElementById('toggle-showFrames').click()")
        page.slide("head_swivel", 0.8)
        page.page.wait_for_timeout(300)
        DOCS_IMG.mkdir(parents=True, exist_ok=True)
        page.png().save(DOCS_IMG / "preview-r2d2.png")
        page.close()


# -- the review page of `urdf-lint diff --html` --------------------------------------------------
def _git(repo, *args):
    import subprocess
    subprocess.run(["git", "-c", "user.email=t@t", "-c", "user.name=t", *args], cwd=repo,
                   check=True, capture_output=True)


def _committed_arm(tmp_path: Path) -> tuple[Path, Path]:
    """(the repository, the entry): the arm committed as the base revision of a diff."""
    repo = tmp_path / "repo"
    repo.mkdir()
    entry = make_robot(repo)
    (repo / "secret.txt").unlink()
    _git(repo, "init", "-q", ".")
    _git(repo, "add", "-A")
    _git(repo, "commit", "-qm", "base")
    return repo, entry


def _diff_html(repo: Path, out: Path) -> dict:
    """``urdf-lint diff HEAD --html out --format json``: its JSON (the CLI, as CI runs it)."""
    import subprocess
    import sys
    r = subprocess.run([sys.executable, "-m", "urdf_lint", "diff", "HEAD", "--html", str(out),
                        "--format", "json"], cwd=repo, capture_output=True, text=True,
                       timeout=600)
    assert r.returncode in (0, 1), r.stderr
    return json.loads(r.stdout)


def _json_changed_links(model: dict) -> set:
    return {c["name"] for c in model["changes"] if c["kind"] == "link"} | \
        {m["link"] for m in model["moved"]}


def _open_review(browser, out: Path) -> Page:
    page = Page(browser, "file://")
    page.page.goto((out / "index.html").as_uri())
    page.ready()
    return page


HIGHLIGHTED = """(() => { const out = new Set(); preview.robot.traverse(c => {
    if (c.isMesh && !c.userData.collision && c.material.emissive &&
        c.material.emissive.getHex() === 0xff1f8f) out.add(c.userData.link); });
    return [...out].sort(); })()"""


def test_the_review_page_opens_from_file_and_shows_the_changed_links(tmp_path, browser):
    repo, entry = _committed_arm(tmp_path)
    text = entry.read_text()
    # the tool's joint moves up 10 cm (tool moves), base_link's visual moves
    text = text.replace('<parent link="lower"/><child link="tool"/><origin xyz="0 0 0.4"/>',
                        '<parent link="lower"/><child link="tool"/><origin xyz="0 0 0.5"/>')
    text = text.replace('<link name="base_link">\n    <visual>',
                        '<link name="base_link">\n    <visual><origin xyz="0.1 0 0"/>')
    entry.write_text(text)
    out = tmp_path / "review"
    doc = _diff_html(repo, out)
    [model] = doc["models"]
    expected = _json_changed_links(model)
    assert expected == {"base_link", "tool"}
    page = _open_review(browser, out)
    assert page.external == [] and page.errors == []
    assert page.js("preview.robots.length") == 2          # base and head, overlaid
    assert set(page.js("preview.data.variants[0].changed_links")) == expected
    # highlighted in the scene: the changed links that have a mesh to tint (tool has none)
    assert page.js(HIGHLIGHTED) == ["base_link"]
    rows = page.js("[...document.querySelectorAll('#changes tr')].length")
    assert rows == 1 + len(model["changes"]) + len(model["moved"])
    # the sliders move both robots
    page.slide("upper_joint", 0.7)
    angles = page.js("preview.robots.map(r => r.joints.upper_joint.angle)")
    assert angles[0] == angles[1] == pytest.approx(0.7, abs=0.01)
    size = sum(f.stat().st_size for f in out.iterdir())
    assert size < 2_000_000
    page.close()


def _stl(triangles: int, seed: int) -> bytes:
    """A binary STL of ``triangles`` triangles (84 + 50 per triangle bytes), its own bytes
    per ``seed`` (the review page inlines identical files once)."""
    import random
    import struct
    rnd = random.Random(seed)
    out = bytearray(b"urdf-lint size fixture".ljust(80, b" ")) + struct.pack("<I", triangles)
    for _ in range(triangles):
        out += struct.pack("<12f", 0, 0, 0, *(rnd.uniform(-0.04, 0.04) for _ in range(9)))
        out += b"\0\0"
    return bytes(out)


def test_the_review_page_of_a_30_link_robot_and_its_size(tmp_path, browser):
    """The size docs/review.md states: a 30-link chain, each link its own 1,000-triangle STL
    (50 KB, a simplified arm segment), one joint moved; the page shows both 30-link robots."""
    from support.repo_shapes import joint, link, package_xml
    repo = tmp_path / "repo"
    pkg = repo / "chain_description"
    (pkg / "meshes").mkdir(parents=True)
    (pkg / "urdf").mkdir()
    (pkg / "package.xml").write_text(package_xml("chain_description"))
    parts = []
    for i in range(30):
        (pkg / "meshes" / f"l{i}.stl").write_bytes(_stl(1000, i))
        parts.append(link(f"l{i}", f"package://chain_description/meshes/l{i}.stl"))
        if i:
            parts.append(joint(f"j{i}", f"l{i - 1}", f"l{i}"))
    entry = pkg / "urdf" / "chain.urdf"
    entry.write_text('<?xml version="1.0"?>\n<robot name="chain">\n' + "".join(parts)
                     + "</robot>\n")
    for args in (("init", "-q", "."), ("add", "-A"), ("commit", "-qm", "base")):
        _git(repo, *args)
    entry.write_text(entry.read_text().replace(
        '<parent link="l14"/><child link="l15"/>\n    <origin xyz="0 0 0.1"',
        '<parent link="l14"/><child link="l15"/>\n    <origin xyz="0 0 0.12"', 1))
    out = tmp_path / "review"
    [model] = _diff_html(repo, out)["models"]
    assert "l15" in _json_changed_links(model)
    page = _open_review(browser, out)
    assert page.external == [] and page.errors == []
    assert page.js("preview.robots.map(r => Object.keys(r.links).length)") == [30, 30]
    page.close()
    sizes = {f.name: f.stat().st_size for f in out.iterdir()}
    meshes = sum((pkg / "meshes" / f"l{i}.stl").stat().st_size for i in range(30))
    total = sum(sizes.values())
    print(f"30-link review page: {total} bytes ({sizes}); meshes {meshes} bytes")
    # the meshes once, as base64 (4/3), plus the page's scripts: the size is the meshes'
    assert meshes * 4 // 3 < sizes["review-data.js"] < meshes * 4 // 3 + 200_000
    assert total < 3_000_000


@pytest.mark.skipif(not os.environ.get("URDF_LINT_DOCS_IMG"),
                    reason="writes docs/img (URDF_LINT_DOCS_IMG=1)")
@pytest.mark.skipif(not (CORPUS / "franka_description").is_dir(), reason="no corpus")
def test_docs_review_page_of_two_corpus_robots(tmp_path, browser):
    """A pull request to a copy of two corpus packages: franka's joint4 moves 2 cm (link4 and
    everything after it move), robotiq's left knuckle 5 mm; the review page of both models,
    each model's changed links equal to diff --format json's, one picture per model."""
    import shutil
    repo = tmp_path / "repo"
    for pkg in ("franka_description", "robotiq_description"):
        shutil.copytree(CORPUS / pkg, repo / pkg, symlinks=True)
    _git(repo, "init", "-q", ".")
    _git(repo, "add", "-A")
    _git(repo, "commit", "-qm", "base")
    arm = repo / "franka_description" / "robots" / "common" / "franka_arm.xacro"
    arm.write_text(arm.read_text().replace('<origin rpy="${pi/2} 0 0" xyz="0.0825 0 0" />',
                                           '<origin rpy="${pi/2} 0 0" xyz="0.1025 0 0" />', 1))
    grip = repo / "robotiq_description" / "urdf" / "robotiq_2f_85_macro.urdf.xacro"
    grip.write_text(grip.read_text().replace('<origin xyz="0.03060114 0.0 0.05490452"',
                                             '<origin xyz="0.03560114 0.0 0.05490452"', 1))
    out = tmp_path / "review"
    doc = _diff_html(repo, out)
    wanted = {"franka_description/robots/panda/panda.urdf.xacro": "review-panda.png",
              "robotiq_description/urdf/robotiq_2f_85_gripper.urdf.xacro": "review-robotiq.png"}
    page = _open_review(browser, out)
    labels = page.js("preview.data.variants.map(v => v.label)")
    by_label = {m["model"]: m for m in doc["models"]}
    for i, label in enumerate(labels):
        model = label.rsplit(" (", 1)[0]
        assert set(page.js(f"preview.data.variants[{i}].changed_links")) == \
            _json_changed_links(by_label[model])
        if model in wanted:
            page.js(f"""(() => {{ const s = document.getElementById('variant');
                s.value = '{i}'; s.dispatchEvent(new Event('change')); }})()""")
            page.page.wait_for_timeout(200)
            page.ready()
            page.page.wait_for_timeout(300)
            DOCS_IMG.mkdir(parents=True, exist_ok=True)
            page.png().save(DOCS_IMG / wanted[model])
    assert page.errors == [] and page.external == []
    page.close()


@pytest.mark.skipif(not (CORPUS / "urdf_tutorial").is_dir(), reason="no corpus")
def test_a_corpus_robot_with_textured_dae_meshes(browser):
    """urdf_tutorial's 08-macroed (the ROS tutorial's R2D2-like robot): its PR2 gripper DAE
    meshes load and their PNG textures are fetched through the page's token URLs."""
    entry = CORPUS / "urdf_tutorial" / "urdf" / "08-macroed.urdf.xacro"
    with serve(entry) as (server, session):
        page = Page(browser, f"http://127.0.0.1:{server.port}/")
        textures = []
        page.page.on("response", lambda r: textures.append((r.url.rsplit("/", 1)[1], r.status))
                     if r.url.endswith(".png") else None)
        page.page.goto(server.url)
        page.ready()
        page.page.wait_for_timeout(1000)    # (textures load after the meshes)
        assert page.js("preview.loadErrors") == [] and page.external == []
        assert page.js("Object.keys(preview.robot.links).length") == \
            len(session.scenes[0].links)
        assert ("l_finger_color.png", 200) in textures
        if os.environ.get("URDF_LINT_DOCS_IMG"):
            page.js("document.getElementById('toggle-showFrames').click()")
            page.slide("gripper_extension", -0.2)
            page.page.wait_for_timeout(300)
            page.png().save(DOCS_IMG / "preview-urdf-tutorial.png")
        page.close()


# -- what a pull request's meshes may make the page fetch ---------------------------------------
BEACON_DAE = """<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
 <asset><unit meter="1"/><up_axis>Z_UP</up_axis></asset>
 <library_images><image id="img"><init_from>http://beacon.invalid/seen.png</init_from></image>
  <image id="img2"><init_from>file:///etc/hostname</init_from></image></library_images>
 <library_effects><effect id="eff"><profile_COMMON>
  <newparam sid="surf"><surface type="2D"><init_from>img</init_from></surface></newparam>
  <newparam sid="samp"><sampler2D><source>surf</source></sampler2D></newparam>
  <newparam sid="surf2"><surface type="2D"><init_from>img2</init_from></surface></newparam>
  <newparam sid="samp2"><sampler2D><source>surf2</source></sampler2D></newparam>
  <technique sid="t"><phong><diffuse><texture texture="samp" texcoord="UV"/></diffuse>
   <specular><texture texture="samp2" texcoord="UV"/></specular></phong></technique>
 </profile_COMMON></effect></library_effects>
 <library_materials><material id="mat"><instance_effect url="#eff"/></material></library_materials>
 <library_geometries><geometry id="g"><mesh>
  <source id="p"><float_array id="pa" count="9">0 0 0 0.1 0 0 0 0.1 0</float_array>
   <technique_common><accessor source="#pa" count="3" stride="3"><param name="X" type="float"/>
   <param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common>
  </source>
  <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
  <triangles material="m" count="1"><input semantic="VERTEX" source="#v" offset="0"/>
   <p>0 1 2</p></triangles>
 </mesh></geometry></library_geometries>
 <library_visual_scenes><visual_scene id="vs"><node id="n"><instance_geometry url="#g">
  <bind_material><technique_common><instance_material symbol="m" target="#mat"/>
  </technique_common></bind_material></instance_geometry></node></visual_scene>
 </library_visual_scenes>
 <scene><instance_visual_scene url="#vs"/></scene>
</COLLADA>
"""
BEACON_LINK = ('<link name="beacon"><visual><geometry><mesh filename="package://arm_description/'
               'meshes/beacon.dae"/></geometry></visual></link>')


class Watched(Page):
    """A Page that also records every request that went out (answered, or failed for another
    reason than the page's CSP, which stops it before it leaves)."""

    def __init__(self, browser, allowed: str):
        super().__init__(browser, allowed)
        self.requests: list[str] = []
        self.page.on("requestfinished", lambda r: self.requests.append(r.url))
        self.page.on("requestfailed", lambda r: r.failure == "csp" or
                     self.requests.append(r.url))


def test_a_mesh_of_the_pull_request_makes_the_review_page_fetch_nothing(tmp_path, browser):
    """A DAE naming ``http://…`` and ``file:///…`` images: the review page (no server, no CSP
    header: from file://) has its CSP in a <meta>, so neither is asked for (no beacon telling
    the attacker who opened the artifact, and when)."""
    repo, entry = _committed_arm(tmp_path)
    (repo / "arm_description" / "meshes" / "beacon.dae").write_text(BEACON_DAE)
    entry.write_text(entry.read_text().replace("</robot>", BEACON_LINK + "</robot>"))
    out = tmp_path / "review"
    _diff_html(repo, out)
    page = Watched(browser, "file://")
    page.page.goto((out / "index.html").as_uri())
    page.ready()
    page.page.wait_for_timeout(500)
    assert "beacon" in page.js("Object.keys(preview.robot.links)")
    assert page.errors == []
    assert page.external == [], page.external
    assert [u for u in page.requests if "hostname" in u or "beacon.invalid" in u] == []
    page.close()


def test_a_mesh_makes_the_preview_fetch_nothing_elsewhere(tmp_path, browser):
    entry = make_robot(tmp_path, BEACON_LINK)
    (entry.parent.parent / "meshes" / "beacon.dae").write_text(BEACON_DAE)
    with serve(entry) as (server, _):
        page = Watched(browser, f"http://127.0.0.1:{server.port}/")
        page.page.goto(server.url)
        page.ready()
        page.page.wait_for_timeout(500)
        assert "beacon" in page.js("Object.keys(preview.robot.links)")
        # (three.js puts a mesh's image names below the mesh's own URL: m/1/http://…, a 404)
        assert page.external == [], page.external
        here = f"http://127.0.0.1:{server.port}/{server.token}/"
        assert page.requests and all(u.startswith(here) for u in page.requests), page.requests
        page.close()


# -- names a pull request writes, shown as text -------------------------------------------------
EVIL = '</script><img src=x onerror="window.pwned=1"><!--\u2028\u2029${x}'
EVIL_XML = (EVIL.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
            .replace('"', "&quot;").replace("${", "$${"))
EVIL_LINK = (f'<link name="{EVIL_XML}"><visual><geometry><box size="0.1 0.1 0.1"/></geometry>'
             f'<material name="{EVIL_XML}"><color rgba="1 0 0 1"/></material></visual></link>'
             f'<joint name="{EVIL_XML}j" type="fixed"><parent link="tool"/>'
             f'<child link="{EVIL_XML}"/></joint>')
NO_MARKUP = """(() => ({pwned: window.pwned === 1,
    imgs: document.querySelectorAll('img').length,
    text: document.body.textContent}))()"""


def _shown_as_text(page):
    assert EVIL in page.js("Object.keys(preview.robot.links)")
    seen = page.js(NO_MARKUP)
    assert seen["pwned"] is False and seen["imgs"] == 0
    return seen["text"]


def test_markup_in_names_is_text_in_the_preview(tmp_path, browser):
    entry = make_robot(tmp_path, EVIL_LINK)
    with serve(entry) as (server, session):
        page = Page(browser, f"http://127.0.0.1:{server.port}/")
        page.page.goto(server.url)
        page.ready()
        _shown_as_text(page)
        assert page.errors == [] and page.external == []
        page.close()


def test_markup_in_names_is_text_in_the_review_page(tmp_path, browser):
    repo, entry = _committed_arm(tmp_path)
    entry.write_text(entry.read_text().replace("</robot>", EVIL_LINK + "</robot>"))
    out = tmp_path / "review"
    _diff_html(repo, out)
    data = (out / "review-data.js").read_text()
    assert "</script" not in data.lower() and "\u2028" not in data and "\u2029" not in data
    page = Page(browser, "file://")
    page.page.goto((out / "index.html").as_uri())
    page.ready()
    text = _shown_as_text(page)
    assert f"link {EVIL}" in text        # (the table of changes names it, as text)
    assert page.errors == [] and page.external == []
    page.close()
