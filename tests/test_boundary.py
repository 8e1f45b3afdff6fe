"""One file-system boundary (``urdf_lint/core/fsbound.py``): no other module of ``urdf_lint/`` or
``rules/`` opens, globs, walks, parses, writes or removes a path itself.

The test walks the AST of every module and fails on a call that touches the file system
outside the boundary. The few exceptions are listed in :data:`ALLOWED`, each with the reason
it is not repository data or cannot go through the boundary; an entry that no longer matches
anything fails too, so the list stays short and true.
"""
from __future__ import annotations

import ast
from pathlib import Path

from conftest import REPO

BOUNDARY = "urdf_lint/core/fsbound.py"

# a call of one of these (module, function) pairs touches the file system
MODULE_CALLS = {
    "os": {"open", "walk", "fwalk", "scandir", "listdir", "remove", "unlink", "rename",
           "replace", "rmdir", "removedirs", "makedirs", "mkdir", "symlink", "link",
           "truncate"},
    "io": {"open", "FileIO"}, "codecs": {"open"},
    "glob": "*", "shutil": "*",
    "etree": {"parse", "iterparse", "XMLSchema", "DTD"},
    "ET": {"parse", "iterparse"}, "ElementTree": {"parse", "iterparse"}, "minidom": {"parse"},
    "np": {"fromfile", "load", "save", "loadtxt", "savetxt", "genfromtxt", "memmap"},
    "tarfile": {"open"}, "zipfile": {"ZipFile"},
    "trimesh": {"load", "load_scene", "load_mesh"},
    "collada": {"Collada"},
}
# a method of these names, whatever the receiver (pathlib.Path's file methods; ``.open``
# is Path.open, Image.open, tarfile.open, ...)
METHODS = {"read_text", "read_bytes", "write_text", "write_bytes", "open", "glob", "rglob",
           "iterdir", "mkdir", "touch", "unlink", "rmdir", "symlink_to", "hardlink_to",
           "tofile"}
SAVE = "save"      # img.save(path), rec.save(path): a method given a path (graph.save() is not)
BUILTINS = {"open"}
MODULES = {"glob", "shutil"}          # importing them at all

# (file, what) -> why it may do that outside the boundary
ALLOWED = {
    ("urdf_lint/meshes/readers.py", "np.loadtxt"):
        "parses a list holding one string, a COLLADA <float_array>'s text (a list is read as "
        "lines, never opened as a path)",
    ("urdf_lint/runner/pool.py", "open"):
        "reads /proc/self/status and /proc/stat: this process's memory and the machine's "
        "run queue, never a path from the repository",
    ("urdf_lint/runner/sandbox.py", "os.listdir"):
        "lists /proc/self/fd to close inherited descriptors before a worker reads a job",
    ("urdf_lint/runner/hardening.py", "open"):
        "reads /proc/self/status: this process's inherited memory, never a repository path",
    ("urdf_lint/runner/hardening.py", "os.listdir"):
        "lists /proc/self/fd to keep a worker's (or the recorder's) own descriptors",
    ("urdf_lint/run/cache.py", "os.open"):
        "the HMAC key in the user's own ~/.cache/urdf-lint (refused inside the repository), "
        "created O_CREAT|O_EXCL|O_NOFOLLOW 0600 and read O_NOFOLLOW",
    ("urdf_lint/run/cache.py", ".mkdir"):
        "the folder of that key (0700), outside the repository",
    ("urdf_lint/render/snapshot.py", "import shutil"):
        "shutil.which finds the rerun executable on PATH (no file is read or written)",
    ("urdf_lint/render/snapshot.py", "shutil.which"):
        "finds the rerun executable on PATH (no file is read or written)",
    ("urdf_lint/meshes/resolve.py", "trimesh.load"):
        "trimesh needs a file name (COLLADA/OBJ resolve their references from it); runs "
        "only in the sandboxed worker, after meshes._readable (inside the roots, regular, "
        "size-capped)",
    ("urdf_lint/meshes/resolve.py", "trimesh.load_scene"):
        "as trimesh.load: sandboxed worker, path checked by meshes._readable",
    ("urdf_lint/meshes/resolve.py", "collada.Collada"):
        "as trimesh.load: sandboxed worker, path checked by meshes._readable",
    ("urdf_lint/meshes/readers.py", "np.fromfile"):
        "reads binary STL records in chunks from the file object fsbound.open_regular "
        "opened (regular, non-blocking), not from a path",
    ("urdf_lint/render/raster.py", ".save"):
        "Pillow encodes into the exclusive temporary file fsbound.temp_path made in the "
        "checked snapshot folder (or into an in-memory buffer)",
    ("urdf_lint/render/recording.py", ".save"):
        "rerun writes a recording into the exclusive temporary file fsbound.temp_path made "
        "in the checked snapshot folder",
}


