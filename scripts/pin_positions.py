"""Print the ``FAIL_AT = [...]`` line for rules whose FAIL example does not pin its positions.

    .venv/bin/python scripts/pin_positions.py          # rules without FAIL_AT
    .venv/bin/python scripts/pin_positions.py --all    # every rule (to compare)

It lints each FAIL example in process, exactly as tests/test_rule_examples.py does, and prints
where the rule reports. Check that each position is the element the rule is about before you
paste the line under the rule's FAIL example.
"""
from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests"))


def positions(rule, workdir: Path) -> list[tuple[int, int]]:
    from conftest import make_package
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import RunRequest, run_check
    name = "urdf/example.urdf.xacro" if "xmlns:xacro" in rule.fail else "urdf/example.urdf"
    pkg = make_package(workdir, "example_pkg", {**rule.example_files, name: rule.fail})
    here = os.getcwd()
    os.chdir(pkg)
    try:
        cfg = load_config(None)
        cfg.select = [rule.code, "UL009"] if rule.code != "UL009" else ["UL"]
        res = run_check(RunRequest(["."], cfg, build_resolver(["."], cfg), in_process=True))
    finally:
        os.chdir(here)
    return sorted({(f.line, f.col) for f in res.findings
                   if f.code == rule.code and f.file == str(pkg / name)})


def main() -> int:
    from urdf_lint.engine.registry import load_rules
    os.environ.setdefault("URDF_LINT_EXAMPLE_SECRET", "s3cr3t-value")
    for code, rule in load_rules().items():
        if rule.fail_at and "--all" not in sys.argv:
            continue
        with tempfile.TemporaryDirectory() as d:
            at = positions(rule, Path(d))
        print(f"{code} (rules/{rule.module.rsplit('.', 1)[1]}.py): FAIL_AT = [{', '.join(f'({a}, {b})' for a, b in at)}]")
    return 0


if __name__ == "__main__":
    sys.exit(main())
