"""Issue 21, items 13-15: nothing a repository names can forge what urdf-lint prints.

Every command's messages go through one escaper (``urdf_lint/core/escape.py``, written by
``emit.say``), checked by walking the code; a hostile file name (newline, ``::``, ``%0A``, an
ANSI escape, a line separator) and hostile link names and ``xacro.fatal`` text then go through
every registered output format and through ``generate``, ``diff`` and ``render``: no line
starts a GitHub workflow command that is not ours, no raw escape byte reaches a terminal, and
the markdown of ``diff`` renders that text as text only.
"""
from __future__ import annotations

import ast
import html
import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from conftest import REPO, make_package, run_cli

pytestmark = pytest.mark.skipif(shutil.which("git") is None, reason="needs git")

EVIL = "a\n::error file=y,line=1::forged%0A\x1b[31mred\u2028::warning::x"
FATAL = "![img](http://evil.example/x.png) [link](http://evil.example) @octocat <b>hi</b> #12"
X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
# a workflow command urdf-lint itself writes (the github format): its file is escaped
OURS = re.compile(r"::(error|warning|notice) file=p/[^\n]*,line=\d+,col=\d+,title=UL\d{3} [a-z0-9-]+::")


def _git(*args, cwd):
    subprocess.run(["git", "-c", "user.email=t@example.invalid", "-c", "user.name=t", *args],
                   cwd=cwd, check=True, capture_output=True)


def _hostile_repo(root: Path, generated: bool = True) -> Path:
    """A git repository whose file names, link names and xacro.fatal text are hostile: a
    URDF with findings, a xacro that fails with xacro.fatal, a stale generated output (a
    models entry of the config)."""
    fatal = FATAL.replace("<", "&lt;").replace(">", "&gt;")
    pkg = make_package(root, "p", {
        f"urdf/{EVIL}.urdf": (
            '<robot name="r"><link name="base"/><joint name="j&#10;::error file=x::pwned" '
            'type="revolute"><parent link="base"/><child link="nope&#10;::warning::x"/>'
            '<limit lower="1" upper="0" effort="1" velocity="1"/></joint></robot>\n'),
        f"urdf/{EVIL}f.urdf.xacro": (
            f'<robot name="f" {X}><link name="base"/>\n'
            f'<xacro:if value="${{python.len(\'x\') == 1}}">'
            f'<link name="${{xacro.fatal(\'{fatal}\')}}"/></xacro:if></robot>\n'),
        f"urdf/{EVIL}g.urdf.xacro": f'<robot name="g" {X}><link name="base"/></robot>\n',
        f"urdf/{EVIL}g.urdf": '<robot name="g"><link name="old"/></robot>\n',
    })
    if generated:
        (root / "urdf-lint.toml").write_text(
            f"[[models]]\npath = {json.dumps(f'p/urdf/{EVIL}g.urdf.xacro')}\n"
            f"output = {json.dumps(f'p/urdf/{EVIL}g.urdf')}\n")
    _git("init", "-q", cwd=root)
    _git("add", "-A", cwd=root)
    _git("commit", "-q", "-m", "base", cwd=root)
    return pkg


def assert_unforged(text: str, what: str, github: bool = False) -> None:
    """No raw terminal escape; no line a CI runner would take for a workflow command, except
    the github format's own (one per finding, its properties escaped)."""
    assert "\x1b" not in text, (what, text)
    for line in re.split(r"\r\n|\r|\n", text):
        if line.lstrip().startswith("::"):
            assert github and OURS.match(line), (what, line)
    if github:
        assert "%0A" not in text.replace("%250A", ""), (what, text)


