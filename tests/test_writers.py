"""The formatter and every writer (issue 31): ``format``, ``check --fix`` and ``generate`` write
through the boundary's one rewrite (:func:`urdf_lint.core.fsbound.rewrite`), which

* resolves a path before deciding it is inside: a symlink named on the command line whose
  target is outside the repository is refused (one located error, exit 2, nothing written);
  one whose target is inside is written through and stays a link (as before);
* is a compare-and-swap: the file must still hold the bytes urdf-lint read, else it is
  skipped with a message and the user's edit survives (the lost update);
* keeps the owner, group and mode of the file it replaces (run as root, another user's file
  stays theirs).

The formatter's proof holds for every value of every arg: whitespace in an ``xacro:if`` body
that only expanding could prove (the models are expanded with the args they are given) is
left as it is. And ``format`` over a repository of symlinks to a secret folder opens nothing
outside the repository, the cache and the runtime (strace)."""
from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

from conftest import DESCRIPTIONS, make_package, run_main
from support import strace

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
# a URDF the formatter lays out (one element per line) and --fix edits (rgba 0..255 -> 0..1)
UGLY = ('<?xml version="1.0"?>\n<robot name="r"><material name="red"><color rgba="255 0 0 1"/>'
        '</material><link name="a"/></robot>\n')
SECRET = b'<robot name="secret"><link name="top_secret"/></robot>\n'


@pytest.fixture()
def repo(tmp_path):
    """(a git repository with package ``p``, a folder outside it holding a secret xacro)."""
    root, outside = tmp_path / "repo", tmp_path / "outside"
    outside.mkdir()
    (outside / "secret.xacro").write_bytes(SECRET)
    make_package(root, "p", {"urdf/r.urdf": UGLY})
    subprocess.run(["git", "init", "-q"], cwd=root, check=True)
    return root, outside


# -- symlinks -------------------------------------------------------------------------------------
def test_format_refuses_a_named_symlink_whose_target_is_outside_the_repository(repo):
    root, outside = repo
    (root / "p" / "urdf" / "evil.xacro").symlink_to(outside / "secret.xacro")
    p = run_main("format", "p/urdf/evil.xacro", cwd=root)
    assert p.returncode == 2, (p.stdout, p.stderr)
    assert "evil.xacro:1:1: resolves outside the repository" in p.stderr, p.stderr
    assert (outside / "secret.xacro").read_bytes() == SECRET
    # with another path named too, that one is still formatted
    p = run_main("format", "p/urdf/evil.xacro", "p/urdf/r.urdf", cwd=root)
    assert p.returncode == 2 and (outside / "secret.xacro").read_bytes() == SECRET
    assert (root / "p" / "urdf" / "r.urdf").read_text() != UGLY


def test_fix_refuses_a_named_symlink_whose_target_is_outside_the_repository(repo):
    root, outside = repo
    (outside / "c.urdf").write_text(UGLY)
    (root / "p" / "urdf" / "c.urdf").symlink_to(outside / "c.urdf")
    p = run_main("check", "p/urdf/c.urdf", "--fix", "--no-cache", "--isolated", cwd=root)
    assert p.returncode in (0, 1), p.stderr
    assert "UL902" in p.stdout + p.stderr      # (not read: as before issue 31, a guard)
    assert (outside / "c.urdf").read_text() == UGLY


def test_format_writes_through_a_named_symlink_whose_target_is_inside_the_repository(repo):
    # (as before issue 31: the link stays a link, its target gets the new layout)
    root, _ = repo
    link = root / "link.urdf"
    link.symlink_to("p/urdf/r.urdf")
    p = run_main("format", "link.urdf", cwd=root)
    assert p.returncode == 0, p.stderr
    assert link.is_symlink() and os.readlink(link) == "p/urdf/r.urdf"
    assert (root / "p" / "urdf" / "r.urdf").read_text().startswith(
        '<?xml version="1.0"?>\n<robot name="r">\n  <material name="red">\n')


# the modules that write repository sources: format, check --fix, --add-suppressions, generate
SOURCE_WRITERS = ("cli/format.py", "run/fix.py", "fix/addsuppress.py", "discovery/generated.py",
                  "cli/generate.py")


def test_format_fix_and_generate_write_only_through_the_one_rewrite():
    import ast
    import urdf_lint
    top = Path(urdf_lint.__file__).parent
    for rel in SOURCE_WRITERS:
        tree = ast.parse((top / rel).read_text())
        calls = {n.func.attr for n in ast.walk(tree) if isinstance(n, ast.Call)
                 and isinstance(n.func, ast.Attribute) and isinstance(n.func.value, ast.Name)
                 and n.func.value.id == "fsbound"}
        writes = calls & {"write_bytes", "write_text", "open_write", "temp_path", "rewrite"}
        assert writes <= {"rewrite"}, (rel, writes)
    assert "rewrite" in {n.func.attr for n in ast.walk(ast.parse(
        (top / "discovery/generated.py").read_text())) if isinstance(n, ast.Call)
        and isinstance(n.func, ast.Attribute)}


