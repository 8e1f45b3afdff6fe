"""Configuration ([tool.urdf-lint]) and inline suppression, end to end through the CLI."""
from __future__ import annotations

import json

from conftest import make_package, run_main

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
ROBOT = f"""<robot name="r" {X}>
  <xacro:macro name="arm" params="name lo hi">
    <link name="${{name}}"/>
    <joint name="${{name}}_joint" type="revolute">
      <parent link="base"/><child link="${{name}}"/><axis xyz="0 0 1"/>
      <limit lower="${{lo}}" upper="${{hi}}" effort="1" velocity="1"/>
    </joint>
  </xacro:macro>
  <link name="base"/>
  <xacro:arm name="a" lo="2" hi="-2"/>
  <!-- urdf-lint: disable-next UL302 -->
  <xacro:arm name="b" lo="3" hi="-3"/>
  <xacro:arm name="c" lo="4" hi="-4"/>
  <!-- urdf-lint: disable UL3 -->
  <xacro:arm name="d" lo="5" hi="-5"/>
  <!-- urdf-lint: enable UL3 -->
  <!-- urdf-lint: disable-next UL105 -->
  <link name="lonely_but_unique"/>
</robot>
"""


def findings(pkg, *extra):
    p = run_main("check", ".", "--no-cache", "--format", "json", *extra, cwd=pkg)
    assert p.returncode in (0, 1), p.stderr
    return json.loads(p.stdout)["findings"], p.returncode


def codes_lines(fs, code):
    return sorted(f["line"] for f in fs if f["code"] == code)


def test_inline_suppression(tmp_path):
    pkg = make_package(tmp_path, "p", {"urdf/r.urdf.xacro": ROBOT})
    fs, rc = findings(pkg, "--select", "UL302,UL009,UL104,UL105")
    # the macro line (6) is one finding with an instance per call site chain; b and d are
    # suppressed
    msgs = sorted(i["message"] for f in fs if f["code"] == "UL302"
                  for i in f.get("instances") or [f])
    assert len([f for f in fs if f["code"] == "UL302"]) == 1
    assert msgs == ["joint 'a_joint': lower 2 > upper -2 (swap them?)",
                    "joint 'c_joint': lower 4 > upper -4 (swap them?)"]
    unused = [f for f in fs if f["code"] == "UL009"]
    assert [u["line"] for u in unused] == [17], unused   # UL105 never fired there
    assert rc == 1


def test_disable_file_and_select_ignore(tmp_path):
    pkg = make_package(tmp_path, "p", {"urdf/r.urdf.xacro": ROBOT.replace(
        "<link name=\"base\"/>", "<!-- urdf-lint: disable-file UL302 -->\n  <link name=\"base\"/>")})
    fs, _ = findings(pkg, "--select", "UL302")
    assert not codes_lines(fs, "UL302")
    fs, rc = findings(pkg, "--select", "UL3", "--ignore", "UL302")
    assert not [f for f in fs if f["code"].startswith("UL30") and f["code"] != "UL303"]


def test_pyproject_config(tmp_path):
    pkg = make_package(tmp_path, "p", {"urdf/r.urdf.xacro": ROBOT, "urdf/other.urdf":
                                       '<robot name="o"><link name="a"><visual><geometry><box size="1 1 1"/></geometry></visual></link></robot>'})
    (pkg / "pyproject.toml").write_text("""
[tool.urdf-lint]
select = ["UL3", "UL8"]
ignore = ["UL009"]
per-file-ignores = { "urdf/other.urdf" = ["UL801"] }
severity = { UL302 = "warning" }
fail-on = "error"
""")
    fs, rc = findings(pkg)
    assert {f["code"] for f in fs} == {"UL302"}
    assert all(f["severity"] == "warning" for f in fs)
    assert rc == 0  # only warnings now
    fs, rc = findings(pkg, "--fail-on", "warning")
    assert rc == 1
    # CLI flags override the config's select; per-file-ignores still hide other.urdf's UL801 ...
    fs, _ = findings(pkg, "--select", "UL801")
    assert fs == []
    # ... which does fire there without the config
    fs, _ = findings(pkg, "--select", "UL801", "--isolated")
    assert [(f["code"], f["file"]) for f in fs] == [("UL801", "urdf/other.urdf")]


def test_models_with_arg_sets(tmp_path):
    body = f'<robot name="$(arg kind)_bot" {X}>\n  <link name="$(arg kind)_base"/>\n</robot>\n'
    pkg = make_package(tmp_path, "p", {"urdf/bot.xacro": body})
    p = run_main("check", ".", "--no-cache", "--format", "json", cwd=pkg)
    assert p.returncode == 1
    assert json.loads(p.stdout)["findings"][0]["code"] == "UL005"
    (pkg / "urdf-lint.toml").write_text("""
[[models]]
path = "urdf/bot.xacro"
args = [{ kind = "small" }, { kind = "large" }]
""")
    p = run_main("check", ".", "--no-cache", "--format", "json", cwd=pkg)
    assert p.returncode == 0, p.stdout
    names = sorted(m["name"] for m in json.loads(p.stdout)["models"])
    assert names == ["large_bot", "small_bot"]


def test_bad_config_is_an_error(tmp_path):
    for text, words in [("select = ['UL999']\n", "unknown rule code"),
                        ("[severity]\nUL302 = 'fatal'\n", "severity"),
                        ("[rule-options.UL307]\ntolerence = 1\n", "unknown option"),
                        ("exclude = 3\n", "exclude")]:
        (tmp_path / "urdf-lint.toml").write_text(text)
        p = run_main("check", ".", cwd=tmp_path)
        assert p.returncode == 2, text
        assert words in p.stderr, (text, p.stderr)


def test_rule_options(tmp_path):
    urdf = ('<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="continuous">'
            '<parent link="a"/><child link="b"/><axis xyz="0 0 1.01"/></joint></robot>')
    pkg = make_package(tmp_path, "p", {"r.urdf": urdf})
    fs, _ = findings(pkg, "--select", "UL307")
    assert len(fs) == 1 and "length 1.01" in fs[0]["message"]
    (pkg / "urdf-lint.toml").write_text("[rule-options.UL307]\ntolerance = 0.05\n")
    fs, _ = findings(pkg, "--select", "UL307")
    assert fs == []
