"""Fixes written back into the xacro source.

A rule that knows the right value yields ``(element, message, request)``, where the request
(:func:`set_attrs`) says which attributes of the *expanded* element should get which values.
:func:`resolve` (run where the model is, in the worker) turns it into a :class:`Fix`: byte
edits of the literal that produced each value, found from the element's origin by tokenising
the start tag in the raw source (:mod:`urdf_lint.fix.sourceedit`):

* a literal in the element itself is edited in place;
* ``${name}`` inside a macro, where the innermost call passes ``name=...``: the call's argument;
* ``${name}`` naming a ``xacro:property`` defined exactly once in the files the model read;
* ``${var['key']...}`` / ``${var.key}`` where ``var`` is a property set by ``load_yaml('f')``:
  the YAML scalar;
* anything else (an expression, ``$(arg)``, a property defined twice) is refused with "not
  fixable automatically: the value comes from the expression at FILE:LINE".

Each kind of fix (``set`` and the structural ones) is a class in :mod:`urdf_lint.fix.kinds`,
one file per kind: its edits, its expected result and its request function. The run then
checks that a fix is right for every model and arg set that uses the edited line
(:mod:`urdf_lint.run.fix`).
"""
from __future__ import annotations

import functools
import os
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from urdf_lint.core.edits import NOT_FIXABLE as NOT_FIXABLE, Edit, Fix
from urdf_lint.fix.request import Request as Request
from urdf_lint.fix.sourceedit import (Attr, StartTag, iter_start_tags, line_col,
                                      start_tag_at)

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.core.locations import Origin
    from urdf_lint.engine.model import Model

Element = Any   # an lxml element (lxml ships no type information here)

_REF = re.compile(r"\$\{\s*([A-Za-z_]\w*)\s*\}")
_YAML_REF = re.compile(r"\$\{\s*([A-Za-z_]\w*)((?:\s*\[\s*(?:'[^']*'|\"[^\"]*\"|\d+)\s*\]"
                       r"|\.[A-Za-z_]\w*)+)\s*\}")
_KEY = re.compile(r"\[\s*(?:'([^']*)'|\"([^\"]*)\"|(\d+))\s*\]|\.([A-Za-z_]\w*)")
_LOAD_YAML = re.compile(r"\$\{\s*(?:xacro\.)?load_yaml\(\s*(?:'([^']*)'|\"([^\"]*)\")\s*\)\s*\}")


def names_in_scope(model: "Model") -> set[str]:
    """The xacro property and macro parameter names defined in the files the model read."""
    src = _Sources(model)
    out: set[str] = set()
    for path in src.xacro_files():
        try:
            d = src.get(path)
        except (OSError, Refuse):
            continue
        for t in iter_start_tags(d, "property"):
            n = t.attr("name")
            if n is not None:
                out.add(n.value)
        for t in iter_start_tags(d, "macro"):
            p = t.attr("params")
            for par in (p.value.split() if p is not None else ()):
                out.add(par.lstrip("*").split(":=")[0].split("=")[0].lstrip("^"))
    return out


class Refuse(Exception):
    """A fix that cannot be made automatically; the message says why."""



class _Sources:
    """The raw bytes of the files a model read (nothing else is read)."""

    def __init__(self, model: "Model") -> None:
        self.allowed = {os.path.realpath(p) for p in list(model.deps) + [model.entry]}
        self.data: dict[str, bytes] = {}

    def get(self, path: str) -> bytes:
        from urdf_lint.core.tree import real_path
        real = real_path(path)     # (asked per value located: remembered within the job)
        if real not in self.allowed:
            raise Refuse(f"{NOT_FIXABLE}: {where(path)} was not read by the model")
        if real not in self.data:
            from urdf_lint.core import fsbound
            self.data[real] = fsbound.read_bytes(real)
        return self.data[real]

    def xacro_files(self) -> list[str]:
        return [p for p in sorted(self.allowed) if p.endswith((".xacro", ".urdf", ".xml"))]


def where(path: str, line: int | None = None) -> str:
    from urdf_lint.core.locations import display_path
    return f"{display_path(path)}:{line}" if line else display_path(path)


def _expression(path: str, data: bytes, off: int) -> Refuse:
    return Refuse(f"{NOT_FIXABLE}: the value comes from the expression at "
                   f"{where(path, line_col(data, off)[0])}")


