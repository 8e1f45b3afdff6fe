"""The one problem type: what rules, expansion and the engine report, up to the reporters.

A :class:`Problem` is created where a problem is found (a rule's ``check``, the expansion's
error table, the run pipeline) with its code, message, source origin (file, line, col and the
macro call chain) and, for snapshots, the link or joint it concerns. It crosses the worker pipe
as is (plain data: urdf_lint.runner.wire), is stored in the cache as
:meth:`Problem.to_record`, and the run pipeline fills in the rule name, the effective severity
and the models it was found in before handing it to the reporters (:meth:`Problem.to_dict` is
the JSON form).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from typing import TYPE_CHECKING, Any, Iterable, NamedTuple, Protocol

from urdf_lint.core.locations import Origin

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.core.edits import Fix

SEVERITIES = ("info", "warning", "error")
SEVERITY_RANK = {s: i for i, s in enumerate(SEVERITIES)}


class Finding(Protocol):
    """What an output format reads of a finding (``BaseFormatter.handle(self, f: Finding)``):
    :class:`Problem` is one; a format written against this sees every field it may show and
    nothing of the pipeline's bookkeeping."""

    @property
    def code(self) -> str: ...
    @property
    def name(self) -> str: ...
    @property
    def severity(self) -> str: ...
    @property
    def message(self) -> str: ...
    @property
    def detail(self) -> str: ...            # what this one instance is about, or ""
    @property
    def file(self) -> str: ...
    @property
    def line(self) -> int: ...
    @property
    def col(self) -> int: ...
    @property
    def chain(self) -> tuple[Any, ...]: ...  # the macro calls that led there, outermost first
    @property
    def target(self) -> tuple[str, str] | None: ...
    @property
    def models(self) -> tuple[str, ...]: ...
    @property
    def severity_from(self) -> tuple[str, ...]: ...
    @property
    def value_from(self) -> tuple[Any, ...]: ...
    @property
    def related(self) -> tuple[Any, ...]: ...  # (file, line, col) of the robot element a
                                               # finding in a configuration file names, or ()
    @property
    def instances(self) -> tuple[Any, ...]: ...   # a grouped finding's instances (Findings)
    @property
    def fix(self) -> "Fix | None": ...

    def each(self) -> tuple[Any, ...]: ...
    def to_dict(self) -> dict[str, Any]: ...


