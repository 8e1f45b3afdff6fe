"""The branches of a xacro model, read from its source (lxml, never evaluated): every
``<xacro:if>``/``<xacro:unless>``, every include and YAML path built from an arg, and the values
the files themselves offer each arg (booleans both ways, the literals it is compared with, the
files and folders that exist where a path built from it points).

:func:`analyse` reads the files; :func:`candidates` proposes the arg assignments that should
take the branches the default args leave out. Whether a branch is taken is never decided here:
the sandboxed workers expand each variant and say which conditions kept their body
(``ModelReport.branches``); :mod:`urdf_lint.run.explore` compares. Nothing here evaluates an
expression of a repository: the texts are matched with regular expressions.
"""
from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from typing import Any, Iterable, Iterator

_XACRO = "xacro"   # (namespaces vary: http://www.ros.org/wiki/xacro, http://wiki.ros.org/xacro)
_ARG = r"""['"]?\$\(\s*arg\s+([A-Za-z_][\w-]*)\s*\)['"]?"""
_NAME = r"""\b([A-Za-z_]\w*)\b"""
_REF = rf"(?:{_ARG}|{_NAME})"
_LIT = r"""(?:(['"])([^'"]*)\{q}|(-?\d+(?:\.\d+)?))"""
_ARG_RE = re.compile(r"\$\(\s*arg\s+([A-Za-z_][\w-]*)\s*\)")
_WORD_RE = re.compile(r"\b[A-Za-z_]\w*\b")
_CMP_RE = re.compile(_REF + r"\s*(==|!=)\s*" + _LIT.format(q="4"))
_CMP_REV_RE = re.compile(_LIT.format(q="1") + r"\s*(==|!=)\s*" + _REF)
_IN_RE = re.compile(_REF + r"\s+(not\s+in|in)\s*[\[(]([^\])]*)[\])]")
_STR_RE = re.compile(r"""(['"])([^'"]*)\1""")
_YAML_RE = re.compile(r"""load_yaml\(\s*(['"])([^'"]*)\1""")
_PATH_SUFFIXES = (".yaml", ".yml", ".xacro", ".urdf")
BOOLS = ("true", "false")
_FALSY = ("false", "0", "False", "")
_TRUTHY = ("true", "1", "True")


@dataclass
class Cond:
    """One ``<xacro:if>``/``<xacro:unless>`` of the source."""
    file: str
    line: int
    col: int
    kind: str                        # "if" or "unless"
    text: str                        # its value, as written
    args: tuple[str, ...] = ()       # the args it reads ($(arg X), or a property set from one)
    compared: dict[str, list[str]] = field(default_factory=dict)   # arg -> literals, == / in
    negated: dict[str, list[str]] = field(default_factory=dict)    # arg -> literals, != / not in
    bare: str | None = None          # the value is one arg: $(arg X) or ${X}
    parent: tuple[Any, ...] | None = None      # the enclosing condition (file, line, col), if any
    in_macro: bool = False

    @property
    def key(self) -> tuple[Any, ...]:
        return (self.file, self.line, self.col)

    @property
    def constant(self) -> bool | None:
        """The value when it is a constant (no expression, no substitution), else None."""
        t = self.text.strip()
        if "$" in t:
            return None
        if t in _FALSY:
            return False
        if t in _TRUTHY:
            return True
        return None


@dataclass
class Choice:
    """A path built from an arg (an include's filename, a YAML file): one branch per value of
    the arg whose file exists."""
    file: str
    line: int
    kind: str                        # "include" or "yaml"
    arg: str
    text: str                        # the path as written
    values: dict[str, str] = field(default_factory=dict)   # value -> the path it names


