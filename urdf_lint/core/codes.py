"""A rule named by its module, for the rooms below the rules (expansion, engine, discovery, fix,
run's worker): they raise findings under codes of rules they must not import (only the registry
loads rule modules). A rule's file is named by its code (``rules/ul904_resource_limit.py`` is
``UL904``), so the name is enough; tests/test_architecture.py checks every name given here is a
rule module whose ``CODE`` matches."""
from __future__ import annotations

import re
from dataclasses import dataclass

RULE_MODULE = re.compile(r"ul(\d{3})_[a-z0-9_]+")


@dataclass(frozen=True)
class RuleName:
    """``RuleName("ul904_resource_limit").CODE == "UL904"`` (read like the module's ``CODE``)."""
    module: str

    def __post_init__(self) -> None:
        if not RULE_MODULE.fullmatch(self.module):
            raise ValueError(f"not a rule module name: {self.module!r}")

    @property
    def CODE(self) -> str:  # noqa: N802 - as the rule module spells it
        return "UL" + self.module[2:5]
