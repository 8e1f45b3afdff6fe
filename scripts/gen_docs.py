#!/usr/bin/env python3
"""Write the README's generated tables from their one source of truth.

Each table sits between ``<!-- generated: NAME -->`` and ``<!-- end: NAME -->`` in README.md:

* ``config-keys``: every key of the config schema (``urdf_lint/config/schema.py``: SCHEMA);
* ``format-keys``: the keys of ``[tool.urdf-lint.format]`` (FORMAT_SCHEMA);
* ``output-formats``: the output formats of ``check`` (``urdf_lint/report/``, the registry);
* ``diff-formats``: the output formats of ``diff`` (``urdf_lint/report/diff/``).

``python scripts/gen_docs.py`` rewrites them; ``--check`` exits 1 when README.md is stale
(tests/test_config_schema.py runs the check).
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

README = Path(__file__).resolve().parent.parent / "README.md"


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


def tables() -> dict[str, str]:
    """Table name -> its Markdown, from the sources."""
    from urdf_lint.config.schema import FORMAT_SCHEMA, SCHEMA
    from urdf_lint.report import diff, registry
    return {
        "config-keys": _key_table(SCHEMA, "key"),
        "format-keys": _key_table(FORMAT_SCHEMA, "key under `[tool.urdf-lint.format]`"),
        "output-formats": _format_table(registry.formats()),
        "diff-formats": _format_table(diff.formats()),
    }


def render(text: str) -> str:
    """``text`` (README.md) with every generated table as its source says."""
    for name, table in tables().items():
        pat = re.compile(rf"(<!-- generated: {re.escape(name)} -->\n).*?(<!-- end: "
                         rf"{re.escape(name)} -->)", re.S)
        if not pat.search(text):
            raise SystemExit(f"README.md: no <!-- generated: {name} --> ... <!-- end: {name} -->")
        text = pat.sub(lambda m, t=table: m.group(1) + t + "\n" + m.group(2), text)
    return text


def main(argv: list[str]) -> int:
    old = README.read_text(encoding="utf-8")
    new = render(old)
    if "--check" in argv:
        if new != old:
            print("README.md is stale: run python scripts/gen_docs.py", file=sys.stderr)
            return 1
        return 0
    if new != old:
        README.write_text(new, encoding="utf-8")
        print("README.md: tables regenerated")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
