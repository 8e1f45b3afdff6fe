"""Every rule in rules/ documents itself and its FAIL example fires while its PASS example does
not, at the positions it pins (``FAIL_AT``). Adding a rule file adds it here automatically."""
from __future__ import annotations

import json
import re

import pytest

from conftest import make_package, run_cli
from urdf_lint.engine.registry import load_rules

RULES = load_rules()


def _write_example(tmp_path, rule, text, passing=False):
    files = {k: v for k, v in rule.example_files.items()}
    if passing:   # a rule about a configuration file may fix the file, not the model
        files.update(rule.pass_files)
    name = "urdf/example.urdf.xacro" if "xmlns:xacro" in text else "urdf/example.urdf"
    files[name] = text
    return make_package(tmp_path, "example_pkg", files)


def _codes(pkg, code):
    p = run_cli("check", ".", "--no-cache", "--select", f"{code},UL009" if code != "UL009" else "UL",
                "--format", "json", "--fail-on", "never", "--target",
                ",".join(RULES[code].example_targets), cwd=pkg,
                env={"URDF_LINT_EXAMPLE_SECRET": "s3cr3t-value"})
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)["findings"]


def test_catalogue_is_well_formed():
    assert len(RULES) >= 50
    for code, r in RULES.items():
        assert re.fullmatch(r"UL\d{3}", code), code
        assert re.fullmatch(r"[a-z0-9]+(-[a-z0-9]+)*", r.name), r.name
        assert r.severity in ("error", "warning", "info"), code
        assert len(r.doc) > 60, f"{code} needs a docstring explaining why and how to fix"
        assert r.fail.strip() and r.passing.strip(), f"{code} needs FAIL and PASS examples"
    names = [r.name for r in RULES.values()]
    assert len(names) == len(set(names))


@pytest.mark.parametrize("code", sorted(RULES))
def test_fail_example_fires(tmp_path, code):
    rule = RULES[code]
    pkg = _write_example(tmp_path, rule, rule.fail)
    found = _codes(pkg, code)
    assert any(f["code"] == code for f in found), f"{code} did not fire on its FAIL example: {found}"
    for f in found:
        if f["code"] == code:
            assert f["line"] >= 1 and f["col"] >= 1 and f["file"].startswith(
                ("urdf/", "config/") if rule.example_at else "urdf/")
    assert "s3cr3t-value" not in json.dumps(found)


def _in_process(tmp_path, monkeypatch, rule, text, passing=False):
    """The findings of ``rule`` on one example, linted in this process (fast: no workers)."""
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import RunRequest, run_check
    pkg = _write_example(tmp_path, rule, text, passing)
    monkeypatch.chdir(pkg)
    monkeypatch.setenv("URDF_LINT_EXAMPLE_SECRET", "s3cr3t-value")
    cfg = load_config(None)
    cfg.select = [rule.code, "UL009"] if rule.code != "UL009" else ["UL"]
    cfg.targets = list(rule.example_targets)   # EXAMPLE_TARGETS (default: ros)
    res = run_check(RunRequest(["."], cfg, build_resolver(["."], cfg), in_process=True))
    assert not res.internal, res.internal
    name = "urdf/example.urdf.xacro" if "xmlns:xacro" in text else "urdf/example.urdf"
    # a rule about a configuration file (SRDF, controller YAML) pins positions in that file
    return [f for f in res.findings if f.code == rule.code], str(pkg / (rule.example_at or name))


@pytest.mark.parametrize("code", sorted(RULES))
def test_fail_example_reports_its_pinned_positions(tmp_path, monkeypatch, code):
    rule = RULES[code]
    assert rule.fail_at, f"{code}: FAIL_AT must list the (line, col) its FAIL example reports"
    found, example = _in_process(tmp_path, monkeypatch, rule, rule.fail)
    at = sorted({(f.line, f.col) for f in found if f.file == example})
    assert at == sorted(rule.fail_at), f"{code} reported at {at}, FAIL_AT says {rule.fail_at}"
    lines = (rule.example_files[rule.example_at] if rule.example_at else rule.fail).splitlines()
    for line, col in rule.fail_at:
        assert 1 <= line <= len(lines) and 1 <= col <= len(lines[line - 1]) + 1, (line, col)
    # a rule that offers a fix (on its own FAIL example) documents it: safe or unsafe
    from urdf_lint.engine.rulesdoc import sections
    doc = sections(rule.doc).get("fix", "")
    if any(f.fix is not None for f in found):
        assert doc.startswith(("safe", "unsafe")), f"{code} offers a fix, 'Fix:' says {doc!r}"