# -- the lost update --------------------------------------------------------------------------
EDIT = '<?xml version="1.0"?>\n<robot name="r"><!-- the user saved this --><link name="a"/></robot>\n'


def _user_saves_after(monkeypatch, module, name: str, f) -> list:
    """Make ``module.name`` save ``EDIT`` to ``f`` once it returns (the first time): the user's
    editor saving the file after urdf-lint read it and before it writes it. The list gets one
    item when it did."""
    real, saved = getattr(module, name), []

    def then_the_user_saves(*args, **kw):
        out = real(*args, **kw)
        if not saved:
            f.write_text(EDIT)
            saved.append(1)
        return out
    monkeypatch.setattr(module, name, then_the_user_saves)
    return saved


def test_format_keeps_an_edit_saved_while_its_proof_runs(repo, monkeypatch):
    import urdf_lint.cli.format as cli_format
    root, _ = repo
    f = root / "p" / "urdf" / "r.urdf"
    saved = _user_saves_after(monkeypatch, cli_format, "prove", f)
    p = run_main("format", ".", cwd=root)
    assert saved and f.read_text() == EDIT
    assert "r.urdf: skipped: it changed while urdf-lint formatted it" in p.stderr, p.stderr
    assert p.returncode == 1 and "internal error" not in p.stderr


def test_fix_keeps_an_edit_saved_while_it_works(repo, monkeypatch):
    import urdf_lint.run.fix as run_fix
    root, _ = repo
    f = root / "p" / "urdf" / "r.urdf"
    # (edited_sources reads the file and computes the fixed bytes; the write follows)
    saved = _user_saves_after(monkeypatch, run_fix, "edited_sources", f)
    p = run_main("check", ".", "--fix", "--no-cache", "--isolated", cwd=root)
    assert saved and f.read_text() == EDIT
    assert "r.urdf: skipped: it changed while urdf-lint fixed it" in p.stderr, p.stderr
    assert "internal error" not in p.stderr and p.returncode in (0, 1)


def test_generate_keeps_an_edit_saved_while_it_works(repo, monkeypatch):
    import urdf_lint.discovery.generated as generated
    root, _ = repo
    (root / "p" / "urdf" / "m.urdf.xacro").write_text(
        f'<?xml version="1.0"?>\n<robot name="m" {X}>\n  <link name="base"/>\n</robot>\n')
    (root / "urdf-lint.toml").write_text('[[models]]\npath = "p/urdf/m.urdf.xacro"\n'
                                         'output = "p/urdf/m.urdf"\n')
    out = root / "p" / "urdf" / "m.urdf"
    out.write_text('<robot name="m"><link name="stale"/></robot>\n')
    saved = _user_saves_after(monkeypatch, generated, "stale_at", out)
    p = run_main("generate", ".", cwd=root)
    assert saved and out.read_text() == EDIT
    assert "m.urdf: skipped: it changed while urdf-lint regenerated it" in p.stderr, p.stderr
    assert p.returncode == 1 and "internal error" not in p.stderr


# -- owner, group and mode ------------------------------------------------------------------------
@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() != 0, reason="needs root")
@pytest.mark.parametrize("command", [("format", "."),
                                     ("check", ".", "--fix", "--no-cache", "--isolated")])
def test_a_rewritten_file_keeps_its_owner_group_and_mode(repo, command):
    root, _ = repo
    f = root / "p" / "urdf" / "r.urdf"
    os.chown(f, 1000, 1000)
    os.chmod(f, 0o640)
    p = run_main(*command, cwd=root)
    assert f.read_text() != UGLY, p.stderr     # it was rewritten
    st = f.stat()
    assert (st.st_uid, st.st_gid, st.st_mode & 0o7777) == (1000, 1000, 0o640)


# -- the proof for every value of every arg -------------------------------------------------------
SIM = (f'<robot name="m" {X}>\n  <xacro:arg name="sim" default="false"/>\n  <link name="l"/>\n'
       '  <xacro:if value="$(arg sim)"><gazebo><plugin name="p" filename="x.so"><robotNamespace>'
       '<xacro:if value="1">/sim</xacro:if></robotNamespace></plugin></gazebo></xacro:if>\n'
       '</robot>\n')


