"""Any path a user passes is handled by what it is (issue 22): a YAML file, a mesh or a texture
lints the models that use it, as the hook does; a folder with no models is a warning (exit 0);
a named file no model uses is said; a path that does not exist is a usage error."""
from __future__ import annotations

import shutil

import pytest

from conftest import DESCRIPTIONS, make_package, run_cli
from repo_shapes import stl_box

TEXTURED = """<robot name="t">
  <material name="skin"><texture filename="package://textured/textures/skin.png"/></material>
  <link name="a"><visual><geometry><mesh filename="package://textured/meshes/a.stl"/></geometry>
    <material name="skin"/></visual></link>
</robot>
"""
PNG = (b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\x00\x00\x00\x01\x00\x00\x00\x01\x08\x02\x00\x00\x00"
       b"\x90wS\xde\x00\x00\x00\x0cIDATx\x9cc\xf8\xcf\xc0\x00\x00\x03\x01\x01\x00\xc9\xfe\x92\xef"
       b"\x00\x00\x00\x00IEND\xaeB`\x82")


@pytest.fixture()
def repo(tmp_path):
    shutil.copytree(DESCRIPTIONS / "r2d2_description", tmp_path / "r2d2_description")
    shutil.copytree(DESCRIPTIONS / "double_pendulum_description",
                    tmp_path / "double_pendulum_description")
    make_package(tmp_path, "textured", {"urdf/t.urdf": TEXTURED, "meshes/a.stl": stl_box(),
                                        "textures/skin.png": PNG})
    (tmp_path / "empty").mkdir()
    (tmp_path / "notes.txt").write_text("not a robot\n")
    return tmp_path


@pytest.mark.parametrize("path, model", [
    ("r2d2_description/config/joint_limits.yaml", "r2d2_description/urdf/r2d2.urdf.xacro"),
    ("r2d2_description/meshes/l_finger.stl", "r2d2_description/urdf/r2d2.urdf.xacro"),
    ("textured/textures/skin.png", "textured/urdf/t.urdf"),
])
def test_an_input_file_lints_the_models_that_use_it(repo, path, model):
    import json
    p = run_cli("check", path, "--no-cache", "--format", "json", "--fail-on", "never", cwd=repo)
    assert p.returncode == 0, p.stderr
    doc = json.loads(p.stdout)
    assert [m["entry"] for m in doc["models"]] == [model]
    assert "UL001" not in {f["code"] for f in doc["findings"]}
    assert "not used by any model" not in p.stderr


def test_a_yaml_change_is_found_through_the_model(repo):
    yaml = repo / "r2d2_description/config/joint_limits.yaml"
    yaml.write_text(yaml.read_text().replace("upper: 0.548", "upper: -0.9"))
    p = run_cli("check", "r2d2_description/config/joint_limits.yaml", "--no-cache", cwd=repo)
    assert p.returncode == 1 and "UL302" in p.stdout, p.stdout + p.stderr


def test_a_folder_with_no_models_is_a_warning(repo):
    p = run_cli("check", "empty", "--no-cache", cwd=repo)
    assert p.returncode == 0
    assert "warning: no robot models found in empty" in p.stderr
    # beside a folder that has models: said for the empty one only
    p = run_cli("check", "empty", "double_pendulum_description", "--no-cache", cwd=repo)
    assert p.returncode == 0 and p.stderr.count("no robot models found") == 1
    # and beside an input file
    p = run_cli("check", "empty", "r2d2_description/config/joint_limits.yaml", "--no-cache", cwd=repo)
    assert p.returncode == 0 and "no robot models found in empty" in p.stderr
    p = run_cli("check", "empty", "-q", "--no-cache", cwd=repo)
    assert p.returncode == 0 and p.stderr == ""


def test_a_named_file_no_model_uses_is_said(repo):
    p = run_cli("check", "notes.txt", "r2d2_description/meshes/l_finger.stl", "--no-cache", cwd=repo)
    assert p.returncode == 0, p.stderr
    assert "note: notes.txt is not used by any model" in p.stderr
    assert "l_finger.stl is not used" not in p.stderr


def test_a_path_that_does_not_exist_is_a_usage_error(repo):
    p = run_cli("check", "nope.yaml", "--no-cache", cwd=repo)
    assert p.returncode == 2 and "no such file or directory: nope.yaml" in p.stderr
