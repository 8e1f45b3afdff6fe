"""The repository model (issue 10): which files are robots (discovery by include graph),
``check FILE`` on a fragment, deletions and renames, config entries, workspaces, generated
outputs and the cache folder. Every case is a fixture repository in the shape of a real one."""
from __future__ import annotations

import json
import re
import os
import shutil
import subprocess

import pytest

from conftest import CORPUS, run_cli
from repo_shapes import colcon_workspace, generated_output_repo, includes_only_repo, write


def entries(p):
    return sorted(m["entry"] for m in json.loads(p.stdout)["models"])


def git(*args, cwd):
    subprocess.run(["git", "-c", "user.email=t@t", "-c", "user.name=t", *args], cwd=cwd,
                   check=True, capture_output=True)


V3 = "v3_description/urdf/"


def test_entry_made_only_of_includes_is_the_one_model(tmp_path):
    includes_only_repo(tmp_path)
    p = run_cli("check", ".", "--no-cache", "--format", "json", cwd=tmp_path)
    assert p.returncode == 0, p.stdout + p.stderr
    # the fragments (including the conditional-only tool.xacro) are never linted alone
    assert entries(p) == [V3 + "robot_v3.xacro"]
    assert json.loads(p.stdout)["findings"] == []
    # the fragments really are read through the model: break the conditional one
    tool = tmp_path / V3 / "tool.xacro"
    tool.write_text(tool.read_text().replace('parent link="arm"', 'parent link="arm2"'))
    p = run_cli("check", ".", "--no-cache", cwd=tmp_path)
    assert p.returncode == 1 and f"{V3}tool.xacro:" in p.stdout and "UL103" in p.stdout, p.stdout


def test_check_file_on_fragment_lints_including_models(tmp_path):
    includes_only_repo(tmp_path)
    (tmp_path / V3 / "arm.xacro").write_text(
        (tmp_path / V3 / "arm.xacro").read_text().replace('<axis xyz="0 0 1"/>', '<axis xyz="0 0 0"/>'))
    p = run_cli("check", V3 + "arm.xacro", "--no-cache", "--format", "json", cwd=tmp_path)
    assert entries(p) == [V3 + "robot_v3.xacro"], p.stdout + p.stderr
    assert "is included by v3_description/urdf/robot_v3.xacro" in p.stderr
    codes = {f["code"] for f in json.loads(p.stdout)["findings"]}
    assert codes == {"UL307"} and p.returncode == 1
    # a macro library no model includes: one clear note, no "robot has no <link>"
    (tmp_path / "lib.xacro").write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
                                        '<xacro:macro name="m"/></robot>\n')
    p = run_cli("check", "lib.xacro", "--no-cache", cwd=tmp_path)
    assert p.returncode == 0 and "UL006" not in p.stdout and "UL201" not in p.stdout
    assert p.stderr.count("lib.xacro") == 1 and "not used by any model" in p.stderr


def test_fragment_listed_as_model_gets_a_hint(tmp_path):
    includes_only_repo(tmp_path)
    (tmp_path / "urdf-lint.toml").write_text(f'[[models]]\npath = "{V3}tool.xacro"\n')
    p = run_cli("check", ".", "--no-cache", cwd=tmp_path)
    assert p.returncode == 1
    line = next(t for t in p.stdout.splitlines() if "UL002" in t)
    assert "deg_to_rad" in line and "included by v3_description/urdf/robot_v3.xacro" in line
    assert "lint v3_description/urdf/robot_v3.xacro instead, or list it under models" in line


def test_corpus_fragments_and_include_only_entries(corpus, tmp_path):
    p = run_cli("check", corpus / "robot_properties_fingers", "--no-cache", "--format", "json",
                "--isolated", cwd=tmp_path)
    got = {e.split("robot_properties_fingers/")[-1] for e in entries(p)}
    # entries of the MANIFEST that only include other files are linted
    for e in ("trifinger_with_stage.urdf.xacro", "edu/trifingeredu_with_stage.urdf.xacro",
              "pro/trifingerpro_with_stage.urdf.xacro"):
        assert "xacro_files/" + e in got
    # included robots that stand alone stay entries; the MANIFEST's fragments do not
    assert "xacro_files/trifinger.urdf.xacro" in got and "xacro_files/stage.urdf.xacro" in got
    assert "xacro_files/trifinger_stage.urdf.xacro" not in got
    assert "xacro_files/edu/trifingeredu_stage.urdf.xacro" not in got
    assert not any("base_link' is not defined" in f["message"] and "xacro_files/" in f["file"]
                   for f in json.loads(p.stdout)["findings"])


