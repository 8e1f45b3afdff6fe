"""Navigation, hover, completion and symbols.

Declarations (macros, properties, args, includes) come from the text the editor has
(:mod:`.index`); links and joints, and the values expressions take, from the expanded models
the workers sent back (``LintSettings.keep_model``) through their source maps: a ``parent
link="${prefix}base_link"`` written in a macro goes to the ``<link>`` that defines it in
whichever file writes it, and an expression's hover shows its value in each model.
"""
from __future__ import annotations

import os
import re

from lsprotocol import types

from urdf_lint.lsp.core import UrdfLintServer, path_uri, uri_path
from urdf_lint.lsp.index import Decl, index_text, macro_params
from urdf_lint.lsp.text import Doc

# where a name of another element is written: (tag, attribute) -> "link" | "joint" | "any"
NAME_REFS = {("parent", "link"): "link", ("child", "link"): "link", ("mimic", "joint"): "joint",
             ("gazebo", "reference"): "any", ("joint", "name"): "joint",
             ("link", "name"): "link"}
REF_CONTEXT = {"transmission", "ros2_control"}   # a <joint name=...> there names a joint


# -- the workspace's declarations -------------------------------------------------------------
class Index:
    """Every xacro file's declarations, re-read when its text changes."""

    def __init__(self):
        self.files: dict = {}

    def of(self, ls: UrdfLintServer, path: str):
        doc = ls.doc(path)
        hit = self.files.get(path)
        if hit is None or hit[0] is not doc.data and hit[0] != doc.data:
            hit = self.files[path] = (doc.data, index_text(path, doc.data))
        return hit[1]

    def all_files(self, ls: UrdfLintServer) -> list[str]:
        """The workspace's xacro files: open or in the include graph, inside the run's roots
        (an include a symlink or ``$(find)`` leads out of them is not indexed)."""
        ws = ls.ws
        if ws is None:
            return []
        files = set(ws.buffers)
        for f, inc in ws.graph.includes.items():
            files.add(f)
            files.update(inc)
        return sorted(f for f in files if f.endswith(".xacro") and ws.readable(f))

    def reachable(self, ls: UrdfLintServer, path: str) -> list[str]:
        """``path``, the files it includes (transitively), then every other xacro file."""
        ws = ls.ws
        out, todo = [], [path]
        while todo:
            f = todo.pop(0)
            if f in out:
                continue
            out.append(f)
            if ws is not None:
                todo.extend(i for i in ws.graph.includes.get(f, ()) if ws.readable(i))
        return out + [f for f in self.all_files(ls) if f not in out]

    def decls(self, ls, path, kind, name=None) -> list[Decl]:
        return [d for f in self.reachable(ls, path) for d in self.of(ls, f).decls
                if d.kind == kind and (name is None or d.name == name)]


INDEX = Index()


# -- the expanded models ------------------------------------------------------------------------
class ModelView:
    """One model's expanded robot with its source map: elements by source origin and by name."""

    def __init__(self, report):
        from lxml import etree
        self.label = report.label
        self.name = os.path.splitext(os.path.basename(report.entry))[0]
        self.root = etree.fromstring(report.kept_model.xml.encode("utf-8"))
        self.at: dict = {}
        self.origin: dict = {}
        for el, o in report.kept_model.origins.align(self.root.iter(tag=etree.Element)).items():
            self.at.setdefault((o.file, o.line, o.col), []).append(el)
            self.origin[el] = o
        self.named = {(el.tag, el.get("name")): el for el in self.root
                      if el.tag in ("link", "joint")}


_views: dict = {}


def views(ls: UrdfLintServer) -> list[ModelView]:
    ws = ls.ws
    out = []
    for r in list(ws.models()) if ws else []:
        if r.kept_model is None or r.kept_model.xml is None:
            continue
        v = _views.get(id(r))
        if v is None or v[0] is not r:
            try:
                v = _views[id(r)] = (r, ModelView(r))
            except Exception:  # noqa: BLE001 - a model lxml cannot hold: no navigation in it
                continue
        out.append(v[1])
    return out


