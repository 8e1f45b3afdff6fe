"""Roots are an immutable snapshot per run (issue 21, items 3 and 4): a package name is never a
path, ``share/NAME`` of an ament prefix really is a child of it, and no pass of a run (discovery,
``check --fix`` round 2, ``--add-suppressions``' second pass, ``diff``'s robot reload) can widen
what the workers may read. Each case is a real repository, run as a user would, with
``AMENT_PREFIX_PATH`` set (a ROS 2 CI job), with the OS sandbox on and off."""
from __future__ import annotations

import dataclasses
import json
import os
import subprocess

import pytest

from conftest import make_package, run_cli

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
SECRET = "ghp_TOPSECRET_0123456789abcdef"
HEAD = f'<?xml version="1.0"?>\n<robot name="{{}}" {X}>\n'
# a fixable finding (UL307, a non-unit axis) in a model of its own, so --fix has a round 2
FIXME = (HEAD.format("fixme") + '  <link name="a"/><link name="b"/>\n'
         '  <joint name="j" type="continuous"><parent link="a"/><child link="b"/>'
         '<axis xyz="0 0 2"/></joint>\n</robot>\n')


def _git(*args, cwd):
    subprocess.run(["git", "-c", "user.email=t@t", "-c", "user.name=t", *args], cwd=cwd,
                   check=True, capture_output=True)


def _attack(tmp_path, form: str):
    """A committed repository whose xacro includes ``$(find NAME)/secret.xacro`` with NAME a
    path to a secret folder, and an ament prefix (the CI job's ``AMENT_PREFIX_PATH``)."""
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "secret.xacro").write_text(f'<robot {X}><link name="{SECRET}"/></robot>\n')
    (outside / "secret.yaml").write_text(f"token: {SECRET}\n")
    prefix = tmp_path / "prefix"
    (prefix / "share" / "ament_index" / "resource_index" / "packages").mkdir(parents=True)
    name = str(outside) if form == "absolute" else "../" * 40 + str(outside).lstrip("/")
    repo = tmp_path / "repo"
    attack = (HEAD.format("r") + '  <link name="base"/>\n'
              f'  <xacro:include filename="$(find {name})/secret.xacro"/>\n'
              f'  <xacro:property name="s" value="${{xacro.load_yaml(\'$(find {name})/secret.yaml\')}}"/>\n'
              '  <link name="${s.token}"/>\n</robot>\n')
    make_package(repo, "p", {"urdf/r.urdf.xacro": attack, "urdf/fixme.urdf.xacro": FIXME})
    _git("init", "-q", cwd=repo)
    _git("add", "-A", cwd=repo)
    _git("commit", "-qm", "base", cwd=repo)
    return repo, {"AMENT_PREFIX_PATH": str(prefix), "CI_DEPLOY_TOKEN": SECRET}


SANDBOX = pytest.mark.parametrize("sandbox", ["1", "0"], ids=["sandbox-on", "sandbox-off"])
FORMS = pytest.mark.parametrize("form", ["absolute", "dotdot"])


def _no_secret(p):
    assert SECRET not in p.stdout + p.stderr, (p.stdout, p.stderr)
    assert "internal error" not in p.stderr, p.stderr
    return p


@SANDBOX
@FORMS
def test_find_of_a_path_is_a_located_unknown_package_in_check(tmp_path, form, sandbox):
    repo, env = _attack(tmp_path, form)
    p = _no_secret(run_cli("check", ".", "--no-cache", "--format", "json", cwd=repo,
                           env=dict(env, URDF_LINT_SANDBOX=sandbox), timeout=120))
    assert p.returncode == 1, p.stderr
    hits = [f for f in json.loads(p.stdout)["findings"] if f["code"] == "UL004"]
    assert hits and hits[0]["file"] == "p/urdf/r.urdf.xacro" and hits[0]["line"] == 4, hits
    assert "not a ROS package name" in hits[0]["message"]


@SANDBOX
@FORMS
@pytest.mark.parametrize("command,says", [("--fix", "Fixed 1 finding"),
                                          ("--add-suppressions", "suppression comment")])
def test_fix_and_add_suppressions_second_pass_gets_no_wider_roots(tmp_path, form, sandbox,
                                                                   command, says):
    """``check --fix`` lints again after fixing (round 2), ``--add-suppressions`` after
    adding the comments: both with the run's one snapshot of the roots."""
    repo, env = _attack(tmp_path, form)
    p = _no_secret(run_cli("check", ".", command, "--no-cache", cwd=repo,
                           env=dict(env, URDF_LINT_SANDBOX=sandbox), timeout=120))
    assert says in p.stderr, p.stderr
    assert SECRET not in (repo / "p/urdf/r.urdf.xacro").read_text()
    if command == "--fix":
        assert "UL004" in p.stdout, p.stdout
        assert 'xyz="0 0 1"' in (repo / "p/urdf/fixme.urdf.xacro").read_text()


@SANDBOX
@FORMS
def test_diff_robot_reload_gets_no_wider_roots(tmp_path, form, sandbox):
    repo, env = _attack(tmp_path, form)
    r = repo / "p/urdf/r.urdf.xacro"
    r.write_text(r.read_text().replace('<link name="base"/>', '<link name="base"/><link name="c"/>'))
    p = _no_secret(run_cli("diff", "HEAD", "--format", "markdown", "--no-cache", cwd=repo,
                           env=dict(env, URDF_LINT_SANDBOX=sandbox), timeout=120))
    assert p.returncode in (0, 1), p.stderr
    assert "not a ROS package name" in p.stdout, p.stdout