def test_no_command_output_can_be_forged(tmp_path):
    """Every registered output format, and the messages of generate, diff and render, with
    a hostile file name (newline, ::, %0A, ANSI escape, U+2028) and hostile names inside."""
    from urdf_lint.report import registry as report
    repo = tmp_path / "repo"
    _hostile_repo(repo)
    env = {"GITHUB_ACTIONS": ""}
    formats = report.names()
    assert {"text", "github", "junit", "json", "sarif"} <= set(formats)
    for fmt in formats:
        p = run_cli("check", ".", "--no-cache", "--format", fmt, cwd=repo, env=env)
        assert p.returncode == 1, (fmt, p.stdout, p.stderr)
        assert_unforged(p.stdout, fmt, github=fmt == "github")
        assert_unforged(p.stderr, fmt)
        if fmt == "github":
            assert len(p.stdout.splitlines()) >= 3, p.stdout
    # check on one file: the note naming it
    p = run_cli("check", f"p/urdf/{EVIL}.urdf", "--no-cache", "-v", cwd=repo, env=env)
    assert_unforged(p.stdout + p.stderr, "check FILE -v")
    # generate: what it (would) rewrite, and a xacro that fails
    for args in (["--check"], []):
        p = run_cli("generate", ".", *args, cwd=repo, env=env)
        assert p.returncode == 1, p.stderr
        assert "regenerate" in p.stdout, p.stdout
        assert_unforged(p.stdout + p.stderr, f"generate {args}")
    # diff: text, json and markdown of a change to every hostile file
    for f in (repo / "p" / "urdf").iterdir():
        f.write_text(f.read_text().replace('name="base"', 'name="base2"').replace(
            'link="base"', 'link="base2"'))
    from urdf_lint.report import diff as diff_formats
    assert {"text", "json", "markdown"} <= set(diff_formats.names())
    for fmt in diff_formats.names():
        p = run_cli("diff", "HEAD", "--format", fmt, "--no-cache", cwd=repo, env=env)
        assert p.returncode in (0, 1), (fmt, p.stderr)
        if fmt in ("text", "json", "markdown"):   # (these show the names: the test bites)
            assert "forged" in p.stdout, (fmt, p.stdout)
        assert_unforged(p.stdout + p.stderr, f"diff {fmt}")
    # render: the files it wrote, and the models it could not draw
    p = run_cli("render", ".", "--out", tmp_path / "snaps", "--no-rrd", cwd=repo, env=env)
    assert p.returncode == 1 and "no snapshot" in p.stderr, p.stderr
    assert_unforged(p.stdout + p.stderr, "render")
    # an error message naming a path
    p = run_cli("check", f"p/urdf/{EVIL}.nope", cwd=repo, env=env)
    assert p.returncode == 2 and "no such file" in p.stderr
    assert_unforged(p.stdout + p.stderr, "usage error")


def _visible(html_text: str) -> str:
    """The text a reader sees: tags dropped, entities decoded, word joiners removed."""
    return html.unescape(re.sub(r"<[^>]+>", "", html_text)).replace("\u2060", "")


def test_diff_markdown_renders_untrusted_text_as_text_only(tmp_path):
    """`diff --format markdown` (a pull-request comment): xacro.fatal text and names render
    as the same visible text, never as an image, a link, HTML or an @mention."""
    cmarkgfm = pytest.importorskip("cmarkgfm")
    from cmarkgfm.cmark import Options
    repo = tmp_path / "repo"
    _hostile_repo(repo, generated=False)
    # the fatal model is linted at HEAD only: a change that reaches it
    f = next((repo / "p" / "urdf").glob("*f.urdf.xacro"))
    f.write_text(f.read_text().replace('<link name="base"/>', '<link name="base"/><!-- x -->'))
    p = run_cli("diff", "HEAD", "--format", "markdown", "--no-cache", cwd=repo,
                env={"GITHUB_ACTIONS": ""})
    md = p.stdout
    assert "octocat" in md, md
    # rendered as GitHub does, raw HTML kept (so that any would show)
    out = cmarkgfm.github_flavored_markdown_to_html(md, options=Options.CMARK_OPT_UNSAFE)
    assert "<a " not in out and "<img" not in out, out
    assert "<b>hi" not in out and "<em>" not in out and "<del>" not in out, out
    # GitHub links these in rendered text itself: none survives as such
    text = html.unescape(re.sub(r"<[^>]+>", "", out))
    assert not re.search(r"@[A-Za-z0-9]", text), text
    assert not re.search(r"#\d", text) and "http://" not in text, text
    # and the reader sees the message as it was written
    assert FATAL in _visible(out), _visible(out)


