"""Output formats: text, json, sarif, github, junit.

JSON schema (``--format json``), version 1::

    {
      "version": 1, "tool": "urdf-lint", "tool_version": "0.1.0",
      "models": [{"entry": str, "args": {str: str}, "name": str, "status": "model"|"failed",
                  "cached": bool (result reused from .urdf_lint_cache),
                  "links": int, "joints": int, "meshes": int}],
      "findings": [{"code": "UL302", "name": "limit-order", "severity": "error"|"warning"|"info",
                    "message": str, "file": str (relative to cwd when below it), "line": int,
                    "col": int, "chain": [[file, line, col], ...]  (macro call sites, outermost first),
                    "models": [str, ...],
                    "fix": {"description": str, "applicability": "safe"|"unsafe",
                            "edits": [{"file": str, "start": int, "end": int, "text": str}]
                                     (byte ranges of the source, replaced by text)
                            | "refused": str (why it is not applied automatically)}
                           (only when the rule has a fix for this finding)}],
      "summary": {"models": int, "errors": int, "warnings": int, "info": int}
    }
"""
from __future__ import annotations

import json
import os
import sys
from collections import Counter

from .. import __version__
from ..locations import Origin, display_path

_COLORS = {"error": "\033[31m", "warning": "\033[33m", "info": "\033[36m"}
_BOLD, _DIM, _RESET = "\033[1m", "\033[2m", "\033[0m"


def _chain_text(f) -> str:
    return Origin(f.file, f.line, f.col, f.chain).format_chain() if f.chain else ""


def _summary(result):
    c = Counter(f.severity for f in result.findings)
    return {"models": len(result.models), "errors": c["error"], "warnings": c["warning"],
            "info": c["info"]}


def text(result, stream, color=False, statistics=False, show_models=True):
    w = stream.write
    current = None
    for f in result.findings:
        path = display_path(f.file)
        if color and path != current:
            if current is not None:
                w("\n")
            w(f"{_BOLD}{path}{_RESET}\n")
            current = path
        if color:
            sev = f"{_COLORS[f.severity]}{f.code}{_RESET}"
            w(f"{path}:{f.line}:{f.col}: {sev} {f.message} {_DIM}[{f.name}]{_RESET}\n")
        else:
            w(f"{path}:{f.line}:{f.col}: {f.code} {f.message} [{f.name}]\n")
        ch = _chain_text(f)
        if ch:
            w(f"    {ch}\n")
        if show_models and len(f.models) > 1:
            shown = ", ".join(f.models[:6]) + (f", +{len(f.models) - 6} more" if len(f.models) > 6 else "")
            w(f"    in {len(f.models)} models: {shown}\n")
    if statistics:
        statistics_table(result, stream)
    s = _summary(result)
    if result.findings:
        w(f"Found {len(result.findings)} problem(s) ({s['errors']} error, {s['warnings']} warning, "
          f"{s['info']} info) in {s['models']} model(s).\n")
    else:
        w(f"All checks passed: {s['models']} model(s).\n")


def statistics_table(result, stream):
    c = Counter((f.code, f.name, f.severity) for f in result.findings)
    for (code, name, sev), n in sorted(c.items(), key=lambda kv: (-kv[1], kv[0])):
        stream.write(f"{n:5d}  {code}  {name:<28} {sev}\n")


def to_json(result, stream):
    doc = {"version": 1, "tool": "urdf-lint", "tool_version": __version__,
           "models": [{"entry": display_path(m.entry), "args": m.args, "status": m.status,
                       "cached": m.cached,
                       "name": m.stats.get("name", ""), "links": m.stats.get("links", 0),
                       "joints": m.stats.get("joints", 0), "meshes": m.stats.get("meshes", 0)}
                      for m in result.models],
           "findings": [dict(f.to_dict(), file=display_path(f.file),
                             chain=[[display_path(c[0]), c[1], c[2]] for c in f.chain])
                        for f in result.findings],
           "summary": _summary(result)}
    json.dump(doc, stream, indent=2)
    stream.write("\n")


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