@dataclass
class Analysis:
    """What a model's sources say of its branches: the args' defaults, the conditions and the
    paths built from an arg (:func:`analyse`), and the files read."""
    defaults: dict[str, str] = field(default_factory=dict)      # arg -> default (as written)
    conds: list[Cond] = field(default_factory=list)
    choices: list[Choice] = field(default_factory=list)
    files: list[str] = field(default_factory=list)

    def values(self, listed: dict[str, list[str]] | None = None) -> dict[str, list[str]]:
        """arg -> the values worth trying, the default excluded: booleans both ways, the
        compared literals, the values a path choice offers, the listed ones."""
        out: dict[str, dict[str, None]] = {}

        def add(a: str, v: str, listed: bool = False) -> None:
            # (the empty string only when listed: `arm_id == ''` checks for "unset", and an
            # empty name makes a degenerate robot, not a branch)
            if v != self.defaults.get(a) and "$" not in v and (v or listed):
                out.setdefault(a, {})[v] = None
        for c in self.conds:
            for a in c.args:
                if c.bare == a or self.defaults.get(a, "").lower() in BOOLS:
                    for v in BOOLS:
                        if self.defaults.get(a, "").lower() != v:
                            add(a, v)
            for a, lits in [*c.compared.items(), *c.negated.items()]:
                for v in lits:
                    add(a, v)
        for ch in self.choices:
            for v in ch.values:
                add(ch.arg, v)
        for a, vs in (listed or {}).items():
            for v in vs:
                add(a, v, listed=True)
        return {a: list(v) for a, v in out.items()}


_TOKENS = (b":if", b":unless", b"$(arg", b":arg")


Parsed = dict[str, tuple[bytes | None, Any]]   # a run's sources: file -> (bytes, root)
_UNPARSED = object()


def _parse(f: str, resolver: Any, tokens: tuple[bytes, ...] = _TOKENS,
           memo: Parsed | None = None) -> Any:
    """The root of a source that can hold anything the caller reads (``tokens``: the bytes
    that say so: a condition, an arg, a value built from one for :func:`analyse`; a
    ``load_yaml`` or a property for :func:`yaml_sources`), read once through the boundary;
    None for a file without these bytes (not parsed: a cached run of a robot with no branches
    needs no lxml) or one that does not parse. ``memo``: what one run has read and parsed
    already (the models of a run share their macro files, and both readers read them: each
    file is read and parsed once; the roots are only read)."""
    data, root = (memo or {}).get(f, (None, _UNPARSED))
    if data is None and root is _UNPARSED:
        from urdf_lint.core import fsbound
        try:
            data = fsbound.read_bytes(f, resolver.roots if resolver is not None else None,
                                      resolved=True)
        except (OSError, ValueError):
            root = None
        if memo is not None:
            memo[f] = (data, root)
    if data is None or not any(t in data for t in tokens):
        return None
    if root is _UNPARSED:
        from lxml import etree
        from urdf_lint.core import fsbound
        try:
            root = etree.fromstring(data, etree.XMLParser(
                resolve_entities=False, no_network=True, load_dtd=False),
                base_url=fsbound.xml_base_url(f))
        except etree.XMLSyntaxError:
            root = None
        if memo is not None:
            memo[f] = (data, root)
    return root


def _local(el: Any) -> str | None:
    """The local name of an lxml element in the xacro namespace, else None (``el.tag`` is
    ``{namespace}local``, as ``etree.QName`` reads it; comments and entities have no str tag)."""
    tag = el.tag
    if not isinstance(tag, str) or not tag.startswith("{"):
        return None
    namespace, _, local = tag[1:].partition("}")
    return local if namespace and _XACRO in namespace else None


