#!/usr/bin/env python3
"""Write the README's generated tables from their one source of truth.

Each table sits between ``<!-- generated: NAME -->`` and ``<!-- end: NAME -->`` in README.md:

* ``config-keys``: every key of the config schema (``urdf_lint/config/schema.py``: SCHEMA);
* ``format-keys``: the keys of ``[tool.urdf-lint.format]`` (FORMAT_SCHEMA);
* ``output-formats``: the output formats of ``check`` (``urdf_lint/report/``, the registry);
* ``diff-formats``: the output formats of ``diff`` (``urdf_lint/report/diff/``);
* ``demo``: what the demo (``urdf-lint check descriptions/``) lints, which rules fire and its
  summary line, from a real run (:func:`demo_paragraph`; tests/test_accuracy.py checks it).

``python scripts/gen_docs.py`` rewrites them; ``--check`` exits 1 when README.md is stale
(tests/test_config_schema.py checks the tables in process, tests/test_accuracy.py the demo).
"""
from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
README = REPO / "README.md"
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
    return out


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


def render(text: str, demo: bool = False) -> str:
    """``text`` (README.md) with every generated block as its source says (the demo's only
    with ``demo``: it runs the demo)."""
    for name, table in tables(demo).items():
        pat = re.compile(rf"(<!-- generated: {re.escape(name)} -->\n).*?(<!-- end: "
                         rf"{re.escape(name)} -->)", re.S)
        if not pat.search(text):
            raise SystemExit(f"README.md: no <!-- generated: {name} --> ... <!-- end: {name} -->")
        text = pat.sub(lambda m, t=table: m.group(1) + t + "\n" + m.group(2), text)
    return text


def main(argv: list[str]) -> int:
    import gen_types    # the generated Python: engine.api's requests (scripts/gen_types.py)
    old = README.read_text(encoding="utf-8")
    new = render(old, demo=True)
    if "--check" in argv:
        stale = [name for name, ok in gen_types.current().items() if not ok]
        stale += ["README.md"] if new != old else []
        if stale:
            print(f"{', '.join(stale)} stale: run python scripts/gen_docs.py", file=sys.stderr)
            return 1
        return 0
    for name in gen_types.write():
        print(f"{name}: regenerated")
    if new != old:
        README.write_text(new, encoding="utf-8")
        print("README.md: tables regenerated")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