def resolve(model: "Model", el: Element, req: Request, src: _Sources | None = None) -> Fix:
    """The :class:`Fix` of ``req`` on ``el`` (refused, with the reason, when it cannot be
    located or traced to one literal)."""
    src = src or _Sources(model)
    if req.on_parent:
        el = el.getparent()
    origin = model.origins.get(el)
    try:
        if origin is None:
            raise Refuse(f"{NOT_FIXABLE}: the element has no source location")
        data = src.get(origin.file)
        tag = start_tag_at(data, origin.line, origin.col)
        if tag is None or tag.name.rpartition(":")[2] != el.tag:
            raise Refuse(f"{NOT_FIXABLE}: <{el.tag}> not found at "
                          f"{where(origin.file, origin.line)}")
        from urdf_lint.fix.kinds import Site, kind
        try:
            k = kind(req.kind)
        except KeyError:
            raise Refuse(f"{NOT_FIXABLE}: unknown fix kind {req.kind!r}") from None
        edits = k.resolve(Site(model, el, origin, data, tag, req, src))
        return Fix(req.description, req.safe, tuple(edits), "", ())
    except Refuse as r:
        return Fix(req.description, req.safe, (), str(r))
    except (OSError, UnicodeDecodeError, ValueError) as e:
        return Fix(req.description, req.safe, (), f"{NOT_FIXABLE}: {e}")


def written(tag: StartTag, name: str, origin: "Origin") -> Attr:
    """The attribute ``name`` of the start tag at ``origin`` (refused when not written there)."""
    a = tag.attr(name)
    if a is None:
        raise Refuse(f"{NOT_FIXABLE}: {name}= is not written at "
                      f"{where(origin.file, origin.line)}")
    return a


def same_value(literal: str, expanded: str | None) -> bool:
    if expanded is None:
        return False
    if literal.strip() == expanded.strip():
        return True
    a, b = literal.split(), expanded.split()
    try:
        return len(a) == len(b) and all(float(x) == float(y) for x, y in zip(a, b, strict=True))
    except ValueError:
        return False


def trace(src: _Sources, file: str, data: bytes, a: Attr, chain: tuple[Any, ...],
          depth: int) -> tuple[str, "Attr | YamlScalar"]:
    """(file, the literal Attr or YAML scalar) that produced attribute ``a``."""
    v = a.value
    if "$" not in v:
        return file, a
    if depth > 8:
        raise _expression(file, data, a.value_start)
    m = _REF.fullmatch(v.strip())
    if m:
        name = m.group(1)
        if chain:   # a macro parameter passed by the innermost call
            cfile, cline, ccol = chain[-1][:3]
            cdata = src.get(cfile)
            call = start_tag_at(cdata, cline, ccol)
            if call is not None:
                p = call.attr(name)
                if p is not None:
                    return trace(src, cfile, cdata, p, chain[:-1], depth + 1)
        return _property(src, name, file, data, a, depth)
    m = _YAML_REF.fullmatch(v.strip())
    while m and chain:   # ${cfg['lower']} in a macro whose call passes cfg="${yaml['arm']}"
        cfile, cline, ccol = chain[-1][:3]
        cdata = src.get(cfile)
        call = start_tag_at(cdata, cline, ccol)
        p = call.attr(m.group(1)) if call is not None else None
        if p is None:    # not passed by the call: a property (as for ${name} above)
            break
        inner = re.fullmatch(r"\$\{(.*)\}", p.value.strip(), re.S)
        if inner is None:
            raise _expression(file, data, a.value_start)
        m = _YAML_REF.fullmatch("${" + inner.group(1).strip() + m.group(2) + "}")
        file, data, a, chain = cfile, cdata, p, chain[:-1]
    if m:
        return _yaml_scalar(src, m, file, data, a)
    raise _expression(file, data, a.value_start)


def _property_defs(src: _Sources, name: str) -> list[tuple[str, bytes, StartTag]]:
    out = []
    for path in src.xacro_files():
        d = src.get(path)
        if name.encode() not in d:
            continue
        for t in iter_start_tags(d, "property"):
            n = t.attr("name")
            if n is not None and n.value == name:
                out.append((path, d, t))
    return out


