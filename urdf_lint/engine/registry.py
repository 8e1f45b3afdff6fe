"""The rule catalogue: every module in ``rules/`` (installed as ``urdf_lint.rules``) is a rule,
and every code urdf-lint reports has one.

A rule module defines:

* ``CODE``, ``NAME``, ``SEVERITY``, a docstring (why, how to fix, options), ``FAIL`` and
  ``PASS`` examples, optional ``FAIL_AT`` (the ``(line, col)`` positions the FAIL example must
  report), ``OPTIONS`` (defaults) and ``EXAMPLE_FILES`` (extra files for the examples);
* ``SCOPE``: ``"model"`` (default) for ``check(model, ctx)`` yielding
  :class:`urdf_lint.engine.api.Report` ``(element, message, severity=None, fix=None)`` (a
  severity raises or lowers that one problem; a fix is a request such as ``set_attrs``) for one
  model, or ``"run"`` for ``check(run, ctx)`` yielding ``Report(origin, message)`` over every
  model of a run (e.g. UL106: the same robot name in two files). A rule imports only
  :mod:`urdf_lint.engine.api` (and its own ``rules/_*.py`` helpers);
* or no ``check`` and ``ORIGIN``, naming the part of urdf-lint that raises the code by
  importing the module and using its ``CODE``: ``"expansion"`` (the xacro integration's error
  table, :mod:`urdf_lint.expansion.errors`) or ``"engine"`` (the lint and run pipeline);
* optional ``NEEDS = {"meshes"}``: the rule loads mesh geometry (slow on a cold cache; shown in
  the rules page so that users know what ``ignore`` saves);
* optional ``TARGETS = {"mujoco": "error", ...}``: the severity (or ``"off"``) per consumer
  target (:mod:`urdf_lint.core.targets`); a literal dict of strings, read like the assignments
  above. A check may give such a dict for one finding (``Report(..., targets=...)``).

``CODE``, ``NAME``, ``SEVERITY``, ``SCOPE`` and ``ORIGIN`` are plain string assignments at the
start of a line: :func:`catalogue` reads them from the sources without importing the 65
modules (~20 ms), which is all a cached run needs (names, severities, which rules run over the
whole run). A module whose assignments it cannot read is imported instead.
"""
from __future__ import annotations

import importlib
import re
from dataclasses import dataclass, field
from types import ModuleType
from typing import TYPE_CHECKING, Any, Callable, Iterable, Iterator, NamedTuple

from urdf_lint.core.plugins import submodule_names

if TYPE_CHECKING:  # pragma: no cover - the rules' module, imported when a rule runs
    from urdf_lint.engine.api import Report

SCOPES = ("model", "run")
ORIGINS = ("rule", "expansion", "engine")
KNOWN_NEEDS = frozenset({"meshes"})


@dataclass
class Rule:
    """A rule module loaded: its code, name, severity, docs, examples, options and check."""
    code: str
    name: str
    severity: str
    doc: str
    check: Callable[..., Iterable[Any]] | None = None
    fail: str = ""
    passing: str = ""
    options: dict[str, Any] = field(default_factory=dict)
    needs: frozenset[str] = frozenset()
    example_files: dict[str, str] = field(default_factory=dict)
    module: str = ""
    scope: str = "model"
    origin: str = "rule"               # who raises it: a rule's check, expansion or the engine
    fail_at: tuple[tuple[int, int], ...] = ()   # ((line, col), ...) the FAIL example must report
    targets: dict[str, str] = field(default_factory=dict)   # target -> severity | "off" (core.targets)
    example_targets: tuple[str, ...] = ("ros",)  # the targets its FAIL and PASS examples are linted with
    example_at: str = ""               # the EXAMPLE_FILES file FAIL_AT is in ("": the FAIL model)
    pass_files: dict[str, str] = field(default_factory=dict)  # PASS_FILES: the PASS example's
                                       # files where they differ from EXAMPLE_FILES (a config file)

    @property
    def summary(self) -> str:
        para = " ".join(self.doc.strip().split("\n\n")[0].split())
        end = para.find(". ")
        return para if end < 0 else para[:end + 1]


_RULES: dict[str, Rule] | None = None