def test_config_states_entries_exactly(tmp_path):
    includes_only_repo(tmp_path)
    (tmp_path / "urdf-lint.toml").write_text(f'[[models]]\npath = "{V3}robot_v3.xacr"\n')
    p = run_cli("check", ".", "--no-cache", cwd=tmp_path)
    assert p.returncode == 2 and p.stdout == ""
    assert f"model '{V3}robot_v3.xacr' does not exist (did you mean '{V3}robot_v3.xacro'?)" in p.stderr
    (tmp_path / "urdf-lint.toml").write_text(
        f'[[models]]\npath = "{V3}robot_v3.xacro"\nargs = [{{with_tol = "false"}}]\n')
    p = run_cli("check", ".", "--no-cache", cwd=tmp_path)
    # xacro accepts an undeclared arg: a located warning at the config line, not exit 2
    assert p.returncode in (0, 1), p.stderr
    assert "urdf-lint.toml:3:" in p.stdout and "UL008" in p.stdout
    assert "arg 'with_tol' is not declared by any xacro:arg" in p.stdout
    assert "(did you mean 'with_tool'?)" in p.stdout
    # discover = false: only the listed variants, each once
    (tmp_path / "other.urdf").write_text("<robot name='x'><link name='a'/></robot>\n")
    (tmp_path / "urdf-lint.toml").write_text(
        f'discover = false\n[[models]]\npath = "{V3}robot_v3.xacro"\n'
        'args = [{with_tool = "false"}, {with_tool = "true"}]\n')
    p = run_cli("check", ".", "--no-cache", "--format", "json", cwd=tmp_path)
    got = [(m["entry"], m["args"]) for m in json.loads(p.stdout)["models"]]
    assert got == [(V3 + "robot_v3.xacro", {"with_tool": "false"}),
                   (V3 + "robot_v3.xacro", {"with_tool": "true"})], p.stdout
    assert p.returncode == 0
    (tmp_path / "urdf-lint.toml").write_text('discover = "no"\n')
    p = run_cli("check", ".", "--no-cache", cwd=tmp_path)
    assert p.returncode == 2 and "invalid value for discover" in p.stderr and "expected true or false" in p.stderr


def test_colcon_workspace_of_package_repositories(tmp_path):
    ws = colcon_workspace(tmp_path / "ws")
    for d in ("robot_description", "robot_meshes", "gripper_description"):
        git("init", "-q", cwd=ws / "src" / d)
    # from inside one package repository: the siblings are found, the ignored copy is not
    p = run_cli("check", ".", "--no-cache", "--format", "json", cwd=ws / "src/robot_description")
    assert p.returncode == 0 and json.loads(p.stdout)["findings"] == [], p.stdout + p.stderr
    assert entries(p) == ["urdf/robot.urdf.xacro"]
    p = run_cli("expand", "urdf/robot.urdf.xacro", cwd=ws / "src/robot_description")
    assert p.returncode == 0 and 'name="finger_joint"' in p.stdout and "broken" not in p.stdout
    # from the workspace root, outside git: one model, no finding
    p = run_cli("check", ".", "--no-cache", "--format", "json", cwd=ws)
    assert entries(p) == ["src/robot_description/urdf/robot.urdf.xacro"], p.stdout + p.stderr
    assert p.returncode == 0 and json.loads(p.stdout)["findings"] == []


def test_install_layout_and_unknown_package_hint(tmp_path):
    ws = colcon_workspace(tmp_path / "ws", install_meshes=True)
    desc = ws / "src/robot_description"
    p = run_cli("check", ".", "--no-cache", "--format", "json", cwd=desc)
    assert p.returncode == 0 and json.loads(p.stdout)["findings"] == [], p.stdout + p.stderr
    # share/robot_meshes without a package.xml: unknown, with the folder to pass
    (ws / "install/share/robot_meshes/package.xml").unlink()
    p = run_cli("check", ".", "--no-cache", cwd=desc)
    assert p.returncode == 1 and "unknown package 'robot_meshes'" in p.stdout
    # the hint's folder is shown as every path is: relative, inside the workspace (issue 22)
    hint = os.path.relpath(ws / "install/share/robot_meshes", desc)
    assert hint.startswith("..") and f"pass --package-path robot_meshes={hint}" in p.stdout
    p = run_cli("check", ".", "--no-cache", "--package-path",
                f"robot_meshes={ws / 'install/share/robot_meshes'}", cwd=desc)
    assert p.returncode == 0, p.stdout