def _property(src: _Sources, name: str, file: str, data: bytes, a: Attr,
              depth: int) -> tuple[str, "Attr | YamlScalar"]:
    defs = _property_defs(src, name)
    if len(defs) != 1:
        if not defs:
            raise _expression(file, data, a.value_start)
        places = ", ".join(where(p, line_col(d, t.start)[0]) for p, d, t in defs)
        raise Refuse(f"{NOT_FIXABLE}: the value comes from the expression at "
                     f"{where(file, line_col(data, a.value_start)[0])} (property '{name}' "
                     f"is defined {len(defs)} times: {places})")
    path, d, t = defs[0]
    val = t.attr("value")
    if val is None:
        raise Refuse(f"{NOT_FIXABLE}: property '{name}' at {where(path, line_col(d, t.start)[0])}"
                      " has no value= literal")
    return trace(src, path, d, val, (), depth + 1)


@dataclass(frozen=True)
class YamlScalar:
    """A scalar value in a YAML file, with its span in the text (the value's own text, after a
    tag), its quoting style and its tag (``!degrees``: one of xacro's units, else "")."""
    value: str
    value_start: int
    value_end: int
    style: str          # "" (plain), "'" or '"'
    tag: str = ""


@functools.lru_cache(maxsize=None)
def _units() -> dict[str, float]:
    """xacro's YAML units, tag -> factor (``xacro.ConstructUnits``: the expansion reads a
    scalar tagged so as ``float(value) * factor``)."""
    import xacro
    return {u.value.tag: u.value.conversion_constant for u in xacro.ConstructUnits}


def _scalar(node: Any, text: str) -> "YamlScalar":
    """The :class:`YamlScalar` of a PyYAML scalar node of ``text`` (byte offsets; PyYAML's
    marks count characters; a node's span starts at its tag: the value's text follows it)."""
    start, end = node.start_mark.index, node.end_mark.index
    tag = node.tag if node.tag.startswith("!") and node.tag in _units() else ""
    if tag and text.startswith(tag, start):
        start += len(tag)
        while start < end and text[start] in " \t":
            start += 1
    s = len(text[:start].encode("utf-8"))
    e = len(text[:end].encode("utf-8"))
    return YamlScalar(node.value, s, e, node.style or "", tag)


def unit_literal(lit: "YamlScalar", expanded: str | None, new: str) -> str:
    """The text to write in place of a YAML scalar tagged with one of xacro's units
    (``!degrees 370.0``, read as radians) for the expanded value ``new``: the shortest number
    the expansion reads back as exactly ``new``. :class:`Refuse` when the literal is not a
    number giving ``expanded``, or no such number exists."""
    k = _units()[lit.tag]
    try:
        if expanded is None or float(lit.value) * k != float(expanded):
            raise ValueError
        want = float(new)
    except ValueError:
        raise Refuse(f"{NOT_FIXABLE}: the {lit.tag} value {lit.value!r} is not a number giving "
                     f"the expanded value {expanded!r}") from None
    x = want / k
    tries = [f"{x:.{d}f}" for d in range(0, 18)] + [repr(x)] + [f"{x:.{d}g}" for d in range(1, 18)]
    for text in tries:
        if "." in text and "e" not in text:
            text = text.rstrip("0")
            text += "0" if text.endswith(".") else ""
        elif "." in lit.value and not any(c in text for c in ".en"):
            text += ".0"      # (written like the literal it replaces)
        if float(text) * k == want:
            return text
    raise Refuse(f"{NOT_FIXABLE}: no {lit.tag} number gives {new!r} exactly")


def _yaml_scalar(src: _Sources, m: "re.Match[str]", file: str, data: bytes,
                 a: Attr) -> tuple[str, "YamlScalar"]:
    var, keys = m.group(1), [k for k in _KEY.findall(m.group(2))]
    defs = _property_defs(src, var)
    if len(defs) != 1:
        raise _expression(file, data, a.value_start)
    path, d, t = defs[0]
    val = t.attr("value")
    lm = _LOAD_YAML.fullmatch(val.value.strip()) if val is not None else None
    if lm is None or val is None:
        raise _expression(file, data, a.value_start)
    ref = lm.group(1) or lm.group(2)
    fm = re.fullmatch(r"\$\(find [\w-]+\)/(.+)", ref)
    if fm:   # $(find pkg)/rest: the one YAML file the model read that ends with rest
        hits = [p for p in src.allowed if p.endswith("/" + fm.group(1))]
        if len(hits) != 1:
            raise _expression(path, d, val.value_start)
        yaml_path = hits[0]
    elif "$" in ref:
        raise _expression(path, d, val.value_start)
    else:
        yaml_path = os.path.normpath(os.path.join(os.path.dirname(path), ref))
    ydata = src.get(yaml_path)
    path_keys = [k[0] or k[1] or k[3] or (int(k[2]) if k[2] else "") for k in keys]
    node = _yaml_node(ydata, path_keys)
    if node is None:
        raise _expression(file, data, a.value_start)
    return yaml_path, node