def test_whitespace_under_an_xacro_if_on_an_unset_arg_is_not_changed_by_format(tmp_path):
    # nobody configured sim: the models are expanded with sim:=false, where the body is not
    # written; with sim:=true (a launch file) the layout would move /sim off its line
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.expansion import expand_file
    f = tmp_path / "m.urdf.xacro"
    f.write_text(SIM)

    def sim_true() -> str:
        res = expand_file(str(f), {"sim": "true"}, build_resolver([str(tmp_path)],
                                                                   load_config(None)))
        assert res.error is None, res.error
        return res.xml
    before = sim_true()
    assert "<robotNamespace>/sim</robotNamespace>" in before
    p = run_main("format", ".", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert sim_true() == before
    assert "cannot be proved for every value of the args" in p.stderr, p.stderr


# -- what format opens ----------------------------------------------------------------------------
def test_format_opens_nothing_outside_the_repository_through_symlinks(repo):
    why = strace.available()
    if why:
        pytest.skip(why)
    root, outside = repo
    tmp = root.parent
    (outside / "sub").mkdir()
    (outside / "sub" / "inner.xacro").write_bytes(SECRET)
    (outside / "urdf-lint.toml").write_text("[format]\nindent = 8\n")
    urdf = root / "p" / "urdf"
    (urdf / "evil.xacro").symlink_to(outside / "secret.xacro")
    (urdf / "evil.urdf").symlink_to(outside / "secret.xacro")
    (urdf / "folder").symlink_to(outside)
    (root / "p" / "meshes").symlink_to(outside / "sub")
    (root / "q").mkdir()
    (root / "q" / "package.xml").symlink_to(outside / "secret.xacro")
    # (a model that includes them: the proof expands it, and reads what its files include)
    (urdf / "m.urdf.xacro").write_text(
        f'<robot name="m" {X}><xacro:include filename="evil.xacro"/>'
        '<xacro:include filename="folder/sub/inner.xacro"/><link name="a"/></robot>\n')
    env = {"XDG_CACHE_HOME": str(tmp / "cache"), "TMPDIR": str(tmp / "tmp"),
           "HOME": str(tmp / "home")}
    allowed = (root, tmp / "cache", tmp / "tmp", tmp / "home")
    for d in allowed[1:]:
        d.mkdir()
    paths, p = strace.opened(["format", "."], cwd=root, env=env)
    assert p.returncode == 0 and "Traceback" not in p.stderr, p.stderr
    assert str(urdf / "r.urdf") in paths, sorted(paths)[:20]   # (it traced what it formatted)
    assert strace.outside_allowed(paths, *allowed) == []
    assert (urdf / "r.urdf").read_text() != UGLY and "top_secret" not in p.stdout + p.stderr
    assert (outside / "secret.xacro").read_bytes() == SECRET
    # a committed config that is a symlink out of the repository is refused, never read
    (root / "urdf-lint.toml").symlink_to(outside / "urdf-lint.toml")
    paths, p = strace.opened(["format", "."], cwd=root, env=env)
    assert p.returncode == 2, p.stderr
    assert "urdf-lint.toml is a symlink leading out of its folder" in p.stderr, p.stderr
    assert strace.outside_allowed(paths, *allowed) == []


# -- a full disk ----------------------------------------------------------------------------
def _file_size_limit(n: int):
    """For a child: writes past ``n`` bytes fail with EFBIG, as on a full disk (SIGXFSZ off)."""
    import resource
    import signal

    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (n, n))
    return limit


def test_fix_on_a_full_disk_is_one_error_and_leaves_every_source_whole(tmp_path):
    """``check --fix`` whose writes fail (a full disk: here a file size limit) says which file
    it could not write, exits 2 and leaves every source as it was, with no temporary file;
    it was an "internal error (please report)" naming no file."""
    import shutil
    import sys
    shutil.copytree(DESCRIPTIONS / "broken", tmp_path / "broken")
    before = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    p = subprocess.run([sys.executable, "-m", "urdf_lint", "check", ".", "--fix", "--no-cache",
                        "-q"], cwd=tmp_path / "broken", capture_output=True, text=True,
                       preexec_fn=_file_size_limit(64))
    lines = p.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("urdf-lint: error: cannot write "), p.stderr
    assert lines[0].endswith(".xacro: File too large") and p.returncode == 2, p.stderr
    after = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    assert after == before


def test_only_a_write_to_standard_output_is_called_one():
    """A full disk or quota (ENOSPC, EDQUOT, EFBIG) with no file named is standard output's; an
    I/O error only where the failing call was a write to it (a read fails with EIO too), and an
    error naming a file never (the boundary names the file of every read and write)."""
    import errno
    from urdf_lint.core import fsbound
    from urdf_lint.core.emit import stdout_failed
    assert stdout_failed(OSError(errno.ENOSPC, "No space left on device"))
    assert stdout_failed(OSError(errno.EDQUOT, "Disk quota exceeded"))
    assert not stdout_failed(OSError(errno.EIO, "Input/output error"))
    assert stdout_failed(OSError(errno.EIO, "Input/output error"), certain=True)
    assert not stdout_failed(OSError(errno.ENOSPC, "No space left on device", "a.urdf"))
    assert not stdout_failed(BrokenPipeError(errno.EPIPE, "Broken pipe"))
    with pytest.raises(OSError) as got:
        with fsbound._named("meshes/m.stl"):
            raise OSError(errno.EIO, "Input/output error")    # (a read of a failing disk)
    assert got.value.filename == "meshes/m.stl" and not stdout_failed(got.value, certain=True)
