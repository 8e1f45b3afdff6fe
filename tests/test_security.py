"""Hostile input: one case per attack class. Each case is real: files on disk, a secret-looking
environment variable, a file outside the repository. Every case must give a located finding and
a non-zero exit, spawn nothing, write nothing outside the output folder, leak no secret, and end
within its limit."""
from __future__ import annotations

import json
import os
import time

import pytest

from conftest import make_package, run_cli

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
SECRET = "ghp_TOPSECRET_0123456789abcdef"


def robot(body, name="r"):
    return f'<?xml version="1.0"?>\n<robot name="{name}" {X}>\n  <link name="base"/>\n{body}\n</robot>\n'


@pytest.fixture()
def world(tmp_path):
    """A repository, a secret file outside it, a marker folder for side effects."""
    repo = tmp_path / "repo"
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "secret.yaml").write_text(f"token: {SECRET}\n")
    (outside / "secret.xacro").write_text(f'<robot {X}><link name="{SECRET}"/></robot>\n')
    (outside / "secret.stl").write_text(f"solid {SECRET}\nendsolid\n")
    marker = tmp_path / "pwned"
    return repo, outside, marker


def lint(repo, *extra, timeout=60):
    before = snapshot(repo.parent)
    t0 = time.monotonic()
    p = run_cli("check", ".", "--no-cache", "--format", "json", *extra, cwd=repo,
                env={"CI_DEPLOY_TOKEN": SECRET, "AWS_SECRET_ACCESS_KEY": SECRET}, timeout=timeout)
    took = time.monotonic() - t0
    assert p.returncode == 1, (p.returncode, p.stdout, p.stderr)
    assert SECRET not in p.stdout and SECRET not in p.stderr
    after = snapshot(repo.parent)
    assert after == before, f"files appeared: {after - before}"
    return json.loads(p.stdout)["findings"], took


def snapshot(top):
    out = set()
    for d, _, files in os.walk(top):
        for f in files:
            out.add(os.path.join(d, f))
    return out


def assert_located(findings, code, file="p/urdf/r.urdf.xacro"):
    hits = [f for f in findings if f["code"] == code]
    assert hits, findings
    assert all(f["line"] >= 1 and f["col"] >= 1 for f in hits)
    assert any(f["file"] == file for f in hits), hits
    return hits


# -- no code execution ----------------------------------------------------------------------
ESCAPES = [
    "${''.__class__.__mro__[1].__subclasses__()}",
    "${python.type(xacro)}",
    "${python.vars(xacro)}",
    "${xacro.load_yaml.__globals__['os'].system('touch MARKER')}",
    "${[c for c in ().__class__.__base__.__subclasses__() if c.__name__ == 'Popen'][0]('touch MARKER', shell=True)}",
    "${python['vars'](math)['__loader__']}",
    "${'{0.__class__.__init__.__globals__}'.format(xacro.tokenize)}",
    "${(lambda: 0).__code__}",
    "$(eval __import__('os').system('touch MARKER'))",
    "$(eval getattr(getattr, '_' + '_self_' + '_'))",
    "$(eval [c for c in ().__class__.__base__.__subclasses__()])",
]


@pytest.mark.parametrize("payload", ESCAPES)
def test_no_code_execution(world, payload):
    repo, _, marker = world
    payload = payload.replace("MARKER", str(marker))
    make_package(repo, "p", {"urdf/r.urdf.xacro": robot(f'  <link name="{payload}"/>')})
    findings, _ = lint(repo)
    codes = {f["code"] for f in findings}
    assert codes & {"UL903", "UL002"}, findings
    assert not marker.exists()


# -- no secrets out -------------------------------------------------------------------------
LEAKS = [
    '<link name="$(env CI_DEPLOY_TOKEN)"/>',
    '<link name="$(optenv AWS_SECRET_ACCESS_KEY fallback)"/>',
    '<link name="${xacro.arg(\'x\')}$(optenv CI_DEPLOY_TOKEN)"/>',
]


@pytest.mark.parametrize("payload", LEAKS)
def test_no_secrets_out(world, tmp_path, payload):
    repo, _, _ = world
    pkg = make_package(repo, "p", {"urdf/r.urdf.xacro": robot("  <xacro:arg name=\"x\" default=\"\"/>\n  " + payload)})
    findings, _ = lint(repo)
    assert_located(findings, "UL901")
    assert SECRET not in json.dumps(findings)
    # nor in an expanded URDF
    out = tmp_path / "out.urdf"
    p = run_cli("expand", pkg / "urdf/r.urdf.xacro", "-o", out, env={"CI_DEPLOY_TOKEN": SECRET,
                                                                    "AWS_SECRET_ACCESS_KEY": SECRET})
    assert SECRET not in p.stdout + p.stderr
    assert not out.exists() or SECRET not in out.read_text()


