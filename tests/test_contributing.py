"""CONTRIBUTING's worked examples, each applied verbatim to a copy of the repository and checked
the way a contributor would (a rule, a rule with a new fix kind, an output format, a config
key), and ``scripts/add_rule.py``'s scaffold made to fire."""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
COPIED = ("urdf_lint", "rules", "descriptions", "scripts", "tests", "docs", "pyproject.toml",
          "README.md", "CONTRIBUTING.md", "SECURITY.md", "ARCHITECTURE.md")


def copy_repo(dst: Path) -> Path:
    """This checkout's code, rules, demo models, tests and docs in ``dst``, importable from
    there: ``urdf_lint/rules`` is a link to ``rules/`` (the editable install maps it)."""
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc")
    for name in COPIED:
        src = REPO / name
        if not src.exists():
            continue
        if src.is_dir():
            shutil.copytree(src, dst / name, ignore=ignore, symlinks=True)
        else:
            shutil.copy(src, dst / name)
    (dst / "urdf_lint" / "rules").symlink_to("../rules")
    return dst


def run(copy: Path, *args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    """``python ARGS`` with the copy's code first on the path."""
    env = {**os.environ, "PYTHONPATH": str(copy), "NO_COLOR": "1"}
    env.pop("GITHUB_ACTIONS", None)
    return subprocess.run([sys.executable, *args], cwd=cwd or copy, env=env,
                          capture_output=True, text=True, timeout=900)


def section(number: int) -> str:
    text = (REPO / "CONTRIBUTING.md").read_text(encoding="utf-8")
    m = re.search(rf"^## {number}\. .*?(?=^## )", text, re.S | re.M)
    assert m, f"CONTRIBUTING.md has no section {number}"
    return m.group(0)


def blocks(number: int) -> list[str]:
    """The ```python blocks of CONTRIBUTING's section ``number``, verbatim."""
    found = re.findall(r"```python\n(.*?)```", section(number), re.S)
    assert found, f"section {number} has no python block"
    return found


def write_rule(copy: Path, block: str) -> str:
    """A rule module's block, written where its CODE and NAME say; its code."""
    code = re.search(r'^CODE = "(UL\d{3})"', block, re.M).group(1)
    name = re.search(r'^NAME = "([a-z0-9-]+)"', block, re.M).group(1)
    (copy / "rules" / f"{code.lower()}_{name.replace('-', '_')}.py").write_text(block)
    return code


def class_name_attr(block: str) -> str:
    return re.search(r'^    name = "(\w+)"', block, re.M).group(1)


def test_worked_example_a_rule(tmp_path):
    copy = copy_repo(tmp_path / "repo")
    (block,) = blocks(1)
    code = write_rule(copy, block)
    p = run(copy, "-m", "urdf_lint", "rule", code)
    assert p.returncode == 0 and code in p.stdout, p.stderr
    # "Then pytest -q -m unit -k CODE": its examples, four ways, and its doc sections
    p = run(copy, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-m", "unit", "-k", code,
            "tests/test_rule_examples.py")
    assert p.returncode == 0, p.stdout[-3000:]
    assert re.search(r"(\d+) passed", p.stdout) and int(
        re.search(r"(\d+) passed", p.stdout).group(1)) >= 4, p.stdout[-500:]


def test_worked_example_a_rule_with_a_new_fix_kind(tmp_path):
    copy = copy_repo(tmp_path / "repo")
    kind, rule = blocks(2)
    (copy / "urdf_lint" / "fix" / "kinds" / f"{class_name_attr(kind)}.py").write_text(kind)
    code = write_rule(copy, rule)
    pkg = tmp_path / "pkg"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text('<package format="3"><name>pkg</name></package>\n')
    robot = pkg / "urdf" / "r.urdf"
    text = '<robot name="r">\n  <!-- kept -->\n  <link  name="base" />\n</robot>\n'
    robot.write_text(text)
    p = run(copy, "-m", "urdf_lint", "check", "--select", code, "--no-cache", ".", cwd=pkg)
    assert p.returncode == 0 and f"{code} link name 'base' is not upper case" in p.stdout, \
        p.stdout + p.stderr                   # a warning: exit 0
    p = run(copy, "-m", "urdf_lint", "check", "--fix", "--select", code, "--no-cache", ".",
            cwd=pkg)
    assert p.returncode == 0, p.stdout + p.stderr
    assert robot.read_text() == text.replace('"base"', '"BASE"'), p.stdout + p.stderr
    p = run(copy, "-m", "urdf_lint", "check", "--select", code, "--no-cache", ".", cwd=pkg)
    assert code not in p.stdout, p.stdout
    p = run(copy, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-m", "unit", "-k", code,
            "tests/test_rule_examples.py")
    assert p.returncode == 0, p.stdout[-3000:]


def test_worked_example_an_output_format(tmp_path):
    copy = copy_repo(tmp_path / "repo")
    (block,) = blocks(3)
    name = class_name_attr(block)
    (copy / "urdf_lint" / "report" / f"{name}.py").write_text(block)
    demo = "descriptions/broken/broken_robots/urdf/limits.urdf.xacro"
    p = run(copy, "-m", "urdf_lint", "check", demo, "--output-format", name, "--no-cache")
    assert p.returncode == 1, p.stderr
    j = run(copy, "-m", "urdf_lint", "check", demo, "--output-format", "json", "--no-cache")
    want = [f["code"] for f in json.loads(j.stdout)["findings"]]
    assert want and p.stdout.splitlines() == want, (p.stdout, want)
    # the config key accepts it too, and the docs' format table gets it from gen_docs.py
    (tmp_path / "cfg").mkdir()                  # not above the copy: the demo must not see it
    (tmp_path / "cfg" / "urdf-lint.toml").write_text(f'output-format = "{name}"\n')
    p = run(copy, "-m", "urdf_lint", "check", "--config",
            str(tmp_path / "cfg" / "urdf-lint.toml"), demo, "--no-cache")
    assert p.stdout.splitlines() == want, p.stdout + p.stderr
    p = run(copy, "scripts/gen_docs.py", "--check")
    assert p.returncode == 1 and \
        "docs/output.md is stale: run python scripts/gen_docs.py" in p.stderr.splitlines(), p.stderr
    p = run(copy, "scripts/gen_docs.py")
    assert p.returncode == 0, p.stderr
    help_ = re.search(r'^    help = "(.*)"', block, re.M).group(1)
    assert f"| `{name}` | {help_} |" in (copy / "docs" / "output.md").read_text()


def test_worked_example_a_config_key(tmp_path):
    copy = copy_repo(tmp_path / "repo")
    (block,) = blocks(4)
    schema = copy / "urdf_lint" / "config" / "schema.py"
    lines = schema.read_text().splitlines(keepends=True)
    start = next(i for i, ln in enumerate(lines) if ln.startswith("SCHEMA"))
    end = next(i for i in range(start, len(lines)) if lines[i].rstrip() == ")")
    lines[end:end] = [block]                 # one more Key(...) at the end of SCHEMA
    # "Add the Config field" where CONTRIBUTING still asks for it
    field = re.search(r"`(\w+: [^`=]+=\s*_default\(\"[a-z-]+\"\))`", section(4))
    if field:
        last = max(i for i, ln in enumerate(lines) if "= _default(" in ln)
        lines[last + 1:last + 1] = [f"    {' '.join(field.group(1).split())}\n"]
    schema.write_text("".join(lines))
    key = re.search(r'Key\("([a-z-]+)"', block).group(1)
    flag = re.search(r'Flag\(\("(--[a-z-]+)",\)', block).group(1)
    p = run(copy, "-m", "urdf_lint", "check", "--help")
    assert p.returncode == 0 and flag in p.stdout, p.stderr
    # the schema and Config agree (the test CONTRIBUTING names), and a repository's own
    # config is held to the key's trust rule
    p = run(copy, "-m", "pytest", "-q", "-p", "no:cacheprovider", "tests/test_config_schema.py",
            "-k", "fields or defaults or trust or flags")
    assert p.returncode == 0, p.stdout[-3000:]
    pkg = tmp_path / "pkg"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "urdf" / "r.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    (pkg / "urdf-lint.toml").write_text(f"{key} = 3\n")
    p = run(copy, "-m", "urdf_lint", "check", "--no-cache", ".", cwd=pkg)
    assert p.returncode == 0 and "Traceback" not in p.stderr, p.stderr
    assert key in p.stderr, p.stderr        # "ignored ... (--trust-config)": a note naming it
    p = run(copy, "-m", "urdf_lint", "check", "--no-cache", "--trust-config", ".", cwd=pkg)
    assert p.returncode == 0 and key not in p.stderr, p.stderr
    p = run(copy, "-m", "urdf_lint", "check", "--no-cache", flag, "2", ".", cwd=pkg)
    assert p.returncode == 0, p.stderr
    p = run(copy, "scripts/gen_docs.py", "--check")
    # the key table and the typed Config block mypy reads (CONTRIBUTING: gen_docs writes both)
    assert p.returncode == 1 and p.stderr.splitlines() == [
        "docs/configuration.md is stale: run python scripts/gen_docs.py",
        "urdf_lint/config/schema.py is stale: run python scripts/gen_docs.py"], p.stderr
    assert run(copy, "scripts/gen_docs.py").returncode == 0
    assert f"| `{key}` |" in (copy / "docs" / "configuration.md").read_text()


def test_add_rule_scaffolds_a_registered_rule_whose_demo_fires(tmp_path):
    """``scripts/add_rule.py CODE NAME`` on a copy: the module and the broken demo model; with
    its TODO condition written, the rule is registered, its examples pass, its demo fires and
    gen_docs.py writes its page."""
    copy = copy_repo(tmp_path / "repo")
    p = run(copy, "scripts/add_rule.py", "UL899", "fails-here", "--severity", "info")
    assert p.returncode == 0, p.stderr
    module = copy / "rules" / "ul899_fails_here.py"
    demo = copy / "descriptions" / "broken" / "broken_robots" / "urdf" / "ul899_fails_here.urdf"
    assert module.is_file() and demo.is_file(), p.stdout
    text = module.read_text()
    assert text.count("TODO") >= 4
    assert run(copy, "scripts/add_rule.py", "UL899", "other").returncode != 0     # taken
    assert run(copy, "scripts/add_rule.py", "UL898", "limit-order").returncode != 0
    assert not (copy / "rules" / "ul898_limit_order.py").exists()
    todo = "        if False:  # TODO: the condition under which this element is wrong\n"
    assert todo in text
    module.write_text(text.replace(todo, '        if link.get("name") == "fails_here":\n'))
    p = run(copy, "-m", "urdf_lint", "rules")
    assert re.search(r"^UL899\s+fails-here\s", p.stdout, re.M), p.stdout[-2000:]
    p = run(copy, "-m", "urdf_lint", "check", str(demo.relative_to(copy)), "--select", "UL899",
            "--no-cache")
    assert re.search(r"ul899_fails_here\.urdf:4:3: UL899 .*\[fails-here\]", p.stdout), \
        p.stdout + p.stderr
    p = run(copy, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-m", "unit", "-k", "UL899",
            "tests/test_rule_examples.py")
    assert p.returncode == 0 and " passed" in p.stdout, p.stdout[-3000:]
    assert run(copy, "scripts/gen_docs.py").returncode == 0
    assert (copy / "docs" / "rules" / "UL899.md").read_text().startswith("# UL899 fails-here")
