"""End to end with the real pre-commit tool: the hook from this checkout lints the models a
commit affects, through the includes, YAML files and meshes they read."""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from conftest import DESCRIPTIONS, REPO

pytestmark = pytest.mark.skipif(shutil.which("git") is None, reason="needs git")


def sh(*cmd, cwd, check=True, env=None):
    e = dict(os.environ)
    e.update(env or {})
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, env=e, timeout=900)
    if check and p.returncode != 0:
        raise AssertionError(f"{cmd} failed:\n{p.stdout}\n{p.stderr}")
    return p


@pytest.fixture(scope="module")
def hook_repo(tmp_path_factory):
    head = sh("git", "rev-parse", "HEAD", cwd=REPO).stdout.strip()
    dirty = sh("git", "status", "--porcelain", "--untracked-files=no", "--", "urdf_lint", "rules",
               "pyproject.toml", ".pre-commit-hooks.yaml", cwd=REPO).stdout.strip()
    if dirty and not os.environ.get("CI"):
        pytest.skip("the pre-commit test installs the hook from HEAD: commit first")
    work = tmp_path_factory.mktemp("precommit") / "robots"
    work.mkdir()
    shutil.copytree(DESCRIPTIONS / "r2d2_description", work / "r2d2_description")
    # docs/ci.md's snippet as pasted, pointed at this checkout and its HEAD
    from test_cli_conventions import documented_precommit_config
    snippet = documented_precommit_config()
    repo_url = re.search(r"repo: (\S+)", snippet).group(1)
    (work / ".pre-commit-config.yaml").write_text(
        snippet.replace(repo_url, str(REPO)).replace("rev: v0.1.0", f"rev: {head}"))
    (work / ".gitignore").write_text(".urdf_lint_cache/\n")
    sh("git", "init", "-q", cwd=work)
    sh("git", "config", "user.email", "t@example.invalid", cwd=work)
    sh("git", "config", "user.name", "t", cwd=work)
    home = Path(tempfile.gettempdir(), "urdf-lint-pre-commit-home")
    env = {"PRE_COMMIT_HOME": str(home), "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}
    sh(sys.executable, "-m", "pre_commit", "install", cwd=work, env=env)
    return work, env


def commit(work, env, msg):
    sh("git", "add", "-A", cwd=work)
    return sh("git", "commit", "-q", "-m", msg, cwd=work, check=False, env=env)


def replace(path, old, new):
    text = path.read_text()
    assert old in text, (path, old)
    path.write_text(text.replace(old, new))


def test_hook_follows_includes_yaml_and_meshes(hook_repo):
    work, env = hook_repo
    pkg = work / "r2d2_description"
    # 1. a clean first commit passes
    p = commit(work, env, "initial")
    assert p.returncode == 0, p.stdout + p.stderr
    # 2. a clean change passes
    replace(pkg / "urdf/r2d2_macros.xacro", 'mass="10" x="0.2"', 'mass="11" x="0.2"')
    p = commit(work, env, "heavier legs")
    assert p.returncode == 0, p.stdout + p.stderr
    # 3. break a macro in the included file: the finding is at the included file's line
    macros = pkg / "urdf/r2d2_macros.xacro"
    replace(macros, '<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>')
    line = next(i for i, t in enumerate(macros.read_text().splitlines(), 1) if '<axis xyz="0 0 0"/>' in t)
    p = commit(work, env, "break wheels")
    out = p.stdout + p.stderr
    assert p.returncode != 0, out
    assert "urdf-lint" in out and "Failed" in out
    # one finding for the macro line, the four wheels it makes folded under it (issue 24)
    assert f"r2d2_description/urdf/r2d2_macros.xacro:{line}:7: UL307 joint '" in out, out
    assert "in 4 joints:" in out and "right_back_wheel_joint" in out, out
    assert "called from r2d2_description/urdf/r2d2_macros.xacro:" in out
    # 4. fix it: passes again
    replace(macros, '<axis xyz="0 0 0"/>', '<axis xyz="0 1.0 0"/>')
    p = commit(work, env, "fix wheels")
    assert p.returncode == 0, p.stdout + p.stderr
    # 5. a YAML value breaks a joint: reported at the xacro line that uses the value
    replace(pkg / "config/joint_limits.yaml", "gripper_extension: {lower: -0.38, upper: 0.0",
            "gripper_extension: {lower: 0.38, upper: 0.0")
    p = commit(work, env, "bad yaml")
    out = p.stdout + p.stderr
    assert p.returncode != 0 and "UL302" in out and "r2d2_description/urdf/r2d2.urdf.xacro:" in out, out
    replace(pkg / "config/joint_limits.yaml", "lower: 0.38, upper: 0.0", "lower: -0.36, upper: 0.0")
    assert commit(work, env, "fix yaml").returncode == 0
    # 6. a mesh replaced by a Git LFS pointer fails where the macro uses it
    good = (pkg / "meshes/l_finger.stl").read_bytes()
    (pkg / "meshes/l_finger.stl").write_text("version https://git-lfs.github.com/spec/v1\noid sha256:0\nsize 1\n")
    p = commit(work, env, "lfs pointer")
    out = p.stdout + p.stderr
    assert p.returncode != 0 and "UL404" in out and "r2d2_description/urdf/r2d2_macros.xacro:" in out, out
    (pkg / "meshes/l_finger.stl").write_bytes(b"re-exported finger".ljust(80, b" ") + good[80:])
    assert commit(work, env, "real mesh").returncode == 0
    # 7. a file no model reads does not fail the hook, and is mentioned
    (pkg / "urdf/unused.xacro").write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
                                           '<xacro:macro name="u"/></robot>\n')
    p = commit(work, env, "unused macro file")
    assert p.returncode == 0, p.stdout + p.stderr