def test_deleted_and_renamed_inputs_with_changed_since(tmp_path):
    includes_only_repo(tmp_path)
    git("init", "-q", cwd=tmp_path)
    git("add", "-A", cwd=tmp_path)
    git("commit", "-qm", "init", cwd=tmp_path)
    git("mv", V3 + "head.xacro", V3 + "head2.xacro", cwd=tmp_path)
    (tmp_path / "v3_description/meshes/arm.stl").unlink()
    p = run_cli("check", ".", "--changed-since", "HEAD", "--format", "json", cwd=tmp_path)
    # the model that included the old name (the new name, included by nothing, is linted too)
    assert V3 + "robot_v3.xacro" in entries(p), p.stdout + p.stderr
    assert any(f["code"] == "UL003" and f["file"] == V3 + "robot_v3.xacro"
               and "head.xacro" in f["message"] for f in json.loads(p.stdout)["findings"])
    git("reset", "-q", "--hard", cwd=tmp_path)
    (tmp_path / "v3_description/meshes/arm.stl").unlink()
    p = run_cli("check", ".", "--changed-since", "HEAD", cwd=tmp_path)
    assert p.returncode == 1 and f"{V3}arm.xacro:" in p.stdout and "UL401" in p.stdout
    git("reset", "-q", "--hard", cwd=tmp_path)
    git("rm", "-q", V3 + "robot_v3.xacro", cwd=tmp_path)
    p = run_cli("check", ".", "--changed-since", "HEAD", cwd=tmp_path)
    assert p.returncode == 0 and f"{V3}robot_v3.xacro was deleted" in p.stderr, p.stderr


def test_generated_output_fresh_stale_and_meshes_relative_to_it(tmp_path):
    generated_output_repo(tmp_path)
    pkg = tmp_path / "gen_description"
    (tmp_path / "urdf-lint.toml").write_text(
        '[[models]]\npath = "gen_description/xacro/robot.xacro"\n'
        'output = "gen_description/robot.urdf"\n')
    # not generated yet: one finding at the output, meshes resolve relative to it (no UL401)
    p = run_cli("check", ".", "--no-cache", "--format", "json", cwd=tmp_path)
    found = json.loads(p.stdout)["findings"]
    assert [(f["code"], f["file"]) for f in found] == [("UL011", "gen_description/robot.urdf")], found
    assert "gen_description/xacro/robot.xacro" in found[0]["message"]
    # generate writes it (exit 1, like a formatter that changed files), then is a no-op
    p = run_cli("generate", cwd=tmp_path)
    assert p.returncode == 1 and "regenerated gen_description/robot.urdf" in p.stdout, p.stderr
    assert 'filename="./meshes/body.STL"' in (pkg / "robot.urdf").read_text()
    assert run_cli("generate", cwd=tmp_path).returncode == 0
    p = run_cli("check", ".", "--no-cache", "--format", "json", cwd=tmp_path)
    assert p.returncode == 0 and json.loads(p.stdout)["findings"] == [], p.stdout
    # the generated URDF is linted too (consumers read it): its meshes resolve next to it
    assert entries(p) == ["gen_description/robot.urdf", "gen_description/xacro/robot.xacro"]
    # without config: the header names the xacro; fresh, then stale after a xacro edit
    (tmp_path / "urdf-lint.toml").unlink()
    p = run_cli("check", ".", "--no-cache", "--format", "json", cwd=tmp_path)
    assert p.returncode == 0 and json.loads(p.stdout)["findings"] == [], p.stdout
    assert entries(p) == ["gen_description/robot.urdf", "gen_description/xacro/robot.xacro"]
    xacro = pkg / "xacro/robot.xacro"
    xacro.write_text(xacro.read_text().replace('value="0.1"', 'value="0.25"'))
    p = run_cli("check", ".", "--no-cache", cwd=tmp_path)
    line = next(i for i, t in enumerate((pkg / "robot.urdf").read_text().splitlines(), 1)
                if 'xyz="0 0 0.1"' in t)
    assert p.returncode == 1
    assert f"gen_description/robot.urdf:{line}:5: UL011 generated file is stale (<joint 'body_joint'> " \
        "> <origin> xyz: '0 0 0.1' in the file, '0 0 0.25' from the xacro)" \
        in p.stdout, p.stdout
    p = run_cli("generate", "--check", cwd=tmp_path)
    assert p.returncode == 1 and "would regenerate gen_description/robot.urdf" in p.stdout
    assert run_cli("generate", cwd=tmp_path).returncode == 1
    assert 'xyz="0 0 0.25"' in (pkg / "robot.urdf").read_text()
    assert run_cli("check", ".", "--no-cache", cwd=tmp_path).returncode == 0


