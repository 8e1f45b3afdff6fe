"""``textDocument/rename`` and ``textDocument/prepareRename``: a macro, property, arg, link or
joint renamed across the workspace's files as one WorkspaceEdit.

* a **macro**: its ``<xacro:macro name>``, every ``<xacro:NAME`` call (and ``</xacro:NAME>``)
  and ``<xacro:call macro="NAME">``;
* a **property**: its ``<xacro:property name>`` and every use in ``${...}`` and ``$(eval
  ...)``, except inside a macro with a parameter of that name (which hides it);
* an **arg**: its ``<xacro:arg name>`` and every ``$(arg NAME)``;
* a **link** or **joint**: every element of every model that names it (the ``<link>``,
  ``parent``/``child``, ``mimic``, ``gazebo reference``, a ``<joint>`` of a transmission or
  ros2_control), found in the expanded models and edited at their source through the source
  map; a name passed to a macro as ``${PARAM}`` is edited at the call that gives it.

Refused, saying why (LSP's RequestFailed error, which the editor shows): where a name is built
by an expression (``name="${prefix}base"``, a macro called through ``xacro:call`` with an
expression), where the config sets the arg, where the new name is taken or not a valid name,
and where an edit would fall outside the workspace folder (``check --fix``'s rule, as the code
actions: an installed package, a file a symlink leads out to)."""
from __future__ import annotations

import os
import re
from typing import Any, Iterator

from lsprotocol import types

from urdf_lint.core.edits import Edit
from urdf_lint.lsp.cursor import At, enclosing_macro
from urdf_lint.lsp.elements import named, ref_kind, targets
from urdf_lint.lsp.index import macro_params
from urdf_lint.lsp.methods import Refused
from urdf_lint.lsp.methods.code_action import workspace_edit
from urdf_lint.lsp.services import ModelView, Services
from urdf_lint.lsp.uris import uri_path

OPTIONS = types.RenameOptions(prepare_provider=True)
_IDENT = re.compile(r"[A-Za-z_]\w*$")
_NAME = re.compile(r"[^\s\"'<>&$]+$")


class Symbol:
    def __init__(self, kind: str, name: str, rng: types.Range, found: Any = None):
        self.kind, self.name, self.range, self.found = kind, name, rng, found


def prepare(sv: Services, params: types.PrepareRenameParams
            ) -> types.PrepareRenamePlaceholder:
    s = symbol(sv, uri_path(params.text_document.uri), params.position)
    return types.PrepareRenamePlaceholder(range=s.range, placeholder=s.name)


def handle(sv: Services, params: types.RenameParams) -> types.WorkspaceEdit:
    path = uri_path(params.text_document.uri)
    s = symbol(sv, path, params.position)
    new = params.new_name
    ok = _IDENT if s.kind in ("property", "arg") else _NAME
    if s.kind == "macro":
        ok = re.compile(r"[A-Za-z_][\w.-]*$")
    if not ok.match(new):
        raise Refused(f"not renamed: {new!r} is not a valid {s.kind} name")
    edits = {"macro": _macro, "property": _property, "arg": _arg}.get(s.kind, _element)(
        sv, path, s, new)
    return _workspace_edit(sv, edits, s)


# -- what is under the cursor -------------------------------------------------------------------
def symbol(sv: Services, path: str, pos: types.Position) -> Symbol:
    doc = sv.doc(path)
    at = At(doc, pos)
    line0 = pos.line

    def span(a: int, b: int) -> types.Range:
        return types.Range(doc.position(line0 + 1, a + 1), doc.position(line0 + 1, b + 1))
    if at.comment:
        raise Refused("nothing to rename here (a comment)")
    for m in re.finditer(r"\$\(arg\s+([\w-]+)\s*\)", at.line):
        if m.start() <= at.i <= m.end():
            return Symbol("arg", m.group(1), span(m.start(1), m.end(1)))
    value = _value_span(at)
    if at.tag and at.tag.startswith("xacro:") and at.attr is None:
        name = at.tag.split(":", 1)[1]
        if name not in _XACRO_TAGS and at.tag_line == line0 + 1:
            a = (at.tag_col or 0) + 6
            if a <= at.i <= a + len(name):
                return Symbol("macro", name, span(a, a + len(name)))
    if at.tag in ("xacro:macro", "xacro:property", "xacro:arg") and at.attr == "name" \
            and value is not None:
        kind = at.tag.split(":")[1]
        text, a, b = value
        if "$" in text:
            raise Refused(f"not renamed: the {kind} name {text!r} is built by an expression")
        return Symbol(kind, text, span(a, b))
    if at.expr() is not None and at.word:
        encl = enclosing_macro(sv, path, at)
        if encl is not None and any(n.lstrip("*") == at.word
                                    for n, _ in macro_params(encl.attrs.get("params", ""))):
            raise Refused(f"not renamed: {at.word!r} is a parameter of the macro {encl.name!r} "
                          "(renaming a parameter is not supported)")
        return Symbol("property", at.word, span(at.word_start, at.word_end))
    if at.attr and value is not None:
        found = _element_at(sv, path, at)
        if found is not None:
            kind, name = found
            text, a, b = value
            if text != name:
                raise Refused(f"not renamed: the {kind} name here is built by an expression "
                              f"({at.attr}=\"{text}\")")
            return Symbol(kind, name, span(a, b))
    raise Refused("nothing to rename here: a macro, property, arg, link or joint name is")


