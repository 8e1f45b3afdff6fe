"""The pytest plugin (entry point ``pytest11``): every robot model a test item, as ``colcon
test`` runs it on an ``ament_python`` package (``python -m pytest --junit-xml=... --junit-prefix=
PKG`` in the package folder), with the ini option switched on in ``setup.cfg``."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import pytest

from conftest import DESCRIPTIONS

SETUP_PY = """from setuptools import setup
setup(name="{name}", version="0.0.1", packages=[], data_files=[])
"""
SETUP_CFG = """[tool:pytest]
testpaths = test
urdf_lint = true
"""
PACKAGE_TEST = "def test_copyright():\n    assert True\n"


def _colcon_package(src, dest):
    """``src`` laid out as a colcon ``ament_python`` package at ``dest``: its package.xml
    says so, setup.py / setup.cfg / resource marker / test folder as ros2 pkg create makes."""
    shutil.copytree(src, dest)
    name = dest.name
    xml = (dest / "package.xml").read_text()
    if "<build_type>" not in xml:
        xml = xml.replace("</package>", "  <export><build_type>ament_python</build_type>"
                                        "</export>\n</package>")
    (dest / "package.xml").write_text(xml)
    (dest / "setup.py").write_text(SETUP_PY.format(name=name))
    (dest / "setup.cfg").write_text(SETUP_CFG)
    (dest / "resource").mkdir()
    (dest / "resource" / name).write_text("")
    (dest / "test").mkdir()
    (dest / "test" / "test_copyright.py").write_text(PACKAGE_TEST)
    return dest


def _colcon_test(pkg, *extra):
    """What ``colcon test`` runs for an ament_python package (colcon-core's pytest step)."""
    junit = pkg.parent / f"{pkg.name}.xml"
    env = dict(os.environ)
    env.pop("GITHUB_ACTIONS", None)
    # (the language server's test plugins in this environment are not a colcon user's: their
    # hook wrappers expect Python test functions)
    p = subprocess.run([sys.executable, "-m", "pytest", f"--junit-xml={junit}",
                        f"--junit-prefix={pkg.name}", "-p", "no:cacheprovider",
                        "-p", "no:pytest-lsp", "-p", "no:asyncio", *extra],
                       cwd=pkg, capture_output=True, text=True, timeout=300, env=env)
    cases = {}
    if junit.is_file():
        for case in ET.parse(junit).iter("testcase"):
            failed = case.find("failure") is not None or case.find("error") is not None
            text = "".join((c.get("message") or "") + (c.text or "") for c in case)
            cases[case.get("name")] = (failed, text)
    return p, cases


def test_colcon_test_lints_each_model_of_a_corpus_package(corpus, tmp_path):
    pkg = _colcon_package(corpus / "urdf_tutorial", tmp_path / "ws" / "src" / "urdf_tutorial")
    p, cases = _colcon_test(pkg)
    assert p.returncode == 0, p.stdout + p.stderr
    models = sorted(n for n in cases if n.startswith("urdf/"))
    assert models == [f"urdf/{n}" for n in sorted(os.listdir(pkg / "urdf"))], cases
    assert "test_copyright" in cases                       # the package's own tests still run
    assert not any(failed for failed, _ in cases.values())

    # a planted defect fails that model's item, at its line, and only that one
    f = pkg / "urdf" / "06-flexible.urdf"
    lines = f.read_text().splitlines(keepends=True)
    assert 'lower="-0.38" upper="0"' in lines[151]
    lines[151] = lines[151].replace('lower="-0.38" upper="0"', 'lower="0.38" upper="0"')
    f.write_text("".join(lines))
    p, cases = _colcon_test(pkg)
    assert p.returncode == 1, p.stdout + p.stderr
    failed = {n for n, (bad, _) in cases.items() if bad}
    assert failed == {"urdf/06-flexible.urdf"}, failed
    assert "urdf/06-flexible.urdf:152:" in cases["urdf/06-flexible.urdf"][1]
    assert "UL302" in cases["urdf/06-flexible.urdf"][1]


def test_config_decides_what_fails_and_k_selects_models(tmp_path):
    pkg = _colcon_package(DESCRIPTIONS / "r2d2_description", tmp_path / "r2d2_description")
    p, cases = _colcon_test(pkg)
    assert p.returncode == 0, p.stdout + p.stderr
    assert any(n.startswith("urdf/") for n in cases), cases
    # a warning (an attribute URDF parsers ignore) fails nothing under the default fail-on ...
    f = pkg / "urdf" / "r2d2.urdf.xacro"
    text = f.read_text()
    assert text.splitlines()[32].strip() == '<origin xyz="0 0 0"/>'
    f.write_text(text.replace('<origin xyz="0 0 0"/>', '<origin xyz="0 0 0" spin="1"/>', 1))
    p, cases = _colcon_test(pkg)
    assert p.returncode == 0, p.stdout + p.stderr
    # ... and fails its model under [tool.urdf-lint] fail-on = "warning"
    (pkg / "urdf-lint.toml").write_text('fail-on = "warning"\n')
    p, cases = _colcon_test(pkg, "-k", "urdf")
    assert p.returncode == 1, p.stdout + p.stderr
    assert "test_copyright" not in cases                   # -k applies to model items too
    assert all(bad for bad, _ in cases.values()) and cases, cases
    assert "urdf/r2d2.urdf.xacro:33:" in cases["urdf/r2d2.urdf.xacro"][1]


def test_a_broken_config_is_one_failing_item_with_the_message(tmp_path):
    pkg = _colcon_package(DESCRIPTIONS / "r2d2_description", tmp_path / "r2d2_description")
    (pkg / "urdf-lint.toml").write_text('fail-onn = "info"\n')
    p, cases = _colcon_test(pkg)
    assert p.returncode == 1, p.stdout + p.stderr
    assert cases["urdf-lint"][0], cases
    assert "unknown key 'fail-onn'" in cases["urdf-lint"][1]
    assert "Traceback" not in p.stdout + p.stderr


def test_without_the_option_nothing_is_added(tmp_path):
    pkg = _colcon_package(DESCRIPTIONS / "r2d2_description", tmp_path / "r2d2_description")
    (pkg / "setup.cfg").write_text("[tool:pytest]\ntestpaths = test\n")
    p, cases = _colcon_test(pkg)
    assert p.returncode == 0, p.stdout + p.stderr
    assert list(cases) == ["test_copyright"]
    p, cases = _colcon_test(pkg, "--urdf-lint")             # the flag alone switches it on
    assert any(n.startswith("urdf/") for n in cases), cases


@pytest.mark.parametrize("pkg", ["r2d2_description"])
def test_the_plugin_is_registered_by_the_installed_package(pkg):
    from importlib.metadata import entry_points
    eps = {e.name: e.value for e in entry_points(group="pytest11")}
    assert eps.get("urdf_lint") == "urdf_lint.cli.pytest_plugin"


# two models sharing an arm macro with a swapped limit: one calls it once (h_), the other
# twice (l_, r_)
from test_grouping import ARM as ARM_MACRO, ONE_ARM as HAND, TWO_ARMS as DUAL  # noqa: E402


def test_each_model_item_shows_its_own_instances_and_a_clean_classname(tmp_path):
    """Two models of one package share a macro with a swapped limit: one finding (at the macro
    line) with an instance per joint. Each model's JUnit failure shows its own joints and call
    chains, never the other model's, and the JUnit classname is a name, not ``PKG.``."""
    src = tmp_path / "src"
    (src / "urdf").mkdir(parents=True)
    (src / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="3"><name>two_arms</name>'
        "<version>0.0.1</version><description>x</description>"
        '<maintainer email="a@b.c">a</maintainer><license>MIT</license></package>\n')
    (src / "urdf" / "arm.xacro").write_text(ARM_MACRO)
    (src / "urdf" / "hand.urdf.xacro").write_text(HAND)
    (src / "urdf" / "dual.urdf.xacro").write_text(DUAL)
    pkg = _colcon_package(src, tmp_path / "ws" / "src" / "two_arms")
    p, cases = _colcon_test(pkg)
    assert p.returncode == 1, p.stdout + p.stderr
    hand_failed, hand = cases["urdf/hand.urdf.xacro"]
    dual_failed, dual = cases["urdf/dual.urdf.xacro"]
    assert hand_failed and dual_failed
    assert "'h_joint'" in hand and "called from urdf/hand.urdf.xacro:5" in hand
    assert "'l_" not in hand and "'r_" not in hand and "dual" not in hand.split(":", 1)[1]
    assert "'l_joint'" in dual and "called from urdf/dual.urdf.xacro:5" in dual
    assert "'r_joint'" in dual and "called from urdf/dual.urdf.xacro:6" in dual
    assert "h_joint" not in dual and "hand.urdf.xacro" not in dual
    assert "1 finding(s) (2 instances)" in dual
    classnames = {c.get("name"): c.get("classname")
                  for c in ET.parse(pkg.parent / "two_arms.xml").iter("testcase")}
    assert classnames["urdf/dual.urdf.xacro"] == "two_arms.urdf_lint", classnames
    assert not any(c.endswith(".") for c in classnames.values()), classnames


def _recipe(name: str) -> str:
    """The block of docs/ci.md under ``<!-- recipe: NAME -->``, as a user pastes it."""
    import re
    readme = (DESCRIPTIONS.parent / "docs" / "ci.md").read_text()
    m = re.search(r"<!-- recipe: " + re.escape(name) + r" -->\n```\w*\n(.*?)```", readme, re.S)
    assert m, f"docs/ci.md has no recipe block {name!r}"
    return m.group(1)


def _two_arms(dest):
    (dest / "urdf").mkdir(parents=True)
    (dest / "urdf" / "arm.xacro").write_text(ARM_MACRO)
    (dest / "urdf" / "hand.urdf.xacro").write_text(HAND)
    (dest / "urdf" / "dual.urdf.xacro").write_text(DUAL)
    return dest


def _package_xml(name: str, build_type: str, test_depend: str) -> str:
    return ('<?xml version="1.0"?>\n<package format="3">\n'
            f"  <name>{name}</name>\n  <version>0.0.1</version>\n  <description>x</description>\n"
            '  <maintainer email="a@b.c">a</maintainer>\n  <license>MIT</license>\n'
            f"{test_depend}"
            f"  <export><build_type>{build_type}</build_type></export>\n</package>\n")


def test_the_documented_colcon_recipe_works_as_pasted_with_real_colcon(tmp_path):
    """docs/ci.md's ament_python recipe, pasted into a package, under real ``colcon build`` and
    ``colcon test`` (colcon-common-extensions from the package index; the ``consumers`` extra):
    each model is a test with its own findings; the package's clean model passes."""
    colcon = os.path.join(os.path.dirname(sys.executable), "colcon")
    if not os.path.exists(colcon):
        pytest.skip("colcon is not installed (pip install colcon-common-extensions)")
    name = "my_robot_description"
    pkg = _two_arms(tmp_path / "ws" / "src" / name)
    (pkg / "urdf" / "clean.urdf").write_text(
        '<?xml version="1.0"?>\n<robot name="clean"><link name="base"/></robot>\n')
    (pkg / "package.xml").write_text(_package_xml(name, "ament_python",
                                                  _recipe("ament_python package.xml")))
    (pkg / "setup.py").write_text(_recipe("ament_python setup.py"))
    (pkg / "setup.cfg").write_text(_recipe("ament_python setup.cfg"))
    (pkg / "resource").mkdir()
    (pkg / "resource" / name).write_text("")
    env = {k: v for k, v in os.environ.items() if k != "GITHUB_ACTIONS"}
    ws = tmp_path / "ws"
    # (the language server's test plugins in this environment are not a colcon user's)
    for step in (["build"], ["test", "--pytest-args", "-p", "no:pytest-lsp", "-p", "no:asyncio"]):
        p = subprocess.run([colcon, *step], cwd=ws, capture_output=True, text=True,
                           timeout=600, env=env)
        assert p.returncode == 0, p.stdout + p.stderr
    junit = ws / "build" / name / "pytest.xml"
    assert junit.is_file(), "colcon ran no pytest: the recipe misses a step"
    cases = {c.get("name"): (c.get("classname"), c.find("failure") is not None,
                             "".join(x.text or "" for x in c))
             for c in ET.parse(junit).iter("testcase")}
    assert set(cases) == {"urdf/hand.urdf.xacro", "urdf/dual.urdf.xacro", "urdf/clean.urdf"}
    assert {c for c, _, _ in cases.values()} == {f"{name}.urdf_lint"}
    assert not cases["urdf/clean.urdf"][1], cases["urdf/clean.urdf"][2]
    assert cases["urdf/hand.urdf.xacro"][1] and cases["urdf/dual.urdf.xacro"][1]
    assert "'l_joint'" in cases["urdf/dual.urdf.xacro"][2]
    assert "'h_joint'" not in cases["urdf/dual.urdf.xacro"][2]


def test_the_documented_ament_cmake_recipe_runs_the_models(tmp_path):
    """What ``ament_add_pytest_test(urdf_lint test WORKING_DIRECTORY ...)`` runs (ament_cmake's
    generated command: ``python -m pytest <pkg>/test -o cache_dir=... --junit-xml=...
    --junit-prefix=PKG`` in the package folder) with docs/ci.md's ``pytest.ini``."""
    cmake = _recipe("ament_cmake CMakeLists.txt")
    assert "ament_add_pytest_test(urdf_lint test WORKING_DIRECTORY" in cmake
    name = "arm_description"
    pkg = _two_arms(tmp_path / name)
    (pkg / "package.xml").write_text(_package_xml(
        name, "ament_cmake", "  <test_depend>ament_cmake_pytest</test_depend>\n"))
    (pkg / "pytest.ini").write_text(_recipe("ament_cmake pytest.ini"))
    (pkg / "test").mkdir()
    junit = tmp_path / "urdf_lint.xunit.xml"
    p = subprocess.run([sys.executable, "-u", "-m", "pytest", str(pkg / "test"),
                        "-o", f"cache_dir={tmp_path / 'cache'}", f"--junit-xml={junit}",
                        f"--junit-prefix={name}", "-p", "no:pytest-lsp", "-p", "no:asyncio"],
                       cwd=pkg, capture_output=True, text=True, timeout=300)
    assert p.returncode == 1, p.stdout + p.stderr
    cases = {c.get("name"): c.get("classname") for c in ET.parse(junit).iter("testcase")}
    assert cases == {"urdf/hand.urdf.xacro": f"{name}.urdf_lint",
                     "urdf/dual.urdf.xacro": f"{name}.urdf_lint"}, cases
