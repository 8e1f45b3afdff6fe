"""xacro expansion without ROS that knows where every output element came from.

We run the real (pinned) xacro and hook a handful of its module globals, all looked up at
call time:

* ``parse`` parses every file with an expat builder that stamps each element with
  ``(file, line, col)`` through minidom user data (invisible to xacro, survives ``cloneNode``);
  it also resolves ``package://`` includes, confines reads to the package roots and refuses
  entity declarations;
* ``handle_macro_call`` / ``grab_macro`` give the elements cloned out of a macro body the
  call chain that produced them;
* ``eval_all`` and friends track the innermost element being evaluated, so that errors point
  at a source line;
* ``$(find)``, ``$(env)``, ``$(optenv)``, ``load_yaml`` and expression evaluation are routed
  through our resolver and policies (see :mod:`urdf_lint.expansion.safe_eval`).

What one expansion collects and tracks is an :class:`ExpansionState`, made by
:func:`expand_file` and passed down; xacro calls the hooks with its own arguments only, so they
reach it through one holder, :data:`CURRENT`, set and reset around the expansion.

The output text is exactly ``doc.toprettyxml(indent='  ')``, i.e. what the xacro CLI writes.
"""
from __future__ import annotations

import io
import os
import re
import sys
import xml.dom
import xml.parsers.expat
from collections import OrderedDict
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from typing import Any, cast
from xml.dom import expatbuilder, minidom

import xacro
import xacro.substitution_args as _subst

from urdf_lint.core import fsbound
from urdf_lint.core.jobs import DEFAULT_ENV_ALLOW
from urdf_lint.core.findings import Problem
from urdf_lint.discovery.packages import PackageResolver
from urdf_lint.expansion import safe_eval
from urdf_lint.core.hashing import read_recorded
from urdf_lint.core.codes import RuleName
from urdf_lint.expansion import clone, splice, traced
from urdf_lint.expansion.errors import RefusedInput, XmlSyntaxError, problem_for
from urdf_lint.expansion.sourcemap import KEY, SourceMap

# the rules raised here, by name (urdf_lint.core.codes: no rule module is imported)
ul007_doctype = RuleName("ul007_doctype")
ul008_xacro_warning = RuleName("ul008_xacro_warning")
ul013_description_error = RuleName("ul013_description_error")
ul014_unreachable_branch = RuleName("ul014_unreachable_branch")
ul901_env_read = RuleName("ul901_env_read")
ul902_outside_roots = RuleName("ul902_outside_roots")


@dataclass
class Expansion:
    """The result of expanding one entry file (plain data: it pickles)."""
    entry: str
    args: dict[str, Any]
    xml: str | None = None
    origins: SourceMap = field(default_factory=SourceMap)   # per output element, document order
    deps: list[str] = field(default_factory=list)  # files read (absolute), entry first
    error: Problem | None = None                  # why it failed (see expansion.errors)
    notes: list[Problem] = field(default_factory=list)  # Problems that did not stop the expansion
    missing: list[str] = field(default_factory=list)  # files looked for and not found
    # file -> [stat before read, digest of bytes read]
    digests: dict[str, list[Any]] = field(default_factory=dict)
    # per output element (document order, as ``origins``): {attribute: ((file, line, col),
    # derived)} for the attributes whose value came from a YAML scalar (expansion.traced)
    values: tuple[dict[str, Any] | None, ...] = ()
    # the variables $(optenv) looked up that are not allow-listed -> whether each was set (the
    # result holds while that stays so: run/cache.py)
    env: dict[str, bool] = field(default_factory=dict)
    # every <xacro:if>/<xacro:unless> evaluated: [file, line, col, kept] (kept: its body was
    # expanded), one per source element and outcome (urdf_lint.run.explore: branch coverage)
    branches: list[list[Any]] = field(default_factory=list)


# ---------------------------------------------------------------------------------------------
# per-expansion state
# (file, line, col, chain) of an element; a chain is ((file, line, col), ...) of macro calls
Origin4 = tuple[str, int, int, tuple[Any, ...]]
# the user data stamped on an element: its Origin4 and whether it is in a macro body
Stamp = tuple[str, int, int, tuple[Any, ...], bool]