def rule_from_module(mod: ModuleType) -> Rule:
    check = getattr(mod, "check", None)
    origin = getattr(mod, "ORIGIN", "rule")
    scope = getattr(mod, "SCOPE", "model")
    needs = frozenset(getattr(mod, "NEEDS", ()))
    where = f"{mod.__name__}"
    if scope not in SCOPES:
        raise RuntimeError(f"{where}: SCOPE must be one of {SCOPES}, not {scope!r}")
    if origin not in ORIGINS:
        raise RuntimeError(f"{where}: ORIGIN must be one of {ORIGINS}, not {origin!r}")
    if (check is None) == (origin == "rule"):
        raise RuntimeError(f"{where}: a rule has either check() or ORIGIN = 'expansion'/'engine'")
    if needs - KNOWN_NEEDS:
        raise RuntimeError(f"{where}: unknown NEEDS {sorted(needs - KNOWN_NEEDS)}")
    from urdf_lint.core.targets import check_table
    targets = check_table(getattr(mod, "TARGETS", {}), where)
    return Rule(code=mod.CODE, name=mod.NAME, severity=mod.SEVERITY, targets=targets,
                doc=(mod.__doc__ or "").strip(), check=check,
                fail=getattr(mod, "FAIL", ""), passing=getattr(mod, "PASS", ""),
                options=dict(getattr(mod, "OPTIONS", {})), needs=needs,
                example_files=dict(getattr(mod, "EXAMPLE_FILES", {})),
                module=mod.__name__, scope=scope, origin=origin,
                fail_at=tuple(tuple(p) for p in getattr(mod, "FAIL_AT", ())),
                example_targets=tuple(getattr(mod, "EXAMPLE_TARGETS", ("ros",))),
                example_at=getattr(mod, "EXAMPLE_AT", ""),
                pass_files=dict(getattr(mod, "PASS_FILES", {})))


def load_rules() -> dict[str, Rule]:
    global _RULES
    if _RULES is not None:
        return _RULES
    import urdf_lint.rules as pkg
    rules: dict[str, Rule] = {}
    for name in submodule_names(pkg.__path__):
        mod = importlib.import_module(f"urdf_lint.rules.{name}")
        code = getattr(mod, "CODE", None)
        if code is None:
            continue
        if code in rules:
            raise RuntimeError(f"duplicate rule code {code} in {name} and {rules[code].module}")
        rules[code] = rule_from_module(mod)
    _RULES = dict(sorted(rules.items()))
    return _RULES


class Entry(NamedTuple):
    """What the catalogue knows of a rule without importing it."""
    code: str
    name: str
    severity: str
    scope: str
    origin: str
    module: str
    targets: dict[str, str] = {}


_CATALOGUE: dict[str, Entry] | None = None
_CATALOGUE_OF: dict[str, Rule] | None = None   # the loaded rules it was made from (None: the sources)
_ASSIGNED = re.compile(r"""^(CODE|NAME|SEVERITY|SCOPE|ORIGIN) = ["']([^"'\n]*)["'][ \t]*$""", re.M)
_TARGETS = re.compile(r"^TARGETS = (\{[^{}]*\})[ \t]*$", re.M)


def _targets_of(source: str, where: str) -> dict[str, str] | None:
    """The ``TARGETS`` literal of a rule's source ({} when it has none; None when it has one
    that is not a plain literal: the module is imported instead)."""
    if "\nTARGETS" not in source:
        return {}
    m = _TARGETS.search(source)
    if m is None:
        return None
    import ast
    from urdf_lint.core.targets import check_table
    try:
        return check_table(ast.literal_eval(m.group(1)), where)
    except (ValueError, SyntaxError):
        return None


def catalogue() -> dict[str, Entry]:
    """code -> :class:`Entry` for every rule, read from the rule sources (or from the loaded
    rules when they are loaded already)."""
    global _CATALOGUE, _CATALOGUE_OF
    if _RULES is not None:   # loaded (or replaced, in a test): they are the truth
        if _CATALOGUE_OF is not _RULES:
            _CATALOGUE = {c: _entry(r) for c, r in _RULES.items()}
            _CATALOGUE_OF = _RULES
        assert _CATALOGUE is not None
        return _CATALOGUE
    if _CATALOGUE is not None and _CATALOGUE_OF is None:
        return _CATALOGUE
    import os
    import urdf_lint.rules as pkg
    from urdf_lint.core import fsbound
    out: dict[str, Entry] = {}
    for folder in pkg.__path__:
        for name in submodule_names([folder]):
            module = f"urdf_lint.rules.{name}"
            try:
                source = fsbound.read_text(os.path.join(folder, name + ".py"))
                found = dict(_ASSIGNED.findall(source))
                targets = _targets_of(source, module)
            except (OSError, UnicodeDecodeError):
                found, targets = {}, None
            if {"CODE", "NAME", "SEVERITY"} <= set(found) and targets is not None:
                e = Entry(found["CODE"], found["NAME"], found["SEVERITY"],
                          found.get("SCOPE", "model"), found.get("ORIGIN", "rule"), module,
                          targets)
            else:   # not plain assignments: ask the module itself
                mod = importlib.import_module(module)
                if getattr(mod, "CODE", None) is None:
                    continue
                e = _entry(rule_from_module(mod))
            if e.code in out:
                raise RuntimeError(f"duplicate rule code {e.code} in {module} and "
                                   f"{out[e.code].module}")
            out[e.code] = e
    _CATALOGUE, _CATALOGUE_OF = dict(sorted(out.items())), None
    return _CATALOGUE