# -- the cursor's context ---------------------------------------------------------------------
class At:
    """What is under the cursor: the enclosing start tag, the attribute and the word."""

    def __init__(self, doc: Doc, pos: types.Position):
        self.doc = doc
        self.line = doc.line(pos.line)
        self.i = doc.char_index(pos)
        text, off = doc.text, _char_offset(doc, pos.line, self.i)
        self.off = off
        lt = text.rfind("<", 0, off)
        gt = text.rfind(">", 0, off)
        self.tag = self.tag_line = self.tag_col = None
        self.attr = self.value = None
        self.in_tag = lt > gt and lt >= 0 and text[lt + 1:lt + 2] not in ("/", "!", "?")
        if self.in_tag:
            m = re.match(r"<([\w:.-]+)", text[lt:])
            self.tag = m.group(1) if m else None
            self.tag_line = text.count("\n", 0, lt) + 1
            self.tag_col = lt - (text.rfind("\n", 0, lt) + 1) + 1
            head = text[lt:off]
            am = re.search(r"""([\w:.-]+)\s*=\s*(["'])([^"']*)$""", head)
            if am:
                self.attr = am.group(1)
                rest = text[off:]
                tail = rest[:rest.find(am.group(2))] if am.group(2) in rest else ""
                self.value = am.group(3) + tail
                self.value_pos = len(am.group(3))
        self.comment = text.rfind("<!--", 0, off) > text.rfind("-->", 0, off)
        s, i = self.line, self.i
        a = i
        while a > 0 and re.match(r"[\w.-]", s[a - 1]):
            a -= 1
        b = i
        while b < len(s) and re.match(r"[\w.-]", s[b]):
            b += 1
        self.word, self.word_start, self.word_end = s[a:b], a, b
        self.before = s[:i]

    def expr(self) -> str | None:
        """The ``${...}`` the cursor is in (its text), if any."""
        s, i = self.line, self.i
        a = s.rfind("${", 0, i)
        if a < 0 or "}" in s[a:i]:
            return None
        b = s.find("}", i)
        return s[a + 2:b if b >= 0 else len(s)]

    def arg(self) -> bool:
        return bool(re.search(r"\$\(arg\s+[\w-]*$", self.line[:self.word_start]
                              + self.word[:self.i - self.word_start]))


def _char_offset(doc: Doc, line0: int, i: int) -> int:
    return sum(len(ln) + 1 for ln in doc.lines[:line0]) + i


def _loc(ls: UrdfLintServer, file: str, line: int, col: int) -> types.Location:
    return types.Location(uri=path_uri(file), range=ls.doc(file).element_range(line, col))


def _enclosing_macro(ls, path, at: At) -> Decl | None:
    """The macro whose body holds the cursor (the last macro start above it whose end is not
    above it: a macro's body is the text up to its end tag)."""
    text = at.doc.text
    best = None
    for d in INDEX.of(ls, path).decls:
        if d.kind != "macro":
            continue
        start = _char_offset(at.doc, d.line - 1, d.col - 1)
        end = text.find("</xacro:macro>", start)
        if start <= at.off and (end < 0 or at.off <= end):
            best = d
    return best


# -- definition / references ------------------------------------------------------------------
# asked first, in order (server.py adds them: the methods' modules import this one)
DEFINITION_FIRST: list = []


