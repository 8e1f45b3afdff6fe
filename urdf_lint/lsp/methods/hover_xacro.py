"""Hover on xacro's own names (``textDocument/hover``, asked first by
:mod:`urdf_lint.lsp.methods.hover`, which shows the Markdown :func:`text` returns):

* ``$(arg NAME)`` and an ``<xacro:arg>`` declaration: the arg's value in each model that
  reads the file, and where it was set (the config's ``[[models]]`` line, or the
  declaration's default);
* an ``<xacro:property>`` declaration: its value as written, every declaration of the name,
  and its value in each model where an attribute is written ``${NAME}``;
* ``${...}`` in a macro call's attribute: what the names are (a parameter of the enclosing
  macro, a property) and the attribute's value in each model at this call (read from the
  elements the call made, where the macro writes the parameter as ``${PARAM}``).

Values come from the expanded models the workers sent back (their source maps), never from
a file outside the run's roots (:meth:`Workspace.readable`, through the index)."""
from __future__ import annotations

import os
import re
from typing import Any

from urdf_lint.core.jobs import ModelReport
from urdf_lint.lsp.cursor import At, enclosing_macro
from urdf_lint.lsp.index import macro_params
from urdf_lint.lsp.methods.diagnostics import model_name
from urdf_lint.lsp.services import Services

_ARG = re.compile(r"\$\(arg\s+([\w-]+)\s*\)")
_ATTR = re.compile(r"""([\w:.-]+)\s*=\s*(?:"([^"]*)"|'([^']*)')""")


def text(sv: Services, path: str, at: At) -> str | None:
    """The hover's Markdown at ``at`` in ``path``, None where it is not on xacro's names."""
    if at.comment:
        return None
    for m in _ARG.finditer(at.line):
        if m.start() <= at.i <= m.end():
            return _arg(sv, path, m.group(1))
    if at.tag in ("xacro:arg", "xacro:property") and at.attr in (None, "name"):
        name = _tag_attrs(at).get("name")
        if name:
            return _arg(sv, path, name) if at.tag == "xacro:arg" else _property(sv, path, name)
    if at.tag and at.tag.startswith("xacro:") and at.attr and at.expr() is not None:
        return _call(sv, path, at)
    return None


def _tag_attrs(at: At) -> dict[str, str]:
    text = at.doc.text
    lt = text.rfind("<", 0, at.off + 1)
    gt = text.find(">", lt)
    return {m.group(1): m.group(2) if m.group(2) is not None else m.group(3)
            for m in _ATTR.finditer(text[lt:gt if gt >= 0 else len(text)])}


def _reading(sv: Services, path: str) -> list[ModelReport]:
    """The models (reports) that read ``path``."""
    ws = sv.ws
    return [r for r in ws.models() if r.entry == path or path in r.deps] if ws else []


def _model(r: ModelReport) -> str:
    return model_name(r.label)


def _where(sv: Services, file: str, line: int) -> str:
    ws = sv.ws
    shown = os.path.relpath(file, ws.root) if ws and ws.contains(file) else \
        os.path.basename(file)
    return f"{shown}:{line}"


def _arg(sv: Services, path: str, name: str) -> str:
    ws = sv.ws
    decls = sv.index.decls(path, "arg", name)
    lines = [f"**arg** `{name}`"]
    rows: dict[tuple[str | None, str], list[str]] = {}
    for r in _reading(sv, path):
        value: str | None
        if name in r.args:
            value, how = r.args[name], _config_where(sv, name)
        else:
            d = next((d for d in decls if d.file in r.deps or d.file == r.entry), None)
            if d is None:
                continue
            value = d.attrs.get("default")
            how = f"default, {_where(sv, d.file, d.line)}" if value is not None else \
                f"no default, {_where(sv, d.file, d.line)}"
        rows.setdefault((value, how), []).append(_model(r))
    for (value, how), models in rows.items():
        shown = "(unset)" if value is None else f"`{value}`"
        lines.append(f"- {shown} in {', '.join(sorted(set(models)))} ({how})")
    if not rows:
        for d in decls[:4]:
            default = d.attrs.get("default")
            lines.append(f"- declared at {_where(sv, d.file, d.line)}" +
                         (f", default `{default}`" if default is not None else ", no default"))
    if ws is not None and len(lines) == 1:
        lines.append("- not declared in the files of this workspace")
    return "\n".join(lines)