class ExpansionState:
    """What one expansion collects (files read, their digests, notes) and tracks (the
    elements being evaluated, the chain of macro calls and includes), for :func:`expand_file`."""

    def __init__(self, resolver: PackageResolver, env_allow: Iterable[str],
                 expr_policy: object = None, env_set: Iterable[str] | None = None) -> None:
        self.resolver = resolver
        self.env_allow = set(env_allow)
        # the names of the variables set where urdf-lint runs (never their values; a worker's
        # own environment is scrubbed, so the parent tells it): None, this process's
        self.env_set = set(os.environ if env_set is None else env_set)
        self.env: dict[str, bool] = {}             # Expansion.env
        self.env_noted: set[tuple[str, str]] = set()   # (file, variable) warned about
        self.deps: dict[str, None] = {}
        self.digests: dict[str, list[Any]] = {}
        self.notes: list[Problem] = []
        self.stack: list[Any] = []     # nodes being evaluated (eval_all / macro calls)
        self.touched: Any = None       # a child node being handled inline by its parent
        self.pending_chain: tuple[Any, ...] = ()  # chain to give to the macro body being cloned
        self.include_chain: tuple[Any, ...] = ()  # chain of the include element being processed
        self.expr_policy = expr_policy
        # expansion.traced: the text -> source of the values eval_text gave in each eval_all
        # being run (innermost last), and per element the attributes that came from YAML
        self.value_frames: list[dict[str, Any]] = []
        self.values: dict[Any, dict[str, Any]] = {}
        # where each arg got its value when no one passed it: its first <xacro:arg default>
        # (file, line, col); the args passed (a [[models]] entry, the command line) are known
        self.arg_origins: dict[str, tuple[Any, ...]] = {}
        self.passed_args: set[str] = set()
        self.passed_origins: dict[str, tuple[Any, ...]] = {}
        # the <xacro:if>/<xacro:unless> whose value xacro checks now, and every outcome seen:
        # (file, line, col, kept)
        self.pending_cond: Any = None
        self.branches: dict[tuple[str, int, int, bool], None] = {}

    def current_node(self) -> Any:
        if self.touched is not None:
            return self.touched
        return self.stack[-1] if self.stack else None

    def note(self, rule: Any, message: str, node: Any = None, loc: Origin4 | None = None,
             severity: str = "") -> None:
        """A problem that does not stop the expansion, reported as ``rule.CODE`` (at
        ``severity`` when given, else the rule's)."""
        if loc is None:
            loc = origin_of(node if node is not None else self.current_node())
        self.notes.append(Problem.at(rule.CODE, message, loc, severity=severity))


# The expansion xacro's hooks serve. xacro calls them as module-level functions with its own
# arguments only, so they find the state here: :func:`_session` sets it for the time of one
# expansion and resets it after. Outside one it is None: the hooks that may run then (the
# parser, the clone handler, ``abs_filename``, ``warning``) do what xacro does; the others
# refuse (:func:`_active`). A context variable, not a module global: another thread never
# sees this one's expansion.
CURRENT: ContextVar[ExpansionState | None] = ContextVar("urdf_lint_expansion", default=None)


def _active() -> ExpansionState:
    """The expansion a hook serves (the hooks xacro calls only while processing a file)."""
    st = CURRENT.get()
    if st is None:
        raise RuntimeError("an xacro hook of urdf-lint ran outside an expansion")
    return st


def origin_of(node: Any) -> Origin4:
    """(file, line, col, chain) of a minidom node, or of its nearest stamped ancestor."""
    while node is not None:
        if node.nodeType == xml.dom.Node.ELEMENT_NODE:
            data: Stamp | None = node.getUserData(KEY)
            if data is not None:
                return data[:4]
        node = node.parentNode
    top = xacro.filestack[0] if xacro.filestack else ""
    return (os.path.abspath(top) if top else "", 1, 1, ())


class _CloneHandler:
    """Copies the origin to clones; a macro body being instantiated gets the call chain."""

    def handle(self, operation: int, key: str, data: Stamp, src: Any, dst: Any) -> None:
        if operation == xml.dom.UserDataHandler.NODE_CLONED and dst is not None:
            dst.setUserData(key, self.cloned(data), self)

    def cloned(self, data: Stamp) -> Stamp:
        """The stamp of a clone of a node stamped ``data`` (also :func:`clone.clone_tree`'s)."""
        file, line, col, chain, template = data
        if template:
            st = CURRENT.get()
            if st is not None:
                chain = st.pending_chain
        return (file, line, col, chain, False)


_HANDLER = _CloneHandler()


