"""``sarif``: SARIF 2.1.0, for GitHub code scanning and other SARIF viewers."""
from __future__ import annotations

import json
import os

from urdf_lint import __version__
from urdf_lint.core.locations import display_path
from urdf_lint.report.base import BaseFormatter, grouped, message

_SARIF_LEVEL = {"error": "error", "warning": "warning", "info": "note"}


def _uri(path):
    rel = display_path(path)
    return rel.replace(os.sep, "/") if not os.path.isabs(rel) else "file://" + rel


def _sarif_fix(fix) -> dict:
    """A SARIF ``fix``: one ``artifactChange`` per file, byte-offset replacements."""
    by_file: dict = {}
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


class SarifFormatter(BaseFormatter):
    name = "sarif"
    help = "SARIF 2.1.0 (GitHub code scanning)"

    def write(self, result):
        result = grouped(result)
        from urdf_lint.engine.registry import load_rules
        rules = load_rules()
        used = sorted({f.code for f in result.findings})
        index = {c: i for i, c in enumerate(used)}
        driver_rules = []
        for c in used:
            r = rules.get(c)
            driver_rules.append({
                "id": c, "name": r.name if r else c,
                "shortDescription": {"text": r.summary if r else c},
                "fullDescription": {"text": r.doc if r else c},
                "defaultConfiguration": {"level": _SARIF_LEVEL[r.severity if r else "error"]},
                "help": {"text": r.doc if r else c},
            })
        results = []
        for f in result.findings:
            res = {"ruleId": f.code, "ruleIndex": index[f.code], "level": _SARIF_LEVEL[f.severity],
                   "message": {"text": message(f)},
                   "locations": [{"physicalLocation": {
                       "artifactLocation": {"uri": _uri(f.file)},
                       "region": {"startLine": max(1, f.line), "startColumn": max(1, f.col)}}}]}
            related = [("macro called here", c) for c in reversed(f.chain)]
            if f.value_from:
                related.append(("value from here", f.value_from))
            places = list(dict.fromkeys((i.file, i.line, i.col) for i in f.instances))
            related += [(i.detail or i.message, (i.file, i.line, i.col)) for i in
                        {(i.file, i.line, i.col): i for i in f.instances}.values()
                        if (i.file, i.line, i.col) != (f.file, f.line, f.col)] \
                if len(places) > 1 else []
            related += [("value from here", i.value_from) for i in f.instances
                        if i.value_from and i.value_from != f.value_from]
            if related:
                res["relatedLocations"] = [
                    {"id": i, "message": {"text": text},
                     "physicalLocation": {"artifactLocation": {"uri": _uri(c[0])},
                                          "region": {"startLine": max(1, c[1]),
                                                     "startColumn": max(1, c[2])}}}
                    for i, (text, c) in enumerate(related)]
            props: dict = {}
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
            if props:
                res["properties"] = props
            if f.fix is not None and f.fix.applicable:
                res["fixes"] = [_sarif_fix(f.fix)]
            results.append(res)
        doc = {"$schema": "https://json.schemastore.org/sarif-2.1.0.json", "version": "2.1.0",
               "runs": [{"tool": {"driver": {"name": "urdf-lint", "version": __version__,
                                             "informationUri": "https://pypi.org/project/urdf-lint/",
                                             "rules": driver_rules}},
                         "results": results}]}
        json.dump(doc, self.stream, indent=2)
        self.stream.write("\n")