def definition(ls: UrdfLintServer, path: str, pos: types.Position) -> list[types.Location]:
    for first in DEFINITION_FIRST:   # (methods.config_definition: SRDF and controller YAML)
        got = first(ls, path, pos)
        if got is not None:
            return got
    doc = ls.doc(path)
    at = At(doc, pos)
    if not at.word and at.value is None:
        return []
    # a macro call: <xacro:NAME
    if at.tag and at.tag.startswith("xacro:") and at.tag_line == pos.line + 1 and \
            at.word and at.tag.endswith(at.word) and at.i <= (at.tag_col or 0) + len(at.tag):
        name = at.tag.split(":", 1)[1]
        return [_loc(ls, d.file, d.line, d.col) for d in INDEX.decls(ls, path, "macro", name)]
    if at.arg():
        return [_loc(ls, d.file, d.line, d.col) for d in INDEX.decls(ls, path, "arg", at.word)]
    if at.expr() is not None and at.word:
        m = _enclosing_macro(ls, path, at)
        if m is not None and any(n.lstrip("*") == at.word
                                 for n, _ in macro_params(m.attrs.get("params", ""))):
            return [_loc(ls, m.file, m.line, m.col)]
        return [_loc(ls, d.file, d.line, d.col) for d in
                INDEX.decls(ls, path, "property", at.word)[:1]]
    if at.value is not None:
        target = _file_target(ls, path, at)
        if target:
            return [types.Location(uri=path_uri(target), range=types.Range(
                types.Position(0, 0), types.Position(0, 0)))]
        return _name_definition(ls, path, at)
    return []


def _file_target(ls, path, at: At) -> str | None:
    """The file an include's filename, a ``package://`` URI or a ``$(find pkg)`` path names."""
    v = at.value or ""
    if not (at.attr == "filename" or "package://" in v or "$(find" in v):
        return None
    ws = ls.ws
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


def _targets(ls, path, at: At):
    """(model view, element at the cursor's start tag) for every model that expands it."""
    if not at.tag_line:
        return
    for v in views(ls):
        for el in v.at.get((path, at.tag_line, at.tag_col), ()):
            yield v, el


def _named(v: ModelView, kind: str, name: str):
    kinds = ("link", "joint") if kind == "any" else (kind,)
    for k in kinds:
        el = v.named.get((k, name))
        if el is not None:
            return el
    return None


def _ref_kind(el, attr: str) -> str | None:
    kind = NAME_REFS.get((el.tag, attr))
    if el.tag == "joint" and attr == "name":
        parent = el.getparent()
        return "joint" if parent is not None and parent.tag in REF_CONTEXT else None
    if el.tag == "link" and attr == "name":
        return None
    return kind


def _name_definition(ls, path, at: At) -> list[types.Location]:
    out: dict = {}
    for v, el in _targets(ls, path, at):
        kind = _ref_kind(el, at.attr or "")
        if kind is None:
            continue
        target = _named(v, kind, el.get(at.attr))
        o = v.origin.get(target) if target is not None else None
        if o is not None:
            out[(o.file, o.line, o.col)] = _loc(ls, o.file, o.line, o.col)
    return list(out.values())


def references(ls: UrdfLintServer, path: str, pos: types.Position,
               include_declaration: bool) -> list[types.Location]:
    doc = ls.doc(path)
    at = At(doc, pos)
    out: dict = {}
    macro = None
    if at.tag == "xacro:macro" and at.attr == "name":
        macro = at.value
    elif at.tag and at.tag.startswith("xacro:") and at.tag_line == pos.line + 1 and \
            at.attr is None:
        macro = at.tag.split(":", 1)[1]
    if macro:
        pat = re.compile(r"<xacro:" + re.escape(macro) + r"(?=[\s/>])")
        return _text_refs(ls, path, pat, "macro", macro, include_declaration, whole=False)
    name = at.word if at.expr() is not None else \
        (at.value if at.tag == "xacro:property" and at.attr == "name" else None)
    if name:
        pat = re.compile(r"\$\{[^}]*\b" + re.escape(name) + r"\b[^}]*\}")
        return _text_refs(ls, path, pat, "property", name, include_declaration, whole=True)
    # a link or joint: every element naming it, in any model
    for v, el in _targets(ls, path, at):
        kind = el.tag if at.attr == "name" and el.tag in ("link", "joint") else \
            _ref_kind(el, at.attr or "")
        if kind is None:
            continue
        target = _named(v, kind, el.get(at.attr))
        if target is None:
            continue
        name_v = target.get("name")
        for e in v.root.iter():
            if not isinstance(e.tag, str) or (e is target and not include_declaration):
                continue
            for a in ("link", "joint", "reference", "name"):
                if e.get(a) == name_v and (e is target or _ref_kind(e, a) in (target.tag, "any")):
                    o = v.origin.get(e)
                    if o is not None:
                        out[(o.file, o.line, o.col)] = _loc(ls, o.file, o.line, o.col)
    return list(out.values())