def _modules():
    for base in ("urdf_lint", "rules"):
        for p in sorted((REPO / base).rglob("*.py")):
            rel = p.relative_to(REPO).as_posix()
            if rel != BOUNDARY:
                yield rel, p


def _dotted(node) -> str | None:
    """``a.b.c`` of an attribute chain of names, else None."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if isinstance(node, ast.Name):
        parts.append(node.id)
        return ".".join(reversed(parts))
    return None


def _in_memory(call: ast.Call) -> bool:
    """A reader handed bytes, not a path: ``X(io.BytesIO(data))`` or ``X(fileobj=...)``."""
    first = call.args[0] if call.args else None
    if isinstance(first, ast.Call) and (_dotted(first.func) or "").endswith("BytesIO"):
        return True
    return any(k.arg == "fileobj" for k in call.keywords)


def file_system_calls(source: str) -> list[tuple[int, str]]:
    """(line, what) of every file-system call or import in ``source``."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            found += [(node.lineno, f"import {a.name}") for a in node.names
                      if a.name.split(".")[0] in MODULES]
        elif isinstance(node, ast.ImportFrom) and node.module:
            top = node.module.split(".")[0]
            if top in MODULES or any(
                    top in MODULE_CALLS and MODULE_CALLS[top] != "*"
                    and a.name in MODULE_CALLS[top] for a in node.names):
                found.append((node.lineno, f"from {node.module} import "
                              + ", ".join(a.name for a in node.names)))
        elif isinstance(node, ast.Call) and not _in_memory(node):
            f = node.func
            if isinstance(f, ast.Name) and f.id in BUILTINS:
                found.append((node.lineno, f.id))
            elif isinstance(f, ast.Attribute):
                name = _dotted(f)
                mod = name.rsplit(".", 2)[-2] if name and "." in name else None
                fns = MODULE_CALLS.get(mod or "")
                if mod == "fsbound":
                    continue
                if fns is not None and (fns == "*" or f.attr in fns):
                    found.append((node.lineno, f"{mod}.{f.attr}"))
                elif (f.attr in METHODS or f.attr == SAVE and node.args) and \
                        mod not in MODULE_CALLS:
                    found.append((node.lineno, f".{f.attr}"))
    return found


def test_no_module_touches_the_file_system_outside_the_boundary():
    bad, used = [], set()
    for rel, path in _modules():
        for line, what in file_system_calls(path.read_text(encoding="utf-8")):
            if (rel, what) in ALLOWED:
                used.add((rel, what))
                continue
            bad.append(f"{rel}:{line}: {what}")
    assert not bad, ("read, list and write files through urdf_lint/core/fsbound.py (or add an "
                     "entry with its reason to ALLOWED):\n" + "\n".join(bad))
    stale = sorted(set(ALLOWED) - used)
    assert not stale, f"ALLOWED entries that match nothing any more: {stale}"