def test_allowed_env_is_read(world):
    repo, _, _ = world
    pkg = make_package(repo, "p", {"urdf/r.urdf.xacro": robot('  <link name="$(env MY_VARIANT)_x"/>')})
    (repo / "urdf-lint.toml").write_text('env-allow = ["MY_VARIANT"]\n')
    # issue 15: the repository's own env-allow counts only when the user trusts its config
    p = run_cli("check", ".", "--no-cache", "--format", "json", "--trust-config", cwd=repo,
                env={"MY_VARIANT": "mk2"})
    assert not [f for f in json.loads(p.stdout)["findings"] if f["code"] == "UL901"], p.stdout
    out = run_cli("expand", pkg / "urdf/r.urdf.xacro", "--trust-config",
                  env={"MY_VARIANT": "mk2"}).stdout
    assert '<link name="mk2_x"/>' in out
    out = run_cli("expand", pkg / "urdf/r.urdf.xacro", "--env-allow", "MY_VARIANT",
                  env={"MY_VARIANT": "mk2"}).stdout
    assert '<link name="mk2_x"/>' in out


# -- no files out ---------------------------------------------------------------------------
def test_include_outside_is_refused(world):
    repo, outside, _ = world
    make_package(repo, "p", {"urdf/r.urdf.xacro": robot(f'  <xacro:include filename="{outside}/secret.xacro"/>')})
    findings, _ = lint(repo)
    assert_located(findings, "UL902")


def test_load_yaml_outside_is_refused(world):
    repo, outside, _ = world
    make_package(repo, "p", {"urdf/r.urdf.xacro": robot(
        f'  <xacro:property name="s" value="${{xacro.load_yaml(\'{outside}/secret.yaml\')}}"/>\n'
        '  <link name="${s.token}"/>')})
    findings, _ = lint(repo)
    assert_located(findings, "UL902")


def test_symlinked_include_outside_is_refused(world):
    repo, outside, _ = world
    pkg = make_package(repo, "p", {"urdf/r.urdf.xacro": robot('  <xacro:include filename="inc.xacro"/>')})
    os.symlink(outside / "secret.xacro", pkg / "urdf/inc.xacro")
    findings, _ = lint(repo)
    assert_located(findings, "UL902")


def test_symlinked_mesh_outside_is_refused(world):
    repo, outside, _ = world
    pkg = make_package(repo, "p", {"urdf/r.urdf": '<robot name="r"><link name="a"><visual><geometry>'
                                   '<mesh filename="package://p/meshes/m.stl"/></geometry></visual></link></robot>'})
    (pkg / "meshes").mkdir()
    os.symlink(outside / "secret.stl", pkg / "meshes/m.stl")
    findings, _ = lint(repo)
    assert [f for f in findings if f["code"] == "UL403" and f["file"] == "p/urdf/r.urdf"], findings


# -- no hangs or blow-ups -------------------------------------------------------------------
@pytest.mark.parametrize("payload,code", [
    ('<link name="${9**9**9}"/>', "UL903"),
    ('<link name="${\'a\' * 10**10}"/>', "UL903"),
    ('<link name="${len([x for x in python.range(10**9)])}"/>', "UL903"),
    ('<xacro:macro name="m"><xacro:m/></xacro:macro>\n  <xacro:m/>', "UL904"),
    ('<link name="${1 &lt;&lt; 10**9}"/>', "UL903"),
])
def test_no_hangs(world, payload, code):
    repo, _, _ = world
    make_package(repo, "p", {"urdf/r.urdf.xacro": robot("  " + payload)})
    findings, took = lint(repo, "--timeout", "20")
    assert_located(findings, code)
    assert took < 20


def test_a_crafted_obj_cannot_stall_the_mesh_reader(world):
    """An OBJ number of 200,000 digits followed by a wrong character: a number pattern that
    could match it in several ways (``\\d+\\.?\\d*``) tried every split, minutes of work for
    one line. The reader declines the file at once and trimesh says what is wrong."""
    repo, _, _ = world
    make_package(repo, "p", {
        "urdf/r.urdf": '<robot name="r"><link name="a"><visual><geometry>'
                       '<mesh filename="package://p/meshes/m.obj"/></geometry></visual></link></robot>',
        "meshes/m.obj": "v " + "1" * 200_000 + "x 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n"})
    findings, took = lint(repo, "--timeout", "20")
    assert not [f for f in findings if f["code"] == "UL904"], findings
    assert took < 20


def test_time_limit_kills_and_others_still_lint(world):
    repo, _, _ = world
    make_package(repo, "p", {"urdf/r.urdf.xacro": robot('  <link name="${python.sum(python.range(10**13))}"/>'),
                             "urdf/ok.urdf": '<robot name="ok"><link name="a"/><link name="b"/></robot>'})
    findings, took = lint(repo, "--timeout", "3")
    hits = [f for f in findings if f["code"] == "UL904"]
    assert hits and "time limit" in hits[0]["message"]
    assert any(f["code"] == "UL104" and f["file"] == "p/urdf/ok.urdf" for f in findings)
    assert took < 15