def analyse(files: Iterable[str], resolver: Any, max_files: int = 200,
            parsed: Parsed | None = None) -> Analysis:
    """The branches of the xacro ``files`` (a model's sources; files an arg-built include may
    name are added and read too, up to ``max_files``; ``parsed``: the run's memo of parsed
    sources, :func:`_parse`)."""
    out = Analysis()
    props: dict[str, set[str]] = {}      # property -> the args its value reads
    todo = [f for f in dict.fromkeys(files) if f.endswith(".xacro")]
    roots = []
    seen: set[str] = set()
    while todo and len(seen) < max_files:
        f = todo.pop(0)
        if f in seen:
            continue
        seen.add(f)
        root = _parse(f, resolver, memo=parsed)
        if root is None:
            continue
        roots.append((f, root))
        for el in root.iter():
            name = _local(el)
            if name == "arg" and el.get("name"):
                out.defaults.setdefault(el.get("name"), el.get("default") or "")
            elif name == "property" and el.get("name"):
                _reads(props, el.get("name"), el.get("value") or el.text or "")
            elif name is not None and name not in _XACRO_TAGS:
                # a macro call: a parameter given an arg (hand="$(arg hand)") reads it
                for k, v in el.attrib.items():
                    _reads(props, k, v)
        for ch in _choices(f, root, out, resolver):
            out.choices.append(ch)
            todo.extend(p for p in ch.values.values()
                        if p.endswith(".xacro") and p not in seen)
    _close(props)
    for f, root in roots:
        out.conds.extend(_conds(f, root, props))
    out.files = [f for f, _ in roots]
    return out


_XACRO_TAGS = {"arg", "property", "macro", "include", "if", "unless", "insert_block",
               "element", "attribute"}


def _reads(props: dict[str, set[str]], name: str, value: str) -> None:
    """``name`` (a property, a macro parameter) is set from ``value``: the args it reads, and
    the properties (to be closed over, :func:`_close`)."""
    got = set(_ARG_RE.findall(value))
    if "${" in value:
        got |= {"$" + w for w in _WORD_RE.findall(re.sub(r"\$\([^)]*\)", "", value))}
    if got:
        props.setdefault(name, set()).update(got)


def _close(props: dict[str, set[str]]) -> None:
    """A name set from another (``$name``) reads that one's args too; then only args stay."""
    for _ in range(6):
        changed = False
        for got in props.values():
            for ref in [g for g in got if g.startswith("$")]:
                more = props.get(ref[1:], set()) - got
                if more:
                    got |= more
                    changed = True
        if not changed:
            break
    for p in list(props):
        props[p] = {g for g in props[p] if not g.startswith("$")}
        if not props[p]:
            del props[p]


def _arg_of(m_arg: str | None, m_name: str | None, props: dict[str, Any]) -> list[str]:
    if m_arg:
        return [m_arg]
    if m_name and m_name in props:
        return sorted(props[m_name])
    return []


def _conds(f: str, root: Any, props: dict[str, Any]) -> list[Cond]:
    out = []
    for el in root.iter():
        kind = _local(el)
        if kind not in ("if", "unless"):
            continue
        text = el.get("value") or ""
        args = set(_ARG_RE.findall(text))
        for w in _WORD_RE.findall(re.sub(r"\$\([^)]*\)", "", text)):
            args |= props.get(w, set())
        c = Cond(f, el.sourceline or 1, 1, kind, text, tuple(sorted(args)))
        _literals(c, text, props)
        bare = re.fullmatch(r"\s*(?:\$\(\s*arg\s+([\w-]+)\s*\)|\$\{\s*([A-Za-z_]\w*)\s*\})\s*",
                            text)
        if bare:
            got = _arg_of(bare.group(1), bare.group(2), props)
            c.bare = got[0] if len(got) == 1 else None
        anc = el.getparent()
        while anc is not None:
            k = _local(anc)
            if k in ("if", "unless") and c.parent is None:
                c.parent = (f, anc.sourceline or 1, 1)
            if k == "macro":
                c.in_macro = True
            anc = anc.getparent()
        out.append(c)
    return out