_XACRO_TAGS = {"macro", "property", "arg", "include", "if", "unless", "insert_block", "call",
               "element", "attribute"}


def _value_span(at: At) -> tuple[str, int, int] | None:
    """(the attribute value at the cursor, its start and end character in the line)."""
    if at.value is None:
        return None
    text = at.value.split("\n", 1)[0]
    q = max(at.value.find('"'), at.value.find("'"))
    if q >= 0:
        text = at.value[:q]
    start = at.i - at.value_pos
    return text, start, start + len(text)


def _element_at(sv: Services, path: str, at: At) -> tuple[str, str] | None:
    """(link | joint, its name) of the element the cursor's attribute names, in any model."""
    for v, el in targets(sv, path, at):
        kind = el.tag if at.attr == "name" and el.tag in ("link", "joint") and not \
            (el.tag == "joint" and ref_kind(el, "name")) else ref_kind(el, at.attr or "")
        if kind is None:
            continue
        target = named(v, kind, el.get(at.attr))
        if target is not None:
            return target.tag, target.get("name")
    return None


# -- the edits ------------------------------------------------------------------------------------
def _files(sv: Services) -> list[str]:
    """The xacro files of the workspace (the index's) and every xacro file a model read
    (an include only expansion resolves, an installed package's: edited nowhere, but a name
    written there refuses the rename rather than leave it half done)."""
    ws = sv.ws
    files = set(sv.index.all_files())
    if ws is not None:
        for r in ws.models():
            files.update(d for d in r.deps if d.endswith(".xacro") and ws.readable(d))
    return sorted(files)


def _edit(sv: Services, file: str, text: str, a: int, b: int, new: str) -> Edit:
    return Edit(file, len(text[:a].encode("utf-8")), len(text[:b].encode("utf-8")), new)


def _decl_pattern(tag: str, attr: str, name: str) -> re.Pattern[str]:
    return re.compile(r"<xacro:" + tag + r"\b[^>]*?\b" + attr + r"""\s*=\s*["'](""" +
                      re.escape(name) + r""")["']""")


def _macro(sv: Services, path: str, s: Symbol, new: str) -> list[Edit]:
    out = []
    for f in _files(sv):
        text = sv.doc(f).text
        for m in re.finditer(r"</?xacro:(" + re.escape(s.name) + r")(?=[\s/>])", text):
            out.append(_edit(sv, f, text, m.start(1), m.end(1), new))
        for pat in (_decl_pattern("macro", "name", s.name), _decl_pattern("call", "macro",
                                                                         s.name)):
            for m in pat.finditer(text):
                out.append(_edit(sv, f, text, m.start(1), m.end(1), new))
        dyn = re.search(r"""<xacro:call\b[^>]*?\bmacro\s*=\s*["']([^"']*\$[^"']*)["']""", text)
        if dyn:
            line = text.count("\n", 0, dyn.start()) + 1
            raise Refused(f"not renamed: {_shown(sv, f)}:{line} calls a macro named by an "
                          f"expression ({dyn.group(1)!r})")
    return out


def _macro_spans(sv: Services, f: str, text: str, name: str) -> list[tuple[int, int]]:
    """(start, end) of the bodies of the macros of ``f`` with a parameter ``name``."""
    lines = text.split("\n")
    out = []
    for d in sv.index.of(f).decls:
        if d.kind == "macro" and any(n.lstrip("*") == name for n, _ in
                                     macro_params(d.attrs.get("params", ""))):
            start = sum(len(ln) + 1 for ln in lines[:d.line - 1]) + d.col - 1
            end = text.find("</xacro:macro>", start)
            out.append((start, end if end >= 0 else len(text)))
    return out


def _property(sv: Services, path: str, s: Symbol, new: str) -> list[Edit]:
    out = []
    word = re.compile(r"(?<![\w.'\"])" + re.escape(s.name) + r"(?![\w'\"])")
    for f in _files(sv):
        text = sv.doc(f).text
        hidden = _macro_spans(sv, f, text, s.name)
        for m in _decl_pattern("property", "name", s.name).finditer(text):
            out.append(_edit(sv, f, text, m.start(1), m.end(1), new))
        for e in re.finditer(r"\$\{([^}]*)\}|\$\(eval\s+([^)]*)\)", text):
            g = 1 if e.group(1) is not None else 2
            for w in word.finditer(text, e.start(g), e.end(g)):
                if not any(a <= w.start() < b for a, b in hidden):
                    out.append(_edit(sv, f, text, w.start(), w.end(), new))
        if _decl_pattern("property", "name", new).search(text):
            raise Refused(f"not renamed: a property {new!r} is declared already "
                          f"({_shown(sv, f)})")
    return out