def test_memory_limit(world):
    repo, _, _ = world
    make_package(repo, "p", {"urdf/r.urdf.xacro": robot('  <link name="${len(python.list(python.range(10**8)))}"/>')})
    (repo / "urdf-lint.toml").write_text("memory-mb = 400\n")
    findings, took = lint(repo)
    assert [f for f in findings if f["code"] in ("UL904", "UL903")], findings


# -- no XML tricks --------------------------------------------------------------------------
def test_external_entity_in_urdf(world):
    repo, outside, _ = world
    make_package(repo, "p", {"urdf/r.urdf": f'<?xml version="1.0"?>\n<!DOCTYPE robot [<!ENTITY s SYSTEM "file://{outside}/secret.yaml">]>\n<robot name="r"><link name="&s;"/></robot>\n'})
    findings, _ = lint(repo)
    assert [f for f in findings if f["code"] == "UL007" and f["line"] == 2]


def test_entity_in_xacro_is_refused(world):
    repo, outside, _ = world
    make_package(repo, "p", {"urdf/r.urdf.xacro": f'<?xml version="1.0"?>\n<!DOCTYPE robot [<!ENTITY s SYSTEM "file://{outside}/secret.yaml">]>\n<robot name="r" {X}><link name="&s;"/></robot>\n'})
    findings, _ = lint(repo)
    assert_located(findings, "UL007")


def test_billion_laughs(world):
    repo, _, _ = world
    ents = '<!ENTITY a0 "lol">' + "".join(f'<!ENTITY a{i} "&a{i-1};&a{i-1};&a{i-1};&a{i-1};&a{i-1};&a{i-1};&a{i-1};&a{i-1};&a{i-1};&a{i-1};">' for i in range(1, 10))
    for name in ("r.urdf", "r.urdf.xacro"):
        make_package(repo / name.replace(".", "_"), "p", {f"urdf/{name}": f'<?xml version="1.0"?>\n<!DOCTYPE robot [{ents}]>\n<robot name="r" {X}><link name="&a9;"/></robot>\n'})
    findings, took = lint(repo)
    assert len([f for f in findings if f["code"] == "UL007"]) >= 2
    assert took < 30


def test_safe_evaluator_still_computes_what_robots_compute():
    """The allow-list covers real descriptions (the corpus byte-identity test covers more)."""
    from urdf_lint.expansion.safe_eval import evaluate
    env = {"a": 2, "d": {"k": [1, 2, 3]}, "s": "left", "str": str}
    look = env.__getitem__
    import math
    assert evaluate("a * 3.5 + 1", look) == 8.0
    assert evaluate("[x * 2 for x in d['k'] if x > 1]", look) == [4, 6]
    assert evaluate("s.upper() + '_' + str(a)", look) == "LEFT_2"
    assert evaluate("'{}_{:.2f}'.format(s, 1/3)", look) == "left_0.33"
    assert evaluate("f'{s}-{a:03d}'", look) == "left-002"
    assert evaluate("1 if s == 'left' else -1", look) == 1
    assert evaluate("(lambda x: x + 1)(a)", look) == 3
    assert evaluate("{k: v for k, v in [('x', 1)]}", look) == {"x": 1}
    assert evaluate("2**10", look) == 1024
    assert abs(evaluate("max(1, 2) * 0.5", lambda n: {"max": max}[n]) - 1.0) < 1e-12
    assert evaluate("'%s-%d' % (s, a)", look) == "left-2"
    assert math.isclose(evaluate("sum([0.1, 0.2])", lambda n: {"sum": sum}[n]), 0.3)


def test_worker_audit_hook_blocks_processes_and_writes(tmp_path):
    """Second line of defence, tested on its own: inside a worker, even code that escaped the
    evaluator cannot start a process or write outside the cache/snapshot folders."""
    import subprocess
    import sys
    marker = tmp_path / "pwned"
    allowed = tmp_path / "cache"
    allowed.mkdir()
    code = f"""
import os, subprocess
from urdf_lint.runner.pool import _install_audit_hook
_install_audit_hook({str(allowed)!r})
results = []
for attempt in (lambda: os.system("touch {marker}"),
                lambda: subprocess.run(["touch", "{marker}"]),
                lambda: open("{marker}", "w"),
                lambda: os.remove("{tmp_path / 'x'}")):
    try:
        attempt()
        results.append("ran")
    except PermissionError:
        results.append("blocked")
with open("{allowed / 'ok.json'}", "w") as f:
    f.write("{{}}")
print(results)
"""
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert p.stdout.strip() == "['blocked', 'blocked', 'blocked', 'blocked']", p.stdout + p.stderr
    assert not marker.exists() and (allowed / "ok.json").exists()


# -- issue 15: no internal error on bad input ----------------------------------------------
def _check_text(repo, *extra, env=None, timeout=120):
    p = run_cli("check", ".", "--no-cache", *extra, cwd=repo, timeout=timeout,
                env=dict({"CI_DEPLOY_TOKEN": SECRET}, **(env or {})))
    assert "internal error" not in p.stderr, p.stderr
    assert SECRET not in p.stdout + p.stderr
    return p