def to_sarif(result, stream):
    from ..registry import load_rules
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
               "message": {"text": f.message},
               "locations": [{"physicalLocation": {
                   "artifactLocation": {"uri": _uri(f.file)},
                   "region": {"startLine": max(1, f.line), "startColumn": max(1, f.col)}}}]}
        if f.chain:
            res["relatedLocations"] = [
                {"id": i, "message": {"text": "macro called here"},
                 "physicalLocation": {"artifactLocation": {"uri": _uri(c[0])},
                                      "region": {"startLine": max(1, c[1]),
                                                 "startColumn": max(1, c[2])}}}
                for i, c in enumerate(reversed(f.chain))]
        if f.models:
            res["properties"] = {"models": f.models}
        if f.fix is not None and f.fix.applicable:
            res["fixes"] = [_sarif_fix(f.fix)]
        results.append(res)
    doc = {"$schema": "https://json.schemastore.org/sarif-2.1.0.json", "version": "2.1.0",
           "runs": [{"tool": {"driver": {"name": "urdf-lint", "version": __version__,
                                         "informationUri": "https://pypi.org/project/urdf-lint/",
                                         "rules": driver_rules}},
                     "results": results}]}
    json.dump(doc, stream, indent=2)
    stream.write("\n")


def _gh_escape(s, prop=False):
    s = s.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")
    if prop:
        s = s.replace(":", "%3A").replace(",", "%2C")
    return s


def to_github(result, stream):
    level = {"error": "error", "warning": "warning", "info": "notice"}
    for f in result.findings:
        msg = f.message
        ch = _chain_text(f)
        if ch:
            msg += f" ({ch})"
        stream.write(f"::{level[f.severity]} file={_gh_escape(display_path(f.file), True)},"
                     f"line={f.line},col={f.col},title={_gh_escape(f.code + ' ' + f.name, True)}"
                     f"::{_gh_escape(msg)}\n")


def to_junit(result, stream):
    from xml.sax.saxutils import escape, quoteattr  # heavy import chain: only for junit
    cases = []
    failures = 0
    for f in result.findings:
        if f.severity == "error":
            failures += 1
        name = f"{f.code} {display_path(f.file)}:{f.line}:{f.col}"
        body = escape(f"{display_path(f.file)}:{f.line}:{f.col}: {f.code} {f.message}\n"
                      + _chain_text(f))
        tag = "failure"
        cases.append(f'    <testcase classname={quoteattr("urdf-lint." + f.code)} name={quoteattr(name)}>'
                     f'<{tag} type={quoteattr(f.severity)} message={quoteattr(f.message)}>'
                     f'{body}</{tag}></testcase>')
    for m in result.models:
        if not any(m.label in f.models for f in result.findings):
            cases.append(f'    <testcase classname="urdf-lint.model" name={quoteattr(m.label)}/>')
    stream.write('<?xml version="1.0" encoding="UTF-8"?>\n')
    stream.write(f'<testsuites name="urdf-lint" tests="{len(cases)}" failures={quoteattr(str(len(result.findings)))}>\n')
    stream.write(f'  <testsuite name="urdf-lint" tests="{len(cases)}" failures="{len(result.findings)}" errors="0">\n')
    stream.write("\n".join(cases) + ("\n" if cases else ""))
    stream.write("  </testsuite>\n</testsuites>\n")


FORMATS = {"text": None, "json": to_json, "sarif": to_sarif, "github": to_github,
           "junit": to_junit}


def write(result, fmt, stream=None, statistics=False, color=None):
    stream = stream or sys.stdout
    if fmt == "text":
        if color is None:
            color = stream.isatty() and not os.environ.get("NO_COLOR")
        text(result, stream, color=color, statistics=statistics)
    else:
        FORMATS[fmt](result, stream)
        if statistics:
            statistics_table(result, sys.stderr)