class _LocatingBuilder(expatbuilder.ExpatBuilderNS):
    _parser: Any   # expat's parser (ExpatBuilder.createParser; not in the typeshed stubs)

    def __init__(self, file: str, chain: tuple[Any, ...]) -> None:
        super().__init__()
        self._file = file
        self._chain = chain

    def install(self, parser: Any) -> None:
        super().install(parser)
        parser.EntityDeclHandler = self._refuse_entity
        parser.StartDoctypeDeclHandler = self._doctype
        try:
            parser.SetParamEntityParsing(xml.parsers.expat.XML_PARAM_ENTITY_PARSING_NEVER)
        except Exception:  # pragma: no cover - very old expat
            pass

    def _refuse_entity(self, name: str, *args: Any) -> None:
        p = self._parser
        raise RefusedInput(f"XML entity declaration '{name}' refused (entities can read files "
                           f"or blow up memory)", ul007_doctype,
                           (self._file, p.CurrentLineNumber, p.CurrentColumnNumber + 1, self._chain))

    def _doctype(self, name: str, system_id: str | None, public_id: str | None,
                 has_subset: bool) -> None:
        p = self._parser
        st = CURRENT.get()
        if st is not None:
            st.note(ul007_doctype, f"DOCTYPE declaration '<!DOCTYPE {name}>' in a robot description; "
                    "remove it (URDF needs none, and urdf-lint never loads DTDs)",
                    loc=(self._file, p.CurrentLineNumber, p.CurrentColumnNumber + 1, self._chain))
        if system_id or public_id:
            raise RefusedInput(f"DOCTYPE with an external DTD ('{system_id or public_id}') refused",
                               ul007_doctype, (self._file, p.CurrentLineNumber,
                                         p.CurrentColumnNumber + 1, self._chain))
        return super().start_doctype_decl_handler(name, system_id, public_id, has_subset)

    def start_element_handler(self, name: str, attributes: Any) -> None:
        super().start_element_handler(name, attributes)
        p = self._parser
        self.curNode.setUserData(KEY, (self._file, p.CurrentLineNumber,
                                       p.CurrentColumnNumber + 1, self._chain, False), _HANDLER)


def parse_bytes(data: bytes, file: str, chain: tuple[Any, ...] = ()) -> Any:
    builder = _LocatingBuilder(file, chain)
    try:
        return builder.parseString(data)
    except xml.parsers.expat.ExpatError as e:
        msg = xml.parsers.expat.ErrorString(e.code)
        raise XmlSyntaxError(f"XML syntax error: {msg}", file, e.lineno, e.offset + 1,
                             chain) from None


# A file a worker parses again and again (UR's ur_macro.xacro for each of its ten models, a
# shared materials file in every model of a package) is parsed the first two times; from the
# third on it is copied from the second parse (clone.copy_document: 0.5 ms for UR's macro
# file against 1.2 ms to parse it), its stamps given the including chain of the moment.
# Kept by path and content digest, the least recently used dropped first beyond PARSED_BYTES
# (a kept document weighs its source's bytes, or NODE_WEIGHT per node when more: a DOM takes
# ~25 times its source, and ~120 times a file of tiny elements; UR's whole description is
# 0.1 MB); a document with a DOCTYPE (its parse notes UL007) is parsed every time.
PARSE_CACHE = True          # (False: every file parsed, for tests)
PARSED_BYTES = 1 << 20      # (~25 MB of DOM at most: a fifth of the least memory-mb)
# (path, digest) -> None once parsed, then (weight, the document kept from the second parse)
_parsed: "OrderedDict[tuple[str, str], tuple[int, Any] | None]" = OrderedDict()