DEEP = "<a>" * 300 + "</a>" * 300


@pytest.mark.parametrize("name,text", [
    ("urdf/r.urdf", f'<robot name="r"><link name="x"/>{DEEP}</robot>\n'),
    ("urdf/r.urdf.xacro", robot(DEEP)),
    ("urdf/r.urdf.xacro", robot('  <link name="' + "a" * (50 * 1024 * 1024) + '"/>')),
    ("urdf/r.urdf.xacro", robot("  <link name=\"${'a\\x01b'}\"/>")),
], ids=["deep-urdf", "deep-xacro", "50MB-attribute", "control-char-in-expression"])
def test_lxml_limits_are_located_findings(world, name, text):
    repo, _, _ = world
    make_package(repo, "p", {name: text})
    p = _check_text(repo, "--format", "json")
    assert p.returncode == 1, p.stderr
    findings = json.loads(p.stdout)["findings"]
    hits = assert_located(findings, "UL001", file=f"p/{name}")
    if name.endswith(".xacro"):  # at the element, not at the top of the file
        assert any(f["line"] >= 3 for f in hits), hits
    t = _check_text(repo)
    assert "All checks passed" not in t.stdout


def test_mesh_directory_and_symlink_loop_are_located(world):
    repo, _, _ = world
    mesh = ('<robot name="r"><link name="a"><visual><geometry><mesh filename="package://p/meshes/'
            '{}"/></geometry></visual></link></robot>\n')
    pkg = make_package(repo, "p", {"urdf/dir.urdf": mesh.format("d.stl"),
                                   "urdf/loop.urdf": mesh.format("l1.stl")})
    (pkg / "meshes" / "d.stl").mkdir(parents=True)
    os.symlink("l2.stl", pkg / "meshes" / "l1.stl")
    os.symlink("l1.stl", pkg / "meshes" / "l2.stl")
    findings, took = lint(repo)
    d = assert_located(findings, "UL401", file="p/urdf/dir.urdf")
    assert any("directory" in f["message"] for f in d), d
    lp = assert_located(findings, "UL401", file="p/urdf/loop.urdf")
    assert any("symbolic links" in f["message"] for f in lp), lp


def test_never_all_checks_passed_after_an_internal_error():
    import io
    from urdf_lint.report import registry as report
    from urdf_lint.run.pipeline import CheckResult
    out = io.StringIO()
    report.write(CheckResult(internal=["boom"]), "text", out)
    assert "All checks passed" not in out.getvalue() and "internal error" in out.getvalue()


def test_check_honours_ros_package_path_and_prints_no_env_value(world, tmp_path):
    repo, _, _ = world
    ext = tmp_path / "ext"
    make_package(ext, "extpkg", {"urdf/arm.xacro": f'<robot {X}><xacro:macro name="arm">'
                                 '<link name="arm"/></xacro:macro></robot>\n'})
    make_package(repo, "p", {"urdf/r.urdf.xacro": robot(
        '  <xacro:include filename="$(find extpkg)/urdf/arm.xacro"/>\n  <xacro:arm/>\n'
        '  <joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>')},
        depends=["extpkg"])   # (undeclared, $(find extpkg) is UL012: issue 33)
    ok = _check_text(repo, "--format", "json", env={"ROS_PACKAGE_PATH": str(ext)})
    assert json.loads(ok.stdout)["findings"] == [], ok.stdout
    # an unknown package names the variables it searched, never their values
    secret_dir = tmp_path / SECRET
    secret_dir.mkdir()
    bad = _check_text(repo, "--format", "json", env={"AMENT_PREFIX_PATH": str(secret_dir)})
    assert bad.returncode == 1
    f = assert_located(json.loads(bad.stdout)["findings"], "UL004")
    assert "AMENT_PREFIX_PATH (1 folder)" in f[0]["message"]


# -- issue 15: output that cannot be forged --------------------------------------------------
FORGED_NAME = "j&#10;::error file=x.py,line=1::pwned"


def _forging_repo(repo):
    pkg = make_package(repo, "p", {"urdf/r.urdf": (
        f'<robot name="r"><link name="base"/><joint name="{FORGED_NAME}" type="fixed">'
        '<parent link="base"/><child link="nope&#10;::warning::x"/></joint></robot>\n')})
    # a file name with a newline, a workflow command and an ANSI escape
    (pkg / "urdf" / "a\n::error file=y::\x1b[31mred.urdf").write_text(
        (pkg / "urdf" / "r.urdf").read_text())
    return pkg


@pytest.mark.parametrize("fmt", ["text", "github", "junit"])
def test_names_cannot_forge_output(world, fmt):
    repo, _, _ = world
    _forging_repo(repo)
    p = _check_text(repo, "--format", fmt, env={"GITHUB_ACTIONS": ""})
    assert p.returncode == 1
    lines = p.stdout.splitlines()
    assert "\x1b" not in p.stdout
    forged = [ln for ln in lines if ln.startswith("::") and ("pwned" in ln.split("::")[-1]
              and not ln.startswith("::error file=p/"))]
    assert not forged, lines
    if fmt == "github":
        assert all(ln.startswith("::") for ln in lines), lines
        assert len(lines) == 4
    else:
        assert not any(ln.startswith("::") for ln in lines), lines
    if fmt == "junit":
        import xml.dom.minidom
        xml.dom.minidom.parseString(p.stdout)
    else:
        assert "\\x0a::error file=x.py,line=1::pwned" in p.stdout