# -- every message through the one escaper, by construction ------------------------------------
# writes to the standard streams outside urdf_lint/core/emit.py's say(), each with its reason
ALLOWED_WRITES = {
    ("core/emit.py", "report_internal"): "safe_lines: every line escaped, later lines indented",
    ("cli/check.py", "progress"): "the progress counter: two numbers",
    ("cli/expand.py", "expand"): "the expanded URDF itself, the product the user asked for",
    ("cli/rules.py", "run"): "the rule catalogue: urdf-lint's own text",
    ("cli/rule.py", "explain"): "one rule's documentation: urdf-lint's own text",
    ("cli/doctor.py", "run"): "this machine's protections: urdf-lint's own text",
    ("cli/main.py", "_main"): "--version: urdf-lint's own text",
    ("cli/fix.py", "check_fix"): "the --diff patch: file names escaped by fixrun.unified_diff, "
                                "every other line starts with ' ', '+', '-' or '@'",
    ("cli/format.py", "cmd_format"): "format --diff: the same patch, from fixrun.unified_diff",
    ("runner/sandbox.py", "enter_worker"): "a worker's own note: the kernel's reasons",
}


def _stream_writes(tree):
    """(function, line) of every print(), sys.stdout/sys.stderr .write() and os.write(1|2)
    whose argument is not a plain string constant."""
    out = []

    def visit(node, func):
        for child in ast.iter_child_nodes(node):
            name = child.name if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)) \
                else func
            if isinstance(child, ast.Call):
                f = child.func
                hit = (isinstance(f, ast.Name) and f.id == "print") or (
                    isinstance(f, ast.Attribute) and f.attr == "write"
                    and isinstance(f.value, ast.Attribute) and f.value.attr in ("stdout", "stderr")
                    and isinstance(f.value.value, ast.Name) and f.value.value.id == "sys") or (
                    isinstance(f, ast.Attribute) and f.attr == "write"
                    and isinstance(f.value, ast.Name) and f.value.id == "os"
                    and isinstance(child.args[0], ast.Constant) and child.args[0].value in (1, 2))
                if hit and not all(isinstance(a, ast.Constant) for a in child.args[-1:]):
                    out.append((func, child.lineno))
            visit(child, name)
    visit(tree, "<module>")
    return out


def test_every_message_goes_through_the_escaper():
    """No module of urdf_lint writes a message to stdout or stderr but through emit.say (or
    an output format, each tested above): a new message cannot forget to escape a name."""
    found, used = [], set()
    for path in sorted((REPO / "urdf_lint").rglob("*.py")):
        for func, line in _stream_writes(ast.parse(path.read_text(), str(path))):
            key = (path.relative_to(REPO / "urdf_lint").as_posix(), func)
            if key in ALLOWED_WRITES:
                used.add(key)
            else:
                found.append(f"{path.relative_to(REPO)}:{line} in {func}()")
    assert not found, "write through urdf_lint.core.emit.say:\n" + "\n".join(found)
    assert used == set(ALLOWED_WRITES), f"stale allow-list entries: {set(ALLOWED_WRITES) - used}"


# -- item 15 (and issue 24 item 19, issue 22): picture names ------------------------------------
def _robot(name: str, links: int) -> str:
    body = "".join(f'<link name="l{i}"><visual><geometry><box size="0.1 0.1 0.1"/></geometry>'
                   f'</visual></link>' for i in range(links))
    joints = "".join(f'<joint name="j{i}" type="fixed"><parent link="l0"/><child link="l{i}"/>'
                     f'<origin xyz="{0.2 * i} 0 0"/></joint>' for i in range(1, links))
    return f'<robot name="{name}">{body}{joints}</robot>\n'


