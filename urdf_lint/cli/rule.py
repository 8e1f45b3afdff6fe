"""``urdf-lint rule CODE``: one rule's documentation."""
from __future__ import annotations

from typing import TYPE_CHECKING

from urdf_lint.cli.rules import plain
from urdf_lint.core.errors import UsageError

if TYPE_CHECKING:  # pragma: no cover
    from argparse import Namespace

    from urdf_lint.cli.parser import Formatter, SubParsers


NAME = "rule"


def add_parser(sub: SubParsers, raw: Formatter) -> None:
    r = sub.add_parser("rule", help="explain one rule", description="Explain one rule.")
    r.add_argument("code", help="a rule code (UL302) or name (limit-order)")


def run(args: Namespace) -> int:
    return explain(args.code)


def explain(code: str) -> int:
    """One rule's documentation on standard output (``rule``, and the MCP ``explain_rule``)."""
    from urdf_lint.engine.registry import find_rule
    r = find_rule(code)
    if r is None:
        from urdf_lint.core.suggest import did_you_mean
        from urdf_lint.engine.registry import load_rules
        rules = load_rules()
        hint = did_you_mean(code, list(rules) + [x.name for x in rules.values()])
        raise UsageError(f"unknown rule {code!r}{hint} (see 'urdf-lint rules')")
    print(f"{r.code} {r.name} (default severity: {r.severity})\n")
    if r.targets:
        print("Per consumer target (config 'targets'): "
              + ", ".join(f"{t} {s}" for t, s in r.targets.items()) + "\n")
    print(plain(r.doc))
    if r.options:
        print("\nOptions (set under [tool.urdf-lint.rule-options." + r.code + "]):")
        for k, v in r.options.items():
            print(f"  {k} = {v!r}")
    from urdf_lint.engine.verdicts import evidence, load
    seen = evidence(r.code)
    if seen:
        print(f"\nMeasured (the consumers' verdicts shipped with urdf-lint, "
              f"{load().get('measured', '?')}; [target]):")
        for line in seen:
            print("  " + line)
    if r.example_at:   # a rule about a configuration file: the file is the example
        print(f"\nFails ({r.example_at}):\n" + r.example_files[r.example_at].strip())
        print("\nagainst the robot:\n" + r.fail.strip())
        for k, v in r.pass_files.items():
            print(f"\nPasses with {k}:\n" + v.strip())
    else:
        print("\nFails:\n" + r.fail.strip())
    print("\nPasses:\n" + r.passing.strip())
    return 0