def _literals(c: Cond, text: str, props: dict[str, Any]) -> None:
    def put(table: dict[str, Any], args: list[str], lit: str | None) -> None:
        for a in args:
            if lit is not None:
                table.setdefault(a, [])
                if lit not in table[a]:
                    table[a].append(lit)
    for m in _CMP_RE.finditer(text):
        lit = m.group(5) if m.group(5) is not None else m.group(6)
        put(c.compared if m.group(3) == "==" else c.negated, _arg_of(m.group(1), m.group(2), props),
            lit)
    for m in _CMP_REV_RE.finditer(text):
        lit = m.group(2) if m.group(2) is not None else m.group(3)
        put(c.compared if m.group(4) == "==" else c.negated, _arg_of(m.group(5), m.group(6), props),
            lit)
    for m in _IN_RE.finditer(text):
        table = c.compared if m.group(3) == "in" else c.negated
        for s in _STR_RE.finditer(m.group(4)):
            put(table, _arg_of(m.group(1), m.group(2), props), s.group(2))


def _path_texts(root: Any) -> Iterator[tuple[Any, str, str]]:
    """(element, kind, text) of every path built from an arg: includes, load_yaml, and arg
    defaults or property values that name a file."""
    for el in root.iter():
        name = _local(el)
        if name == "include" and "$(arg" in (el.get("filename") or ""):
            yield el, "include", el.get("filename")
        values = [v for v in el.attrib.values()] if isinstance(el.tag, str) else []
        for v in values:
            for m in _YAML_RE.finditer(v):
                if "$(arg" in m.group(2):
                    yield el, "yaml", m.group(2)
        if name in ("arg", "property"):
            v = (el.get("default") if name == "arg" else el.get("value")) or ""
            if "$(arg" in v and v.strip().endswith(_PATH_SUFFIXES):
                yield el, "yaml" if v.strip().endswith((".yaml", ".yml")) else "include", v


def _choices(f: str, root: Any, out: Analysis, resolver: Any) -> list[Choice]:
    got = []
    for el, kind, text in _path_texts(root):
        for a in dict.fromkeys(_ARG_RE.findall(text)):
            ch = Choice(f, el.sourceline or 1, kind, a, text)
            ch.values = _existing(text, a, out.defaults, os.path.dirname(f), resolver)
            got.append(ch)
    return got


def _existing(text: str, arg: str, defaults: dict[str, Any], base: str, resolver: Any) -> dict[str, str]:
    """value -> path for each value of ``arg`` whose file exists where ``text`` points (the
    other args at their defaults; other expressions match anything)."""
    from urdf_lint.core import fsbound
    from urdf_lint.discovery.discover import _FIND_RE
    marker = "\0ARG\0"
    t = text.strip()
    for _ in range(3):   # an arg's default may itself read args
        t = _ARG_RE.sub(lambda m: marker if m.group(1) == arg else defaults.get(m.group(1), "*"),
                        t)
    t = re.sub(r"\$\{[^}]*\}|\$\((?!find\s)[^)]*\)", "*", t)
    if resolver is not None:
        try:
            t = _FIND_RE.sub(lambda m: str(resolver.find(m.group(1))), t)
        except Exception:  # noqa: BLE001 - an unknown package: no value is found here
            return {}
    if "$" in t or marker not in t or not t.split(marker)[-1].strip("/"):
        return {}   # (the whole name is the arg's: any entry of the folder would match)
    path = os.path.normpath(os.path.join(base, t))
    pattern = path.replace(marker, "*")
    found = fsbound.bounded_glob(pattern)
    if not found:
        return {}
    rx = re.compile("^" + re.escape(path).replace(re.escape(marker), "([^/]+)")
                    .replace(r"\*", "[^/]*") + "$")
    out: dict[str, str] = {}
    for p in sorted(found):
        m = rx.match(p)
        if m and m.group(1) not in out:
            out[m.group(1)] = os.path.realpath(p)
    return out


