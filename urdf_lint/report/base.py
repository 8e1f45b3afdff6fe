"""The base of every output format (after flake8's ``BaseFormatter``)."""
from __future__ import annotations

from collections import Counter
from dataclasses import dataclass
from typing import IO, TYPE_CHECKING, Any, Iterable, Protocol, Sequence, TypeVar

from urdf_lint.core.findings import Finding
from urdf_lint.core.locations import Origin, display_path, portable
from urdf_lint.core.escape import escape_text

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.core.findings import Problem
    from urdf_lint.core.jobs import ModelReport

__all__ = ["BaseFormatter", "Finding", "Outcome", "ReportOptions"]

_COLORS = {"error": "\033[31m", "warning": "\033[33m", "info": "\033[36m"}
BOLD, DIM, RESET = "\033[1m", "\033[2m", "\033[0m"
MODELS_SHOWN = 3


@dataclass
class ReportOptions:
    """How a report is written: colour, source frames, quiet, model lists."""
    color: bool = False
    show_source: bool = False
    roots: tuple[str, ...] | None = None     # --show-source reads sources only inside these (fsbound)
    quiet: bool = False            # findings only: no summary line
    show_models: bool = True
    # code -> the rule (its name, summary, doc and severity), for formats that describe the
    # rules they report (SARIF); handed over by the caller, which knows the rules
    rules: Any = None
    coverage: bool = False          # check --coverage: the branches never taken, per model


def coverage_rows(result: Any) -> list[dict[str, Any]]:
    """The branch coverage of a run's models (``CheckResult.coverage``), by model label."""
    cov = getattr(result, "coverage", None) or {}
    return [cov[k] for k in sorted(cov)]


def coverage_text(result: Any) -> list[str]:
    """``check --coverage`` in text: per model the branches taken, then each one never taken
    with why (escaped by the caller's writer)."""
    from urdf_lint.core.locations import display_path
    lines = []
    for c in coverage_rows(result):
        lines.append(f"{c['model']}: {c['taken']}/{c['branches']} branch(es) taken "
                     f"({c['taken_at_defaults']} at the defaults; {len(c['variants'])} "
                     f"variant(s) linted" + (f", {c['cut_by_budget']} cut by the budget"
                                             if c["cut_by_budget"] else "") + ")")
        for row in c["not_taken"]:
            what = row["kind"] + (f" {row['arg']}:={row['choice']}" if "choice" in row else "")
            lines.append(f"  {display_path(row['file'])}:{row['line']}: {what} "
                         f"{row['value']!r} never taken: {row['why']}")
    if not lines:
        lines.append("coverage: no xacro model was explored (explore = false, or no "
                     "explored model)")
    return lines


class Outcome(Protocol):
    """What a format writes: a run's findings (each a :class:`Finding`) and its models
    (``urdf_lint.run.pipeline.CheckResult`` is one)."""

    @property
    def findings(self) -> Sequence["Problem"]: ...
    @property
    def models(self) -> Sequence["ModelReport"]: ...


class BaseFormatter:
    """Subclass, set ``name`` and ``help``, and override :meth:`handle` (one finding, a
    :class:`Finding`) and/or :meth:`start` / :meth:`finish` (the whole report, an
    :class:`Outcome`)."""

    name = ""
    help = ""

    def __init__(self, stream: IO[str], options: ReportOptions | None = None):
        self.stream = stream
        self.options = options or ReportOptions()

    def write(self, result: Outcome) -> None:
        result = grouped(result)
        self.start(result)
        for f in result.findings:
            self.handle(f)
        self.finish(result)

    def start(self, result: Outcome) -> None:
        pass

    def handle(self, f: Finding) -> None:
        pass

    def finish(self, result: Outcome) -> None:
        pass

    def statistics(self, result: Outcome) -> None:
        """``--statistics``: only the count per rule, most frequent first."""
        result = grouped(result)
        for (code, name, sev), n in counts(result):
            self.stream.write(f"{n:5d}  {code}  {name:<28} {sev}\n")
        for c in coverage_rows(result):   # branch coverage (run.explore), when it ran
            if not c["branches"]:
                continue
            self.stream.write(escape_text(
                f"branches {c['taken']}/{c['branches']} taken ({c['taken_at_defaults']} at the "
                f"defaults, {len(c['variants'])} variant(s)): {c['model']}") + "\n")

    # helpers ---------------------------------------------------------------------------------
    def paint(self, text: str, style: str) -> str:
        return f"{style}{text}{RESET}" if self.options.color else text

    def severity_color(self, severity: str) -> str:
        return _COLORS.get(severity, "")

    def summary_line(self, result: Outcome) -> str:
        s = summary(result)
        if result.findings:
            return (f"Found {len(result.findings)} problem(s) ({s['errors']} error, "
                    f"{s['warnings']} warning, {s['info']} info) in {s['models']} model(s).")
        internal = getattr(result, "internal", None)   # (a result may have none)
        if internal:  # never "passed" after an internal error
            return (f"Checks incomplete: {len(internal)} internal error(s), see above; "
                    f"no problems found in {s['models']} model(s).")
        return f"All checks passed: {s['models']} model(s)."