def test_summary_md_escapes_markdown_and_html():
    from urdf_lint.core.jobs import ModelReport
    from urdf_lint.run.pipeline import CheckResult
    from urdf_lint.render.snapshot import write_summary
    import tempfile
    m = ModelReport("/r/a.urdf", {"x": "<img src=x onerror=alert(1)>](http://evil) | `b`\n# h"},
                    links=1, snapshot={"png": "/tmp/s/a.png"})
    with tempfile.TemporaryDirectory() as d:
        text = open(write_summary(CheckResult(models=[m]), d), encoding="utf-8").read()
    import re
    for ln in text.splitlines():
        if ln.startswith(("### ", "![")):  # plain Markdown: no HTML, no link of the name's
            assert "<img" not in ln and not re.search(r"(?<!\\)\]\(http", ln), ln
    assert "\n# h" not in text
    row = next(ln for ln in text.splitlines() if ln.startswith("| `"))
    assert row.count(" | ") == 6, row  # the name did not add table cells


# -- issue 15: roots, precisely ---------------------------------------------------------------
def test_working_directory_is_never_a_root(world, tmp_path):
    """`cd / && urdf-lint check /tmp/x`: the folder the user stands in widens nothing."""
    repo, outside, _ = world
    make_package(repo, "p", {"urdf/r.urdf.xacro": robot(
        '  <xacro:include filename="../../../outside/secret.xacro"/>')})
    p = run_cli("check", repo, "--no-cache", "--format", "json", cwd=tmp_path)
    assert p.returncode == 1 and SECRET not in p.stdout + p.stderr
    hits = [f for f in json.loads(p.stdout)["findings"] if f["code"] == "UL902"]
    assert hits, p.stdout


def _git(*args, cwd):
    import subprocess
    subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True)


def test_without_git_roots_fail_closed(world, tmp_path):
    repo, _, _ = world
    make_package(repo, "a", {"urdf/r.urdf.xacro": robot(
        '  <xacro:include filename="../../b/lib.xacro"/>\n  <xacro:m/>')})
    (repo / "b").mkdir()
    (repo / "b" / "lib.xacro").write_text(f'<robot {X}><xacro:macro name="m"><link name="l"/>'
                                          '</xacro:macro></robot>\n')
    _git("init", "-q", cwd=repo)
    with_git = run_cli("check", "a", "--no-cache", "--format", "json", cwd=repo)
    assert not [f for f in json.loads(with_git.stdout)["findings"] if f["code"] == "UL902"]
    nogit = tmp_path / "nogit"
    nogit.mkdir()
    p = run_cli("check", "a", "--no-cache", "--format", "json", cwd=repo,
                env={"PATH": str(nogit)})
    assert p.returncode == 1
    assert [f for f in json.loads(p.stdout)["findings"] if f["code"] == "UL902"], p.stdout


def test_colcon_workspace_is_a_root(tmp_path):
    def two_packages(top):
        make_package(top, "other", {"urdf/arm.xacro": f'<robot {X}><xacro:macro name="arm">'
                                    '<link name="arm"/></xacro:macro></robot>\n'})
        make_package(top, "p", {"urdf/r.urdf.xacro": robot(
            '  <xacro:include filename="$(find other)/urdf/arm.xacro"/>\n  <xacro:arm/>\n'
            '  <joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>')},
            depends=("other",))
    # sibling folders that are no workspace: the neighbour is not a root, so not found
    two_packages(tmp_path / "loose")
    p = run_cli("check", tmp_path / "loose" / "p", "--no-cache", "--format", "json", cwd=tmp_path)
    assert [f["code"] for f in json.loads(p.stdout)["findings"]] == ["UL004"]
    # a colcon workspace (src/ holding packages) holding the linted path is a root
    two_packages(tmp_path / "ws" / "src")
    p = run_cli("check", tmp_path / "ws" / "src" / "p", "--no-cache", "--format", "json",
                cwd=tmp_path)
    assert json.loads(p.stdout)["findings"] == [], p.stdout