def test_the_checker_sees_every_kind_of_file_access():
    """The AST check itself: each pattern it must refuse is found (else the test above could
    pass on anything)."""
    src = """
import glob, shutil
from os import walk
from pathlib import Path
from lxml import etree
def f(p):
    open(p)
    Path(p).read_text(); Path(p).read_bytes(); Path(p).write_text("x"); Path(p).write_bytes(b"")
    Path(p).open(); Path(p).glob("*"); Path(p).rglob("*"); Path(p).iterdir(); Path(p).mkdir()
    etree.parse(p); glob.glob(p); os.walk(p); os.scandir(p); os.listdir(p); shutil.rmtree(p)
    os.open(p, 0); os.remove(p); os.replace(p, p); os.makedirs(p)
    trimesh.load(p); np.fromfile(p); img.save(p); minidom.parse(p); ET.parse(p)
"""
    whats = [w for _, w in file_system_calls(src)]
    for expected in ["import glob", "import shutil", "from os import walk", "open",
                     ".read_text", ".read_bytes", ".write_text", ".write_bytes", ".open",
                     ".glob", ".rglob", ".iterdir", ".mkdir", "etree.parse", "glob.glob",
                     "os.walk", "os.scandir", "os.listdir", "shutil.rmtree", "os.open",
                     "os.remove", "os.replace", "os.makedirs", "trimesh.load", "np.fromfile",
                     ".save", "minidom.parse", "ET.parse"]:
        assert expected in whats, expected
    assert file_system_calls("x = s.replace('a', 'b'); fsbound.read_bytes(p)\n"
                             "tarfile.open(fileobj=b); collada.Collada(io.BytesIO(d))\n"
                             "graph.save()\n") == []


def test_the_allow_list_is_short_and_says_why():
    assert len(ALLOWED) <= 15
    for (rel, what), why in ALLOWED.items():
        assert Path(REPO, rel).is_file(), rel
        assert len(why) > 30, (rel, what)


# -- the routes of issue 21 that went around the boundary ------------------------------------
# Each is written as an attacker would: a repository (a git work tree) whose files and config
# are theirs, a secret file outside it and a secret in the environment. Each must end with a
# clean located refusal (or safely), write nothing outside the repository, print no secret
# and end in bounded time.
import json  # noqa: E402
import os  # noqa: E402
import subprocess  # noqa: E402
import time  # noqa: E402

import pytest  # noqa: E402

from conftest import make_package, run_cli  # noqa: E402

SECRET = "ghp_TOPSECRET_fsbound_0123456789"
X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
XACRO = f'<?xml version="1.0"?>\n<robot name="r" {X}>\n  <link name="base"/>\n</robot>\n'
RGBA_255 = ('<?xml version="1.0"?>\n<robot name="r">\n  <material name="red"><color rgba="255 0 0 1"/>'
            '</material>\n  <link name="a"/>\n</robot>\n')


@pytest.fixture()
def attack(tmp_path):
    """(repo, outside): a git repository with package ``p``, and a folder outside it holding
    a secret."""
    repo, outside = tmp_path / "repo", tmp_path / "outside"
    outside.mkdir()
    (outside / "secret.txt").write_text(f"token = {SECRET}\n")
    make_package(repo, "p", {"urdf/r.urdf.xacro": XACRO})
    subprocess.run(["git", "init", "-q"], cwd=repo, check=True)
    return repo, outside


def _files(top):
    return {os.path.join(d, f) for d, _, fs in os.walk(top) for f in fs} | \
        {d for d, _, _ in os.walk(top)}


def attempt(repo, outside, *args, timeout=60, codes=(0, 1, 2)):
    """Run urdf-lint in ``repo`` with a secret in its environment: no secret in its output,
    nothing new outside the repository, done within ``timeout``; the completed process."""
    before = _files(outside)
    t0 = time.monotonic()
    p = run_cli(*args, cwd=repo, timeout=timeout, env={"CI_DEPLOY_TOKEN": SECRET})
    assert time.monotonic() - t0 < timeout
    assert SECRET not in p.stdout + p.stderr, (p.stdout, p.stderr)
    assert "internal error" not in p.stderr, p.stderr
    assert _files(outside) == before, _files(outside) - before
    assert p.returncode in codes, (p.returncode, p.stdout, p.stderr)
    return p


def config(repo, text):
    (repo / "urdf-lint.toml").write_text(text)


# item 1
def test_generate_refuses_an_output_outside_the_repository_and_creates_no_folder(attack):
    repo, outside = attack
    config(repo, '[[models]]\npath = "p/urdf/r.urdf.xacro"\n'
                 'output = "../outside/site-packages/evil.pth"\n')
    p = attempt(repo, outside, "generate", ".", codes=(2,))
    assert "urdf-lint.toml:3: output = '../outside/site-packages/evil.pth' is outside the " \
           "repository" in p.stderr, p.stderr
    assert not (outside / "site-packages").exists()


