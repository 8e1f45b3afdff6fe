"""The documentation as artefacts: a README of at most 200 lines, every relative link in the
README and docs/ leading somewhere, and the generated pages (one per rule, the key and format
tables) current, with ``scripts/gen_docs.py --check`` failing on a stale one."""
from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from support.scripts import load_script

REPO = Path(__file__).resolve().parent.parent
# pages other sessions are writing at the same time: a link to one is tolerated only while
# the page does not exist on this branch (once it does, its links and anchors are checked);
# empty this set once they are all merged
PENDING: set[str] = set()


def _gen_docs():
    return load_script("gen_docs")


def test_readme_is_at_most_200_lines_and_has_the_two_commands():
    text = (REPO / "README.md").read_text(encoding="utf-8")
    assert len(text.splitlines()) <= 200, len(text.splitlines())
    assert "bash scripts/bootstrap.sh && .venv/bin/urdf-lint check descriptions/" in text
    assert "bash scripts/bootstrap.sh && .venv/bin/python -m pytest -q" in text


# -- links -----------------------------------------------------------------------------------
_LINK = re.compile(r"\[[^\]\n]*\]\(([^)\s]+)\)")
_FENCE = re.compile(r"^(```|~~~).*?^\1", re.S | re.M)


def slug(heading: str) -> str:
    """GitHub's anchor for a heading's text."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower().replace("`", ""))
    return text.replace(" ", "-")


def anchors(text: str) -> set[str]:
    out: set[str] = set()
    for m in re.finditer(r"^#{1,6} (.+?)\s*$", _FENCE.sub("", text), re.M):
        base = slug(m.group(1))
        name, n = base, 0
        while name in out:
            n += 1
            name = f"{base}-{n}"
        out.add(name)
    return out


def broken_links(root: Path, pending: set[str] = frozenset()) -> list[str]:
    """Every relative link (and #anchor into a Markdown page) in README.md, the other top-level
    Markdown files and docs/ under ``root`` that leads nowhere, as ``page: link``."""
    pages = sorted(root.glob("*.md")) + sorted((root / "docs").rglob("*.md"))
    bad = []
    for page in pages:
        text = _FENCE.sub("", page.read_text(encoding="utf-8"))
        for link in _LINK.findall(text):
            if re.match(r"[a-z][a-z0-9+.-]*:", link):      # https:, mailto:
                continue
            path, _, frag = link.partition("#")
            target = (page.parent / path).resolve() if path else page
            rel = target.relative_to(root).as_posix() if target.is_relative_to(root) else None
            if not target.exists():
                if rel not in pending:
                    bad.append(f"{page.relative_to(root)}: {link}")
                continue
            if frag and target.suffix == ".md" and \
                    frag not in anchors(target.read_text(encoding="utf-8")):
                bad.append(f"{page.relative_to(root)}: {link} (no such heading)")
    return bad


def test_every_relative_link_in_the_docs_resolves():
    assert broken_links(REPO, PENDING) == []


def test_a_broken_link_or_anchor_is_found(tmp_path):
    (tmp_path / "docs").mkdir()
    (tmp_path / "README.md").write_text(
        "# T\n\nSee [a](docs/a.md), [b](docs/a.md#the-two-commands), [x](docs/gone.md),\n"
        "[y](docs/a.md#nowhere), [web](https://example.org/x.md), [self](#t).\n\n"
        "```md\n[in code](docs/nothing.md)\n```\n")
    (tmp_path / "docs" / "a.md").write_text("# A\n\n## The two `commands`\n\n[up](../README.md)\n")
    assert broken_links(tmp_path) == ["README.md: docs/gone.md",
                                      "README.md: docs/a.md#nowhere (no such heading)"]
    assert broken_links(tmp_path, {"docs/gone.md"}) == \
        ["README.md: docs/a.md#nowhere (no such heading)"]


# -- generated pages -------------------------------------------------------------------------
def _copy_docs(dst: Path) -> None:
    shutil.copy(REPO / "README.md", dst / "README.md")
    shutil.copytree(REPO / "docs", dst / "docs")


def test_generated_pages_are_current_and_a_stale_one_is_found(tmp_path):
    """One page per rule and the rules index, and the key and format tables, are what
    scripts/gen_docs.py writes from the sources; an edited, missing or extra page is stale."""
    gen = _gen_docs()
    from urdf_lint.engine.registry import load_rules
    rules = load_rules()
    assert gen.stale() == [], "docs/ is stale: run python scripts/gen_docs.py"
    assert {p.stem for p in (REPO / "docs" / "rules").glob("UL*.md")} == set(rules)
    page = (REPO / "docs" / "rules" / "UL302.md").read_text()
    assert page.startswith("# UL302 limit-order\n") and "**How to fix.**" in page
    assert 'lower="2.1" upper="-2.1"' in page            # the FAIL example
    index = (REPO / "docs" / "rules" / "README.md").read_text()
    assert all(f"[{code}]({code}.md)" in index for code in rules)

    _copy_docs(tmp_path)
    gen.use_root(tmp_path)
    assert gen.stale() == []
    d = tmp_path / "docs"
    (d / "rules" / "UL302.md").write_text(page.replace("Swap the two values", "Swap them"))
    (d / "rules" / "UL303.md").unlink()
    (d / "rules" / "UL999.md").write_text("# UL999 gone\n")
    conf = (d / "configuration.md").read_text()
    (d / "configuration.md").write_text(conf.replace("| `timeout` | a number of seconds > 0 | 30 |",
                                                     "| `timeout` | a number of seconds > 0 | 31 |"))
    assert sorted(p.relative_to(tmp_path).as_posix() for p in gen.stale()) == [
        "docs/configuration.md", "docs/rules/UL302.md", "docs/rules/UL303.md",
        "docs/rules/UL999.md"]


def test_gen_docs_check_fails_on_a_stale_page_and_writing_fixes_it(tmp_path):
    """``python scripts/gen_docs.py --check`` (the demo included) exits 1 naming the stale page,
    0 once the script has rewritten it."""
    _copy_docs(tmp_path)
    script = [sys.executable, str(REPO / "scripts" / "gen_docs.py")]
    p = subprocess.run([*script, "--check", "--root", str(tmp_path)], capture_output=True,
                       text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    fmt = tmp_path / "docs" / "formatter.md"
    fmt.write_text(fmt.read_text().replace("| `indent` | an integer of spaces > 0 | 2 |",
                                           "| `indent` | an integer of spaces > 0 | 4 |"))
    readme = tmp_path / "README.md"
    readme.write_text(re.sub(r"It lints \d+ models", "It lints 3 models", readme.read_text()))
    p = subprocess.run([*script, "--check", "--root", str(tmp_path)], capture_output=True,
                       text=True, timeout=600)
    assert p.returncode == 1
    assert p.stderr.splitlines() == [
        "README.md is stale: run python scripts/gen_docs.py",
        "docs/formatter.md is stale: run python scripts/gen_docs.py"], p.stderr
    subprocess.run([*script, "--root", str(tmp_path)], check=True, capture_output=True,
                   timeout=600)
    assert (tmp_path / "README.md").read_text() == (REPO / "README.md").read_text()
    p = subprocess.run([*script, "--check", "--root", str(tmp_path)], capture_output=True,
                       text=True, timeout=600)
    assert p.returncode == 0, p.stderr


@pytest.mark.parametrize("page", ["configuration.md", "formatter.md", "output.md", "review.md",
                                  "checking.md"])
def test_each_generated_block_lives_in_its_page(page):
    gen = _gen_docs()
    text = (REPO / "docs" / page).read_text(encoding="utf-8")
    names = {n for n, p in gen.PAGES.items() if p.name == page}
    assert names and all(f"<!-- generated: {n} -->" in text for n in names)


# -- each room says what it owns and what it may import ---------------------------------------
def allowed_imports(contracts: list[dict]) -> dict[str, set[str]]:
    """{room: the rooms it may import} by the import-linter contracts: every room in a lower
    layer (rooms of one layer, ``a | b``, are independent), less what a ``forbidden`` contract
    forbids it."""
    layers = next(c for c in contracts if c["type"] == "layers")["layers"]
    rooms = [[m.strip().strip("()").removeprefix("urdf_lint.") for m in layer.split("|")]
             for layer in layers]
    out = {r: {b for lower in rooms[i + 1:] for b in lower}
           for i, layer in enumerate(rooms) for r in layer}
    for c in contracts:
        if c["type"] == "forbidden":
            for src in c["source_modules"]:
                out[src.removeprefix("urdf_lint.")] -= {
                    m.removeprefix("urdf_lint.") for m in c["forbidden_modules"]}
    return out


def room_doc_errors(pkg: Path, contracts: list[dict]) -> list[str]:
    """What is wrong with the docstring of each room's ``__init__.py`` under ``pkg``: it must
    say what the room owns (a first paragraph that is more than a pointer elsewhere) and have a
    ``May import:`` paragraph naming exactly the rooms the contracts allow it."""
    import ast
    allowed = allowed_imports(contracts)
    errors = []
    for init in sorted(pkg.glob("*/__init__.py")):
        room = init.parent.name
        doc = ast.get_docstring(ast.parse(init.read_text(encoding="utf-8"))) or ""
        paras = [" ".join(p.split()) for p in doc.split("\n\n")]
        if len(paras[0]) < 60 or "see ARCHITECTURE.md" in paras[0]:
            errors.append(f"{room}: the docstring does not say what the room owns")
        may = [p for p in paras if p.startswith("May import:")]
        if len(may) != 1:
            errors.append(f"{room}: no 'May import:' paragraph")
            continue
        named = set(re.findall(r"``(\w+)``", may[0]))
        if room not in allowed:
            errors.append(f"{room}: not in the layers contract")
        elif named != allowed[room]:
            errors.append(f"{room}: 'May import:' names {sorted(named)}, the contracts allow "
                          f"{sorted(allowed[room])}")
    return errors


def _contracts() -> list[dict]:
    from pyproject import pyproject
    return pyproject()["tool"]["importlinter"]["contracts"]


def test_each_room_says_what_it_owns_and_may_import():
    contracts = _contracts()
    assert len(list((REPO / "urdf_lint").glob("*/__init__.py"))) >= 14
    assert room_doc_errors(REPO / "urdf_lint", contracts) == []


def test_a_room_doc_that_disagrees_with_the_contracts_is_found(tmp_path):
    contracts = _contracts()
    for room, doc in {"core": "core: see ARCHITECTURE.md.",
                      "config": "The configuration: the schema, loading, trust and the policy of "
                                "severities.\n\nMay import: ``core``, ``report``, ``run``.",
                      "runner": "Forked workers and their scheduler, handed a handler; it knows "
                                "neither lint nor render.\n\nMay import: ``discovery``, "
                                "``config``, ``report``, ``core``."}.items():
        (tmp_path / room).mkdir()
        (tmp_path / room / "__init__.py").write_text(f'"""{doc}"""\n')
    assert room_doc_errors(tmp_path, contracts) == [
        "config: 'May import:' names ['core', 'report', 'run'], the contracts allow "
        "['core', 'report']",
        "core: the docstring does not say what the room owns",
        "core: no 'May import:' paragraph"]


# -- the walk of a request through the rooms (scripts/walk_check.py) --------------------------
def test_the_walk_of_a_command_starts_in_the_cli_and_counts_its_returns():
    walk = load_script("walk_check")
    assert walk.excursions(["cli", "config", "cli", "config", "cli", "run", "cli"], "cli") == \
        ["cli", "config x2", "run"]
    assert walk.excursions(["cli.main", "core.lazy", "cli.check", "run.pipeline"], "cli") == \
        ["cli", "core.lazy", "run.pipeline"]
    w = walk.walk(["rule", "UL302"])
    assert w.rc == 0 and w.rooms[0] == "cli" and "engine" in w.rooms, w.rooms
    assert all(a != b for a, b in zip(w.rooms, w.rooms[1:], strict=False))       # repeats collapsed
    n = walk.counts(w)
    assert n["stays"] == len(w.rooms) and n["cli re-entries"] == w.rooms.count("cli") - 1
    assert w.modules[0].startswith("urdf_lint.cli.")
