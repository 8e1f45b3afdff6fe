"""``json``: the whole result as one document; the schema is in :mod:`urdf_lint.report`."""
from __future__ import annotations

import json
from typing import Any

from urdf_lint import __version__
from urdf_lint.core.locations import display_path
from urdf_lint.core.locations import portable
from urdf_lint.report.base import Outcome, BaseFormatter, counts, coverage_rows, grouped, summary


def _shown(d: dict[str, Any]) -> dict[str, Any]:
    """A finding's dict with its paths as the report shows them (relative to cwd, in the message too)."""
    d["file"] = display_path(d["file"])
    d["message"] = portable(d["message"])
    d["chain"] = [[display_path(c[0]), c[1], c[2]] for c in d["chain"]]
    if "value_from" in d:
        d["value_from"] = [display_path(d["value_from"][0])] + d["value_from"][1:]
    if "related" in d:
        d["related"] = [display_path(d["related"][0])] + d["related"][1:]
    if "instances" in d:
        d["instances"] = [_shown(i) for i in d["instances"]]
    return d


def _coverage(c: dict[str, Any]) -> dict[str, Any]:
    """One model's branch coverage as the report shows it (paths relative to cwd)."""
    c = dict(c)
    c["entry"] = display_path(c["entry"])
    c["not_taken"] = [{**r, "file": display_path(r["file"])} for r in c["not_taken"]]
    c["takers"] = {f"{display_path(k.rpartition(':')[0])}:{k.rpartition(':')[2]}": v
                   for k, v in c["takers"].items()}
    return c


class JsonFormatter(BaseFormatter):
    name = "json"
    help = "one JSON document (schema version 1)"

    def write(self, result: Outcome) -> None:
        result = grouped(result)
        doc = {"version": 1, "tool": "urdf-lint", "tool_version": __version__,
               "models": [{"entry": display_path(m.entry), "args": m.args, "status": m.status,
                           "cached": m.cached,
                           "name": m.stats.get("name", ""), "links": m.stats.get("links", 0),
                           "joints": m.stats.get("joints", 0), "meshes": m.stats.get("meshes", 0)}
                          for m in result.models],
               "findings": [_shown(f.to_dict()) for f in result.findings],
               "summary": summary(result)}
        if self.options.coverage:
            doc["coverage"] = [_coverage(c) for c in coverage_rows(result)]
        self.stream.write(json.dumps(doc, indent=2))   # (one write: not one per token)
        self.stream.write("\n")

    def statistics(self, result: Outcome) -> None:
        """The count per rule, then (when exploration ran) one row per model that has
        branches: ``{"model", "entry", "branches", "taken", "taken_at_defaults", "variants",
        "cut_by_budget"}`` (the text's ``branches N/M taken`` lines)."""
        result = grouped(result)
        rows: list[dict[str, Any]] = [{"code": code, "name": name, "severity": sev, "count": n}
                                      for (code, name, sev), n in counts(result)]
        rows += [{"model": c["model"], "entry": display_path(c["entry"]),
                  "branches": c["branches"], "taken": c["taken"],
                  "taken_at_defaults": c["taken_at_defaults"], "variants": len(c["variants"]),
                  "cut_by_budget": c["cut_by_budget"]}
                 for c in coverage_rows(result) if c["branches"]]
        self.stream.write(json.dumps(rows, indent=2))
        self.stream.write("\n")