def test_corpus_generated_outputs_are_fresh(corpus, tmp_path):
    """robot_properties_fingers checks in upstream's own xacro output for every xacro file:
    every pair is recognised from its header and found fresh."""
    p = run_cli("check", corpus / "robot_properties_fingers", "--no-cache", "--format", "json",
                "--isolated", "--select", "UL011", cwd=tmp_path)
    assert p.returncode == 0 and json.loads(p.stdout)["findings"] == [], p.stdout
    p = run_cli("generate", corpus / "robot_properties_fingers", "--check", cwd=tmp_path)
    # nothing stale: one summary line (issue 22: it printed nothing on success)
    assert p.returncode == 0 and p.stdout == \
        "urdf-lint generate: 14 generated URDF(s) checked, all up to date.\n", p.stdout + p.stderr


def test_cache_folder_markers_and_place(tmp_path, monkeypatch):
    # (mesh facts no longer go into the repository's cache folder: they are the user's signed
    # store, written by the parent only; tests/test_mesh_store.py)
    # outside git the cache goes under the working directory, not into the linted folder
    includes_only_repo(tmp_path / "work" / "robots")
    p = run_cli("check", "robots", cwd=tmp_path / "work", env={"URDF_LINT_CACHE_DIR": ""})
    assert p.returncode == 0, p.stdout + p.stderr
    assert (tmp_path / "work/.urdf_lint_cache/CACHEDIR.TAG").is_file()
    assert (tmp_path / "work/.urdf_lint_cache/.gitignore").is_file()
    assert not (tmp_path / "work/robots/.urdf_lint_cache").exists()


def test_render_fragment_renders_its_model_and_fails_without_snapshot(tmp_path):
    pytest.importorskip("PIL")
    repo = tmp_path / "repo"
    includes_only_repo(repo)
    out = tmp_path / "snap"
    p = run_cli("render", V3 + "arm.xacro", "--out", out, "--no-rrd", cwd=repo)
    assert p.returncode == 0, p.stderr
    (png,) = [f.name for f in out.glob("*.png")]   # the model's picture name: stem + key hash
    assert re.fullmatch(r"v3_description__urdf__robot_v3-[0-9a-f]{10}\.png", png), png
    # a requested model that cannot be snapshotted is a failure, not a blank image
    (repo / V3 / "main.xacro").unlink()
    p = run_cli("render", V3 + "robot_v3.xacro", "--out", tmp_path / "snap2", "--no-rrd", cwd=repo)
    assert p.returncode == 1 and "v3_description/urdf/robot_v3.xacro: no snapshot" in p.stderr


def test_a_file_new_under_a_glob_include_is_a_fragment_on_the_next_run(tmp_path):
    """The include graph is memoised by file stamps; an include of `parts/*.xacro` matches a
    new file without its includer changing, so such an includer is read again every run."""
    NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
    pkg = tmp_path / "robot_description"
    write(pkg, {"package.xml": "<package format='3'><name>robot_description</name></package>"})
    write(pkg, {"urdf/robot.urdf.xacro": f'<robot name="r" {NS}>\n  <link name="base"/>\n'
          '  <xacro:include filename="parts/*.xacro"/>\n</robot>\n'})
    write(pkg, {"urdf/parts/arm.xacro": f'<robot {NS}>\n  <link name="arm"/>\n'
          '  <joint name="a" type="fixed"><parent link="base"/><child link="arm"/></joint>\n</robot>\n'})

    def models():
        p = run_cli("check", ".", "--format", "json", cwd=tmp_path)
        assert p.returncode == 0, p.stdout + p.stderr
        return sorted(m["entry"].rsplit("/", 1)[-1] for m in json.loads(p.stdout)["models"])
    assert models() == ["robot.urdf.xacro"]
    write(pkg, {"urdf/parts/tool.xacro": f'<robot {NS}>\n  <link name="tool"/>\n'
          '  <joint name="t" type="fixed"><parent link="arm"/><child link="tool"/></joint>\n</robot>\n'})
    assert models() == ["robot.urdf.xacro"]      # not linted alone ("parent link 'arm'...")