# -- issue 15: the linted repository cannot loosen the guarantees ------------------------------
def test_repository_config_cannot_loosen(world, tmp_path):
    repo, outside, _ = world
    make_package(repo, "p", {"urdf/r.urdf.xacro": robot(
        '  <link name="$(optenv CI_DEPLOY_TOKEN none)"/>\n'
        '  <xacro:include filename="$(find ext)/secret.xacro"/>')})
    (outside / "package.xml").write_text("<package><name>ext</name></package>")
    elsewhere = tmp_path / "elsewhere-cache"
    (repo / "urdf-lint.toml").write_text(
        'env-allow = ["CI_DEPLOY_TOKEN"]\n'
        f'package-paths = {{ ext = "{outside}" }}\n'
        f'cache-dir = "{elsewhere}"\n'
        'timeout = 100000\nmemory-mb = 1000000\njobs = 500\n')
    p = run_cli("check", ".", "--format", "json", cwd=repo, env={"CI_DEPLOY_TOKEN": SECRET})
    assert p.returncode == 1 and SECRET not in p.stdout + p.stderr
    for key in ("env-allow", "package-paths", "cache-dir", "timeout", "memory-mb", "jobs"):
        assert f"ignored '{key}'" in p.stderr, (key, p.stderr)
    codes = {f["code"] for f in json.loads(p.stdout)["findings"]}
    assert {"UL901", "UL004"} <= codes, codes
    assert not elsewhere.exists()


def test_numeric_limits_are_clamped():
    from urdf_lint.config import trust
    from urdf_lint.config.schema import Config
    cfg = Config(timeout=1e9, memory_mb=10 ** 9, jobs=10 ** 6, raw={})
    trust.apply(cfg, "/nonexistent", trusted=True)
    assert (cfg.timeout, cfg.memory_mb, cfg.jobs) == (600.0, 65536, 64)
    cfg = Config(timeout=-5, memory_mb=1, jobs=0, raw={})
    trust.clamp(cfg)
    assert (cfg.timeout, cfg.memory_mb, cfg.jobs) == (0.5, 128, 1)


# -- issue 15: the cache cannot lie -------------------------------------------------------------
BROKEN = '<robot name="r"><link name="a"/><link name="b"/></robot>\n'   # two roots: UL104


def _entries(repo):
    return sorted((repo / ".urdf_lint_cache" / "results").rglob("*.json"))


def test_forged_or_foreign_cache_entry_is_ignored(world, tmp_path):
    repo, _, _ = world
    make_package(repo, "p", {"urdf/r.urdf": BROKEN})
    key_a = {"XDG_CACHE_HOME": str(tmp_path / "home-a")}
    p = run_cli("check", ".", "--format", "json", cwd=repo, env=key_a)
    assert p.returncode == 1
    [entry] = _entries(repo)
    # forge "clean" into the entry, as a committed cache would
    mac, blob = entry.read_text().split("\n", 1)
    rec = json.loads(blob)
    assert rec["result"]["problems"]
    rec["result"]["problems"] = []
    entry.write_text(mac + "\n" + json.dumps(rec))
    p = run_cli("check", ".", "--format", "json", cwd=repo, env=key_a)
    assert p.returncode == 1 and json.loads(p.stdout)["models"][0]["cached"] is False
    # an entry signed with another key (another machine, a fresh clone) is ignored too
    p = run_cli("check", ".", "--format", "json", cwd=repo,
                env={"XDG_CACHE_HOME": str(tmp_path / "home-b")})
    assert p.returncode == 1 and json.loads(p.stdout)["models"][0]["cached"] is False
    key = tmp_path / "home-a" / "urdf-lint" / "key"
    assert key.stat().st_mode & 0o777 == 0o600


def test_git_tracked_or_symlinked_cache_is_refused(world, tmp_path):
    repo, _, _ = world
    make_package(repo, "p", {"urdf/r.urdf": BROKEN})
    _git("init", "-q", cwd=repo)
    run_cli("check", ".", cwd=repo)
    _git("add", "-f", ".urdf_lint_cache", cwd=repo)
    p = run_cli("check", ".", "--format", "json", cwd=repo)
    assert "not using the cache" in p.stderr and "tracked by git" in p.stderr
    assert json.loads(p.stdout)["models"][0]["cached"] is False
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    link_repo = tmp_path / "repo2"
    make_package(link_repo, "p", {"urdf/r.urdf": BROKEN})
    os.symlink(elsewhere, link_repo / ".urdf_lint_cache")
    p = run_cli("check", ".", "--format", "json", cwd=link_repo)
    assert "is a symlink" in p.stderr and not any(elsewhere.iterdir())


def test_cache_records_the_bytes_the_worker_read(tmp_path, monkeypatch):
    """A file edited during a run: the result of the old content is never filed under the new."""
    from urdf_lint.run.cache import Cache, file_record
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "home"))
    f = tmp_path / "r.urdf"
    f.write_text(BROKEN)
    read = file_record(str(f))                    # what the worker saw
    f.write_text('<robot name="r"><link name="a"/></robot>\n')   # edited meanwhile
    from urdf_lint.core.findings import Problem
    from urdf_lint.core.jobs import LintJob, LintSettings, ModelReport
    cache = Cache(str(tmp_path / "c"))
    job = LintJob(str(f), kind="urdf")
    settings = LintSettings(resolver={})
    res = ModelReport(str(f), {}, deps=[str(f)], problems=[Problem.at("UL104", "x", (str(f), 1, 1))],
                      digests={str(f): read})
    cache.put(job, settings, res)
    assert cache.get(job, settings) is None
    res.digests = {str(f): file_record(str(f))}
    cache.put(job, settings, res)
    assert cache.get(job, settings) is not None