def test_a_symlinked_ament_share_leading_out_is_no_package(tmp_path):
    """``share/NAME`` listed by the ament index but symlinked out of the prefix (an install
    step of the repository can make one) is not that package."""
    from urdf_lint.discovery.packages import PackageNotFound, PackageResolver
    outside = tmp_path / "outside"
    outside.mkdir()
    prefix = tmp_path / "prefix"
    index = prefix / "share" / "ament_index" / "resource_index" / "packages"
    index.mkdir(parents=True)
    for name in ("evil", "good"):
        (index / name).write_text("")
    os.symlink(outside, prefix / "share" / "evil")
    (prefix / "share" / "good").mkdir()
    repo = tmp_path / "repo"
    repo.mkdir()
    env = dict(os.environ, AMENT_PREFIX_PATH=str(prefix))
    old = os.environ.get("AMENT_PREFIX_PATH")
    os.environ["AMENT_PREFIX_PATH"] = env["AMENT_PREFIX_PATH"]
    try:
        res = PackageResolver.build([repo], extra_roots=[repo])
    finally:
        if old is None:
            del os.environ["AMENT_PREFIX_PATH"]
        else:
            os.environ["AMENT_PREFIX_PATH"] = old
    assert res.find("good") == prefix / "share" / "good"
    with pytest.raises(PackageNotFound):
        res.find("evil")
    assert res.is_inside(prefix / "share" / "good" / "x.xacro")
    assert not res.is_inside(prefix / "share" / "evil" / "x.xacro")
    assert not res.is_inside(outside / "x.xacro")


@pytest.mark.parametrize("name,ok", [
    ("ur_description", True), ("abb_irb2400_support", True), ("Franka-Description", True),
    ("3d_sensors", True), ("/etc", False), ("..", False), (".", False), ("../x", False),
    ("a/b", False), ("a.b", False), ("-rf", False), ("", False), ("a\\b", False),
    ("a\x00b", False), ("x" * 201, False),
])
def test_package_names_are_names_not_paths(name, ok):
    from urdf_lint.discovery.packages import valid_package_name
    assert valid_package_name(name) is ok


def test_every_corpus_package_name_is_valid(corpus):
    from urdf_lint.discovery.packages import PackageResolver, valid_package_name
    names = PackageResolver.build([corpus]).scanned
    assert len(names) > 10
    assert [n for n in names if not valid_package_name(n)] == []


def test_the_resolver_is_an_immutable_snapshot(tmp_path, monkeypatch):
    """Looking packages up (found in the environment, or not found) changes nothing a worker
    gets, and nothing can be added to the roots."""
    from urdf_lint.discovery.packages import PackageNotFound, PackageResolver
    ext = tmp_path / "ext"
    make_package(ext, "extpkg", {"urdf/a.xacro": f"<robot {X}/>\n"})
    repo = tmp_path / "repo"
    make_package(repo, "p", {})
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(ext))
    res = PackageResolver.build([repo], extra_roots=[repo])
    before = res.to_dict()
    assert res.find("extpkg") == (ext / "extpkg").resolve()
    for bad in ("nopkg", str(tmp_path), "../" * 9 + "etc"):
        with pytest.raises(PackageNotFound):
            res.find(bad)
    assert res.to_dict() == before
    with pytest.raises(dataclasses.FrozenInstanceError):
        res.roots = (tmp_path,)  # type: ignore[misc]
    with pytest.raises(AttributeError):
        res.roots.append(tmp_path)  # type: ignore[attr-defined]
    with pytest.raises(TypeError):
        res.scanned["x"] = tmp_path  # type: ignore[index]
    # the environment's packages are roots, deterministically (not only once looked up)
    fresh = PackageResolver.from_dict(before)
    assert fresh.is_inside(ext / "extpkg" / "urdf" / "a.xacro")
    assert not fresh.is_inside(tmp_path / "elsewhere")
    import pickle
    assert pickle.loads(pickle.dumps(res)).to_dict() == before


def test_a_jobs_real_paths_are_asked_once_and_forgotten_with_it(tmp_path, monkeypatch):
    """Within one lint job (``paths_fixed``, entered by the worker per job) the roots test
    resolves a path's symlinks once; the next job (or the language server's next edit) sees a
    symlink that changed meanwhile."""
    from urdf_lint.core import tree
    from urdf_lint.discovery.packages import PackageResolver
    pkg, outside = tmp_path / "pkg", tmp_path / "outside"
    (pkg / "meshes").mkdir(parents=True)
    outside.mkdir()
    link = pkg / "meshes" / "m"
    link.symlink_to(pkg / "meshes")
    res = PackageResolver(roots=(pkg,))
    asked = []
    real = os.path.realpath
    monkeypatch.setattr(tree.os.path, "realpath", lambda p: asked.append(p) or real(p))
    with tree.paths_fixed():
        assert res.is_inside(link) and res.is_inside(link) and res.is_inside(str(link))
        assert len(asked) == 1
        link.unlink()
        link.symlink_to(outside)
        assert res.is_inside(link)     # (the job's first answer)
    assert not res.is_inside(link)     # the next job: outside the roots
    with tree.paths_fixed():
        assert not res.is_inside(link)
