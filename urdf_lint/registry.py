"""The rule catalogue: every module in ``rules/`` (installed as ``urdf_lint.rules``) is a rule.

A rule module defines ``CODE``, ``NAME``, ``SEVERITY``, a docstring, ``FAIL`` and ``PASS``
examples, optional ``OPTIONS`` (defaults), ``NEEDS`` (e.g. ``{"meshes"}``) and
``EXAMPLE_FILES``, and either a ``check(model, ctx)`` generator yielding ``(element, message)``
or ``ORIGIN = "expansion"`` for problems that expansion itself reports.
"""
from __future__ import annotations

import importlib
import pkgutil
from dataclasses import dataclass, field


@dataclass
class Rule:
    code: str
    name: str
    severity: str
    doc: str
    check: object = None
    fail: str = ""
    passing: str = ""
    options: dict = field(default_factory=dict)
    needs: frozenset = frozenset()
    example_files: dict = field(default_factory=dict)
    module: str = ""

    @property
    def summary(self) -> str:
        para = " ".join(self.doc.strip().split("\n\n")[0].split())
        end = para.find(". ")
        return para if end < 0 else para[:end + 1]


_RULES: dict | None = None


def load_rules() -> dict:
    global _RULES
    if _RULES is not None:
        return _RULES
    import urdf_lint.rules as pkg
    rules = {}
    for info in sorted(pkgutil.iter_modules(pkg.__path__), key=lambda i: i.name):
        if info.name.startswith("_"):
            continue
        mod = importlib.import_module(f"urdf_lint.rules.{info.name}")
        code = getattr(mod, "CODE", None)
        if code is None:
            continue
        if code in rules:
            raise RuntimeError(f"duplicate rule code {code} in {info.name} and {rules[code].module}")
        rules[code] = Rule(code=code, name=mod.NAME, severity=mod.SEVERITY,
                           doc=(mod.__doc__ or "").strip(), check=getattr(mod, "check", None),
                           fail=getattr(mod, "FAIL", ""), passing=getattr(mod, "PASS", ""),
                           options=dict(getattr(mod, "OPTIONS", {})),
                           needs=frozenset(getattr(mod, "NEEDS", ())),
                           example_files=dict(getattr(mod, "EXAMPLE_FILES", {})),
                           module=mod.__name__)
    _RULES = dict(sorted(rules.items()))
    return _RULES


def codes_to_names() -> dict:
    return {c: r.name for c, r in load_rules().items()}


def find_rule(code_or_name: str) -> Rule | None:
    rules = load_rules()
    if code_or_name.upper() in rules:
        return rules[code_or_name.upper()]
    for r in rules.values():
        if r.name == code_or_name:
            return r
    return None