def _config_where(sv: Services, name: str) -> str:
    """Where the config sets an arg: ``pyproject.toml:12`` (a ``[[models]]`` entry)."""
    ws = sv.ws
    cfg_path = getattr(ws.cfg, "path", None) if ws else None
    if not cfg_path:
        return "given to the model"
    from urdf_lint.discovery.discover import config_line
    line, _ = config_line(cfg_path, name)
    return f"set in {_where(sv, os.path.realpath(cfg_path), line)}"


def _property(sv: Services, path: str, name: str) -> str:
    lines = [f"**property** `{name}`"]
    for d in sv.index.decls(path, "property", name)[:6]:
        value = d.attrs.get("value")
        lines.append(f"- {_where(sv, d.file, d.line)}: " +
                     (f"`{value}`" if value is not None else "a block") +
                     (f" (in macro {d.in_macro})" if d.in_macro else ""))
    vals = _values(sv, sv.index.all_files(), name)
    if vals:
        lines.append("\nvalue " + "; ".join(f"`{v}` in {', '.join(sorted(set(ms)))}"
                                            for v, ms in vals.items()))
    return "\n".join(lines)


def _call(sv: Services, path: str, at: At) -> str | None:
    """``${...}`` in a macro call's attribute: the names it reads, the value per model."""
    assert at.tag is not None and at.attr is not None
    macro = at.tag.split(":", 1)[1]
    lines = []
    word = at.word
    if word:
        m = enclosing_macro(sv, path, at)
        params = dict(macro_params(m.attrs.get("params", ""))) if m is not None else {}
        if m is not None and word in params:
            default = params[word]
            lines.append(f"`{word}`: parameter of macro `{m.name}`" +
                         (f", default `{default}`" if default is not None else ", required"))
        else:
            for d in sv.index.decls(path, "property", word)[:1]:
                lines.append(f"`{word}`: property = `{d.attrs.get('value', '')}` "
                             f"({_where(sv, d.file, d.line)})")
    site = (path, at.tag_line, at.tag_col)
    vals: dict[str, list[str]] = {}
    for d in sv.index.decls(path, "macro", macro)[:1]:
        vals = _values(sv, [d.file], at.attr, site)
    if vals:
        lines.append(f"`{at.attr}` = " + "; ".join(
            f"`{v}` in {', '.join(sorted(set(ms)))}" for v, ms in vals.items()))
    return "\n\n".join(lines) if lines else None


def _values(sv: Services, files: list[str], name: str, site: tuple[Any, ...] | None = None
            ) -> dict[str, list[str]]:
    """{value: [model]} of the attributes written exactly ``${NAME}`` in ``files``, in each
    model (only the elements a macro call at ``site`` made, when given)."""
    pat = re.compile(r"""([\w:.-]+)\s*=\s*["']\$\{\s*""" + re.escape(name) + r"""\s*\}["']""")
    spots = []
    for f in files:
        text = sv.doc(f).text
        for m in pat.finditer(text):
            lt = text.rfind("<", 0, m.start())
            line = text.count("\n", 0, lt) + 1
            spots.append((f, line, lt - (text.rfind("\n", 0, lt) + 1) + 1, m.group(1)))
    out: dict[str, list[str]] = {}
    if not spots:
        return out
    for v in sv.views():
        for f, line, col, attr in spots:
            for el in v.at.get((f, line, col), ()):
                o = v.origin.get(el)
                if site is not None and (o is None or
                                         site not in [tuple(c)[:3] for c in o.chain]):
                    continue
                if el.get(attr) is not None:
                    out.setdefault(el.get(attr), []).append(model_name(v.label))
    return out