def traced_scalar(model: "Model", src: _Sources, el: Element,
                  attr: str) -> tuple[str, "YamlScalar"] | None:
    """(yaml file, :class:`YamlScalar`) of the YAML scalar the expansion read ``attr`` of
    ``el`` from, when it is that scalar's literal value (not computed from it); else None."""
    got = (getattr(model, "value_origins", {}).get(el) or {}).get(attr)
    if not got or got[1]:
        return None
    (file, line, col), _ = got
    if str(file).endswith((".toml", ".xacro", ".urdf")):
        return None      # an arg set in the config or at its <xacro:arg>: not a YAML scalar
    node = _yaml_node_at(src.get(file), line, col)
    return (file, node) if node is not None else None


def _yaml_node_at(ydata: bytes, line: int, col: int) -> "YamlScalar | None":
    """The scalar of a YAML text that starts at 1-based ``line``, ``col``, or None."""
    import yaml
    try:
        text = ydata.decode("utf-8")
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except (yaml.YAMLError, UnicodeDecodeError):
        return None
    stack = [root]
    while stack:
        node = stack.pop()
        if isinstance(node, yaml.ScalarNode):
            m = node.start_mark
            if (m.line + 1, m.column + 1) == (line, col):
                return _scalar(node, text)
        elif isinstance(node, yaml.SequenceNode):
            stack.extend(node.value)
        elif isinstance(node, yaml.MappingNode):
            stack.extend(v for _, v in node.value)
    return None


def _yaml_node(ydata: bytes, keys: list[str | int]) -> "YamlScalar | None":
    import yaml
    try:
        root = yaml.compose(ydata.decode("utf-8"), Loader=yaml.SafeLoader)
    except yaml.YAMLError:
        return None
    node = root
    for k in keys:
        if isinstance(node, yaml.MappingNode):
            node = next((v for kn, v in node.value if kn.value == str(k)), None)
        elif isinstance(node, yaml.SequenceNode) and isinstance(k, int) and k < len(node.value):
            node = node.value[k]
        else:
            return None
        if node is None:
            return None
    if not isinstance(node, yaml.ScalarNode):
        return None
    return _scalar(node, ydata.decode("utf-8"))


def yaml_text(new: str, lit: YamlScalar) -> str:
    if lit.style == "'":
        return "'" + new.replace("'", "''") + "'"
    if lit.style == '"':
        return '"' + new.replace("\\", "\\\\").replace('"', '\\"') + '"'
    return new


