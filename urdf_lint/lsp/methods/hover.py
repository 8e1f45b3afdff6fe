"""``textDocument/hover``: first xacro's own names (:mod:`.hover_xacro`: an arg's and a
property's value in each model, a macro call's ``${...}``), then a rule code in a suppression
comment, a macro call (parameters, defaults, doc comment), an expression's value in each model
(and the YAML line it came from), a link or joint in each model (with its frame at zero)."""
from __future__ import annotations

import os
import re

from lsprotocol import types

from urdf_lint.lsp.cursor import At, params_of
from urdf_lint.lsp.elements import describe, pose_text, targets
from urdf_lint.lsp.index import macro_params
from urdf_lint.lsp.methods import hover_xacro
from urdf_lint.lsp.methods.branch_hover import branch_hover
from urdf_lint.lsp.services import ModelView, Services


def handle(sv: Services, params: types.HoverParams) -> types.Hover | None:
    path, pos = params_of(params)
    return hover(sv, path, pos)


def hover(sv: Services, path: str, pos: types.Position) -> types.Hover | None:
    at = At(sv.doc(path), pos)
    first = hover_xacro.text(sv, path, at)   # ($(arg), xacro:arg/property, calls)
    if first is not None:
        return markdown(first)
    if at.comment:
        return _rule(at)
    # a condition's start tag: which models expand its body (docs/coverage.md)
    if (got := branch_hover(sv, path, at.tag, at.tag_line)) is not None:
        return got
    for answer in (_macro, _value, _element):
        got = answer(sv, path, at, pos)
        if got is not None:
            return got
    return None


def _rule(at: At) -> types.Hover | None:
    m = re.search(r"urdf[-_]lint\s*:", at.line)
    if m and re.fullmatch(r"UL\d+", at.word or ""):
        from urdf_lint.engine.registry import load_rule
        rule = load_rule(at.word)
        if rule is not None:
            return markdown(f"**{rule.code} {rule.name}** ({rule.severity})\n\n{rule.summary}")
    return None


def _macro(sv: Services, path: str, at: At, pos: types.Position) -> types.Hover | None:
    name = at.on_macro_call(pos)
    if name is None:
        return None
    for d in sv.index.decls(path, "macro", name)[:1]:
        params = macro_params(d.attrs.get("params", ""))
        plist = "\n".join(f"- `{n}`" + (f" = `{v}`" if v is not None else " (required)")
                          for n, v in params)
        text = f"**macro {name}** ({os.path.basename(d.file)}:{d.line})\n\n{plist}"
        return markdown(text + (f"\n\n{d.doc}" if d.doc else ""))
    return None


def _value(sv: Services, path: str, at: At, pos: types.Position) -> types.Hover | None:
    expr = at.expr()
    if expr is None or not at.attr:
        return None
    vals: dict[str | None, list[str]] = {}
    keys = _yaml_keys(sv, path, expr)
    for v, el in targets(sv, path, at):
        val = el.get(at.attr)
        src = _yaml_source(sv, v, keys, val)
        vals.setdefault(val, []).append(v.name + (f" ({src})" if src else ""))
    if not vals:
        return None
    return markdown(f"`{at.attr}` = " + "; ".join(
        f"`{val}` in {', '.join(sorted(set(ms)))}" for val, ms in vals.items()))


def _element(sv: Services, path: str, at: At, pos: types.Position) -> types.Hover | None:
    if at.tag not in ("link", "joint") or at.attr != "name":
        return None
    rows = [f"- **{v.name}**: " + describe(el) + pose_text(v, el)
            for v, el in targets(sv, path, at)]
    return markdown(f"**{at.tag}**\n\n" + "\n".join(dict.fromkeys(rows))) if rows else None


def _yaml_keys(sv: Services, path: str, expr: str) -> set[str]:
    """Names an expression's value may be stored under in a YAML file: its identifiers and
    quoted subscripts, and those of the properties it names (one level down)."""
    def names(text: str) -> set[str]:
        return set(re.findall(r"[A-Za-z_]\w*", text)) | set(re.findall(r"\[\s*['\"](\w+)['\"]", text))
    keys = names(expr)
    for k in list(keys):
        for d in sv.index.decls(path, "property", k)[:1]:
            keys |= names(d.attrs.get("value", ""))
    return keys


def _yaml_source(sv: Services, v: ModelView, keys: set[str], value: str | None) -> str:
    """``file:line`` of the YAML scalar a value came from (a key the expression names, holding
    a number of the value), among the YAML files the model read; "" when none is found."""
    ws = sv.ws
    if not value or not keys or ws is None:
        return ""
    try:
        numbers = {float(x) for x in value.split()}
    except ValueError:
        return ""
    report = next((r for r in ws.models() if r.label == v.label), None)
    for f in (report.deps if report else ()):
        if not f.endswith((".yaml", ".yml")):
            continue
        for n, line in enumerate(sv.doc(f).lines, 1):
            m = re.match(r"\s*(\w+)\s*:\s*([-+0-9.eE]+)\s*(#.*)?$", line)
            if m and m.group(1) in keys:
                try:
                    if float(m.group(2)) in numbers:
                        return f"{os.path.relpath(f, ws.root)}:{n}"
                except ValueError:
                    continue
    return ""


def markdown(text: str) -> types.Hover:
    return types.Hover(contents=types.MarkupContent(kind=types.MarkupKind.Markdown, value=text))