def _text_refs(ls, path, pat, kind, name, include_declaration, whole) -> list[types.Location]:
    """Where ``pat`` matches in any xacro file (``whole``: the match's range, else the start
    tag's), with the declarations of ``kind`` ``name`` when asked."""
    out: dict = {}
    for f in INDEX.all_files(ls):
        fd = ls.doc(f)
        for m in pat.finditer(fd.text):
            ln = fd.text.count("\n", 0, m.start()) + 1
            col = m.start() - (fd.text.rfind("\n", 0, m.start()) + 1) + 1
            out[(f, ln, col)] = types.Location(uri=path_uri(f), range=types.Range(
                fd.position(ln, col), fd.position(ln, col + len(m.group(0))))) if whole \
                else _loc(ls, f, ln, col)
    if include_declaration:
        for d in INDEX.decls(ls, path, kind, name):
            out[(d.file, d.line, d.col)] = _loc(ls, d.file, d.line, d.col)
    return list(out.values())


# -- hover --------------------------------------------------------------------------------------
def hover(ls: UrdfLintServer, path: str, pos: types.Position) -> types.Hover | None:
    doc = ls.doc(path)
    at = At(doc, pos)
    if at.comment:
        m = re.search(r"urdf[-_]lint\s*:", at.line)
        if m and re.fullmatch(r"UL\d+", at.word or ""):
            from urdf_lint.engine.registry import load_rule
            rule = load_rule(at.word)
            if rule is not None:
                return _md(f"**{rule.code} {rule.name}** ({rule.severity})\n\n{rule.summary}")
        return None
    if at.tag and at.tag.startswith("xacro:") and at.attr is None and \
            at.tag_line == pos.line + 1:
        name = at.tag.split(":", 1)[1]
        for d in INDEX.decls(ls, path, "macro", name)[:1]:
            params = macro_params(d.attrs.get("params", ""))
            plist = "\n".join(f"- `{n}`" + (f" = `{v}`" if v is not None else " (required)")
                              for n, v in params)
            text = f"**macro {name}** ({os.path.basename(d.file)}:{d.line})\n\n{plist}"
            return _md(text + (f"\n\n{d.doc}" if d.doc else ""))
    expr = at.expr()
    if expr is not None and at.attr:
        vals: dict = {}
        keys = _yaml_keys(ls, path, expr)
        for v, el in _targets(ls, path, at):
            val = el.get(at.attr)
            src = _yaml_source(ls, v, keys, val)
            vals.setdefault(val, []).append(v.name + (f" ({src})" if src else ""))
        if vals:
            return _md(f"`{at.attr}` = " + "; ".join(
                f"`{val}` in {', '.join(sorted(set(ms)))}" for val, ms in vals.items()))
    if at.tag in ("link", "joint") and at.attr == "name":
        rows = []
        for v, el in _targets(ls, path, at):
            rows.append(f"- **{v.name}**: " + _describe(el) + _pose_text(v, el))
        if rows:
            return _md(f"**{at.tag}**\n\n" + "\n".join(dict.fromkeys(rows)))
    return None


def _yaml_keys(ls, path, expr: str) -> set:
    """Names an expression's value may be stored under in a YAML file: its identifiers and
    quoted subscripts, and those of the properties it names (one level down)."""
    def names(text):
        return set(re.findall(r"[A-Za-z_]\w*", text)) | set(re.findall(r"\[\s*['\"](\w+)['\"]", text))
    keys = names(expr)
    for k in list(keys):
        for d in INDEX.decls(ls, path, "property", k)[:1]:
            keys |= names(d.attrs.get("value", ""))
    return keys


