"""Code actions: each finding's fix (byte edits, possibly of another file: a property, a
macro argument, a YAML scalar) as a quick fix, suppression comments for the next element or
the whole file, and "fix all safe" for the document."""
from __future__ import annotations

from lsprotocol import types

from urdf_lint.core import overlay
from urdf_lint.core.edits import Fix
from urdf_lint.lsp.core import UrdfLintServer, path_uri, uri_path

FIX_ALL = types.CodeActionKind.SourceFixAll.value + ".urdf-lint"


def _workspace_edit(ls: UrdfLintServer, edits) -> types.WorkspaceEdit | None:
    """LSP text edits from byte edits, per file, against the text the editor has; None when
    an edit is of a file the run may not write (``check --fix``'s rule: outside the
    workspace folder, an installed package, a file a symlink leads out to)."""
    ws = ls.ws
    if ws is None or not all(ws.writable(e.file) for e in edits):
        return None
    changes: dict = {}
    for e in edits:
        doc = ls.doc(e.file)
        changes.setdefault(path_uri(e.file), []).append(types.TextEdit(
            range=types.Range(doc.offset_position(e.start), doc.offset_position(e.end)),
            new_text=e.text))
    return types.WorkspaceEdit(changes=changes)


def _fix_action(ls, f, diag) -> types.CodeAction | None:
    fix: Fix | None = f.fix
    if fix is None or not fix.applicable:
        return None
    edit = _workspace_edit(ls, fix.edits)
    if edit is None:
        return None
    title = fix.description + ("" if fix.safe else " (unsafe: check the result)")
    return types.CodeAction(title=f"{f.code}: {title}", kind=types.CodeActionKind.QuickFix,
                            diagnostics=[diag] if diag else None, is_preferred=fix.safe,
                            edit=edit)


def _suppress_next(ls, f, diag) -> types.CodeAction | None:
    from urdf_lint.fix.addsuppress import suppression_edits
    if not ls.ws.writable(f.file):   # (--add-suppressions leaves it alone too; nor is it read)
        return None
    with overlay.using(ls.ws.buffers):
        edits, _ = suppression_edits([f])
    es = [e for v in edits.values() for e in v]
    edit = _workspace_edit(ls, es) if es else None
    if edit is None:
        return None
    return types.CodeAction(title=f"Disable {f.code} for the next element",
                            kind=types.CodeActionKind.QuickFix,
                            diagnostics=[diag] if diag else None, edit=edit)


def _suppress_file(ls, f, diag) -> types.CodeAction | None:
    from urdf_lint.core.edits import Edit
    if not f.file.endswith((".xacro", ".urdf", ".xml")) or not ls.ws.writable(f.file):
        return None
    data = ls.doc(f.file).data
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
                            edit=_workspace_edit(ls, [edit]))


def _overlaps(a: types.Range, b: types.Range) -> bool:
    return not ((a.end.line, a.end.character) < (b.start.line, b.start.character) or
                (b.end.line, b.end.character) < (a.start.line, a.start.character))


def fix_all_safe(ls, path: str) -> types.CodeAction | None:
    """Every safe fix of the findings in ``path`` whose edits do not overlap."""
    ws = ls.ws
    chosen: list = []
    taken: list = []
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
    edit = _workspace_edit(ls, list(dict.fromkeys(chosen))) if chosen else None
    if edit is None:
        return None
    return types.CodeAction(title="urdf-lint: fix all safe", kind=FIX_ALL, edit=edit)


def register(server: UrdfLintServer) -> None:
    server.feature(types.TEXT_DOCUMENT_CODE_ACTION, types.CodeActionOptions(
        code_action_kinds=[types.CodeActionKind.QuickFix, FIX_ALL]))(code_action)


def code_action(ls: UrdfLintServer, params: types.CodeActionParams):
    ws = ls.ws
    if ws is None:
        return None
    path = uri_path(params.text_document.uri)
    only = params.context.only
    out: list = []
    want_quick = not only or any(str(k).startswith("quickfix") for k in only)
    if want_quick:
        doc = ls.doc(path)
        for f in ws.findings_in(path):
            rng = doc.element_range(f.line, f.col)
            if not _overlaps(rng, params.range):
                continue
            diag = next((d for d in params.context.diagnostics
                         if d.code == f.code and d.range == rng), None)
            for make in (_fix_action, _suppress_next, _suppress_file):
                a = make(ls, f, diag)
                if a is not None:
                    out.append(a)
    if not only or any(str(k).startswith("source") for k in only):
        a = fix_all_safe(ls, path)
        if a is not None:
            out.append(a)
    return out
