"""The diagnostics of one file, published by the server after each lint
(``textDocument/publishDiagnostics``): one per finding as ``check`` groups them
(:func:`urdf_lint.core.findings.group`), the macro chain as related information, a finding
whose value is written in this file (a YAML scalar) at that value, a config mistake at its
line, and for a file outside the roots one "not linted" diagnostic."""
from __future__ import annotations

import os

from lsprotocol import types

from urdf_lint.core.findings import Problem
from urdf_lint.core.locations import related_label
from urdf_lint.lsp.services import Services
from urdf_lint.lsp.state import Workspace
from urdf_lint.lsp.text import Doc
from urdf_lint.lsp.uris import path_uri

SOURCE = "urdf-lint"
SEVERITY = {"error": types.DiagnosticSeverity.Error, "warning": types.DiagnosticSeverity.Warning,
            "info": types.DiagnosticSeverity.Information}


def handle(sv: Services, path: str) -> list[types.Diagnostic]:
    """The diagnostics of ``path`` (a real path) from the findings held now."""
    ws = sv.ws
    if ws is None:
        return []
    if path in ws.buffers and not ws.readable(path):
        return [not_linted(ws, path)]
    out = _config_diagnostics(sv, ws, path)
    findings = ws.findings_in(path)
    valued = ws.findings_valued_in(path)
    if not findings and not valued:
        return out
    doc = sv.doc(path)
    out.extend(_value_diagnostics(sv, doc, valued))
    out.extend(_finding_diagnostics(sv, ws, doc, findings))
    return out


def _config_diagnostics(sv: Services, ws: Workspace, path: str) -> list[types.Diagnostic]:
    cp = ws.config_problem
    if cp is None or cp.file != path:
        return []
    line = max(cp.line, 1)
    text = sv.doc(path).line(line - 1)
    return [types.Diagnostic(
        range=types.Range(types.Position(line - 1, len(text) - len(text.lstrip())),
                          types.Position(line - 1, len(text))),
        message=cp.message, severity=types.DiagnosticSeverity.Error, source=SOURCE,
        code="config")]


def _finding_diagnostics(sv: Services, ws: Workspace, doc: Doc,
                         findings: list[Problem]) -> list[types.Diagnostic]:
    """One diagnostic per finding, as check counts them (core.findings.group): a macro line
    that makes 24 links wrong in 10 models is one diagnostic listing them."""
    from urdf_lint.core.findings import group
    from urdf_lint.report.base import fold_instances
    out = []
    docs: dict[str, Doc] = {}
    several = len(ws.models()) > 1
    for f in group(findings):
        related = []
        # every instance's call sites (a grouped finding: each call of the macro line)
        for (cf, cl, cc) in dict.fromkeys(tuple(c) for i in f.each() for c in i.chain):
            cdoc = docs.get(cf) or docs.setdefault(cf, sv.doc(cf))
            related.append(types.DiagnosticRelatedInformation(
                location=types.Location(uri=path_uri(cf), range=cdoc.element_range(cl, cc)),
                message="macro called here"))
        if f.related:   # a finding in an SRDF or a controller YAML: the robot's element
            rf, rl, rc = f.related
            rdoc = docs.get(rf) or docs.setdefault(rf, sv.doc(rf))
            related.append(types.DiagnosticRelatedInformation(
                location=types.Location(uri=path_uri(rf), range=rdoc.element_range(rl, rc)),
                message=f"{related_label(rf)} here"))
        models = [m for m in f.models if m]
        msg = f.message
        folded = fold_instances(f)
        if folded:
            msg += f" ({folded})"
        if models and several:
            names = [model_name(m) for m in models]
            msg += f" (in {', '.join(names[:4])}{' ...' if len(names) > 4 else ''})"
        out.append(types.Diagnostic(
            range=doc.element_range(f.line, f.col), message=msg,
            severity=SEVERITY.get(f.severity, types.DiagnosticSeverity.Error),
            code=f.code, source=SOURCE, related_information=related or None,
            data={"name": f.name}))
    return out


def _value_diagnostics(sv: Services, doc: Doc, valued: list[Problem]) -> list[types.Diagnostic]:
    """A finding whose value is written in this file (a YAML scalar): one diagnostic at
    that value, pointing at the element that uses it (once per value, code and message)."""
    out = []
    seen = set()
    for f in valued:
        assert f.value_from is not None
        _, line, col = f.value_from
        key = (f.code, f.message, line, col)
        if key in seen:
            continue
        seen.add(key)
        text = doc.line(line - 1)
        start = max(col - 1, 0)
        use = sv.doc(f.file)
        out.append(types.Diagnostic(
            range=types.Range(types.Position(line - 1, start),
                              types.Position(line - 1, max(len(text.rstrip()), start))),
            message=f"{f.message} (the value is used at {os.path.basename(f.file)}:{f.line})",
            severity=SEVERITY.get(f.severity, types.DiagnosticSeverity.Error),
            code=f.code, source=SOURCE, data={"name": f.name},
            related_information=[types.DiagnosticRelatedInformation(
                location=types.Location(uri=path_uri(f.file),
                                        range=use.element_range(f.line, f.col)),
                message="the value is used here")]))
    return out


def not_linted(ws: Workspace, path: str) -> types.Diagnostic:
    """The one diagnostic of an open file outside the run's roots: it is not linted (no
    diagnostic would look clean), and why."""
    return types.Diagnostic(
        range=types.Range(types.Position(0, 0), types.Position(0, 0)),
        message=f"not linted: this file is outside the roots of the workspace {ws.root} "
        "(the packages, git repository and colcon workspace holding it); urdf-lint reads "
        "no file there", severity=types.DiagnosticSeverity.Information, source=SOURCE,
        code="not-linted")


def model_name(label: str) -> str:
    """``ur10`` for the model ``urdf/ur10.xacro`` (its args kept: ``ur [robot_model:=ur5e]``)."""
    entry, _, args = label.partition(" [")
    name = os.path.splitext(os.path.basename(entry))[0]
    return f"{name} [{args}" if args else name
