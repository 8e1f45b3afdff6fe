#!/usr/bin/env python3
"""Scaffold a rule: ``python scripts/add_rule.py CODE NAME [--severity S]``.

Writes ``rules/ulNNN_NAME.py`` with the fixed doc sections (what it finds, ``Why:``, ``How to
fix:``), ``CODE``, ``NAME``, ``SEVERITY``, ``FAIL``/``FAIL_AT``/``PASS`` examples and a
``check`` whose condition is a TODO, and a broken demo model under
``descriptions/broken/broken_robots/urdf/`` that makes the rule fire once the condition is
written. Then: fill in the TODOs, run ``pytest -q -m unit -k CODE`` (the examples are checked
four ways) and ``python scripts/gen_docs.py`` (the rule's page and the demo's numbers).
Refuses a code or a name that is taken, and writes nothing then.
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
RULES = REPO / "rules"
DEMO = REPO / "descriptions" / "broken" / "broken_robots" / "urdf"
SEVERITIES = ("error", "warning", "info")

RULE = '''"""TODO: what it finds, in one sentence (the summary `urdf-lint rules` shows).

Why: TODO: why it matters: which consumer rejects or misreads it, with its version.

How to fix: TODO: what to change in the description.
"""
CODE = "{code}"
NAME = "{name}"
SEVERITY = "{severity}"
FAIL = """<robot name="r">
  <link name="fails_here"/>
</robot>
"""
FAIL_AT = [(2, 3)]          # (line, column) of each finding in FAIL
PASS = """<robot name="r">
  <link name="base_link"/>
</robot>
"""
from typing import TYPE_CHECKING

from urdf_lint.engine.api import Report

if TYPE_CHECKING:   # the rule API's types, for mypy and editors
    from urdf_lint.engine.api import Checked, Context, Model


def check(model: "Model", ctx: "Context") -> "Checked":
    # what the rule looks at: model.top_links(), model.root.iter("joint"), ... (engine/api.py)
    for link in model.top_links():
        if False:  # TODO: the condition under which this element is wrong
            yield Report(link, f"link '{{link.get('name')}}': TODO: say what is wrong")
'''

DEMO_MODEL = '''<?xml version="1.0"?>
<!-- The broken demo model of {code} {name} (rules/{module}.py): it makes the rule fire. -->
<robot name="{robot}">
  <link name="fails_here"/>
</robot>
'''


def scaffold(code: str, name: str, severity: str = "warning",
             repo: Path = REPO) -> list[Path]:
    """Write the rule module and its demo model under ``repo``; the paths written."""
    if not re.fullmatch(r"UL\d{3}", code):
        raise SystemExit(f"add_rule: {code!r} is not a rule code (ULnnn)")
    if not re.fullmatch(r"[a-z][a-z0-9]*(-[a-z0-9]+)*", name):
        raise SystemExit(f"add_rule: {name!r} is not a rule name (lower-case words joined by -)")
    if severity not in SEVERITIES:
        raise SystemExit(f"add_rule: severity {severity!r} is not one of {', '.join(SEVERITIES)}")
    rules = repo / RULES.relative_to(REPO)
    for taken in rules.glob("ul[0-9][0-9][0-9]_*.py"):
        text = taken.read_text(encoding="utf-8")
        if taken.name.startswith(code.lower() + "_") or re.search(
                rf'^NAME = "{re.escape(name)}"$', text, re.M):
            raise SystemExit(f"add_rule: {code} or {name} is taken by {taken.name}")
    module = f"{code.lower()}_{name.replace('-', '_')}"
    rule = rules / f"{module}.py"
    demo = repo / DEMO.relative_to(REPO) / f"{module}.urdf"
    if demo.exists():
        raise SystemExit(f"add_rule: {demo} exists")
    rule.write_text(RULE.format(code=code, name=name, severity=severity), encoding="utf-8")
    demo.write_text(DEMO_MODEL.format(code=code, name=name, module=module, robot=module),
                    encoding="utf-8")
    return [rule, demo]


def main(argv: list[str]) -> int:
    args = [a for a in argv if not a.startswith("--")]
    severity = argv[argv.index("--severity") + 1] if "--severity" in argv else "warning"
    if severity in args:
        args.remove(severity)
    if len(args) != 2:
        print(__doc__.strip().splitlines()[0], file=sys.stderr)
        return 2
    for path in scaffold(args[0], args[1], severity):
        print(f"wrote {path.relative_to(REPO)}")
    print(f"next: fill in the TODOs, then .venv/bin/python -m pytest -q -m unit -k {args[0]} "
          "and .venv/bin/python scripts/gen_docs.py")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