def parsed(data: bytes, file: str, chain: tuple[Any, ...], digest: str) -> Any:
    """:func:`parse_bytes` of a file's ``data``, or a copy of an earlier parse of the same
    bytes with its stamps' including chain set to ``chain``."""
    if not PARSE_CACHE:
        return parse_bytes(data, file, chain)
    key = (file, digest)
    kept = _parsed.get(key)
    if kept is not None:
        _parsed.move_to_end(key)
        return clone.copy_document(kept[1], lambda d: (d[0], d[1], d[2], chain, d[4]))
    doc = parse_bytes(data, file, chain)
    if key not in _parsed:
        _parsed[key] = None
    elif doc.doctype is None and doc.documentElement is not None \
            and clone.usable(doc.documentElement):
        # (weighed by its nodes too: a file of tiny elements, ``<a/>``, takes ~120 bytes of
        # DOM per byte of source, not ~25; one heavier than the whole bound is never copied)
        weight = max(len(data), NODE_WEIGHT * _count_nodes(doc))
        if weight > PARSED_BYTES:
            return doc
        _parsed[key] = (weight, clone.copy_document(doc, lambda d: d))
        _parsed.move_to_end(key)      # (the newest: evicted last)
        total = sum(v[0] for v in _parsed.values() if v is not None)
        while total > PARSED_BYTES:
            old = _parsed.popitem(last=False)[1]
            total -= old[0] if old is not None else 0
    if len(_parsed) > MAX_PARSED_KEYS:
        _parsed.popitem(last=False)
    return doc


MAX_PARSED_KEYS = 4096
NODE_WEIGHT = 20   # source bytes a DOM node counts as (~500 bytes of DOM, at ~25 per byte)


def _count_nodes(doc: Any) -> int:
    """The nodes of a document (elements, their attributes, texts, comments)."""
    n, todo = 0, [doc]
    while todo:
        node = todo.pop()
        n += 1 + (len(node.attributes) if node.attributes else 0)
        todo.extend(node.childNodes)
    return n


# ---------------------------------------------------------------------------------------------
# hooks
_orig: dict[str, Any] = {}


def _hook_parse(inp: Any, filename: str | None = None) -> Any:
    if inp is None:
        path = os.path.join(xacro.root_dir, cast(str, filename))   # xacro passes one with inp None
        absolute = os.path.abspath(path)
        st = CURRENT.get()
        chain = st.include_chain if st else ()
        if st is not None and not st.resolver.is_inside(absolute):
            xacro.filestack.pop()
            raise RefusedInput(f"include '{filename}' resolves outside the package roots and the "
                               "linted repository; it was not read", ul902_outside_roots)
        try:
            data, record = read_recorded(path)   # (an overlay's bytes: core.overlay)
        except (IOError, OSError) as e:
            xacro.filestack.pop()
            raise xacro.XacroException((e.strerror or str(e)) + ": " + str(e.filename), exc=e) from e
        if st is not None:
            st.deps[absolute] = None
            st.digests[absolute] = record   # what was read, for the cache
        return parsed(data, absolute, chain, record[1])
    if isinstance(inp, str):
        return parse_bytes(inp.encode("utf-8"), "<string>")
    if hasattr(inp, "read"):
        data = inp.read()
        return parse_bytes(data.encode("utf-8") if isinstance(data, str) else data, "<stream>")
    return inp


def _hook_abs_filename_spec(filename_spec: Any) -> str:
    spec = str(filename_spec)
    st = CURRENT.get()
    if spec.startswith("package://") and st is not None:
        spec = str(st.resolver.find(spec[len("package://"):].partition("/")[0]) /
                   spec[len("package://"):].partition("/")[2])
    if spec.startswith("file://"):
        spec = spec[len("file://"):]
    path: str = _orig["abs_filename_spec"](spec)
    if st is not None and not any(c in path for c in "*?["):
        # a path the package's build installs from another folder of its source tree
        mapped, via = st.resolver.installed(path)
        if via is not None:
            st.deps[via] = None
            return mapped
    return path


TEXT_KEY = "#text"   # Expansion.values: the source of an element's text, beside its attributes


def _hook_eval_all(node: Any, macros: Any, symbols: Any) -> None:
    st = _active()
    st.stack.append(node)
    st.touched = None
    attrs = list(node.attributes.items()) if node.attributes else []
    # the element's own text (``<param name="initial_value">${ip['joint_1']}</param>``) is
    # evaluated in this frame too: noted as ``#text``
    texts = [c.data for c in node.childNodes
             if c.nodeType == c.TEXT_NODE and "$" in c.data] if node.childNodes else []
    frame: dict[str, Any] = {}
    st.value_frames.append(frame)
    _orig["eval_all"](node, macros, symbols)
    st.value_frames.pop()
    if frame:
        got = {name: frame[text] for name, text in attrs if text in frame}
        for text in texts:
            if text in frame:
                got.setdefault(TEXT_KEY, frame[text])
        if got:
            st.values[node] = got
    st.stack.pop()
    st.touched = None


