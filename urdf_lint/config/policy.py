"""Policy: which codes run, which findings are kept, and at what severity.

One matcher decides whether a code pattern (from ``select``, ``ignore``, ``per-file-ignores``,
``severity``, ``rule-options`` or a suppression comment) applies to a rule: ``ALL``, a code
prefix (``UL3`` = every joint-limit rule, ``UL302`` = that rule) or the rule's name
(``limit-order``). Where several patterns apply, the most specific (longest) one wins.
"""
from __future__ import annotations

import fnmatch
import os
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Iterable

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.config.schema import Config


def code_matches(pattern: str, code: str, name: str = "") -> bool:
    """Does ``pattern`` (ALL, a code prefix or a rule name) apply to rule ``code``/``name``?"""
    return pattern == "ALL" or code.startswith(pattern) or (bool(name) and pattern == name)


def specificity(patterns: Iterable[str], code: str, name: str = "") -> int:
    """The length of the most specific pattern that applies, -1 when none does."""
    return max((len(p) for p in patterns if code_matches(p, code, name)), default=-1)


@dataclass(frozen=True)
class Policy:
    """Which findings a run reports and at what severity: select, ignore, per-file ignores and
    severity overrides."""
    select: tuple[str, ...] = ("UL",)
    ignore: tuple[str, ...] = ()
    per_file_ignores: dict[str, Any] = field(default_factory=dict)  # glob -> [patterns]
    severity: dict[str, Any] = field(default_factory=dict)  # pattern -> severity
    root: str = "."                                        # per-file globs are relative to it
    targets: tuple[str, ...] = ("ros",)                    # consumer targets (urdf_lint.core.targets)

    @classmethod
    def from_config(cls, cfg: "Config") -> "Policy":
        return cls(select=tuple(cfg.select) + tuple(cfg.extend_select), ignore=tuple(cfg.ignore),
                   per_file_ignores={k: list(v) for k, v in cfg.per_file_ignores.items()},
                   severity=dict(cfg.severity), root=cfg.root, targets=tuple(cfg.targets))

    def is_selected(self, code: str, name: str = "") -> bool:
        s = specificity(self.select, code, name)
        return s >= 0 and s > specificity(self.ignore, code, name)

    def selected_codes(self, rules: dict[str, Any]) -> list[str]:
        """The codes selected and applying to at least one selected target (a rule whose
        ``TARGETS`` turns it off for all of them does not run)."""
        from urdf_lint.core.targets import applies
        return [c for c, r in rules.items() if self.is_selected(c, r.name)
                and (not getattr(r, "targets", None) or applies(r.targets, r.severity,
                                                                 self.targets))]

    def ignored_for_file(self, code: str, name: str, file: str) -> bool:
        if not self.per_file_ignores:
            return False
        try:
            rel = os.path.relpath(file, self.root)
        except ValueError:
            rel = file
        for pattern, codes in self.per_file_ignores.items():
            if fnmatch.fnmatch(rel, pattern) or fnmatch.fnmatch(os.path.basename(file), pattern):
                if any(code_matches(c, code, name) for c in codes):
                    return True
        return False

    def severity_of(self, code: str, name: str, default: str) -> str:
        """The configured severity of a rule (the most specific override wins)."""
        over = self.override_of(code, name)
        return default if over is None else over

    def override_of(self, code: str, name: str) -> str | None:
        """The severity the config sets for a rule (the most specific pattern), or None."""
        best, sev = -1, None
        for pattern, s in self.severity.items():
            if code_matches(pattern, code, name) and len(pattern) > best:
                best, sev = len(pattern), s
        return sev