def counts(result: Outcome) -> list[tuple[tuple[str, str, str], int]]:
    c = Counter((f.code, f.name, f.severity) for f in result.findings)
    return sorted(c.items(), key=lambda kv: (-kv[1], kv[0]))


def summary(result: Outcome) -> dict[str, int]:
    c = Counter(f.severity for f in result.findings)
    return {"models": len(result.models), "errors": c["error"], "warnings": c["warning"],
            "info": c["info"]}


def targets_tag(f: Finding) -> str:
    """`` [mujoco, drake]``: the selected targets that make a finding this severe, or ""."""
    return f" [{', '.join(f.severity_from)}]" if getattr(f, "severity_from", ()) else ""


def chain_text(f: Finding) -> str:
    """The macro call chain, one visible line (names are the description's)."""
    return escape_text(Origin(f.file, f.line, f.col, f.chain).format_chain()) if f.chain else ""


def fold(names: Iterable[str], shown: int = MODELS_SHOWN) -> str:
    """``a, b, c and 4 more`` (each item escaped to one visible line)."""
    items = [escape_text(i) for i in names]
    head = ", ".join(items[:shown])
    return head + (f" and {len(items) - shown} more" if len(items) > shown else "")


def message(f: Finding) -> str:
    """A finding's message as every format shows it: a path in it (``looked for
    /home/.../meshes/x.stl``) is shown as the locations are, relative (see
    :func:`urdf_lint.core.locations.portable`)."""
    return portable(f.message)


_O = TypeVar("_O", bound=Outcome)


def grouped(result: _O) -> _O:
    """``result`` with its findings grouped (:func:`urdf_lint.core.findings.group`): every format
    counts and shows one finding per source location and rule (and per root cause)."""
    import copy
    from urdf_lint.core.findings import group
    if getattr(result, "_grouped", False):
        return result
    out = copy.copy(result)
    out.__dict__.update(findings=group(result.findings), _grouped=True)
    return out


INSTANCES_SHOWN = 3


def fold_instances(f: Finding, shown: int = INSTANCES_SHOWN) -> str:
    """``in 42 links: a, b, c, ... (+39)`` for a grouped finding, "" for a single one."""
    if not f.instances:
        return ""
    from urdf_lint.core.findings import instances_summary
    noun, labels = instances_summary(f)
    if len(labels) < 2:
        return ""
    head = ", ".join(escape_text(i) for i in labels[:shown])
    more = f", ... (+{len(labels) - shown})" if len(labels) > shown else ""
    return f"in {len(labels)} {noun}: {head}{more}"


def value_from_text(f: Finding, shown: int = 3) -> str:
    """``value from config/joint_limits.yaml:28`` when the value came from elsewhere; for a
    finding grouped over instances whose values come from different places, ``values from``
    each of them (``a.yaml:10, a.yaml:12, ... (+2)``)."""
    places = sorted({(str(i.value_from[0]), int(i.value_from[1]))
                     for i in getattr(f, "instances", ()) or () if getattr(i, "value_from", None)})
    if len(places) < 2:
        got = f.value_from or (places[0] if places else None)
        return f"value from {escape_text(display_path(got[0]))}:{got[1]}" if got else ""
    head = ", ".join(f"{escape_text(display_path(p))}:{n}" for p, n in places[:shown])
    more = f", ... (+{len(places) - shown})" if len(places) > shown else ""
    return f"values from {head}{more}"


def related_text(f: Finding) -> str:
    """``robot element at urdf/robot.urdf.xacro:12`` for a finding in a configuration file
    (SRDF, controller YAML) about an element of the robot."""
    if not f.related:
        return ""
    from urdf_lint.core.locations import related_label
    return (f"{related_label(f.related[0])} at {escape_text(display_path(f.related[0]))}:"
            f"{f.related[1]}")


def refused_text(f: Finding) -> str:
    """Why the finding's fix is not applied automatically when that names the expression the
    value comes from (``... the value comes from the expression at FILE:LINE``), or ""."""
    if f.fix is None or "comes from" not in f.fix.refused:
        return ""
    return escape_text(f.fix.refused)


def location(f: Finding) -> str:
    return f"{escape_text(display_path(f.file))}:{f.line}:{f.col}"
