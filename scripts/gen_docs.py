#!/usr/bin/env python3
"""Write the generated documentation from its one source of truth.

Blocks between ``<!-- generated: NAME -->`` and ``<!-- end: NAME -->`` in README.md and the
pages of ``docs/`` (each block in one page; :data:`PAGES` says where):

* ``config-keys``: every key of the config schema (``urdf_lint/config/schema.py``: SCHEMA),
  in docs/configuration.md;
* ``format-keys``: the keys of ``[tool.urdf-lint.format]`` (FORMAT_SCHEMA), docs/formatter.md;
* ``output-formats``: the output formats of ``check`` (``urdf_lint/report/``, the registry),
  docs/output.md;
* ``diff-formats``: the output formats of ``diff`` (``urdf_lint/report/diff/``), docs/review.md;
* ``demo``: what the demo (``urdf-lint check descriptions/``) lints, which rules fire and its
  summary line, from a real run (:func:`demo_paragraph`; tests/test_accuracy.py checks it),
  in README.md; ``demo-yaml``: its first value read from YAML, docs/checking.md;
  ``r2d2-yaml``: the seed R2D2 with a limit swapped in its YAML, checked and fixed
  (:func:`r2d2_example`), in README.md.

Whole pages (:func:`pages`): ``docs/rules/ULnnn.md``, one per rule, from the rule module's
docstring and examples (``urdf_lint/engine/rulesdoc.py``), and their index
``docs/rules/README.md``.

``python scripts/gen_docs.py`` rewrites them (and removes the page of a rule that is gone);
``--check`` writes nothing and exits 1 when any of them is stale (tests/test_docs.py checks the
same in process, without the demo; tests/test_accuracy.py the demo).
"""
from __future__ import annotations

import functools
import os
import re
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


def use_root(root: Path) -> None:
    """Read and write the pages under ``root`` (default: this checkout; the code documented is
    always this checkout's)."""
    global README, DOCS, RULES_DIR, PAGES
    README = root / "README.md"
    DOCS = root / "docs"
    RULES_DIR = DOCS / "rules"
    # the page holding each generated block
    PAGES = {"demo": README, "r2d2-yaml": README, "demo-yaml": DOCS / "checking.md",
             "config-keys": DOCS / "configuration.md", "format-keys": DOCS / "formatter.md",
             "output-formats": DOCS / "output.md", "diff-formats": DOCS / "review.md"}


use_root(REPO)
sys.path.insert(0, str(REPO))   # this checkout's code, as the demo it runs uses
sys.path.insert(0, str(REPO / "scripts"))


def _row(*cells: str) -> str:
    return "| " + " | ".join(c.replace("|", " or ") for c in cells) + " |"


def _key_table(keys, first: str) -> str:
    rows = [f"| {first} | value | default | what |", "|---|---|---|---|"]
    rows += [_row(f"`{k.name}`", k.type.expected, k.default_text, k.help) for k in keys]
    return "\n".join(rows)


def _format_table(formats: dict) -> str:
    rows = ["| format | what |", "|---|---|"]
    rows += [_row(f"`{name}`", cls.help) for name, cls in formats.items()]
    return "\n".join(rows)


def run_demo() -> str:
    """The output of the README's demo, run as a user runs it (it exits 1: it finds errors)."""
    p = subprocess.run([sys.executable, "-m", "urdf_lint", "check", "descriptions/", "--no-cache"],
                       cwd=REPO, capture_output=True, text=True,
                       env={**os.environ, "NO_COLOR": "1"}, timeout=600)
    if p.returncode != 1:
        raise SystemExit(f"the demo exited {p.returncode}, not 1:\n{p.stderr}")
    return p.stdout


def demo_paragraph(output: str) -> str:
    """The README's demo paragraph for a run of it (:func:`run_demo`): how many models, which
    rules fire (and why the others do not), and the summary line it ends with."""
    summary = output.splitlines()[-1]
    models = int(re.search(r"in (\d+) model", summary).group(1))
    from urdf_lint.core.targets import applies
    from urdf_lint.engine.registry import load_rules
    rules = load_rules()
    fired = set(re.findall(r"^\S+:\d+:\d+: (UL\d{3}) ", output, re.M))
    off = sorted(c for c, r in rules.items()
                 if c not in fired and not applies(r.targets, r.severity, ["ros"]))
    quiet = sorted(set(rules) - fired - set(off))
    targets = sorted({t for c in off for t, sev in rules[c].targets.items()
                      if t != "*" and sev != "off"})
    why = []
    if quiet == ["UL904"]:
        why.append("`UL904`, the time and memory limit, which would make the demo wait")
    elif quiet:
        why.append(", ".join(f"`{c}`" for c in quiet))
    if off:
        names = ", ".join(f"`{c}`" for c in off[:-1]) + (" and " if len(off) > 1 else "") + \
            f"`{off[-1]}`"
        why.append(f"{names}, which {'are' if len(off) > 1 else 'is'} off for the default "
                   f"target: add `--target {','.join(targets)}` to see them")
    but = f" (all but {', and '.join(why)})" if why else ""
    text = (f"It lints {models} models: the two seed robots pass, and the broken "
            f"ones under `descriptions/broken/` make {len(fired)} of the {len(rules)} rules "
            f"fire{but}, each at its xacro line with the macro chain. It ends with `{summary}` "
            "and exits 1, as a lint run with errors does.")
    return _wrap(text)


