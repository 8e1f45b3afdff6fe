"""``urdf-lint rules``: the rule catalogue."""
from __future__ import annotations

import re
import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # pragma: no cover
    from argparse import Namespace

    from urdf_lint.cli.parser import Formatter, SubParsers


NAME = "rules"


def add_parser(sub: SubParsers, raw: Formatter) -> None:
    rl = sub.add_parser("rules", help="list the rule catalogue", description="List the rule catalogue.")
    rl.add_argument("--format", choices=["text", "markdown"], default="text",
                    help="text: one line per rule; markdown: the full rules page (default: text)")


def plain(text: str) -> str:
    """Docstring text for a terminal: reST literals (````x````) become ```x```."""
    return re.sub(r"``(.+?)``", r"`\1`", text, flags=re.S)


def first_sentence(doc: str) -> str:
    """The first sentence of a rule's docstring, as plain text (an ellipsis is not an end)."""
    para = " ".join(plain(doc).strip().split("\n\n")[0].split())
    m = re.search(r"(?<!\.)\.(?!\.)\s+", para)
    return para if m is None else para[:m.start() + 1]


def run(args: Namespace) -> int:
    from urdf_lint.engine.registry import load_rules
    if args.format == "markdown":
        from urdf_lint.engine.rulesdoc import markdown
        sys.stdout.write(markdown(load_rules()))
        return 0
    for code, r in load_rules().items():
        print(f"{code}  {r.name:<28} {r.severity:<8} {first_sentence(r.doc)}")
    return 0