def _yaml_source(ls, v: "ModelView", keys: set, value: str | None) -> str:
    """``file:line`` of the YAML scalar a value came from (a key the expression names, holding
    a number of the value), among the YAML files the model read; "" when none is found."""
    if not value or not keys:
        return ""
    try:
        numbers = {float(x) for x in value.split()}
    except ValueError:
        return ""
    ws = ls.ws
    report = next((r for r in ws.models() if r.label == v.label), None) if ws else None
    for f in (report.deps if report else ()):
        if not f.endswith((".yaml", ".yml")):
            continue
        for n, line in enumerate(ls.doc(f).lines, 1):
            m = re.match(r"\s*(\w+)\s*:\s*([-+0-9.eE]+)\s*(#.*)?$", line)
            if m and m.group(1) in keys:
                try:
                    if float(m.group(2)) in numbers:
                        from urdf_lint.core.locations import display_path
                        return f"{os.path.relpath(f, ws.root) if ws else display_path(f)}:{n}"
                except ValueError:
                    continue
    return ""


def _describe(el) -> str:
    if el.tag == "joint":
        parts = [f"`{el.get('name')}` {el.get('type')}"]
        p, c = el.find("parent"), el.find("child")
        parts.append(f"parent `{p.get('link') if p is not None else '?'}`, "
                     f"child `{c.get('link') if c is not None else '?'}`")
        lim = el.find("limit")
        if lim is not None:
            parts.append("limits " + ", ".join(f"{k} {lim.get(k)}" for k in
                                                ("lower", "upper", "effort", "velocity")
                                                if lim.get(k) is not None))
        return "; ".join(parts)
    m = el.find("inertial/mass")
    return f"`{el.get('name')}`" + (f"; mass {m.get('value')}" if m is not None else "")


def _frame(el):
    """The 4x4 transform of an element's <origin> (URDF: R = Rz(yaw) Ry(pitch) Rx(roll))."""
    import math
    import numpy as np
    o = el.find("origin")

    def nums(attr):
        try:
            got = [float(x) for x in (o.get(attr) or "0 0 0").split()] if o is not None \
                else [0.0] * 3
        except ValueError:
            got = [0.0] * 3
        return (got + [0.0] * 3)[:3]
    (x, y, z), (r, p, w) = nums("xyz"), nums("rpy")
    cr, sr, cp, sp, cw, sw = (math.cos(r), math.sin(r), math.cos(p), math.sin(p),
                              math.cos(w), math.sin(w))
    m = np.eye(4)
    m[:3, :3] = [[cw * cp, cw * sp * sr - sw * cr, cw * sp * cr + sw * sr],
                 [sw * cp, sw * sp * sr + cw * cr, sw * sp * cr - cw * sr],
                 [-sp, cp * sr, cp * cr]]
    m[:3, 3] = [x, y, z]
    return m


def world_pose(v: "ModelView", el):
    """(xyz, rpy) of a link's or joint's frame at the zero configuration, or None (a loop)."""
    import math
    import numpy as np
    by_child = {}
    for j in v.root.findall("joint"):
        c = j.find("child")
        if c is not None:
            by_child[c.get("link")] = j
    chain = [el] if el.tag == "joint" else []
    link = el.find("parent").get("link") if el.tag == "joint" and el.find("parent") is not None \
        else el.get("name")
    seen = set()
    while link in by_child:
        if link in seen:
            return None
        seen.add(link)
        j = by_child[link]
        chain.append(j)
        p = j.find("parent")
        link = p.get("link") if p is not None else None
    m = np.eye(4)
    for j in reversed(chain):
        m = m @ _frame(j)
    rpy = (math.atan2(m[2, 1], m[2, 2]), math.asin(max(-1.0, min(1.0, -m[2, 0]))),
           math.atan2(m[1, 0], m[0, 0]))
    return [round(float(x), 4) + 0.0 for x in m[:3, 3]], [round(r, 4) + 0.0 for r in rpy]