def guesses(c: Cond, defaults: dict[str, str], values: dict[str, list[str]]
            ) -> list[dict[str, str]]:
    """The assignments (of this condition's args only) likely to keep its body, best first:
    read from the text, never evaluated (the workers say whether they did)."""
    want = c.kind == "if"
    out: list[dict[str, str]] = []
    if c.bare is not None:
        out.append({c.bare: "true" if want else "false"})
    for a, lits in (c.compared if want else c.negated).items():
        out.extend({a: v} for v in lits)
    for a, lits in (c.negated if want else c.compared).items():
        out.extend({a: v} for v in values.get(a, []) if v not in lits)
    for a in c.args:
        out.extend({a: v} for v in values.get(a, []))
    seen: list[dict[str, str]] = []
    for g in out:
        g = {k: v for k, v in g.items() if v != defaults.get(k)}
        if any(v == "" and v not in values.get(k, ()) for k, v in g.items()):
            continue
        if g and g not in seen:
            seen.append(g)
    return seen


def merged(a: dict[str, Any], b: dict[str, Any]) -> dict[str, Any] | None:
    """``a`` and ``b`` together, or None when they set one arg differently."""
    if any(k in b and b[k] != v for k, v in a.items()):
        return None
    return {**a, **b}


# -- the YAML files a load_yaml reads, resolved from the text ----------------------------------
_YAML_TOKENS = (b"load_yaml", b"property")
_SUBST_RE = re.compile(r"\$\{([^}]*)\}|\$\(([^)]*)\)")     # xacro's ${expr} and $(extension)
_IDENT_RE = re.compile(r"[A-Za-z_]\w*")
_MAX_PATHS = 32      # the values one text may stand for (a property defined in many scopes)
_MAX_DEPTH = 6       # properties set from properties


@dataclass
class YamlSources:
    """What one file says of the YAML it may load: ``load_yaml(...)``'s argument texts and the
    properties it defines (name -> value texts), each with the file."""
    calls: list[tuple[str, str]] = field(default_factory=list)        # (argument, file)
    props: dict[str, list[tuple[str, str]]] = field(default_factory=dict)   # name -> (value, file)


def yaml_sources(f: str, resolver: Any, parsed: Parsed | None = None) -> YamlSources:
    """The ``load_yaml`` calls and the property definitions of the xacro file ``f`` (lxml, read
    through the boundary; nothing evaluated)."""
    out = YamlSources()
    root = _parse(f, resolver, _YAML_TOKENS, parsed) if f.endswith(".xacro") else None
    if root is None:
        return out
    for el in root.iter():
        if not isinstance(el.tag, str):
            continue
        if _local(el) == "property" and el.get("name"):
            value = el.get("value", el.get("default", el.text or ""))
            out.props.setdefault(el.get("name"), []).append((value, f))
        for text in [*el.attrib.values(), el.text or ""]:
            out.calls.extend((arg, f) for arg in _call_args(text, "load_yaml"))
    return out


def yaml_reads(sources: Iterable[YamlSources], resolver: Any) -> set[str]:
    """The YAML files the ``load_yaml`` calls of ``sources`` (a model's files) may read, as far
    as the text alone says: a literal path (``load_yaml('$(find pkg)/a.yaml')``), or a
    property whose value is one (``<xacro:property name="cfg" value="$(find pkg)/a.yaml"/>``
    then ``load_yaml(cfg)``; ``${...}`` joins of literals and such properties too), wherever
    the call stands (a macro, a branch the defaults leave out). A relative path counts from the
    call's file and from the property's. A superset: a property defined twice gives both;
    what only expansion can tell (an arg, a macro parameter) is left out."""
    sources = list(sources)
    props: dict[str, list[tuple[str, str]]] = {}
    for src in sources:
        for name, values in src.props.items():
            props.setdefault(name, []).extend(values)
    out: set[str] = set()
    for src in sources:
        for arg, f in src.calls:
            for path, base in _expr_values(arg, f, props, resolver, _MAX_DEPTH):
                out.update(_absolute(path, {os.path.dirname(f), os.path.dirname(base)}, resolver))
    return out