def assert_passes(p):
    """The hook passed (after restoring a file the commit may have nothing left to commit)."""
    out = p.stdout + p.stderr
    assert "Failed" not in out and ("Passed" in out or p.returncode == 0), out


def test_hook_deletions_and_renames(hook_repo):
    """pre-commit passes only files that exist; the hook asks git for what the commit deletes
    or renames away and re-lints the models that read it."""
    work, env = hook_repo
    pkg = work / "r2d2_description"
    assert commit(work, env, "start clean").returncode in (0, 1)   # nothing to commit is fine
    # 1. deleting the macro file fails at the include in the model
    macros = pkg / "urdf/r2d2_macros.xacro"
    saved = macros.read_bytes()
    macros.unlink()
    p = commit(work, env, "drop macros")
    out = p.stdout + p.stderr
    assert p.returncode != 0 and "(no files to check)" not in out, out
    assert "r2d2_description/urdf/r2d2.urdf.xacro:8:3: UL003 included file not found" in out, out
    macros.write_bytes(saved)
    assert_passes(commit(work, env, "macros back"))
    # 2. renaming the YAML file fails at the xacro line that loads it; following the rename passes
    sh("git", "mv", "r2d2_description/config/joint_limits.yaml",
       "r2d2_description/config/limits.yaml", cwd=work)
    p = commit(work, env, "rename yaml")
    out = p.stdout + p.stderr
    assert p.returncode != 0 and "UL003" in out and "joint_limits.yaml" in out, out
    assert "r2d2_description/urdf/r2d2.urdf.xacro:44:5: UL003" in out, out
    replace(pkg / "urdf/r2d2.urdf.xacro", "config/joint_limits.yaml", "config/limits.yaml")
    p = commit(work, env, "follow the rename")
    assert p.returncode == 0, p.stdout + p.stderr
    # 3. deleting a mesh fails where the macro uses it; restoring it passes
    mesh = pkg / "meshes/l_finger.stl"
    saved = mesh.read_bytes()
    mesh.unlink()
    p = commit(work, env, "drop mesh")
    out = p.stdout + p.stderr
    assert p.returncode != 0 and "UL401" in out, out
    assert "r2d2_description/urdf/r2d2_macros.xacro:116:11: UL401" in out, out
    mesh.write_bytes(saved)
    assert_passes(commit(work, env, "mesh back"))
    # 4. deleting the model itself does not fail the commit (check notes it as gone)
    (pkg / "urdf/r2d2.urdf.xacro").unlink()
    p = commit(work, env, "drop the robot")
    assert p.returncode == 0, p.stdout + p.stderr