class Fixer:
    """Resolves the fix requests of one model (reads each source file once)."""

    def __init__(self, model: Any) -> None:
        self.model = model
        self.src = _Sources(model)
        self._index: dict[Element, int] | None = None
        self._value_from_memo: dict[tuple[Any, ...], tuple[Any, ...]] = {}

    def index(self, el: Element) -> int:
        if self._index is None:
            from lxml import etree
            self._index = {e: i for i, e in enumerate(self.model.root.iter(tag=etree.Element))}
        i: int = self._index[el]
        return i

    def value_from(self, el: Element, attrs: tuple[str, ...] = (),
                   message: str = "") -> tuple[Any, ...]:
        """``(file, line, col)`` of where the value of ``el`` comes from when that is not the
        element's own line: the YAML scalar read by ``load_yaml``, the ``xacro:property`` or the
        macro call's argument that holds the literal. The attributes ``attrs`` (a fix's) are
        traced, else every attribute written with ``$``; the first that leads elsewhere wins.
        ``()`` when the value is written at the element or cannot be traced. A value the
        expansion saw come from a YAML scalar (:mod:`urdf_lint.expansion.traced`: through
        properties, sub-dicts, macro parameters, arithmetic) names that scalar."""
        got = getattr(self.model, "value_origins", {}).get(el)
        if got:
            # the attributes the message names first (``limit velocity=-1.7``), the text last
            named = set(re.findall(r"[A-Za-z_]+", message))
            for name in attrs or sorted(got, key=lambda n: (n not in named, n.startswith("#"), n)):
                if name in got:
                    return tuple(got[name][0])
        origin = self.model.origins.get(el)
        if origin is None:
            return ()
        # one trace per source location (a macro line many links share is traced once)
        key = (origin.file, origin.line, origin.col, tuple(map(tuple, origin.chain)),
               tuple(attrs))
        if key not in self._value_from_memo:
            self._value_from_memo[key] = self._value_from_source(origin, attrs)
        return self._value_from_memo[key]

    def _value_from_source(self, origin: Any, attrs: tuple[str, ...] | list[str]) -> tuple[Any, ...]:
        try:
            data = self.src.get(origin.file)
            tag = start_tag_at(data, origin.line, origin.col)
            if tag is None:
                return ()
            written = [a for a in tag.attrs if "$" in a.value] if not attrs else \
                [a for a in (tag.attr(n) for n in attrs) if a is not None and "$" in a.value]
            for a in written:
                try:
                    file, lit = trace(self.src, origin.file, data, a, tuple(origin.chain), 0)
                except Refuse:
                    continue
                fdata = self.src.get(file)
                line, col = line_col(fdata, lit.value_start)
                here = {(origin.file, origin.line)} | {(c[0], c[1]) for c in origin.chain}
                if isinstance(lit, Attr) and (file, line) in here:
                    continue   # written at the element or at a macro call the chain shows
                return (file, line, col)
        except (Refuse, OSError, UnicodeDecodeError, ValueError):
            return ()
        return ()

    def fix(self, el: Element, req: Request) -> Fix:
        f = resolve(self.model, el, req, self.src)
        if f.refused:
            return f
        from urdf_lint.fix.kinds import kind
        i = self.index(el.getparent() if req.on_parent else el)
        return Fix(f.description, f.safe, f.edits, "", kind(req.kind).expect(req, i))

    def traced(self, req: Request | None) -> tuple[str, ...]:
        """The attributes of a request whose source the finding names (``value_from``)."""
        from urdf_lint.fix.kinds import kinds
        k = kinds().get(req.kind) if req is not None else None
        return k.traced(req) if k is not None and req is not None else ()


_REMOVABLE = re.compile(rb"<!--\s*urdf-lint:\s*(disable-next|disable-file)\b.*?-->", re.S)


def remove_comment(loc: tuple[Any, ...]) -> Fix | None:
    """The fix of an unused ``disable-next`` / ``disable-file`` comment at ``loc`` (file, line,
    col): delete it, with its line when it is alone there (a ``disable`` range is left alone:
    its ``enable`` would dangle)."""
    from urdf_lint.fix.sourceedit import offset_of
    data = _source_bytes(loc[0])
    if data is None:
        return None
    off = offset_of(data, loc[1], loc[2])
    m = _REMOVABLE.match(data, off) if off is not None else None
    if m is None:
        return None
    start, end = m.start(), m.end()
    line_start = data.rfind(b"\n", 0, start) + 1
    nl = data.find(b"\n", end)
    line_end = len(data) if nl < 0 else nl + 1
    if not data[line_start:start].strip() and not data[end:line_end].strip():
        start, end = line_start, line_end        # alone on its line: the whole line goes
    return Fix("remove the unused suppression comment", True, (Edit(loc[0], start, end, ""),),
               "", (("none", 0, "", ""),))


_SOURCE: list[Any] = [None, None]   # ((path, size, mtime), its bytes): one read for all its comments


def _source_bytes(path: str) -> bytes | None:
    """The bytes of ``path``, read once for all the unused comments of one file."""
    try:
        st = os.stat(path)
        key = (path, st.st_size, st.st_mtime_ns)
        if _SOURCE[0] != key:
            from urdf_lint.core import fsbound  # a regular file of bounded size (the boundary)
            _SOURCE[:] = [key, fsbound.read_bytes(path)]
    except OSError:
        return None
    data: bytes = _SOURCE[1]
    return data