def test_render_refuses_a_symlinked_out(world, tmp_path):
    repo, _, _ = world
    make_package(repo, "p", {"urdf/r.urdf": BROKEN})
    target = tmp_path / "target"
    target.mkdir()
    os.symlink(target, repo / "snaps")
    for cmd in (["render", ".", "--out", "snaps"], ["check", ".", "--render", "snaps"]):
        p = run_cli(*cmd, cwd=repo)
        assert p.returncode == 2 and "symlink" in p.stderr, p.stderr
    assert not any(target.iterdir())


def test_trimesh_is_pinned_to_5():
    import re
    from importlib.metadata import requires, version
    assert int(version("trimesh").split(".")[0]) >= 5
    assert any(re.match(r"trimesh\s*>=\s*5", r) for r in requires("urdf-lint"))


# -- issue 15: the parent reads nothing it should not --------------------------------------------
def _bounded(repo, *extra, timeout=60):
    """check must end quickly, with a bounded footprint, and no secret anywhere."""
    import resource
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    p = run_cli("check", ".", "--format", "json", *extra, cwd=repo, timeout=timeout,
                env={"CI_DEPLOY_TOKEN": SECRET})
    grown = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    assert grown < max(before, 1) + 2_000_000, grown  # KiB: well under 2 GB
    assert "internal error" not in p.stderr, p.stderr
    assert SECRET not in p.stdout + p.stderr
    return p


def test_entry_symlinked_to_dev_zero_or_outside(world):
    repo, outside, _ = world
    pkg = make_package(repo, "p", {"urdf/ok.urdf": BROKEN})
    os.symlink("/dev/zero", pkg / "urdf" / "zero.urdf")
    (outside / "secret.urdf").write_text(f'<robot name="{SECRET}"><link name="a"/></robot>\n')
    os.symlink(outside / "secret.urdf", pkg / "urdf" / "leak.urdf")
    t0 = time.monotonic()
    p = _bounded(repo)
    assert time.monotonic() - t0 < 30
    assert p.returncode == 1
    findings = json.loads(p.stdout)["findings"]
    assert_located(findings, "UL902", file="p/urdf/leak.urdf")
    assert [f for f in findings if f["file"] == "p/urdf/zero.urdf"], findings
    # the second run reads the cache: still bounded, still located
    p = _bounded(repo)
    assert [f for f in json.loads(p.stdout)["findings"] if f["file"] == "p/urdf/zero.urdf"]


def test_dae_texture_to_dev_zero_and_obj_mtllib_outside(world):
    repo, outside, _ = world
    (outside / "evil.mtl").write_text(f"newmtl m\nmap_Kd {SECRET}.png\n")
    dae = ('<?xml version="1.0"?><COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" '
           'version="1.4.1"><library_images><image id="i"><init_from>zero.png</init_from>'
           '</image></library_images></COLLADA>\n')
    mesh = ('<robot name="r"><link name="a"><visual><geometry><mesh filename="package://p/meshes/'
            '{}"/></geometry></visual></link></robot>\n')
    rel = os.path.relpath(outside / "evil.mtl", repo / "p" / "meshes")
    pkg = make_package(repo, "p", {"urdf/dae.urdf": mesh.format("m.dae"),
                                   "urdf/obj.urdf": mesh.format("m.obj"),
                                   "meshes/m.dae": dae,
                                   "meshes/m.obj": f"mtllib {rel}\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"})
    os.symlink("/dev/zero", pkg / "meshes" / "zero.png")
    t0 = time.monotonic()
    p = _bounded(repo, "--no-cache")
    p = _bounded(repo)
    p = _bounded(repo)
    assert time.monotonic() - t0 < 60
    assert SECRET not in p.stdout


def test_suppression_comments_are_read_only_from_the_roots(tmp_path):
    """Files the parent scans for suppression comments pass the same confinement as reads."""
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.engine.suppress import parse_directives
    inside = tmp_path / "repo"
    inside.mkdir()
    (inside / "a.xacro").write_text("<!-- urdf-lint: disable-file UL1 --><robot/>")
    os.symlink("/dev/zero", inside / "z.xacro")
    os.mkfifo(inside / "f.xacro")
    r = PackageResolver.build([inside], extra_roots=[inside])
    assert r.readable(inside / "a.xacro")
    assert not r.readable(inside / "z.xacro") and not r.readable(inside / "f.xacro")
    assert not r.readable("/etc/hostname")
    t0 = time.monotonic()
    assert parse_directives(str(inside / "f.xacro")) == []   # a FIFO does not block
    assert parse_directives(str(inside / "z.xacro")) == []
    assert time.monotonic() - t0 < 2
    assert parse_directives(str(inside / "a.xacro"))