def _hook_eval_text(text: str, symbols: Any) -> Any:
    """xacro's ``eval_text``; a result read from YAML (:mod:`.traced`) is noted for the element
    whose ``eval_all`` runs (its attributes are evaluated first, so the first note of a text
    is the attribute's)."""
    if type(text) is str and "$" not in text:
        # what xacro's lexer returns for plain text (one TEXT token: the text itself), without
        # lexing it: most attribute values and texts of a robot hold no expression
        return text
    result = _orig["eval_text"](text, symbols)
    st = CURRENT.get()
    if type(result) is str and "$(arg" in text and st is not None:
        # a value that is one arg, at its default: it comes from the <xacro:arg> line
        m = _ARG_ONLY.fullmatch(text.strip())
        name = m.group(1) if m else None
        origin = (st.passed_origins.get(name) if name in st.passed_args
                  else st.arg_origins.get(name)) if name else None
        if origin is not None:
            result = traced.traced(result, origin)
    src = traced.source_of(result)
    if src is not None and st is not None and st.value_frames:
        st.value_frames[-1].setdefault(text, src)
    return result


_ARG_ONLY = re.compile(r"\$\(arg\s+([^\s()]+)\s*\)")


def _hook_handle_macro_call(node: Any, macros: Any, symbols: Any) -> Any:
    st = _active()
    if node.tagName != "xacro:call" and not node.tagName.startswith("xacro:"):
        return False
    st.stack.append(node)
    st.touched = None
    saved = st.pending_chain
    file, line, col, chain = origin_of(node)
    st.pending_chain = tuple(chain) + ((file, line, col),)
    try:
        result = _orig["handle_macro_call"](node, macros, symbols)
    except KeyError as e:  # xacro lets some lookups escape as KeyError
        raise xacro.XacroException("unknown macro or namespace: %s" % e) from None
    st.pending_chain = saved
    st.stack.pop()
    st.touched = None
    return result


def _mark_template(elt: Any) -> None:
    stack = [elt]
    while stack:
        n = stack.pop()
        if n.nodeType == xml.dom.Node.ELEMENT_NODE:
            data = n.getUserData(KEY)
            if data is not None and not data[4]:
                n.setUserData(KEY, data[:4] + (True,), _HANDLER)
            stack.extend(n.childNodes)


FAST_CLONE = True    # macro bodies cloned by clone.clone_tree (False: by minidom, for tests)


def _hook_grab_macro(elt: Any, macros: Any) -> None:
    st = _active()
    st.touched = elt
    _mark_template(elt)
    _orig["grab_macro"](elt, macros)
    if type(elt) is minidom.Element and FAST_CLONE and clone.usable(elt):
        elt.__class__ = clone.MacroBody     # xacro clones it at every call: the fast clone
    st.touched = None


def _hook_grab_property(elt: Any, table: Any) -> None:
    st = _active()
    st.touched = elt
    _orig["grab_property"](elt, table)
    st.touched = None


def _hook_process_include(elt: Any, macros: Any, symbols: Any, func: Any) -> None:
    st = _active()
    st.touched = elt
    saved = st.include_chain
    st.include_chain = origin_of(elt)[3]
    _orig["process_include"](elt, macros, symbols, func)
    st.include_chain = saved
    st.touched = None


def _hook_check_attrs(tag: Any, required: Any, optional: Any) -> Any:
    st = _active()
    st.touched = tag
    if getattr(tag, "tagName", "") == "xacro:arg" and tag.hasAttribute("name"):
        # (xacro keeps an arg's first value: a later <xacro:arg> of the name changes nothing)
        st.arg_origins.setdefault(tag.getAttribute("name"), tuple(origin_of(tag)[:3]))
    st.pending_cond = tag if getattr(tag, "tagName", "") in _CONDS else None
    return _orig["check_attrs"](tag, required, optional)


_CONDS = ("xacro:if", "xacro:unless")


def _hook_get_boolean_value(value: Any, condition: Any) -> Any:
    """xacro's ``get_boolean_value``; for the condition of the ``<xacro:if>``/``<xacro:unless>``
    being handled (:func:`_hook_check_attrs` saw it), the outcome is recorded: whether its body
    is kept (branch coverage, :mod:`urdf_lint.run.explore`)."""
    result = _orig["get_boolean_value"](value, condition)
    st = CURRENT.get()
    node = st.pending_cond if st is not None else None
    if st is not None and node is not None and condition is not None and \
            node.getAttribute("value") == condition:
        st.pending_cond = None
        f, line, col = origin_of(node)[:3]
        kept = bool(result) != (node.tagName == "xacro:unless")
        if not kept and (f, line, col, kept) not in st.branches and \
                _CONSTANT.fullmatch(condition):
            st.note(ul014_unreachable_branch,
                    f"<{node.tagName} value=\"{condition.strip()}\">: a constant, so its "
                    "body is never expanded (no arg reaches it); delete it, or make it depend "
                    "on an arg", loc=origin_of(node))
        st.branches[(f, line, col, kept)] = None
    return result


