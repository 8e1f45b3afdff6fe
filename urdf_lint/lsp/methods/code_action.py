"""``textDocument/codeAction``: each finding's fix (byte edits, possibly of another file: a
property, a macro argument, a YAML scalar) as a quick fix, suppression comments for the next
element or the whole file, and "fix all safe" for the document. Only files ``check --fix``
would write are edited (:meth:`urdf_lint.lsp.state.Workspace.writable`)."""
from __future__ import annotations

from typing import Callable

from lsprotocol import types

from urdf_lint.core import overlay
from urdf_lint.core.edits import Edit, Fix
from urdf_lint.core.findings import Problem
from urdf_lint.lsp.services import Services
from urdf_lint.lsp.uris import path_uri, uri_path

FIX_ALL = types.CodeActionKind.SourceFixAll.value + ".urdf-lint"
OPTIONS = types.CodeActionOptions(code_action_kinds=[types.CodeActionKind.QuickFix, FIX_ALL])
Diag = types.Diagnostic | None


def handle(sv: Services, params: types.CodeActionParams) -> list[types.CodeAction] | None:
    ws = sv.ws
    if ws is None:
        return None
    path = uri_path(params.text_document.uri)
    only = params.context.only
    out: list[types.CodeAction] = []
    if not only or any(str(k).startswith("quickfix") for k in only):
        doc = sv.doc(path)
        for f in ws.findings_in(path):
            rng = doc.element_range(f.line, f.col)
            if not _overlaps(rng, params.range):
                continue
            diag = next((d for d in params.context.diagnostics
                         if d.code == f.code and d.range == rng), None)
            for make in ACTIONS:
                a = make(sv, f, diag)
                if a is not None:
                    out.append(a)
    if not only or any(str(k).startswith("source") for k in only):
        a = fix_all_safe(sv, path)
        if a is not None:
            out.append(a)
    return out


def workspace_edit(sv: Services, edits: list[Edit]) -> types.WorkspaceEdit | None:
    """LSP text edits from byte edits, per file, against the text the editor has; None when
    an edit is of a file the run may not write (``check --fix``'s rule: outside the
    workspace folder, an installed package, a file a symlink leads out to)."""
    ws = sv.ws
    if ws is None or not all(ws.writable(e.file) for e in edits):
        return None
    changes: dict[str, list[types.TextEdit]] = {}
    for e in edits:
        doc = sv.doc(e.file)
        changes.setdefault(path_uri(e.file), []).append(types.TextEdit(
            range=types.Range(doc.offset_position(e.start), doc.offset_position(e.end)),
            new_text=e.text))
    return types.WorkspaceEdit(changes=changes)


def _fix_action(sv: Services, f: Problem, diag: Diag) -> types.CodeAction | None:
    fix: Fix | None = f.fix
    if fix is None or not fix.applicable:
        return None
    edit = workspace_edit(sv, list(fix.edits))
    if edit is None:
        return None
    title = fix.description + ("" if fix.safe else " (unsafe: check the result)")
    return types.CodeAction(title=f"{f.code}: {title}", kind=types.CodeActionKind.QuickFix,
                            diagnostics=[diag] if diag else None, is_preferred=fix.safe,
                            edit=edit)


def _suppress_next(sv: Services, f: Problem, diag: Diag) -> types.CodeAction | None:
    from urdf_lint.fix.addsuppress import suppression_edits
    ws = sv.ws
    if ws is None or not ws.writable(f.file):   # (--add-suppressions leaves it alone too)
        return None
    with overlay.using(ws.buffers):
        edits, _ = suppression_edits([f])
    es = [e for v in edits.values() for e in v]
    edit = workspace_edit(sv, es) if es else None
    if edit is None:
        return None
    return types.CodeAction(title=f"Disable {f.code} for the next element",
                            kind=types.CodeActionKind.QuickFix,
                            diagnostics=[diag] if diag else None, edit=edit)


def _suppress_file(sv: Services, f: Problem, diag: Diag) -> types.CodeAction | None:
    ws = sv.ws
    if ws is None or not f.file.endswith((".xacro", ".urdf", ".xml")) or \
            not ws.writable(f.file):
        return None
    data = sv.doc(f.file).data
    at = 0
    if data.lstrip().startswith(b"<?xml"):
        end = data.find(b"?>")
        nl = data.find(b"\n", end)
        at = len(data) if nl < 0 else nl + 1
    eol = "\r\n" if b"\r\n" in data[:at + 200] else "\n"
    edit = Edit(f.file, at, at, f"<!-- urdf-lint: disable-file {f.code} -->{eol}")
    return types.CodeAction(title=f"Disable {f.code} for this file",
                            kind=types.CodeActionKind.QuickFix,
                            diagnostics=[diag] if diag else None,
                            edit=workspace_edit(sv, [edit]))


ACTIONS: tuple[Callable[[Services, Problem, Diag], types.CodeAction | None], ...] = (
    _fix_action, _suppress_next, _suppress_file)


def _overlaps(a: types.Range, b: types.Range) -> bool:
    return not ((a.end.line, a.end.character) < (b.start.line, b.start.character) or
                (b.end.line, b.end.character) < (a.start.line, a.start.character))


def fix_all_safe(sv: Services, path: str) -> types.CodeAction | None:
    """Every safe fix of the findings in ``path`` whose edits do not overlap."""
    ws = sv.ws
    if ws is None:
        return None
    chosen: list[Edit] = []
    taken: list[tuple[str, int, int]] = []
    for f in ws.findings_in(path):
        fix = f.fix
        if fix is None or not fix.applicable or not fix.safe or \
                not all(ws.writable(e.file) for e in fix.edits):
            continue
        spans = [(e.file, e.start, e.end) for e in fix.edits]
        if any(a == c and b < d2 and b2 < e2 for (a, b, e2) in spans
               for (c, b2, d2) in taken):
            continue
        taken.extend(spans)
        chosen.extend(fix.edits)
    edit = workspace_edit(sv, list(dict.fromkeys(chosen))) if chosen else None
    if edit is None:
        return None
    return types.CodeAction(title="urdf-lint: fix all safe", kind=FIX_ALL, edit=edit)