def _lookalike_repo(root: Path) -> Path:
    """Four models whose readable picture names the old naming confused: p/urdf/arm.urdf and
    p/urdf_arm.urdf (diff and render), X.xacro and X.urdf (render)."""
    make_package(root, "p", {
        "urdf/arm.urdf": _robot("arm", 2), "urdf_arm.urdf": _robot("decoy", 3),
        "urdf/X.xacro": _robot("x_xacro", 4).replace("<robot ", f"<robot {X} "),
        "urdf/X.urdf": _robot("x_urdf", 5)})
    _git("init", "-q", cwd=root)
    _git("add", "-A", cwd=root)
    _git("commit", "-q", "-m", "base", cwd=root)
    return root


MODELS = ("p/urdf/arm.urdf", "p/urdf_arm.urdf", "p/urdf/X.xacro", "p/urdf/X.urdf")


def test_picture_names_never_collide_and_render_and_diff_agree(tmp_path):
    pytest.importorskip("PIL")
    from PIL import Image
    from urdf_lint.core.locations import picture_name
    repo = _lookalike_repo(tmp_path / "repo")
    want = {m: picture_name(m) for m in MODELS}
    assert len(set(want.values())) == 4, want
    snaps = tmp_path / "snaps"
    p = run_cli("render", ".", "--out", snaps, "--no-rrd", cwd=repo)
    assert p.returncode == 0, p.stderr
    pngs = {Path(ln).name for ln in p.stdout.splitlines()}
    assert pngs == {f"{n}.png" for n in want.values()}, (pngs, want)
    # each picture is its own robot: four different images
    assert len({Image.open(snaps / f).tobytes() for f in pngs}) == 4
    # diff --render names the same robots' pictures the same way
    for m in MODELS:
        f = repo / m
        f.write_text(f.read_text().replace('xyz="0.2 0 0"', 'xyz="0.3 0 0"'))
    out = tmp_path / "diff"
    p = run_cli("diff", "HEAD", "--format", "json", "--render", out, "--no-rrd", "--no-cache",
                cwd=repo)
    assert p.returncode == 0, p.stderr
    got = {m["model"]: m["picture"] for m in json.loads(p.stdout)["models"]}
    assert got == want, got
    after = {f.name for f in out.glob("*.after.png")}
    assert after == {f"{n}.after.png" for n in want.values()}, after


def test_a_picture_name_two_models_share_is_drawn_for_neither(tmp_path, monkeypatch, capsys):
    """The names of a run are checked before anything is written: should two models get the
    same name (a hash collision, which a repository could grind for), neither picture is
    drawn and each says why, in render and in diff --render."""
    pytest.importorskip("PIL")
    from urdf_lint.core import locations
    from urdf_lint.cli.main import main
    repo = _lookalike_repo(tmp_path / "repo")
    monkeypatch.chdir(repo)
    monkeypatch.setattr(locations, "picture_name", lambda rel, args=None, key=None: "same")
    snaps = tmp_path / "snaps"
    assert main(["render", ".", "--out", str(snaps), "--no-rrd"]) == 1
    err = capsys.readouterr().err
    assert err.count("has the picture name same: neither is drawn") == 4, err
    assert not list(snaps.glob("same*")), list(snaps.iterdir())
    for m in MODELS:
        (repo / m).write_text((repo / m).read_text() + "<!-- changed -->\n")
    out = tmp_path / "diff"
    main(["diff", "HEAD", "--render", str(out), "--no-rrd", "--no-cache"])
    err = capsys.readouterr().err
    assert err.count("has the picture name same: neither is drawn") == 4, err
    assert not list(out.glob("same*")), list(out.iterdir())