@dataclass(frozen=True)
class Problem:
    """One finding: a rule code, its message and severity, where it is (and the macro chain
    that led there), and the fix that would remove it."""
    code: str
    message: str
    origin: Origin
    target: tuple[str, str] | None = None   # ("link" | "joint", name) it concerns, for snapshots
    name: str = ""                          # the rule's name (set by the run pipeline)
    severity: str = ""                      # a rule's choice for this one problem ("" = the
                                            # rule's default); effective once the pipeline ran
    models: tuple[str, ...] = ()            # display labels of the models it was found in
    fix: "Fix | None" = None                # a source fix (urdf_lint.core.edits), if the rule has one
    consumers: tuple[Any, ...] | None = None  # ((target, severity | "off"), ...) the rule chose
                                            # for this one problem (None: the rule's TARGETS)
    severity_from: tuple[str, ...] = ()     # the selected targets that make it this severe
                                            # (set by the pipeline; urdf_lint.core.targets)
    detail: str = ""                        # what this one instance is about, when the message
                                            # is a root cause's (the mesh URI of an unknown package)
    group: str = ""                         # a root cause's key ("package:NAME"): instances of one
                                            # cause are one finding wherever they are
    value_from: tuple[Any, ...] = ()        # (file, line, col) of where the value came from, when
                                            # not from the element's own line (YAML, a property)
    instances: tuple[Any, ...] = ()         # the Problems a grouped finding stands for (set by
                                            # group(); empty for a single instance)
    related: tuple[Any, ...] = ()           # (file, line, col) of the robot element a finding in
                                            # a configuration file (SRDF, controller YAML) names

    @classmethod
    def at(cls, code: str, message: str, loc: Any, target: Any = None, severity: str = "",
           fix: "Fix | None" = None, consumers: dict[str, str] | None = None,
           value_from: Any = (), related: Any = ()) -> "Problem":
        """A problem at ``loc``: an :class:`Origin` or a ``(file, line, col[, chain])`` tuple.
        ``severity``: set only when the rule chose it for this one problem; ``fix``: a
        :class:`urdf_lint.core.edits.Fix` when the rule has one; ``consumers``: the target table
        the rule chose for this one problem (:mod:`urdf_lint.core.targets`)."""
        chain = tuple(tuple(c) for c in (loc[3] if len(loc) > 3 else ()))
        return cls(code, message, Origin(loc[0], int(loc[1]), int(loc[2]), chain),
                   tuple(target) if target else None,
                   severity=severity if severity in SEVERITIES else "", fix=fix,
                   consumers=tuple(sorted(consumers.items())) if consumers else None,
                   value_from=_loc3(value_from), related=_loc3(related))

    # -- the origin, flat ----------------------------------------------------------------------
    @property
    def file(self) -> str:
        return self.origin.file

    @property
    def line(self) -> int:
        return self.origin.line

    @property
    def col(self) -> int:
        return self.origin.col

    @property
    def chain(self) -> tuple[Any, ...]:
        return self.origin.chain

    def key(self) -> tuple[str, int, int, str, str, str]:
        return (self.file, self.line, self.col, self.code, self.message, self.detail)

    @property
    def count(self) -> int:
        """How many instances (elements, references) this finding stands for."""
        return len(self.instances) or 1

    def each(self) -> tuple[Any, ...]:
        """The instances of a grouped finding, or the finding itself."""
        return self.instances or (self,)

    def replace(self, **changes: Any) -> "Problem":
        """A copy with ``changes`` (``dataclasses.replace`` without its per-field init: a run
        renames and re-rates every finding, thousands on a large repository)."""
        if not changes.keys() <= _FIELDS:
            raise TypeError(f"Problem has no field(s) {sorted(set(changes) - _FIELDS)}")
        new = object.__new__(Problem)
        new.__dict__.update(self.__dict__)
        new.__dict__.update(changes)
        return new

    # -- serialisation ---------------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """The JSON report's form of a finding (schema in :mod:`urdf_lint.report`)."""
        d = {"code": self.code, "name": self.name, "severity": self.severity,
             "message": self.message, "file": self.file, "line": self.line, "col": self.col,
             "chain": [list(c) for c in self.chain], "models": list(self.models)}
        if self.fix is not None:   # absent when there is no fix: the JSON stays as it was
            d["fix"] = self.fix.to_dict()
        if self.severity_from:     # only when a selected target raised it
            d["severity_from"] = list(self.severity_from)
        if self.detail:
            d["detail"] = self.detail
        if self.value_from:
            d["value_from"] = list(self.value_from)
        if self.related:
            d["related"] = list(self.related)
        if self.instances:
            d["count"] = len(self.instances)
            d["instances"] = [dict(i.to_dict(), **({"target": list(i.target)} if i.target
                                                   else {})) for i in self.instances]
        return d

    def to_record(self) -> dict[str, Any]:
        """Plain data for the cache (everything a worker produced)."""
        d = {"code": self.code, "message": self.message, "file": self.file, "line": self.line,
             "col": self.col, "chain": [list(c) for c in self.chain]}
        if self.target:
            d["target"] = list(self.target)
        if self.severity:
            d["severity"] = self.severity
        if self.fix is not None:
            d["fix"] = self.fix.to_record()
        if self.consumers is not None:
            d["consumers"] = [list(c) for c in self.consumers]
        if self.detail:
            d["detail"] = self.detail
        if self.group:
            d["group"] = self.group
        if self.value_from:
            d["value_from"] = list(self.value_from)
        if self.related:
            d["related"] = list(self.related)
        return d

    @classmethod
    def from_record(cls, d: dict[str, Any]) -> "Problem":
        return cls._build(d["code"], d["message"], d["file"], d["line"], d["col"],
                          d.get("chain", ()), d.get("target"), "", d.get("severity", ""), (),
                          d.get("fix"), d.get("consumers"), (), d.get("detail", ""),
                          d.get("group", ""), d.get("value_from", ()), (),
                          d.get("related", ()))

    def to_row(self) -> list[Any]:
        """Everything, the run pipeline's fields too, as one list: the run memo
        (:mod:`urdf_lint.run.runcache`) writes and reads a run's findings thousands at a time."""
        return [self.code, self.message, self.file, self.line, self.col,
                [list(c) for c in self.chain], list(self.target) if self.target else None,
                self.name, self.severity, list(self.models),
                self.fix.to_record() if self.fix is not None else None,
                [list(c) for c in self.consumers] if self.consumers is not None else None,
                list(self.severity_from), self.detail, self.group, list(self.value_from),
                [i.to_row() for i in self.instances], list(self.related)]

    @classmethod
    def from_row(cls, row: list[Any]) -> "Problem":
        return cls._build(*row)

    @classmethod
    def _build(cls, code: str, message: str, file: str, line: int, col: int, chain: Any,
               target: Any, name: str, severity: str, models: Any, fix: Any,
               consumers: Any = None, severity_from: Any = (), detail: str = "",
               group: str = "", value_from: Any = (), instances: Any = (),
               related: Any = ()) -> "Problem":
        """From plain data (a record or a row): built directly, without the dataclass init,
        since every field is known here."""
        if fix:
            from urdf_lint.core.edits import Fix
            fix = Fix.from_record(fix)
        new = object.__new__(cls)
        new.__dict__.update(
            code=code, message=message,
            origin=Origin(file, int(line), int(col), tuple(tuple(c) for c in chain)),
            target=tuple(target) if target else None, name=name,
            severity=severity if severity in SEVERITIES else "", models=tuple(models),
            fix=fix or None,
            consumers=tuple(tuple(c) for c in consumers) if consumers is not None else None,
            severity_from=tuple(severity_from), detail=detail, group=group,
            value_from=_loc3(value_from), instances=tuple(cls.from_row(r) for r in instances),
            related=_loc3(related))
        return new