# -- issue 21 item 6: a committed file named like an option is only a file -------------------
HOOK_SECRET = "hunter2-token-of-the-ci-job"
OPTION_NAMED = "--env-allow=TOKEN,x.yaml"
X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
LEAKING_XACRO = f"""<robot name="r" {X}>
  <xacro:property name="lim" value="${{xacro.load_yaml('$(find p)/../{OPTION_NAMED}')}}"/>
  <link name="base"/>
  <link name="arm"/>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="${{lim['lower']}}" upper="${{lim['upper']}}" effort="1" velocity="1"/>
  </joint>
  <joint name="k" type="fixed"><parent link="arm"/><child link="$(optenv TOKEN nobody)"/></joint>
</robot>
"""


def test_a_file_named_like_an_option_is_only_a_file(tmp_path):
    """pre-commit appends the commit's file names to the hook's arguments: a committed
    `--env-allow=TOKEN,x.yaml` became an option and the model printed the CI job's token.
    With the shipped hook (and with a user's own `args:` that lack the final `--`) the name
    is a file: the YAML it names is linted through the model that reads it, no secret."""
    head = sh("git", "rev-parse", "HEAD", cwd=REPO).stdout.strip()
    dirty = sh("git", "status", "--porcelain", "--untracked-files=no", "--", "urdf_lint",
               "pyproject.toml", ".pre-commit-hooks.yaml", cwd=REPO).stdout.strip()
    if dirty and not os.environ.get("CI"):
        pytest.skip("the pre-commit test installs the hook from HEAD: commit first")
    from test_cli_conventions import documented_precommit_config
    snippet = documented_precommit_config()
    repo_url = re.search(r"repo: (\S+)", snippet).group(1)
    config = snippet.replace(repo_url, str(REPO)).replace("rev: v0.1.0", f"rev: {head}")
    work = tmp_path / "robots"
    pkg = work / "p"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="3"><name>p</name><version>0.0.0</version>'
        '<description>t</description><maintainer email="a@b.c">t</maintainer>'
        '<license>BSD</license></package>\n')
    (pkg / "urdf" / "r.urdf.xacro").write_text(LEAKING_XACRO)
    yaml_file = work / OPTION_NAMED
    yaml_file.write_text("lower: -1.0\nupper: 1.0\n")
    (work / ".pre-commit-config.yaml").write_text(config)
    (work / ".gitignore").write_text(".urdf_lint_cache/\n")
    sh("git", "init", "-q", cwd=work)
    sh("git", "config", "user.email", "t@example.invalid", cwd=work)
    sh("git", "config", "user.name", "t", cwd=work)
    sh("git", "add", "-A", cwd=work)
    sh("git", "commit", "-q", "-n", "-m", "initial", cwd=work)
    home = Path(tempfile.gettempdir(), "urdf-lint-pre-commit-home")
    env = {"PRE_COMMIT_HOME": str(home), "TOKEN": HOOK_SECRET,
           "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}

    def run_hook():
        sh("git", "add", "-A", cwd=work)
        p = sh(sys.executable, "-m", "pre_commit", "run", "urdf-lint", cwd=work, env=env,
               check=False)
        sh("git", "commit", "-q", "-n", "-m", "step", cwd=work, check=False)
        return p.returncode, p.stdout + p.stderr

    # 1. the xacro and the option-named YAML change together: the token stays out (the env
    #    read is refused, UL901) and the YAML's bad limits are reported
    (pkg / "urdf" / "r.urdf.xacro").write_text(LEAKING_XACRO + "<!-- touched -->\n")
    yaml_file.write_text("lower: 1.0\nupper: -1.0\n")
    code, out = run_hook()
    assert HOOK_SECRET not in out, out
    assert code != 0 and "UL901" in out and "UL302" in out, out
    # 2. only the YAML changes: it reaches the hook as a file, so its model is linted
    yaml_file.write_text("lower: 2.0\nupper: -2.0\n")
    code, out = run_hook()
    assert code != 0 and "UL302" in out and "2 > upper -2" in out, out
    # 3. a user's own args without the final `--`: still a file, said so, no token
    (work / ".pre-commit-config.yaml").write_text(config.replace(
        "# args: [--baseline, urdf-lint-baseline.json, --]", "args: [--fail-on, error]"))
    assert "args: [--fail-on, error]" in (work / ".pre-commit-config.yaml").read_text()
    (pkg / "urdf" / "r.urdf.xacro").write_text(LEAKING_XACRO + "<!-- again -->\n")
    yaml_file.write_text("lower: 3.0\nupper: -3.0\n")
    code, out = run_hook()
    assert HOOK_SECRET not in out, out
    assert code != 0 and "3 > upper -3" in out and "UL901" in out, out
    assert f"{OPTION_NAMED} is a file, not an option" in out, out


def test_documented_local_hook_works_as_pasted(tmp_path):
    """docs/ci.md's ``repo: local`` snippet, pasted unchanged into a repository where urdf-lint
    is installed (on PATH, as `pip install` puts it): a clean commit passes, a broken joint
    fails at its xacro line."""
    from test_cli_conventions import documented_precommit_config
    work = tmp_path / "robots"
    shutil.copytree(DESCRIPTIONS / "r2d2_description", work / "r2d2_description")
    (work / ".pre-commit-config.yaml").write_text(documented_precommit_config("local"))
    (work / ".gitignore").write_text(".urdf_lint_cache/\n")
    sh("git", "init", "-q", cwd=work)
    sh("git", "config", "user.email", "t@example.invalid", cwd=work)
    sh("git", "config", "user.name", "t", cwd=work)
    env = {"PRE_COMMIT_HOME": str(tmp_path / "pre-commit-home"),
           "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}
    sh(sys.executable, "-m", "pre_commit", "install", cwd=work, env=env)
    p = commit(work, env, "initial")
    assert p.returncode == 0 and "urdf-lint" in p.stdout + p.stderr, p.stdout + p.stderr
    macros = work / "r2d2_description/urdf/r2d2_macros.xacro"
    replace(macros, '<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>')
    line = next(i for i, t in enumerate(macros.read_text().splitlines(), 1)
                if '<axis xyz="0 0 0"/>' in t)
    p = commit(work, env, "break wheels")
    out = p.stdout + p.stderr
    assert p.returncode != 0 and "Failed" in out, out
    assert f"r2d2_description/urdf/r2d2_macros.xacro:{line}:7: UL307" in out, out


def test_warnings_are_seen_when_the_hook_passes(hook_repo):
    """A warning (an attribute URDF parsers ignore; a misspelt <orgin> is an error now, issue
    25) does not fail the commit, and
    pre-commit hides a passing hook's output: the hook is verbose, so the finding and the
    one-line summary are shown on the passing commit (issue 22)."""
    work, env = hook_repo
    assert commit(work, env, "start clean").returncode in (0, 1)   # nothing to commit is fine
    typo = work / "typo_description" / "urdf" / "typo.urdf"
    typo.parent.mkdir(parents=True)
    typo.write_text('<robot name="typo">\n  <link name="a"/>\n  <link name="b"/>\n'
                    '  <joint name="j" type="fixed">\n    <parent link="a"/>\n'
                    '    <child link="b"/>\n    <origin xyz="0 0 1" spin="1"/>\n  </joint>\n</robot>\n')
    p = commit(work, env, "a typo")
    out = p.stdout + p.stderr
    assert p.returncode == 0 and "Passed" in out, out
    assert "typo_description/urdf/typo.urdf:7:5: UL210 unknown attribute 'spin'" in out, out
    assert re.search(r"urdf-lint: 1 model\(s\) affected by 1 file\(s\): 0 error\(s\), "
                     r"\d+ warning\(s\), \d+ info \(\d+ in the committed files\)", out), out
    # a commit with no robot file says so in one line
    (work / "README.txt").write_text("notes\n")
    p = commit(work, env, "notes")
    out = p.stdout + p.stderr
    assert p.returncode == 0 and "urdf-lint: no robot description file in this commit" in out, out
