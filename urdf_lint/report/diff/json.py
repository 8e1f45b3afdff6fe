"""``json``: the diff for tools."""
from __future__ import annotations

from typing import Any

import json

from urdf_lint.report.diff.base import DiffResult, DiffFormatter


class JsonDiff(DiffFormatter):
    name = "json"
    help = "for tools: every model, change, movement and finding"

    def render(self, result: DiffResult) -> str:
        return to_json(result)


def to_json(r: DiffResult) -> str:
    from urdf_lint.core.locations import display_path

    def rel(p: str) -> str:
        return display_path(p)
    models: list[dict[str, Any]] = []
    doc = {"version": 1, "base": r.base, "head": r.head, "models_total": r.total_models,
           "base_expanded": r.base_expanded, "models": models}
    for m in r.models:
        models.append({
            "model": m.model, "status": m.status, "error": m.error, "picture": m.picture,
            "changes": [c.to_dict(rel) for c in m.changes],
            "moved": [{"link": link, "distance": d, "angle": a} for link, d, a in m.moved],
            "findings_introduced": [_finding(m, fk, s) for fk, s in m.findings_introduced],
            "findings_fixed": [_finding(m, fk, s) for fk, s in m.findings_fixed]})
    return json.dumps(doc, indent=2) + "\n"


def _finding(m: Any, fk: tuple[str, str, str], severity: str) -> dict[str, Any]:
    """A finding introduced or fixed (``m`` its ModelDiff), with its line in the revision
    that has it (when known)."""
    out: dict[str, Any] = {"code": fk[0], "file": fk[1], "message": fk[2], "severity": severity}
    at = m.finding_lines.get(fk)
    if at and at[0]:
        out["line"], out["col"] = at
    rel = m.finding_related.get(fk)
    if rel:      # the robot element (its xacro line) an SRDF or YAML finding is about
        out["related"] = list(rel)
    source = m.finding_value_from.get(fk)
    if source:   # the line its value comes from (a YAML scalar), as check's value_from
        out["value_from"] = list(source)
    return out