def _wrap(text: str, width: int = 99) -> str:
    """``text`` wrapped at ``width`` without breaking inside a `code span`."""
    lines, line = [], ""
    for word in re.findall(r"`[^`]*`[^\s]*|\S+", text):
        if line and len(line) + 1 + len(word) > width:
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}" if line else word
    return "\n".join([*lines, line])


@functools.lru_cache(maxsize=None)
def tables(demo: bool = True) -> dict[str, str]:
    """Block name -> its Markdown, from the sources (``demo``: run the demo for its block)."""
    from urdf_lint.config.schema import FORMAT_SCHEMA, SCHEMA
    from urdf_lint.report import diff, registry
    out = {
        "config-keys": _key_table(SCHEMA, "key"),
        "format-keys": _key_table(FORMAT_SCHEMA, "key under `[tool.urdf-lint.format]`"),
        "output-formats": _format_table(registry.formats()),
        "diff-formats": _format_table(diff.formats()),
    }
    if demo:
        output = run_demo()
        out["demo"] = demo_paragraph(output)
        out["demo-yaml"] = yaml_example(output)
        out["r2d2-yaml"] = r2d2_example()
    return out


R2D2_SWAP = ("gripper_extension: {lower: -0.38, upper: 0.0,",
             "gripper_extension: {lower: 0.0, upper: -0.38,")


def r2d2_example() -> str:
    """The seed R2D2 with its gripper extension's limits swapped in its YAML (a copy, in a
    temporary folder): what ``check`` says (the xacro line, ``value from`` the YAML line) and
    what ``--fix`` then does to the YAML, as the runs print them."""
    import shutil
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        pkg = Path(tmp) / "r2d2_description"
        shutil.copytree(REPO / "descriptions" / "r2d2_description", pkg)
        limits = pkg / "config" / "joint_limits.yaml"
        before = limits.read_text()
        if R2D2_SWAP[0] not in before:
            raise SystemExit(f"{limits.name} no longer holds {R2D2_SWAP[0]!r}")
        limits.write_text(before.replace(*R2D2_SWAP))

        def run(*args: str) -> subprocess.CompletedProcess:
            return subprocess.run([sys.executable, "-m", "urdf_lint", "check",
                                   "r2d2_description/", "--no-cache", *args], cwd=tmp,
                                  capture_output=True, text=True, timeout=600,
                                  env={**os.environ, "NO_COLOR": "1"})
        checked, fixed = run(), run("--fix")
        after = limits.read_text()
    if checked.returncode != 1 or "value from" not in checked.stdout or after != before:
        raise SystemExit(f"the R2D2 example did not find and fix its YAML:\n{checked.stdout}"
                         f"{checked.stderr}\n{fixed.stderr}\n{after}")
    line = next(i for i, t in enumerate(before.splitlines(), 1) if t.startswith(R2D2_SWAP[0]))
    return "\n".join([
        "```console",
        f"$ sed -i 's/{R2D2_SWAP[0]}/{R2D2_SWAP[1]}/' r2d2_description/config/joint_limits.yaml",
        "$ urdf-lint check r2d2_description/", checked.stdout.rstrip(),
        "$ urdf-lint check r2d2_description/ --fix", fixed.stderr.rstrip(),
        f"$ sed -n {line}p r2d2_description/config/joint_limits.yaml",
        before.splitlines()[line - 1], "```"])


def yaml_example(output: str) -> str:
    """The demo's first finding whose value comes from a YAML file, as the run printed it (the
    finding, its call chain and the ``value from`` line), in a console block."""
    lines = output.splitlines()
    for i, line in enumerate(lines):
        if line.lstrip().startswith("value from ") and ".yaml:" in line:
            start = i
            while start > 0 and lines[start].startswith("    "):
                start -= 1
            shown = "\n".join(lines[start:i + 1])
            return f"```console\n$ urdf-lint check descriptions/\n...\n{shown}\n...\n```"
    raise SystemExit("the demo shows no finding with a value from a YAML file")