def _pose_text(v, el) -> str:
    got = world_pose(v, el)
    if got is None:
        return ""
    xyz, rpy = got
    return f"; world pose at zero: xyz {' '.join(map(str, xyz))}, rpy {' '.join(map(str, rpy))}"


def _md(text: str) -> types.Hover:
    return types.Hover(contents=types.MarkupContent(kind=types.MarkupKind.Markdown, value=text))


# -- completion ---------------------------------------------------------------------------------
# asked first, in order (server.py adds them): (ls, path, pos) -> items or None
COMPLETION_FIRST: list = []


def completion(ls: UrdfLintServer, path: str, pos: types.Position) -> list[types.CompletionItem]:
    for first in COMPLETION_FIRST:   # (methods.config_definition: SRDF and controller YAML)
        got = first(ls, path, pos)
        if got is not None:
            return got
    at = At(ls.doc(path), pos)
    for complete in _COMPLETERS:
        got = complete(ls, path, at)
        if got is not None:
            return got
    return []


# Each completer returns its items where the cursor is its kind of place, else None (the next
# one is asked); they are asked in this order (see _COMPLETERS).
def _complete_codes(ls, path, at) -> list | None:
    """Rule codes in a suppression comment."""
    if not (at.comment and re.search(r"urdf[-_]lint\s*:\s*[\w-]*\s.*$", at.before)):
        return None
    from urdf_lint.engine.registry import catalogue
    return [types.CompletionItem(label=code, detail=e.name,
                                 kind=types.CompletionItemKind.EnumMember)
            for code, e in catalogue().items()]


def _complete_macros(ls, path, at) -> list | None:
    """Macro names after ``<xacro:``, with their required parameters as a snippet."""
    if not re.search(r"<xacro:[\w-]*$", at.before):
        return None
    items: dict = {}
    for d in INDEX.decls(ls, path, "macro"):
        if d.name in items:
            continue
        req = [n for n, v in macro_params(d.attrs.get("params", ""))
               if v is None and not n.startswith("*")]
        snippet = d.name + "".join(f' {n}="${{{i}}}"' for i, n in enumerate(req, 1)) + "/>"
        items[d.name] = types.CompletionItem(
            label=d.name, kind=types.CompletionItemKind.Function,
            detail=f"macro ({os.path.basename(d.file)}:{d.line})",
            insert_text=snippet, insert_text_format=types.InsertTextFormat.Snippet)
    return list(items.values())


def _complete_package_files(ls, path, at) -> list | None:
    pm = re.search(r"package://([\w-]+)/([^\"'\s]*)$", at.before)
    return _package_files(ls, pm.group(1), pm.group(2)) if pm else None


def _in_attribute_name(at) -> bool:
    """Inside a tag where an attribute name goes (not its value, not the tag's name)."""
    return bool(at.in_tag and at.value is None and at.tag) and \
        not re.search(r"<[\w:.-]*$", at.before)


def _complete_macro_params(ls, path, at) -> list | None:
    """Parameter names inside a macro call (those not written yet)."""
    if not (_in_attribute_name(at) and at.tag.startswith("xacro:")):
        return None
    items: dict = {}
    name = at.tag.split(":", 1)[1]
    start = at.doc.text.rfind("<", 0, at.off)
    written = set(re.findall(r"([\w-]+)\s*=", at.doc.text[start:at.off]))
    for d in INDEX.decls(ls, path, "macro", name)[:1]:
        for n, default in macro_params(d.attrs.get("params", "")):
            if not n.startswith("*") and n not in written:
                items[n] = types.CompletionItem(
                    label=n, kind=types.CompletionItemKind.Property,
                    detail="required" if default is None else f"default {default}",
                    insert_text=f'{n}="${{1}}"',
                    insert_text_format=types.InsertTextFormat.Snippet)
    return list(items.values())