# item 2
def _plant_tmp_links(path, target):
    """A symlink ``PATH.tmp<pid>`` for every pid the system can hand out."""
    pid_max = int(open("/proc/sys/kernel/pid_max").read()) if os.path.exists(
        "/proc/sys/kernel/pid_max") else 32768
    for pid in range(1, min(pid_max, 1 << 16) + 1):
        os.symlink(target, f"{path}.tmp{pid}")


def test_predictable_temp_names_cannot_redirect_generate_or_fix(attack):
    repo, outside = attack
    pwned = outside / "pwned.pth"
    config(repo, '[[models]]\npath = "p/urdf/r.urdf.xacro"\noutput = "p/urdf/r.urdf"\n')
    out = repo / "p" / "urdf" / "r.urdf"
    _plant_tmp_links(out, pwned)
    attempt(repo, outside, "generate", "p", codes=(1,), timeout=120)
    assert not pwned.exists()
    assert not out.is_symlink() and "<robot" in out.read_text()
    # check --fix rewrites a source in place the same way
    (repo / "urdf-lint.toml").unlink()
    fixed = repo / "p" / "urdf" / "c.urdf"
    fixed.write_text(RGBA_255)
    _plant_tmp_links(fixed, pwned)
    attempt(repo, outside, "check", "p", "--fix", "--no-cache", timeout=120)
    assert not pwned.exists()
    assert not fixed.is_symlink() and 'rgba="1 0 0 1"' in fixed.read_text()


# item 5
def test_show_source_prints_nothing_from_outside_the_roots(attack):
    repo, outside = attack
    (outside / "secret.urdf").write_text(f'<robot name="r">\n  <link name="{SECRET}"/>\n</robot>\n')
    config(repo, '[[models]]\npath = "p/urdf/r.urdf.xacro"\noutput = "../outside/secret.urdf"\n')
    p = attempt(repo, outside, "check", ".", "--show-source", "--no-cache", codes=(2,))
    assert "output = '../outside/secret.urdf' is outside the repository" in p.stderr
    # a user who trusts the config still gets no line of a file outside the roots
    attempt(repo, outside, "check", ".", "--show-source", "--no-cache", "--trust-config",
            codes=(1,))


# item 8
@pytest.mark.parametrize("kind", ["dev-stdout", "fifo"])
def test_special_files_never_block_discovery_or_header_detection(attack, kind):
    repo, outside = attack
    d = repo / "p" / "urdf"
    for name in ("s.xacro", "s.urdf"):   # discovery's parse; generated-output header detection
        if kind == "fifo":
            os.mkfifo(d / name)
        else:
            os.symlink("/dev/stdout", d / name)
    p = attempt(repo, outside, "check", ".", "--no-cache", "--format", "json", timeout=60,
                codes=(1,))
    assert {f["file"] for f in json.loads(p.stdout)["findings"]} >= {"p/urdf/s.xacro",
                                                                      "p/urdf/s.urdf"}
    attempt(repo, outside, "generate", ".", timeout=60, codes=(0,))


# item 9
def test_include_globs_are_bounded_in_the_parent(attack):
    repo, outside = attack
    d = repo / "p" / "urdf"
    for n in range(5):
        os.symlink(".", d / f"l{n}")
    pattern = "*/" * 30 + "x.xacro"
    (d / "g.urdf.xacro").write_text(
        f'<robot name="g" {X}>\n  <xacro:include filename="{pattern}"/>\n  <link name="a"/>\n</robot>\n')
    t0 = time.monotonic()
    p = attempt(repo, outside, "check", ".", "--no-cache", "--timeout", "3", "--format", "json",
                timeout=60, codes=(1,))
    assert time.monotonic() - t0 < 45
    assert [f for f in json.loads(p.stdout)["findings"] if f["file"] == "p/urdf/g.urdf.xacro"]


