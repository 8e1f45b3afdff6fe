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
            "findings_introduced": [{"code": fk[0], "file": fk[1], "message": fk[2],
                                     "severity": s} for fk, s in m.findings_introduced],
            "findings_fixed": [{"code": fk[0], "file": fk[1], "message": fk[2], "severity": s}
                               for fk, s in m.findings_fixed]})
    return json.dumps(doc, indent=2) + "\n"