def test_no_secret_in_cache_or_recordings(world, tmp_path):
    """The env secrets and a secret file outside the roots end up in no file urdf-lint writes:
    cache entries, mesh facts, .rrd recordings, PNGs, summary.md."""
    repo, outside, _ = world
    pkg = make_package(repo, "p", {"urdf/r.urdf.xacro": robot(
        '  <link name="$(optenv CI_DEPLOY_TOKEN x)">\n'
        '    <visual><geometry><mesh filename="package://p/meshes/m.stl"/></geometry></visual>\n'
        '  </link>\n  <joint name="j" type="fixed"><parent link="base"/>'
        '<child link="x"/></joint>')})
    (pkg / "meshes").mkdir()
    os.symlink(outside / "secret.stl", pkg / "meshes" / "m.stl")
    snaps = tmp_path / "snaps"
    p = run_cli("check", ".", "--render", snaps, cwd=repo, timeout=300,
                env={"CI_DEPLOY_TOKEN": SECRET, "XDG_CACHE_HOME": str(tmp_path / "home")})
    p2 = run_cli("check", ".", cwd=repo, env={"CI_DEPLOY_TOKEN": SECRET,
                                               "XDG_CACHE_HOME": str(tmp_path / "home")})
    assert p.returncode == p2.returncode == 1
    written = [f for top in (repo / ".urdf_lint_cache", snaps) for f in top.rglob("*")
               if f.is_file()]
    assert any(f.suffix == ".json" for f in written) and any(f.suffix == ".png" for f in written)
    for f in written:
        assert SECRET.encode() not in f.read_bytes(), f


# -- the shared escaping helper in the formats that came with the restructured main ---------------
def test_concise_format_cannot_be_forged(world):
    repo, _, _ = world
    _forging_repo(repo)
    p = _check_text(repo, "--format", "concise", env={"GITHUB_ACTIONS": ""})
    assert p.returncode == 1
    assert "\x1b" not in p.stdout
    assert not any(ln.startswith("::") for ln in p.stdout.splitlines()), p.stdout
    assert "\\x0a::error file=x.py,line=1::pwned" in p.stdout


def test_diff_reports_escape_names():
    """urdf-lint diff's text and markdown show a description's names as one visible line."""
    from urdf_lint.report import diff as diff_formats
    from urdf_lint.report.diff.markdown import to_markdown
    from urdf_lint.report.diff.text import to_text
    from urdf_lint.review.run import DiffResult
    from urdf_lint.review.robotdiff import Change, ModelDiff
    evil = "j\n::error file=x.py,line=1::pwned\x1b[31m\u202e"
    r = DiffResult("base", "head", models=[ModelDiff(
        "p/r.urdf", "changed", changes=[Change("joint", evil, "changed", "limit.upper",
                                                1.0, f"<img src=x> | `{evil}`")],
        error=evil)], total_models=1)
    text = to_text(r)
    assert "\x1b" not in text and "\u202e" not in text
    assert not any(ln.startswith("::") for ln in text.splitlines()), text
    md = to_markdown(r)
    assert "\x1b" not in md and "\u202e" not in md and "<img" not in md
    assert not any(ln.startswith("::") for ln in md.splitlines()), md
    for name, cls in diff_formats.formats().items():   # every registered format, a new one too
        out = cls().render(r)
        assert "\x1b" not in out and "\u202e" not in out, name
        assert not any(ln.startswith("::") for ln in out.splitlines()), (name, out)


def test_case_check_lists_no_folder_outside_the_roots(tmp_path, monkeypatch):
    """The case-mismatch check (UL402) walks folders to find the real spelling: only folders
    inside the package roots are ever listed, also for a reference that points outside them
    (issue 15: it listed the names of folders outside the roots)."""
    from types import SimpleNamespace
    from urdf_lint.meshes import resolve as meshes
    from urdf_lint.discovery.packages import PackageResolver
    outside = tmp_path / "Private" / "Keys"
    outside.mkdir(parents=True)
    (outside / "id.stl").write_text("solid x\nendsolid x\n")
    pkg = make_package(tmp_path / "repo", "p", {"meshes/Part.STL": "solid x\nendsolid x\n"})
    model = SimpleNamespace(resolver=PackageResolver.build([pkg]), base_dir=str(pkg / "urdf"))
    listed = []
    real = os.listdir
    monkeypatch.setattr(meshes.os, "listdir", lambda p: listed.append(os.path.realpath(p)) or real(p))
    monkeypatch.setattr(meshes, "_listings", {})
    inside = meshes.resolve(model, "package://p/meshes/part.stl")
    assert inside.status is meshes.MeshStatus.CASE_MISMATCH, inside
    for uri in (f"file://{tmp_path}/private/keys/ID.stl", f"file://{outside}/ID.stl",
                "package://p/../../../Private/keys/id.stl"):
        ref = meshes.resolve(model, uri)
        assert ref.status is not meshes.MeshStatus.OK and ref.status is not \
            meshes.MeshStatus.CASE_MISMATCH, (uri, ref)
    assert listed, "the inside reference was checked by listing its folders"
    root = os.path.realpath(pkg)
    assert all(p == root or p.startswith(root + os.sep) for p in listed), listed
