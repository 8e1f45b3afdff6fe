"""``sarif``: SARIF 2.1.0, for GitHub code scanning and other SARIF viewers."""
from __future__ import annotations

import json
import os
from typing import Any

from urdf_lint import __version__
from urdf_lint.core.edits import Fix
from urdf_lint.core.locations import display_path
from urdf_lint.report.base import BaseFormatter, Finding, Outcome, grouped, message

_SARIF_LEVEL = {"error": "error", "warning": "warning", "info": "note"}


def _uri(path: str) -> str:
    rel = display_path(path)
    return rel.replace(os.sep, "/") if not os.path.isabs(rel) else "file://" + rel


def _sarif_fix(fix: Fix) -> dict[str, Any]:
    """A SARIF ``fix``: one ``artifactChange`` per file, byte-offset replacements."""
    by_file: dict[str, list[Any]] = {}
    for e in fix.edits:
        by_file.setdefault(e.file, []).append(e)
    return {"description": {"text": fix.description + ("" if fix.safe else " (unsafe)")},
            "artifactChanges": [
                {"artifactLocation": {"uri": _uri(path)},
                 "replacements": [{"deletedRegion": {"byteOffset": e.start,
                                                     "byteLength": e.end - e.start},
                                   "insertedContent": {"text": e.text}}
                                  for e in sorted(edits, key=lambda e: e.start)]}
                for path, edits in sorted(by_file.items())]}


def _region(file: str, line: int, col: int) -> dict[str, Any]:
    return {"artifactLocation": {"uri": _uri(file)},
            "region": {"startLine": max(1, line), "startColumn": max(1, col)}}


def _driver_rule(code: str, r: Any) -> dict[str, Any]:
    """The ``tool.driver.rules`` entry of ``code`` (rule ``r``, None if unknown)."""
    return {
        "id": code, "name": r.name if r else code,
        "shortDescription": {"text": r.summary if r else code},
        "fullDescription": {"text": r.doc if r else code},
        "defaultConfiguration": {"level": _SARIF_LEVEL[r.severity if r else "error"]},
        "help": {"text": r.doc if r else code},
    }


def _related(f: Finding) -> list[tuple[str, tuple[Any, ...]]]:
    """(text, (file, line, col)) of a finding's related places: the macro calls, where its
    value comes from, its other instances and where their values come from."""
    related = [("macro called here", c) for c in reversed(f.chain)]
    if f.value_from:
        related.append(("value from here", f.value_from))
    if f.related:
        from urdf_lint.core.locations import related_label
        related.append((f"{related_label(f.related[0])} here", f.related))
    places = list(dict.fromkeys((i.file, i.line, i.col) for i in f.instances))
    related += [(i.detail or i.message, (i.file, i.line, i.col)) for i in
                {(i.file, i.line, i.col): i for i in f.instances}.values()
                if (i.file, i.line, i.col) != (f.file, f.line, f.col)] \
        if len(places) > 1 else []
    related += [("value from here", i.value_from) for i in f.instances
                if i.value_from and i.value_from != f.value_from]
    return related


def _properties(f: Finding) -> dict[str, Any]:
    props: dict[str, Any] = {}
    if f.models:
        props["models"] = f.models
    if f.detail and not f.instances:
        props["detail"] = f.detail
    if f.instances:
        props["count"] = len(f.instances)
        props["instances"] = [
            {"message": i.message, "file": display_path(i.file), "line": i.line,
             "col": i.col, **({"detail": i.detail} if i.detail else {}),
             **({"target": list(i.target)} if i.target else {}),
             "models": list(i.models)} for i in f.instances]
    if f.severity_from:
        props["severityFrom"] = list(f.severity_from)
    return props


def _sarif_result(f: Finding, rule_index: int) -> dict[str, Any]:
    res: dict[str, Any] = {"ruleId": f.code, "ruleIndex": rule_index, "level": _SARIF_LEVEL[f.severity],
           "message": {"text": message(f)},
           "locations": [{"physicalLocation": _region(f.file, f.line, f.col)}]}
    related = _related(f)
    if related:
        res["relatedLocations"] = [
            {"id": i, "message": {"text": text}, "physicalLocation": _region(c[0], c[1], c[2])}
            for i, (text, c) in enumerate(related)]
    props = _properties(f)
    if props:
        res["properties"] = props
    if f.fix is not None and f.fix.applicable:
        res["fixes"] = [_sarif_fix(f.fix)]
    return res


class SarifFormatter(BaseFormatter):
    name = "sarif"
    help = "SARIF 2.1.0 (GitHub code scanning)"

    def write(self, result: Outcome) -> None:
        result = grouped(result)
        rules = self.options.rules or {}
        used = sorted({f.code for f in result.findings})
        index = {c: i for i, c in enumerate(used)}
        driver_rules = [_driver_rule(c, rules.get(c)) for c in used]
        results = [_sarif_result(f, index[f.code]) for f in result.findings]
        doc = {"$schema": "https://json.schemastore.org/sarif-2.1.0.json", "version": "2.1.0",
               "runs": [{"tool": {"driver": {"name": "urdf-lint", "version": __version__,
                                             "informationUri": "https://pypi.org/project/urdf-lint/",
                                             "rules": driver_rules}},
                         "results": results}]}
        self.stream.write(json.dumps(doc, indent=2))   # (one write: not one per token)
        self.stream.write("\n")