def _call_args(text: str, func: str) -> list[str]:
    """The argument text of each call of ``func`` in ``text`` (quotes kept, parentheses
    matched outside quotes)."""
    out = []
    start = text.find(func + "(")
    while start >= 0:
        i = start + len(func) + 1
        depth, quote, arg_start = 1, "", i
        while i < len(text) and depth:
            c = text[i]
            if quote:
                quote = "" if c == quote else quote
            elif c in "'\"":
                quote = c
            elif c == "(":
                depth += 1
            elif c == ")":
                depth -= 1
            i += 1
        if depth == 0:
            out.append(text[arg_start:i - 1].strip())
        start = text.find(func + "(", i)
    return out


def _split_plus(expr: str) -> list[str] | None:
    """The terms of ``a + 'b' + c`` (None for anything but literals and names joined by +)."""
    terms, cur, quote = [], "", ""
    for c in expr:
        if quote:
            quote = "" if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c == "+":
            terms.append(cur.strip())
            cur = ""
            continue
        elif c in "()[]{},":
            return None
        cur += c
    terms.append(cur.strip())
    return terms


Values = list[tuple[str, str]]   # (a string the text may evaluate to, the file it was written in)


def _join(a: Values, b: Values) -> Values:
    return [(x + y, fb or fa) for x, fa in a for y, fb in b][:_MAX_PATHS]


def _expr_values(expr: str, f: str, props: dict[str, list[tuple[str, str]]], resolver: Any,
                 depth: int) -> Values:
    """The strings a ``${...}`` expression (or load_yaml's argument) may give: literals and
    properties joined by ``+``; [] when it holds anything else."""
    terms = _split_plus(expr)
    if not terms or depth <= 0:
        return []
    got: Values = [("", "")]
    for t in terms:
        if len(t) >= 2 and t[0] == t[-1] and t[0] in "'\"":
            vals = _text_values(t[1:-1], f, props, resolver, depth)
        elif _IDENT_RE.fullmatch(t):
            vals = [v for value, pf in props.get(t, ())
                    for v in _text_values(value, pf, props, resolver, depth - 1)]
        else:
            return []
        if not vals:
            return []
        got = _join(got, vals)
    return got


def _text_values(text: str, f: str, props: dict[str, list[tuple[str, str]]], resolver: Any,
                 depth: int) -> Values:
    """The strings a xacro text may give: its literal parts, ``$(find pkg)`` and ``${...}``
    (:func:`_expr_values`); [] when another substitution (an arg, an env) is in it."""
    got: Values = [("", f)]
    pos = 0
    for m in _SUBST_RE.finditer(text):
        got = _join(got, [(text[pos:m.start()], f)])
        pos = m.end()
        if m.group(1) is not None:
            vals = _expr_values(m.group(1).strip(), f, props, resolver, depth)
        else:
            ext = m.group(2).split()
            vals = [(p, f) for p in _find(ext, resolver)]
        if not vals:
            return []
        got = _join(got, vals)
    return _join(got, [(text[pos:], f)])


def _find(ext: list[str], resolver: Any) -> list[str]:
    if len(ext) != 2 or ext[0] != "find" or resolver is None:
        return []
    try:
        return [str(resolver.find(ext[1]))]
    except Exception:  # noqa: BLE001 - an unknown package: expansion reports it
        return []


def _absolute(path: str, bases: set[str], resolver: Any) -> set[str]:
    """The files a load_yaml path names: ``package://``, absolute, or relative to one of
    ``bases`` (real paths; the file need not exist: a deleted YAML still re-lints)."""
    path = path.strip()
    if not path or "$" in path:
        return set()
    if path.startswith("package://"):
        pkg, _, rel = path[len("package://"):].partition("/")
        found = _find(["find", pkg], resolver)
        return {os.path.realpath(os.path.join(found[0], rel))} if found else set()
    if path.startswith("file://"):
        path = path[len("file://"):]
    if os.path.isabs(path):
        return {os.path.realpath(path)}
    return {os.path.realpath(os.path.join(b, path)) for b in bases if b}