def render(text: str, demo: bool = False, names: set[str] | None = None) -> str:
    """``text`` (a page) with every generated block it holds as its source says (the demo's
    only with ``demo``: it runs the demo); ``names``: the blocks it must hold."""
    for name, table in tables(demo).items():
        pat = re.compile(rf"(<!-- generated: {re.escape(name)} -->\n).*?(<!-- end: "
                         rf"{re.escape(name)} -->)", re.S)
        if not pat.search(text):
            if names and name in names:
                raise SystemExit(f"no <!-- generated: {name} --> ... <!-- end: {name} -->")
            continue
        text = pat.sub(lambda m, t=table: m.group(1) + t + "\n" + m.group(2), text)
    return text


RULES_INTRO = """\
# Rules

Generated by `python scripts/gen_docs.py` from each rule module in `rules/` (its docstring,
`SEVERITY`, `TARGETS`, `FAIL` and `PASS`): do not edit. `urdf-lint rules` lists the catalogue in
a terminal, `urdf-lint rule UL302` (or `rule limit-order`) explains one, and
`urdf-lint rules --format markdown` writes this catalogue as one page.

Select or ignore rules by code, prefix (`UL3`) or name. Families: `UL0` input and expansion,
`UL1` tree, `UL2` required elements and values, `UL3` joint limits, `UL4` meshes and textures,
`UL5` materials, `UL6` inertial, `UL7` cross-references (transmission, ros2_control, gazebo),
`UL8` information, `UL9` security. Which consumer program each rule speaks for:
[targets](../targets.md); how to add a rule: [CONTRIBUTING.md](../../CONTRIBUTING.md).
"""


def pages() -> dict[Path, str]:
    """The pages written whole from the sources: one per rule and the rules index."""
    from urdf_lint.engine.registry import load_rules
    from urdf_lint.engine.rulesdoc import rule_body, summary_table, targets_table
    rules = load_rules()
    out: dict[Path, str] = {}
    for code, r in rules.items():
        src = f"rules/{r.module.rsplit('.', 1)[-1]}.py"
        lines = [f"# {code} {r.name}", "", f"<!-- Generated from `{src}` by "
                 "`python scripts/gen_docs.py`: edit the rule module, not this page. -->", ""]
        lines += rule_body(code, r)
        lines += ["", f"[All rules](README.md) · source: [`{src}`](../../{src})"]
        out[RULES_DIR / f"{code}.md"] = "\n".join(lines) + "\n"
    index = [RULES_INTRO, *summary_table(rules, lambda code, r: f"{code}.md"), "",
             *targets_table(rules, lambda code, r: f"{code}.md")]
    out[RULES_DIR / "README.md"] = "\n".join(index) + "\n"
    return out


def stale(demo: bool = False) -> list[Path]:
    """The generated pages and blocks that differ from their sources (``demo``: run the demo and
    check its blocks too), and rule pages of rules that no longer exist."""
    out = []
    for path, want in pages().items():
        if not path.is_file() or path.read_text(encoding="utf-8") != want:
            out.append(path)
    out += sorted(set(RULES_DIR.glob("UL*.md")) - set(pages()))
    for page in sorted(set(PAGES.values())):
        text = page.read_text(encoding="utf-8")
        names = {n for n, p in PAGES.items() if p == page and (demo or not n.startswith("demo"))}
        if render(text, demo, names) != text:
            out.append(page)
    return out


def main(argv: list[str]) -> int:
    """``[--check] [--root DIR]``: write (or only check) the pages under DIR (default: here)."""
    root = Path(argv[argv.index("--root") + 1]).resolve() if "--root" in argv else REPO
    use_root(root)
    import gen_types    # the generated Python: engine.api's requests, Config (scripts/gen_types.py)
    if "--check" in argv:
        bad = [str(path.relative_to(root)) for path in stale(demo=True)]
        bad += [name for name, ok in gen_types.current().items() if not ok]
        for name in bad:
            print(f"{name} is stale: run python scripts/gen_docs.py", file=sys.stderr)
        return 1 if bad else 0
    for name in gen_types.write():
        print(f"{name}: regenerated")
    for page in sorted(set(PAGES.values())):
        old = page.read_text(encoding="utf-8")
        new = render(old, demo=True, names={n for n, p in PAGES.items() if p == page})
        if new != old:
            page.write_text(new, encoding="utf-8")
            print(f"{page.relative_to(root)}: tables regenerated")
    want = pages()
    RULES_DIR.mkdir(parents=True, exist_ok=True)
    for path in sorted(set(RULES_DIR.glob("UL*.md")) - set(want)):
        path.unlink()
        print(f"{path.relative_to(root)}: removed (no such rule)")
    for path, text in want.items():
        if not path.is_file() or path.read_text(encoding="utf-8") != text:
            path.write_text(text, encoding="utf-8")
            print(f"{path.relative_to(root)}: written")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