def _loc3(loc: Any) -> tuple[Any, ...]:
    """``(file, line, col)`` of a value's source, or ``()``."""
    return (loc[0], int(loc[1]), int(loc[2])) if loc else ()


class Cause(NamedTuple):
    """A root cause a rule names after its message: every problem with the same ``key`` is
    one finding of ``code`` with ``message``, its instances (the rule's messages, at their own
    locations) listed under it. ``urdf_lint.rules._meshes``: an unknown package is one UL004
    with every mesh reference that names it."""
    code: str
    key: str
    message: str


_FIELDS = frozenset(f.name for f in dataclasses.fields(Problem))


def exit_status(severities: Iterable[str], internal: bool, fail_on: str) -> int:
    """The exit code of a run: 2 on an internal error, 1 when a severity reaches ``fail_on``
    (error | warning | info; never: always 0), else 0. Unknown severities count as errors."""
    if internal:
        return 2
    if fail_on == "never":
        return 0
    threshold = SEVERITY_RANK[fail_on]
    return 1 if any(SEVERITY_RANK.get(s, 2) >= threshold for s in severities) else 0


def merge(findings: list[Problem]) -> list[Problem]:
    """One finding per source location and message; the models that share it are listed."""
    out: dict[tuple[str, int, int, str, str, str], Any] = {}
    for f in findings:
        k = f.key()
        if k in out:
            have = out[k]
            more = tuple(m for m in f.models if m not in have.models)
            if more:
                have = out[k] = have.replace(models=have.models + more)
            if have.fix is not None and f.fix is not None and have.fix != f.fix:
                from urdf_lint.core.edits import combine
                out[k] = have.replace(fix=combine(have.fix, f.fix, have.models[0] if
                                                  have.models else "", f.models[0] if
                                                  f.models else ""))
        else:
            out[k] = f
    return sorted(out.values(), key=lambda f: (f.file, f.line, f.col, f.code, f.message))