# a condition that is a literal (true/false/1/0, bare or as ${...}): the same in every variant
_CONSTANT = re.compile(r"\s*(?:true|false|True|False|[01]|\$\{\s*(?:True|False|true|false|[01])"
                       r"\s*\})\s*")


def _hook_reqd_attrs(tag: Any, attrs: Any) -> Any:
    _active().touched = tag
    return _orig["reqd_attrs"](tag, attrs)


def _hook_load_yaml(filename: Any) -> Any:
    st = _active()
    path = os.path.abspath(xacro.abs_filename_spec(filename))
    if not st.resolver.is_inside(path):
        raise RefusedInput(f"load_yaml('{filename}') resolves outside the package roots and the "
                           "linted repository; it was not read", ul902_outside_roots)
    st.deps[path] = None
    loader = _yaml_loader()
    if loader is None:
        return _orig["load_yaml"](path)
    # what xacro.load_yaml does, with libyaml's parser (3-5x faster than PyYAML's pure-Python
    # one; UR's descriptions read eight YAML files per model): the same SafeConstructor, the
    # same unit tags, the same wrapper, include bookkeeping and errors
    filename = xacro.abs_filename_spec(path)
    # read through the boundary: a regular file, bounded (a FIFO never blocks); the stream
    # keeps the file's name for YAML's error marks, and open()'s newline translation
    f = io.StringIO(fsbound.read_text(filename), newline=None)
    f.name = filename
    xacro.filestack.append(filename)
    try:
        return xacro.YamlListWrapper.wrap(traced.load(f, loader, filename))
    finally:
        xacro.filestack.pop()
        xacro.all_includes.append(filename)


_YAML_LOADER: list[Any] = []


def _yaml_loader() -> Any:
    """A SafeLoader on libyaml (``yaml.CSafeLoader``) with xacro's unit constructors
    (``!degrees``, ``!millimeters``, ...), or None when PyYAML was built without libyaml."""
    if not _YAML_LOADER:
        import yaml
        cls: Any = None
        if getattr(yaml, "__with_libyaml__", False):
            cls = type("XacroCSafeLoader", (yaml.CSafeLoader,), {})
            for unit in xacro.ConstructUnits:
                cls.add_constructor(unit.value.tag, unit.constructor)
        _YAML_LOADER.append(cls)
    return _YAML_LOADER[0]




def _hook_eval_find(pkg: str) -> str:
    return str(_active().resolver.find(pkg))


def _hook_eval_env(name: str) -> Any:
    st = _active()
    if name in st.env_allow:
        return _orig["eval_env"](name)
    st.note(ul901_env_read, f"$(env {name}) reads an environment variable that is not in "
            f"'env-allow'; the value was not substituted (add it to env-allow if it is safe)")
    return ""


def _hook_eval_optenv(name: str, default: Any = "") -> Any:
    """An allow-listed variable is read; another one never is: its default is used, which is
    what xacro makes where the variable is unset (nothing to say), and differs from it where it
    is set (a warning, once per file and variable)."""
    st = _active()
    if name in st.env_allow:
        return _orig["eval_optenv"](name, default)
    is_set = st.env[name] = name in st.env_set
    if is_set:
        loc = origin_of(st.current_node())
        if (loc[0], name) not in st.env_noted:
            st.env_noted.add((loc[0], name))
            st.note(ul901_env_read, f"$(optenv {name}) reads an environment variable that is set "
                    "here but not in 'env-allow': its default was used, so the output differs "
                    "from xacro's in this environment (add it to env-allow if it is safe to read)",
                    loc=loc, severity="warning")
    return default


def _hook_warning(*args: Any, **kwargs: Any) -> str:
    st = CURRENT.get()
    if st is not None:
        msg = " ".join(str(a) for a in args).strip()
        if msg:
            st.note(ul008_xacro_warning, "xacro: " + msg)
    return ""


