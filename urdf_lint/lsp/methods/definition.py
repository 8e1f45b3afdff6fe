"""``textDocument/definition``: a macro call goes to its macro, ``$(arg x)`` to the arg, a
name in an expression to the macro parameter or property, a file name to the file, a link or
joint name to the element that defines it in whichever file writes it (through the expanded
models' source maps)."""
from __future__ import annotations

import os
import re

from lsprotocol import types

from urdf_lint.lsp.cursor import At, enclosing_macro, params_of
from urdf_lint.lsp.elements import named, ref_kind, targets
from urdf_lint.lsp.index import macro_params
from urdf_lint.lsp.methods import config_definition
from urdf_lint.lsp.services import Services
from urdf_lint.lsp.uris import path_uri


def handle(sv: Services, params: types.DefinitionParams) -> list[types.Location] | None:
    path, pos = params_of(params)
    first = config_definition.definition(sv, path, pos)   # an SRDF or controller YAML
    if first is not None:
        return first
    return definition(sv, path, pos) or None


def definition(sv: Services, path: str, pos: types.Position) -> list[types.Location]:
    at = At(sv.doc(path), pos)
    if not at.word and at.value is None:
        return []
    # a macro call: <xacro:NAME
    if at.tag and at.tag.startswith("xacro:") and at.tag_line == pos.line + 1 and \
            at.word and at.tag.endswith(at.word) and at.i <= (at.tag_col or 0) + len(at.tag):
        name = at.tag.split(":", 1)[1]
        return [sv.loc(d.file, d.line, d.col) for d in sv.index.decls(path, "macro", name)]
    if at.arg():
        return [sv.loc(d.file, d.line, d.col) for d in sv.index.decls(path, "arg", at.word)]
    if at.expr() is not None and at.word:
        m = enclosing_macro(sv, path, at)
        if m is not None and any(n.lstrip("*") == at.word
                                 for n, _ in macro_params(m.attrs.get("params", ""))):
            return [sv.loc(m.file, m.line, m.col)]
        return [sv.loc(d.file, d.line, d.col) for d in
                sv.index.decls(path, "property", at.word)[:1]]
    if at.value is not None:
        target = file_target(sv, path, at)
        if target:
            return [types.Location(uri=path_uri(target), range=types.Range(
                types.Position(0, 0), types.Position(0, 0)))]
        return _name_definition(sv, path, at)
    return []


def file_target(sv: Services, path: str, at: At) -> str | None:
    """The file an include's filename, a ``package://`` URI or a ``$(find pkg)`` path names."""
    v = at.value or ""
    ws = sv.ws
    if ws is None or not (at.attr == "filename" or "package://" in v or "$(find" in v):
        return None
    try:
        if v.startswith("package://"):
            p = str(ws.resolver.resolve_uri(v, os.path.dirname(path)))
        else:
            p = re.sub(r"\$\(find\s+([\w-]+)\)", lambda m: str(ws.resolver.find(m.group(1))), v)
            if "$" in p:
                return None
            p = os.path.join(os.path.dirname(path), p)
    except Exception:  # noqa: BLE001 - an unknown package: nowhere to go
        return None
    p = os.path.realpath(p)
    return p if ws.readable(p) and os.path.isfile(p) else None


def _name_definition(sv: Services, path: str, at: At) -> list[types.Location]:
    out: dict[tuple[str, int, int], types.Location] = {}
    for v, el in targets(sv, path, at):
        kind = ref_kind(el, at.attr or "")
        if kind is None:
            continue
        target = named(v, kind, el.get(at.attr))
        o = v.origin.get(target) if target is not None else None
        if o is not None:
            out[(o.file, o.line, o.col)] = sv.loc(o.file, o.line, o.col)
    return list(out.values())