def _complete_urdf_attributes(ls, path, at) -> list | None:
    """The attributes of a URDF element."""
    if not (_in_attribute_name(at) and not at.tag.startswith("xacro:")):
        return None
    attrs = URDF_ATTRIBUTES.get(at.tag.split(":")[-1])
    if not attrs:
        return None
    return [types.CompletionItem(label=a, kind=types.CompletionItemKind.Property,
                                 insert_text=f'{a}="${{1}}"',
                                 insert_text_format=types.InsertTextFormat.Snippet)
            for a in attrs]


def _complete_elements(ls, path, at) -> list | None:
    if not re.search(r"<[\w-]*$", at.before) or at.comment:
        return None
    return [types.CompletionItem(label=e, kind=types.CompletionItemKind.Keyword)
            for e in URDF_ATTRIBUTES]


def _complete_args(ls, path, at) -> list | None:
    if not re.search(r"\$\(arg\s+[\w-]*$", at.before):
        return None
    items: dict = {}
    for d in INDEX.decls(ls, path, "arg"):
        items.setdefault(d.name, types.CompletionItem(
            label=d.name, kind=types.CompletionItemKind.Variable,
            detail=f"arg, default {d.attrs.get('default')!r}"))
    return list(items.values())


def _complete_packages(ls, path, at) -> list | None:
    if not re.search(r"(package://|\$\(find\s+)[\w-]*$", at.before):
        return None
    ws = ls.ws
    names = set(ws.resolver.explicit) | set(ws.resolver.scanned) if ws else set()
    return [types.CompletionItem(label=n, kind=types.CompletionItemKind.Module)
            for n in sorted(names)]


def _complete_expression(ls, path, at) -> list | None:
    """Inside ``${...}``: the enclosing macro's parameters, then the properties."""
    if at.expr() is None:
        return None
    items: dict = {}
    m = _enclosing_macro(ls, path, at)
    if m is not None:
        for n, _default in macro_params(m.attrs.get("params", "")):
            if not n.startswith("*"):
                items[n] = types.CompletionItem(label=n, kind=types.CompletionItemKind.Variable,
                                                detail=f"parameter of {m.name}")
    for d in INDEX.decls(ls, path, "property"):
        items.setdefault(d.name, types.CompletionItem(
            label=d.name, kind=types.CompletionItemKind.Constant,
            detail=f"property = {d.attrs.get('value', '')}"[:80]))
    return list(items.values())


def _complete_references(ls, path, at) -> list | None:
    """Link (or joint) names of the models this file is part of, in a reference."""
    if not (at.value is not None and at.tag in ("parent", "child", "gazebo", "mimic") and
            at.attr in ("link", "reference", "joint")):
        return None
    items: dict = {}
    want = "joint" if at.attr == "joint" else "link"
    for view in views(ls):
        if path not in _model_files(view):
            continue
        for (k, n) in view.named:
            if k == want or at.attr == "reference":
                items.setdefault(n, types.CompletionItem(
                    label=n, kind=types.CompletionItemKind.Reference,
                    detail=f"{k} in {view.name}"))
    return list(items.values())


_COMPLETERS = (_complete_codes, _complete_macros, _complete_package_files,
               _complete_macro_params, _complete_urdf_attributes, _complete_elements,
               _complete_args, _complete_packages, _complete_expression,
               _complete_references)


# the URDF schema's elements and their attributes (urdfdom, plus the common ROS extensions)
URDF_ATTRIBUTES = {
    "robot": ["name", "version"], "link": ["name", "type"], "joint": ["name", "type"],
    "parent": ["link"], "child": ["link"], "origin": ["xyz", "rpy"], "axis": ["xyz"],
    "limit": ["lower", "upper", "effort", "velocity"], "dynamics": ["damping", "friction"],
    "mimic": ["joint", "multiplier", "offset"], "calibration": ["rising", "falling"],
    "safety_controller": ["soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"],
    "inertial": [], "mass": ["value"],
    "inertia": ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"], "visual": ["name"],
    "collision": ["name"], "geometry": [], "box": ["size"], "cylinder": ["radius", "length"],
    "sphere": ["radius"], "mesh": ["filename", "scale"], "material": ["name"],
    "color": ["rgba"], "texture": ["filename"], "transmission": ["name"],
    "gazebo": ["reference"], "ros2_control": ["name", "type"],
}
MAX_LISTED = 200


