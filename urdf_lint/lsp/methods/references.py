"""``textDocument/references``: the calls of a macro, the expressions naming a property, and
every element naming a link or joint in any model."""
from __future__ import annotations

import re

from lsprotocol import types

from urdf_lint.lsp.cursor import At, params_of
from urdf_lint.lsp.elements import named, ref_kind, targets
from urdf_lint.lsp.services import Services
from urdf_lint.lsp.uris import path_uri

Found = dict[tuple[str, int, int], types.Location]


def handle(sv: Services, params: types.ReferenceParams) -> list[types.Location] | None:
    path, pos = params_of(params)
    return references(sv, path, pos, params.context.include_declaration) or None


def references(sv: Services, path: str, pos: types.Position,
               include_declaration: bool) -> list[types.Location]:
    at = At(sv.doc(path), pos)
    macro = None
    if at.tag == "xacro:macro" and at.attr == "name":
        macro = at.value
    elif at.tag and at.tag.startswith("xacro:") and at.tag_line == pos.line + 1 and \
            at.attr is None:
        macro = at.tag.split(":", 1)[1]
    if macro:
        pat = re.compile(r"<xacro:" + re.escape(macro) + r"(?=[\s/>])")
        return _text_refs(sv, path, pat, "macro", macro, include_declaration, whole=False)
    name = at.word if at.expr() is not None else \
        (at.value if at.tag == "xacro:property" and at.attr == "name" else None)
    if name:
        pat = re.compile(r"\$\{[^}]*\b" + re.escape(name) + r"\b[^}]*\}")
        return _text_refs(sv, path, pat, "property", name, include_declaration, whole=True)
    return _element_refs(sv, path, at, include_declaration)


def _element_refs(sv: Services, path: str, at: At,
                  include_declaration: bool) -> list[types.Location]:
    """A link or joint: every element naming it, in any model."""
    out: Found = {}
    for v, el in targets(sv, path, at):
        kind = el.tag if at.attr == "name" and el.tag in ("link", "joint") else \
            ref_kind(el, at.attr or "")
        if kind is None:
            continue
        target = named(v, kind, el.get(at.attr))
        if target is None:
            continue
        name_v = target.get("name")
        for e in v.root.iter():
            if not isinstance(e.tag, str) or (e is target and not include_declaration):
                continue
            for a in ("link", "joint", "reference", "name"):
                if e.get(a) == name_v and (e is target or ref_kind(e, a) in (target.tag, "any")):
                    o = v.origin.get(e)
                    if o is not None:
                        out[(o.file, o.line, o.col)] = sv.loc(o.file, o.line, o.col)
    return list(out.values())


def _text_refs(sv: Services, path: str, pat: re.Pattern[str], kind: str, name: str,
               include_declaration: bool, whole: bool) -> list[types.Location]:
    """Where ``pat`` matches in any xacro file (``whole``: the match's range, else the start
    tag's), with the declarations of ``kind`` ``name`` when asked."""
    out: Found = {}
    for f in sv.index.all_files():
        fd = sv.doc(f)
        for m in pat.finditer(fd.text):
            ln = fd.text.count("\n", 0, m.start()) + 1
            col = m.start() - (fd.text.rfind("\n", 0, m.start()) + 1) + 1
            out[(f, ln, col)] = types.Location(uri=path_uri(f), range=types.Range(
                fd.position(ln, col), fd.position(ln, col + len(m.group(0))))) if whole \
                else sv.loc(f, ln, col)
    if include_declaration:
        for d in sv.index.decls(path, kind, name):
            out[(d.file, d.line, d.col)] = sv.loc(d.file, d.line, d.col)
    return list(out.values())