def _hook_print_location(*args: Any, **kwargs: Any) -> str:
    return ""


def _said(*args: Any, **kwargs: Any) -> str:
    """What ``${xacro.error(...)}`` and its kin print: their arguments, as xacro joins them."""
    return " ".join(str(a) for a in args).strip()


def _hook_xacro_error(*args: Any, **kwargs: Any) -> str:
    """``${xacro.error(...)}``: stock xacro prints the message (with the location) and goes
    on; here a located error with the message (UL013)."""
    st = CURRENT.get()
    if st is not None:
        st.note(ul013_description_error, "xacro.error: " + (_said(*args) or "(no message)"))
    return ""


def _hook_xacro_warning(*args: Any, **kwargs: Any) -> str:
    """``${xacro.warning(...)}``: a located warning, as xacro's own warnings (UL008)."""
    return _hook_warning(_said(*args))


def _hook_xacro_message(*args: Any, **kwargs: Any) -> str:
    """``${xacro.message(...)}``: xacro prints it; no finding."""
    return ""


def _install_hooks() -> None:
    if _orig:
        return
    for name in ("parse", "abs_filename_spec", "eval_all", "handle_macro_call", "grab_macro",
                 "grab_property", "process_include", "check_attrs", "reqd_attrs", "load_yaml",
                 "warning", "print_location", "safe_eval", "eval_text", "get_boolean_value"):
        _orig[name] = getattr(xacro, name)
    _orig["eval_env"] = _subst._eval_env
    _orig["eval_optenv"] = _subst._eval_optenv
    xacro.parse = _hook_parse
    xacro.abs_filename_spec = _hook_abs_filename_spec
    xacro.eval_all = _hook_eval_all
    xacro.eval_text = _hook_eval_text
    xacro.handle_macro_call = _hook_handle_macro_call
    xacro.grab_macro = _hook_grab_macro
    xacro.grab_property = _hook_grab_property
    xacro.process_include = _hook_process_include
    xacro.check_attrs = _hook_check_attrs
    xacro.get_boolean_value = _hook_get_boolean_value
    xacro.reqd_attrs = _hook_reqd_attrs
    xacro.warning = _hook_warning
    xacro.print_location = _hook_print_location
    xacro.safe_eval = safe_eval.xacro_safe_eval
    _subst._eval_find = _hook_eval_find
    _subst._eval_env = _hook_eval_env
    _subst._eval_optenv = _hook_eval_optenv
    _subst._eval_dict["find"] = _hook_eval_find
    _subst._eval_dict["env"] = _hook_eval_env
    _subst._eval_dict["optenv"] = _hook_eval_optenv
    _subst._eval = safe_eval.substitution_eval
    # the expression namespace captured load_yaml / abs_filename when it was built
    g = xacro._global_symbols
    ns = g["xacro"]
    dict.__setitem__(ns, "load_yaml", _hook_load_yaml)
    dict.__setitem__(ns, "abs_filename", _hook_abs_filename_spec)
    # the description's own messages (xacro wrapped the functions when it built the namespace)
    dict.__setitem__(ns, "error", _hook_xacro_error)
    dict.__setitem__(ns, "warning", _hook_xacro_warning)
    dict.__setitem__(ns, "message", _hook_xacro_message)
    dict.__setitem__(ns, "print_location", _hook_print_location)
    dict.__setitem__(g, "load_yaml", _hook_load_yaml)
    dict.__setitem__(g, "abs_filename", _hook_abs_filename_spec)
    safe_eval.install_xacro_symbols(g)
    splice.install()


@contextmanager
def _session(state: ExpansionState) -> Iterator[ExpansionState]:
    """Run one expansion with ``state``: the hooks installed, :data:`CURRENT` set to it (and
    reset after), xacro's module state fresh and its chatter on stdout/stderr captured."""
    _install_hooks()
    old_stderr, old_stdout = sys.stderr, sys.stdout
    sys.stderr = io.StringIO()
    sys.stdout = io.StringIO()
    token = CURRENT.set(state)
    xacro.all_includes = []
    xacro.verbosity = 1
    xacro.substitution_args_context.clear()
    splice.reset()
    try:
        yield state
    finally:
        splice.reset()
        CURRENT.reset(token)
        sys.stderr, sys.stdout = old_stderr, old_stdout
        xacro.all_includes = []