def test_unbounded_include_globs_count_as_unresolved(tmp_path):
    """A glob the parent can match within its bound is resolved as xacro would (the include
    graph needs it); one that would look at too many entries counts as unresolved."""
    from urdf_lint.discovery.discover import _read_includes
    f = tmp_path / "a.xacro"
    (tmp_path / "b.xacro").write_text(f'<robot {X}/>')
    for n in range(5):
        os.symlink(".", tmp_path / f"l{n}")
    f.write_text(f'<robot {X}><xacro:include filename="*.xacro"/>'
                 f'<xacro:include filename="{"*/" * 30}b.xacro"/></robot>')
    t0 = time.monotonic()
    inc, unresolved, _, _ = _read_includes(str(f), None)
    assert time.monotonic() - t0 < 5
    assert inc == [str(f.resolve()), str((tmp_path / "b.xacro").resolve())] and unresolved == 1


@pytest.mark.parametrize("pattern", ["*.xacro", "sub/*.xacro", "*/x?.xacro", "[ab].xacro",
                                     "nothing*", "*/*", ".h*", "*"])
def test_bounded_glob_matches_what_glob_matches(tmp_path, pattern, monkeypatch):
    import glob
    from urdf_lint.core.fsbound import bounded_glob
    for rel in ("a.xacro", "b.xacro", "sub/x1.xacro", "sub/y.xacro", ".hidden.xacro",
                "sub2/x2.xacro"):
        (tmp_path / rel).parent.mkdir(exist_ok=True)
        (tmp_path / rel).write_text("")
    os.symlink("sub", tmp_path / "lnk")
    for base in (str(tmp_path) + os.sep, ""):
        monkeypatch.chdir(tmp_path)
        assert sorted(bounded_glob(base + pattern)) == sorted(glob.glob(base + pattern))


# item 12
@pytest.mark.parametrize("cmd", [["render", ".", "--out", "build/snaps"],
                                 ["check", ".", "--render", "build/snaps"]])
def test_snapshots_never_go_through_a_committed_symlinked_folder(attack, cmd):
    repo, outside = attack
    snaps = outside / "snaps"
    snaps.mkdir()
    victim = snaps / "victim.png"
    victim.write_bytes(b"users' own picture")
    import hashlib
    # a planted manifest naming the victim with its digest: the cleaner must not reach it
    (snaps / ".urdf-lint-snapshots.json").write_text(json.dumps({"files": {
        "victim.png": hashlib.blake2b(victim.read_bytes(), digest_size=16).hexdigest()}}))
    os.symlink(outside, repo / "build")
    p = attempt(repo, outside, *cmd, codes=(2,))
    assert "build" in p.stderr and "symlink" in p.stderr, p.stderr
    assert victim.exists()


def test_the_stale_snapshot_cleaner_checks_every_component(tmp_path):
    from urdf_lint.core.fsbound import BoundaryError
    from urdf_lint.render.snapshot import clear_stale
    (tmp_path / "real" / "snaps").mkdir(parents=True)
    os.symlink(tmp_path / "real", tmp_path / "link")
    with pytest.raises(BoundaryError, match="symlink"):
        clear_stale(str(tmp_path / "link" / "snaps"), str(tmp_path))


# item 16
def test_a_baseline_from_the_config_is_confined_and_bounded(attack):
    repo, outside = attack
    config(repo, 'baseline = "/dev/zero"\n')
    p = attempt(repo, outside, "check", ".", "--no-cache", codes=(2,), timeout=30)
    assert "urdf-lint.toml:1: baseline = '/dev/zero' is outside the repository" in p.stderr
    # trusted (or named on the command line) it is still read only as a bounded regular file
    for extra in (["--trust-config"], ["--baseline", "/dev/zero"]):
        p = attempt(repo, outside, "check", ".", "--no-cache", *extra, codes=(2,), timeout=30)
        assert "not a regular file" in p.stderr, p.stderr


# item 18
@pytest.mark.parametrize("name", ["urdf-lint.toml", "pyproject.toml"])
def test_deeply_nested_toml_is_a_config_error(attack, name):
    repo, outside = attack
    body = "x = " + "[" * 50_000 + "]" * 50_000 + "\n"
    (repo / name).write_text(body if name != "pyproject.toml" else "[tool.urdf-lint]\n" + body)
    p = attempt(repo, outside, "check", ".", "--no-cache", codes=(2,))
    assert f"{name}: invalid TOML: nested too deeply" in p.stderr, p.stderr