def _entry(r: Rule) -> Entry:
    return Entry(r.code, r.name, r.severity, r.scope, r.origin, r.module, r.targets)


def load_rule(code: str) -> Rule | None:
    """One rule, importing only its own module."""
    if _RULES is not None:
        return _RULES.get(code)
    e = catalogue().get(code)
    if e is None:
        return None
    rule = _LOADED.get(code)
    if rule is None:
        rule = _LOADED[code] = rule_from_module(importlib.import_module(e.module))
    return rule


_LOADED: dict[str, Rule] = {}


def as_report(item: Any, code: str) -> Report:
    """The :class:`urdf_lint.engine.api.Report` a check yielded. A tuple ``(item, message,
    extras...)`` (the form before ``Report``; accepted for one release, with a
    ``DeprecationWarning`` naming the rule) has its extras sorted by type: a string is a
    severity, a dict a target table, a :class:`urdf_lint.core.findings.Cause` the root cause,
    anything else a fix request."""
    from urdf_lint.engine.api import Report
    if isinstance(item, Report):
        return item
    import warnings
    warnings.warn(f"rule {code} yields a tuple; yield urdf_lint.engine.api.Report(element, "
                  "message, severity=None, fix=None) instead (tuples are accepted until the "
                  "next release)", DeprecationWarning, stacklevel=2)
    from urdf_lint.core.findings import Cause
    sev, req, table, cause = None, None, None, None
    for x in item[2:]:
        if isinstance(x, Cause):
            cause = x
        elif isinstance(x, str):
            sev = x
        elif isinstance(x, dict):
            table = x
        elif x is not None:
            req = x
    return Report(item[0], item[1], sev, req, table, cause)


def run_rules(scope: str, selected: Iterable[str], options: dict[str, dict[str, Any]], subject: Any,
              ctx: Any, internal: list[str], where: str = "", with_fix: bool = False,
              with_table: bool = False, with_related: bool = False) -> Iterator[tuple[Any, ...]]:
    """Yield (rule, first item, message, severity or "") for every problem that a selected rule
    of ``scope`` finds in ``subject`` (a Model, or a run), each rule with its options (defaults,
    then ``options[code]``) in ``ctx.options``; with ``with_fix`` also the fix request or None
    (:mod:`urdf_lint.fix.fixes`) and the root cause or None, with ``with_table`` then the target
    table or None: the fields of the :class:`urdf_lint.engine.api.Report` the rule yields
    (:func:`as_report`; a severity of None is ""). A rule that crashes adds an internal error and the others
    still run."""
    import traceback
    entries = catalogue()
    for code in selected:
        e = entries.get(code)
        if e is None or e.scope != scope or e.origin != "rule":
            continue
        rule = load_rule(code)
        if rule is None or rule.check is None or rule.scope != scope:
            continue
        ctx.options = {**rule.options, **options.get(code, {})}
        try:
            for item in rule.check(subject, ctx):
                r = as_report(item, code)
                table = r.targets
                if table is not None:
                    from urdf_lint.core.targets import check_table
                    table = check_table(table, f"rule {code}")
                yield ((rule, r.element, r.message, r.severity or "")
                       + ((r.fix, r.cause) if with_fix else ()) + ((table,) if with_table else ())
                       + ((r.related,) if with_related else ()))
        except Exception:  # noqa: BLE001 - a crashing rule must not hide the others
            internal.append(f"rule {code} crashed{where}:\n{traceback.format_exc()}")


def codes_to_names() -> dict[str, str]:
    return {c: e.name for c, e in catalogue().items()}


def find_rule(code_or_name: str) -> Rule | None:
    rules = load_rules()
    if code_or_name.upper() in rules:
        return rules[code_or_name.upper()]
    for r in rules.values():
        if r.name == code_or_name:
            return r
    return None