# ---------------------------------------------------------------------------------------------
def _elements(node: Any, out: list[tuple[Any, ...] | None]) -> list[tuple[Any, ...] | None]:
    for c in node.childNodes:
        if c.nodeType == xml.dom.Node.ELEMENT_NODE:
            data = c.getUserData(KEY)
            out.append(tuple(data[:4]) if data is not None else None)
            _elements(c, out)
    return out


def _element_values(node: Any, values: dict[Any, dict[str, Any]],
                    out: list[dict[str, Any] | None]) -> list[dict[str, Any] | None]:
    """Per output element (document order, as :func:`_elements`): its YAML-sourced
    attributes, or None."""
    for c in node.childNodes:
        if c.nodeType == xml.dom.Node.ELEMENT_NODE:
            out.append(values.get(c))
            _element_values(c, values, out)
    return out


def _macro_context() -> list[str]:
    names: list[str] = []
    for m in reversed(xacro.macrostack or []):
        try:
            names.append(m.body.getAttribute("name"))
        except Exception:
            pass
    return names


def classify_error(e: BaseException, st: ExpansionState, entry: str = "",
                   before: bool = False) -> Problem:
    """Turn an exception from xacro into one located problem (see :mod:`.errors`); one with
    no element to point at is at line 1 of the file on top of xacro's stack, else (nothing
    there, or it happened ``before`` xacro started: the stack is the last job's) of
    ``entry``."""
    here = origin_of(st.current_node()) if st.current_node() is not None else None
    if here is None:
        top = os.path.abspath(xacro.filestack[0]) if xacro.filestack and xacro.filestack[0] else ""
        here = ((entry if before else top or entry), 1, 1, ())
    return problem_for(e, here, _macro_context(), deps=list(st.deps))


def expand_file(path: str, args: dict[str, Any] | None = None, resolver: PackageResolver | None = None,
                env_allow: Iterable[str] = DEFAULT_ENV_ALLOW, display_name: str | None = None,
                expr_policy: object = None, env_set: Iterable[str] | None = None,
                arg_origins: dict[str, tuple[str, int, int]] | None = None) -> Expansion:
    """Expand one xacro (or URDF) file in process. Never raises for bad input. Bytes to read
    instead of a file's (an editor's buffer, a layout ``format`` proves) come from
    :mod:`urdf_lint.core.overlay`, installed around the job by the worker. ``env_set``: the
    names of the environment variables that are set (None: this process's). ``arg_origins``:
    where the config sets each passed arg (a value written as that arg is located there)."""
    path = os.path.abspath(path)
    args = dict(args or {})
    res = Expansion(entry=path, args=dict(args))
    if resolver is None:
        resolver = PackageResolver.build([os.path.dirname(path)], extra_roots=[os.path.dirname(path)])
    st = ExpansionState(resolver, env_allow, expr_policy, env_set)
    with _session(st):
        before = True   # until xacro opens the entry
        try:
            if not resolver.is_inside(path):
                raise RefusedInput(f"'{path}' is outside the package roots", ul902_outside_roots)
            st.passed_args = set(args)
            st.passed_origins = dict(arg_origins or {})
            with safe_eval.policy(expr_policy):
                before = False
                doc = xacro.process_file(display_name or path, mappings=dict(args))
            res.xml = doc.toprettyxml(indent="  ")
            res.origins = SourceMap.from_stamps(_elements(doc, []))
            if st.values:
                res.values = tuple(_element_values(doc, st.values, []))
        except BaseException as e:  # noqa: BLE001 - every failure becomes a diagnostic
            if isinstance(e, (KeyboardInterrupt, SystemExit)) and not isinstance(e, SystemExit):
                raise
            res.error = classify_error(e, st, path, before)
            from urdf_lint.expansion.errors import wrapped
            inner = wrapped(e)   # the innermost error (a missing YAML file is wrapped twice)
            # a file looked for and not there, or a folder read as a file: the result holds
            # until a regular file appears at that path (urdf_lint/run/cache.py)
            if isinstance(inner, OSError) and getattr(inner, "filename", None) and \
                    not os.path.isfile(str(inner.filename)):
                res.missing.append(os.path.abspath(str(inner.filename)))
        res.deps = [path] + [d for d in st.deps if d != path and d not in res.missing]
        res.digests = dict(st.digests)
        res.notes = st.notes
        res.env = dict(st.env)
        res.branches = [list(b) for b in st.branches]
    return res
