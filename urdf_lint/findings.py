"""The one problem type: what rules, expansion and the engine report, up to the reporters.

A :class:`Problem` is created where a problem is found (a rule's ``check``, the expansion's
error table, the run pipeline) with its code, message, source origin (file, line, col and the
macro call chain) and, for snapshots, the link or joint it concerns. It crosses the worker pipe
as is (it pickles), is stored in the cache as :meth:`Problem.to_record`, and the run pipeline
fills in the rule name, the effective severity and the models it was found in before handing
it to the reporters (:meth:`Problem.to_dict` is the JSON form).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from typing import TYPE_CHECKING

from .locations import Origin

if TYPE_CHECKING:  # pragma: no cover
    from .fixes import Fix

SEVERITIES = ("info", "warning", "error")
SEVERITY_RANK = {s: i for i, s in enumerate(SEVERITIES)}


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
    fix: "Fix | None" = None                # a source fix (urdf_lint.fixes), if the rule has one
    consumers: tuple | None = None          # ((target, severity | "off"), ...) the rule chose
                                            # for this one problem (None: the rule's TARGETS)
    severity_from: tuple[str, ...] = ()     # the selected targets that make it this severe
                                            # (set by the pipeline; urdf_lint.targets)

    @classmethod
    def at(cls, code: str, message: str, loc, target=None, severity: str = "",
           fix=None, consumers: dict | None = None) -> "Problem":
        """A problem at ``loc``: an :class:`Origin` or a ``(file, line, col[, chain])`` tuple.
        ``severity``: set only when the rule chose it for this one problem; ``fix``: a
        :class:`urdf_lint.fixes.Fix` when the rule has one; ``consumers``: the target table
        the rule chose for this one problem (:mod:`urdf_lint.targets`)."""
        chain = tuple(tuple(c) for c in (loc[3] if len(loc) > 3 else ()))
        return cls(code, message, Origin(loc[0], int(loc[1]), int(loc[2]), chain),
                   tuple(target) if target else None,
                   severity=severity if severity in SEVERITIES else "", fix=fix,
                   consumers=tuple(sorted(consumers.items())) if consumers else None)

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
    def chain(self) -> tuple:
        return self.origin.chain

    def key(self):
        return (self.file, self.line, self.col, self.code, self.message)

    def replace(self, **changes) -> "Problem":
        """A copy with ``changes`` (``dataclasses.replace`` without its per-field init: a run
        renames and re-rates every finding, thousands on a large repository)."""
        if not changes.keys() <= _FIELDS:
            raise TypeError(f"Problem has no field(s) {sorted(set(changes) - _FIELDS)}")
        new = object.__new__(Problem)
        new.__dict__.update(self.__dict__)
        new.__dict__.update(changes)
        return new

    # -- serialisation ---------------------------------------------------------------------------
    def to_dict(self) -> dict:
        """The JSON report's form of a finding (schema in :mod:`urdf_lint.report`)."""
        d = {"code": self.code, "name": self.name, "severity": self.severity,
             "message": self.message, "file": self.file, "line": self.line, "col": self.col,
             "chain": [list(c) for c in self.chain], "models": list(self.models)}
        if self.fix is not None:   # absent when there is no fix: the JSON stays as it was
            d["fix"] = self.fix.to_dict()
        if self.severity_from:     # only when a selected target raised it
            d["severity_from"] = list(self.severity_from)
        return d

    def to_record(self) -> dict:
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
        return d

    @classmethod
    def from_record(cls, d: dict) -> "Problem":
        return cls._build(d["code"], d["message"], d["file"], d["line"], d["col"],
                          d.get("chain", ()), d.get("target"), "", d.get("severity", ""), (),
                          d.get("fix"), d.get("consumers"))

    def to_row(self) -> list:
        """Everything, the run pipeline's fields too, as one list: the run memo
        (:mod:`urdf_lint.runcache`) writes and reads a run's findings thousands at a time."""
        return [self.code, self.message, self.file, self.line, self.col,
                [list(c) for c in self.chain], list(self.target) if self.target else None,
                self.name, self.severity, list(self.models),
                self.fix.to_record() if self.fix is not None else None,
                [list(c) for c in self.consumers] if self.consumers is not None else None,
                list(self.severity_from)]

    @classmethod
    def from_row(cls, row: list) -> "Problem":
        return cls._build(*row)

    @classmethod
    def _build(cls, code, message, file, line, col, chain, target, name, severity, models,
               fix, consumers=None, severity_from=()) -> "Problem":
        """From plain data (a record or a row): built directly, without the dataclass init,
        since every field is known here."""
        if fix:
            from .fixes import Fix
            fix = Fix.from_record(fix)
        new = object.__new__(cls)
        new.__dict__.update(
            code=code, message=message,
            origin=Origin(file, int(line), int(col), tuple(tuple(c) for c in chain)),
            target=tuple(target) if target else None, name=name,
            severity=severity if severity in SEVERITIES else "", models=tuple(models),
            fix=fix or None,
            consumers=tuple(tuple(c) for c in consumers) if consumers is not None else None,
            severity_from=tuple(severity_from))
        return new


_FIELDS = frozenset(f.name for f in dataclasses.fields(Problem))


def exit_status(severities, internal: bool, fail_on: str) -> int:
    """The exit code of a run: 2 on an internal error, 1 when a severity reaches ``fail_on``
    (error | warning | info; never: always 0), else 0. Unknown severities count as errors."""
    if internal:
        return 2
    if fail_on == "never":
        return 0
    threshold = SEVERITY_RANK[fail_on]
    return 1 if any(SEVERITY_RANK.get(s, 2) >= threshold for s in severities) else 0


# the name the reporters and older code use
Finding = Problem


def merge(findings: list[Problem]) -> list[Problem]:
    """One finding per source location and message; the models that share it are listed."""
    out: dict = {}
    for f in findings:
        k = f.key()
        if k in out:
            have = out[k]
            more = tuple(m for m in f.models if m not in have.models)
            if more:
                have = out[k] = have.replace(models=have.models + more)
            if have.fix is not None and f.fix is not None and have.fix != f.fix:
                from .fixes import combine
                out[k] = have.replace(fix=combine(have.fix, f.fix, have.models[0] if
                                                  have.models else "", f.models[0] if
                                                  f.models else ""))
        else:
            out[k] = f
    return sorted(out.values(), key=lambda f: (f.file, f.line, f.col, f.code, f.message))