def _package_files(ls: UrdfLintServer, package: str, partial: str) -> list:
    """Files and folders below a package for ``package://pkg/partial`` (inside the roots)."""
    ws = ls.ws
    if ws is None:
        return []
    try:
        base = os.path.realpath(str(ws.resolver.find(package)))
    except Exception:  # noqa: BLE001 - an unknown package: nothing to list
        return []
    if not base:
        return []
    folder = os.path.realpath(os.path.join(base, os.path.dirname(partial)))
    if not (folder == base or folder.startswith(base + os.sep)) or not ws.resolver.is_inside(folder):
        return []
    out = []
    try:
        from urdf_lint.core import fsbound
        names = sorted(fsbound.list_dir(folder))[:MAX_LISTED]
    except OSError:
        return []
    for n in names:
        if n.startswith("."):
            continue
        is_dir = os.path.isdir(os.path.join(folder, n))
        out.append(types.CompletionItem(
            label=n + ("/" if is_dir else ""),
            kind=types.CompletionItemKind.Folder if is_dir else types.CompletionItemKind.File))
    return out


def _model_files(v: ModelView) -> set:
    got = getattr(v, "_files", None)
    if got is None:
        got = v._files = {k[0] for k in v.at}   # type: ignore[attr-defined]
    return got


# -- symbols -----------------------------------------------------------------------------------
SYMBOL_KIND = {"macro": types.SymbolKind.Function, "property": types.SymbolKind.Constant,
               "arg": types.SymbolKind.Variable, "link": types.SymbolKind.Struct,
               "joint": types.SymbolKind.Interface}


def document_symbols(ls: UrdfLintServer, path: str) -> list[types.DocumentSymbol]:
    doc = ls.doc(path)
    out = []
    for d in INDEX.of(ls, path).decls:
        if d.kind == "include":
            continue
        rng = doc.element_range(d.line, d.col)
        out.append(types.DocumentSymbol(name=d.name or "?", kind=SYMBOL_KIND[d.kind], range=rng,
                                        selection_range=rng, detail=d.kind))
    return out


def workspace_symbols(ls: UrdfLintServer, query: str) -> list[types.WorkspaceSymbol]:
    out = []
    q = query.lower()
    for f in INDEX.all_files(ls):
        for d in INDEX.of(ls, f).decls:
            if d.kind != "include" and q in d.name.lower():
                out.append(types.WorkspaceSymbol(name=d.name, kind=SYMBOL_KIND[d.kind],
                                                 location=_loc(ls, d.file, d.line, d.col)))
    return out


def register(server: UrdfLintServer) -> None:
    def doc_path(params) -> str:
        return uri_path(params.text_document.uri)

    @server.feature(types.TEXT_DOCUMENT_DEFINITION)
    def _definition(ls, params: types.DefinitionParams):
        return definition(ls, doc_path(params), params.position) or None

    @server.feature(types.TEXT_DOCUMENT_REFERENCES)
    def _references(ls, params: types.ReferenceParams):
        return references(ls, doc_path(params), params.position,
                          params.context.include_declaration) or None

    @server.feature(types.TEXT_DOCUMENT_HOVER)
    def _hover(ls, params: types.HoverParams):
        return hover(ls, doc_path(params), params.position)

    @server.feature(types.TEXT_DOCUMENT_COMPLETION, types.CompletionOptions(
        trigger_characters=[":", "{", " ", "/", '"']))
    def _completion(ls, params: types.CompletionParams):
        return types.CompletionList(is_incomplete=False,
                                    items=completion(ls, doc_path(params), params.position))

    @server.feature(types.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
    def _symbols(ls, params: types.DocumentSymbolParams):
        return document_symbols(ls, doc_path(params))

    @server.feature(types.WORKSPACE_SYMBOL)
    def _workspace_symbols(ls, params: types.WorkspaceSymbolParams):
        return workspace_symbols(ls, params.query)