def _arg(sv: Services, path: str, s: Symbol, new: str) -> list[Edit]:
    ws = sv.ws
    if ws is not None and any(s.name in a for spec in getattr(ws.cfg, "models", None) or ()
                              for a in spec.arg_sets):
        raise Refused(f"not renamed: the config ({_shown(sv, ws.cfg.path or '')}) sets the arg "
                      f"{s.name!r} for a model; rename it there first")
    out = []
    for f in _files(sv):
        text = sv.doc(f).text
        for m in _decl_pattern("arg", "name", s.name).finditer(text):
            out.append(_edit(sv, f, text, m.start(1), m.end(1), new))
        for m in re.finditer(r"\$\(arg\s+(" + re.escape(s.name) + r")\s*\)", text):
            out.append(_edit(sv, f, text, m.start(1), m.end(1), new))
    return out


REF_ATTRS = ("link", "joint", "reference", "name")


def _element(sv: Services, path: str, s: Symbol, new: str) -> list[Edit]:
    """Every element of every model naming the link or joint, edited at its source."""
    out: dict[tuple[str, int], Edit] = {}
    for v in sv.views():
        target = v.named.get((s.kind, s.name))
        if target is None:
            continue
        if (s.kind, new) in v.named:
            raise Refused(f"not renamed: the model {v.name} has a {s.kind} {new!r} already")
        for e in v.root.iter():
            if not isinstance(e.tag, str):
                continue
            for a in REF_ATTRS:
                if e.get(a) != s.name:
                    continue
                if not (e is target and a == "name" or ref_kind(e, a) in (s.kind, "any")):
                    continue
                edit = _source_edit(sv, v, e, a, s.name, new)
                out[(edit.file, edit.start)] = edit
    return list(out.values())


def _source_edit(sv: Services, v: ModelView, el: Any, attr: str, name: str, new: str
                 ) -> Edit:
    """The edit of the source attribute ``attr`` that wrote ``name`` for ``el``: its literal
    value, or the literal given at the macro call for a value written ``${PARAM}``."""
    o = v.origin.get(el)
    if o is None:
        raise Refused(f"not renamed: an element naming {name!r} has no source location")
    f, at_line, at_col, chain = o.file, o.line, o.col, list(o.chain)
    while True:
        text = sv.doc(f).text
        start = sum(len(ln) + 1 for ln in text.split("\n")[:at_line - 1]) + at_col - 1
        end = text.find(">", start)
        m = re.compile(r"""\s""" + re.escape(attr) + r"""\s*=\s*(["'])(.*?)\1""", re.S).search(
            text, start, end if end >= 0 else len(text))
        where = f"{_shown(sv, f)}:{at_line}"
        if m is None:
            raise Refused(f"not renamed: {where} does not write {attr}= for {name!r}")
        value = m.group(2)
        if value == name:
            return _edit(sv, f, text, m.start(2), m.end(2), new)
        p = re.fullmatch(r"\$\{\s*([A-Za-z_]\w*)\s*\}", value)
        if p is None or not chain:
            raise Refused(f"not renamed: the name {name!r} is built by an expression at "
                          f"{where} ({attr}=\"{value}\")")
        attr = p.group(1)   # given at the macro call that made the element
        f, at_line, at_col = tuple(chain.pop())[:3]


_DECLARED = ("macro", "property", "arg")


def _declarations(sv: Services, s: Symbol, edits: list[Edit]) -> Iterator[bool]:
    """For each edit, whether it renames a declaration of the symbol."""
    tag = {"macro": "macro", "property": "property", "arg": "arg"}[s.kind]
    for e in edits:
        data = sv.doc(e.file).data
        head = data[:e.start]
        lt = head.rfind(b"<")
        yield head[lt:].startswith(b"<xacro:" + tag.encode()) and b">" not in head[lt:]


def _shown(sv: Services, f: str) -> str:
    ws = sv.ws
    return os.path.relpath(f, ws.root) if ws is not None and ws.contains(f) else f


def _workspace_edit(sv: Services, edits: list[Edit], s: Symbol) -> types.WorkspaceEdit:
    """One WorkspaceEdit (the code actions' confinement: every file inside the workspace
    folder), or refused naming the file outside it."""
    ws = sv.ws
    outside = sorted({e.file for e in edits if ws is None or not ws.writable(e.file)})
    if outside:
        raise Refused(f"not renamed: the {s.kind} {s.name!r} is also written in {outside[0]}, "
                      "outside the workspace folder (an installed package?); nothing was "
                      "changed")
    if not edits:
        raise Refused(f"not renamed: no place writes the {s.kind} {s.name!r}")
    if s.kind in _DECLARED and not any(d for d in _declarations(sv, s, edits)):
        raise Refused(f"not renamed: the declaration of the {s.kind} {s.name!r} is not in "
                      "the files of the workspace; nothing was changed")
    got = workspace_edit(sv, sorted(set(edits), key=lambda e: (e.file, e.start)))
    assert got is not None   # (every file was checked above)
    return got