def test_an_absolute_symlink_in_a_diffed_tree_is_not_an_internal_error(attack):
    repo, outside = attack

    def git(*a):
        subprocess.run(["git", "-c", "user.email=t@t", "-c", "user.name=t", *a], cwd=repo,
                       check=True, capture_output=True)
    git("add", "-A")
    git("commit", "-qm", "base")
    os.symlink(outside / "secret.txt", repo / "p" / "urdf" / "abs.xacro")
    os.symlink("/etc/hostname", repo / "p" / "urdf" / "etc.urdf")
    git("add", "-A")
    git("commit", "-qm", "head")
    attempt(repo, outside, "diff", "HEAD~1", "HEAD", codes=(0, 1))


# config paths (task item 3): confined like package-paths
@pytest.mark.parametrize("entry, key", [
    ('[[models]]\npath = "p/urdf/r.urdf.xacro"\nmesh-base = "../outside"\n', "mesh-base"),
    ('[[models]]\npath = "p/urdf/r.urdf.xacro"\noutput = "gen/r.urdf"\n', "output"),
    ('baseline = "gen/baseline.json"\n', "baseline"),
])
def test_config_paths_must_stay_in_the_repository_without_symlinks(attack, entry, key):
    repo, outside = attack
    os.symlink(outside, repo / "gen")
    config(repo, entry)
    line = entry.count("\n")
    p = attempt(repo, outside, "check", ".", "--no-cache", codes=(2,))
    assert f"urdf-lint.toml:{line}: {key} = " in p.stderr, p.stderr
    assert ("goes through the symlink 'gen'" in p.stderr) or "outside the repository" in p.stderr
    # the user may trust the config
    attempt(repo, outside, "check", ".", "--no-cache", "--trust-config", codes=(0, 1, 2))


def test_the_parent_writes_no_path_a_worker_sent_outside_the_output_folder(tmp_path):
    """A worker's reply is data: a snapshot path pointing elsewhere (a compromised worker,
    a forged result) is not written by the parent, which holds the secrets."""
    import types
    import zlib
    from urdf_lint.render.snapshot import finish_snapshots
    out, elsewhere = tmp_path / "snaps", tmp_path / "elsewhere"
    out.mkdir()
    elsewhere.mkdir()
    image = (2, 2, zlib.compress(b"\x00" * 12))
    evil = types.SimpleNamespace(label="m", entry=str(tmp_path / "m.urdf"), links=1, snapshot={
        "name": "../elsewhere/x", "png": str(elsewhere / "x.png"), "rrd": None, "problems": [],
        "image": image, "title": "m"})
    good = types.SimpleNamespace(label="g", entry=str(tmp_path / "g.urdf"), links=1, snapshot={
        "name": "g", "png": str(out / "g.png"), "rrd": None, "problems": [],
        "image": image, "title": "g"})
    finish_snapshots([evil, good], [], str(out))
    assert list(elsewhere.iterdir()) == []
    assert evil.snapshot["png"] is None and "not in the output folder" in evil.snapshot["problems"][0]
    assert (out / "g.png").is_file()


def test_config_paths_inside_the_repository_are_kept(attack):
    repo, outside = attack
    config(repo, 'baseline = "base.json"\n[[models]]\npath = "p/urdf/r.urdf.xacro"\n'
                 'mesh-base = "."\noutput = "p/urdf/gen/r.urdf"\n')
    attempt(repo, outside, "check", ".", "--no-cache", "--write-baseline", "base.json",
            codes=(0,))
    attempt(repo, outside, "generate", ".", codes=(1,))   # written: it was stale
    assert (repo / "p" / "urdf" / "gen" / "r.urdf").is_file()
    attempt(repo, outside, "generate", ".", codes=(0,))


def test_a_deeply_nested_planted_manifest_is_ignored(attack):
    """The snapshot folder's manifest may be committed: 50,000 nested arrays in it are not
    an internal error (nothing it names is removed)."""
    repo, outside = attack
    snaps = repo / "snapshots"
    snaps.mkdir()
    (snaps / ".urdf-lint-snapshots.json").write_text("[" * 50_000 + "]" * 50_000)
    (snaps / "keep.png").write_bytes(b"theirs")
    attempt(repo, outside, "render", ".", "--out", "snapshots", "--no-rrd", codes=(0, 1))
    assert (snaps / "keep.png").read_bytes() == b"theirs"