def group(findings: Iterable[Problem]) -> list[Problem]:
    """One finding per source location and rule, and one per root cause: the problems of one
    macro line used by 42 fingers (messages differing only by the finger's name or values, at
    one severity) are one finding with 42 instances; the problems naming one root cause
    (``Problem.group``, e.g. an unknown package) are one finding wherever they are, at its
    first location. A grouped
    finding is the first instance with its ``instances`` set, the highest severity, every model,
    the YAML/property source its instances share, and one fix for all (``fixes.combine``)."""
    groups: dict[tuple[Any, ...], list[Problem]] = {}
    for f in findings:
        k = ("", f.code, f.group, 0, 0, "", "") if f.group else \
            (f.file, f.code, "", f.line, f.col, f.severity, _template(f.message))
        groups.setdefault(k, []).append(f)
    out = []
    for fs in groups.values():
        if len(fs) == 1 and not fs[0].instances:
            out.append(fs[0])
            continue
        fs = sorted((i for f in fs for i in f.each()),
                    key=lambda f: (f.file, f.line, f.col, f.message, f.detail))
        head = fs[0]
        sev = max((f.severity for f in fs), key=lambda s: SEVERITY_RANK.get(s, 2))
        models = tuple(dict.fromkeys(m for f in fs for m in f.models))
        froms = {f.value_from for f in fs}
        fix = head.fix if all(f.fix == head.fix for f in fs) else None
        if fix is None and any(f.fix is not None for f in fs):
            from urdf_lint.core.edits import combine
            fixes = [f.fix for f in fs if f.fix is not None]
            fix = fixes[0]
            for other in fixes[1:]:
                fix = combine(fix, other)
        out.append(head.replace(severity=sev, models=models, fix=fix, instances=tuple(fs),
                                value_from=head.value_from if len(froms) == 1 else ()))
    return sorted(out, key=lambda f: (f.file, f.line, f.col, f.code, f.message))


@dataclass(frozen=True)
class Tally:
    """The one counting rule of every command: a finding is what :func:`group` makes (one per
    source location and rule, one per root cause), counted once however many elements or models
    it stands for; its instances are said in parentheses where they differ
    (``2 finding(s) (6 instances)``). Severities are the grouped findings'."""
    findings: int
    instances: int
    errors: int
    warnings: int
    infos: int

    def phrase(self, noun: str = "finding(s)") -> str:
        """``N NOUN`` plus `` (M instances)`` when M differs from N."""
        more = f" ({self.instances} instances)" if self.instances != self.findings else ""
        return f"{self.findings} {noun}{more}"


def tally(findings: Iterable[Problem]) -> Tally:
    """How many findings (and instances) ``findings`` are, grouped as every report groups them."""
    grouped = group(findings)
    sev = {"error": 0, "warning": 0, "info": 0}
    for f in grouped:
        sev[f.severity] = sev.get(f.severity, 0) + 1
    return Tally(len(grouped), sum(f.count for f in grouped), sev["error"], sev["warning"],
                 sev["info"])


_VARYING = None


def _template(message: str) -> str:
    """A message with what varies between the instances of one problem (quoted names, paths,
    numbers) blanked: two different problems a rule finds on one element ("effort=0",
    "velocity=0") stay two findings, the same problem on 42 fingers is one."""
    global _VARYING
    if _VARYING is None:
        import re
        _VARYING = re.compile(r"'[^']*'|\"[^\"]*\"|[^\s'\"()]*/[^\s'\"()]*"
                              r"|[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")
    return _VARYING.sub("#", message)


def instance_label(f: Finding, by_place: bool) -> str:
    """How one instance of a grouped finding is named in a folded list: its place (and
    detail) when the group spans places, else its element's name, detail or models."""
    if by_place:
        from urdf_lint.core.locations import display_path
        where = f"{display_path(f.file)}:{f.line}"
        return f"{where} {f.detail}" if f.detail else where
    if f.target:
        return f.target[1]
    return f.detail or ", ".join(f.models) or f.message


def instances_summary(f: Finding) -> tuple[str, list[str]]:
    """(noun, labels) for a grouped finding: ``("links", [names])``, ``("places", [...])``;
    labels are unique, in order."""
    items = f.each()
    by_place = len({(i.file, i.line, i.col) for i in items}) > 1
    labels = list(dict.fromkeys(instance_label(i, by_place) for i in items))
    if by_place:
        noun = "places"
    else:
        kinds = {i.target[0] for i in items if i.target}
        noun = (kinds.pop() + "s") if len(kinds) == 1 and all(i.target for i in items) \
            else "instances"
    return noun, labels
