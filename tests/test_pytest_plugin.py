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