@pytest.mark.parametrize("code", sorted(RULES))
def test_pass_example_is_clean_in_process(tmp_path, monkeypatch, code):
    rule = RULES[code]
    found, _ = _in_process(tmp_path, monkeypatch, rule, rule.passing, passing=True)
    assert not found, found


@pytest.mark.parametrize("code", sorted(RULES))
def test_pass_example_is_clean(tmp_path, code):
    rule = RULES[code]
    pkg = _write_example(tmp_path, rule, rule.passing, passing=True)
    found = _codes(pkg, code)
    assert not [f for f in found if f["code"] == code], found


def test_rules_and_rule_commands():
    p = run_cli("rules")
    assert p.returncode == 0 and "UL302  limit-order" in p.stdout
    p = run_cli("rule", "UL302")
    assert p.returncode == 0 and "limit-order" in p.stdout and "Fails:" in p.stdout
    p = run_cli("rule", "limit-order")
    assert p.returncode == 0 and p.stdout.startswith("UL302")
    assert run_cli("rule", "UL999").returncode == 2


@pytest.mark.parametrize("code", sorted(RULES))
def test_docstring_has_the_fixed_sections(code):
    from urdf_lint.engine.rulesdoc import sections
    rule = RULES[code]
    s = sections(rule.doc)        # raises on a missing, repeated or misplaced section
    assert len(s["why"]) > 20 and len(s["how to fix"]) > 10, s
    if rule.options:
        assert "options" in s, f"{code} has OPTIONS, so its docstring needs an Options: section"
        for key in rule.options:
            assert f"`{key}`" in s["options"], f"{code}: option {key} is not documented"
    else:
        assert "options" not in s, f"{code} documents options it does not have"
    assert "``" not in rule.doc, f"{code}: reST markup; write `code` in single backticks"


@pytest.mark.parametrize("code", sorted(RULES))
def test_rule_help_cites_nothing_outside_the_product(code):
    """A user reads `urdf-lint rule CODE` in an installed wheel: the project's test files and
    paths of the machine it was built on mean nothing there."""
    import re
    doc = RULES[code].doc
    bad = re.findall(r"tests/\S*|test_\w+\.py|/work/\S*|shared/notes\S*|consumer-facts\S*|"
                     r"\bhere:", doc)
    assert not bad, f"{code}'s help cites {bad}"


def test_sections_parser_rejects_bad_docstrings():
    from urdf_lint.engine.rulesdoc import DocError, sections
    good = "What.\n\nWhy: because.\n\nHow to fix: do it."
    assert sections(good)["how to fix"] == "do it."
    for bad in ("What only.", "What.\n\nHow to fix: x.\n\nWhy: y.", "What.\n\nWhy: a.",
                "What.\n\nWhy: a.\n\nWhy: b.\n\nHow to fix: c."):
        with pytest.raises(DocError):
            sections(bad)


def test_rules_markdown_page():
    p = run_cli("rules", "--format", "markdown")
    assert p.returncode == 0, p.stderr
    page = p.stdout
    assert page.startswith("# urdf-lint rules\n")
    for code, r in RULES.items():
        assert f"\n## {code} {r.name}\n" in page
        assert f"| [{code}](#{code.lower()}-{r.name}) | `{r.name}` | {r.severity} |" in page
    ul302 = page.split("## UL302 limit-order")[1].split("\n## ")[0]
    assert "**Why.**" in ul302 and "**How to fix.**" in ul302
    assert "Reported at line 4, col 5" in ul302 and 'lower="2.1" upper="-2.1"' in ul302
    assert "`tolerance`" in page.split("## UL307")[1].split("\n## ")[0]
