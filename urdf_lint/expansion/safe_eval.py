"""A sound allow-list evaluator for xacro's ``${...}`` and ``$(eval ...)`` expressions.

xacro evaluates expressions with Python's ``eval`` and a deny-list; that sandbox was escaped
here. We instead walk the expression's AST and evaluate only what robot descriptions compute.

The invariant (see SECURITY.md, "The evaluator invariant", and tests/test_evaluator_invariant.py)
------------------------------------------------------------------------------------------------
Every object an expression can hold is one of:

* a **value**: ``str``, numbers, ``bool``, ``None``, ``list``/``tuple``/``dict``/``set``/
  ``frozenset``/``range``/``slice`` and xacro's YAML wrappers (plus the iterators the allowed
  builtins return, which expose nothing: attribute access and indexing on them are refused);
* a **namespace** (``xacro.Table``), read through a read-only view: its mutating dict methods are
  not reachable, so one model cannot change what the next model in the same worker sees;
* an **allowed callable**, which is exactly one of
  - an entry of :data:`ALLOWED` (a fixed table of builtins, ``math`` functions and xacro's
    helpers, held by strong reference and compared by identity, so an address is never reused),
  - a :class:`SafeCallable` (a marker type that only this module creates: allow-listed methods of
    values, ``str.format`` with the safe formatter, the ``$(eval)`` helpers),
  - a :class:`_Lambda` written in the expression itself (its body is evaluated by this walker).

Every call site checks its callee **and every callable among its arguments** against that set,
so higher-order builtins (``map``, ``filter``, ``sorted``, ``min``, ``max``, ``list.sort``, ``key=``,
xacro's deprecation wrappers) can only ever call allowed callables. ``type``, ``vars`` and the
other introspection builtins are removed from xacro's namespaces when the hooks are installed,
so they are not reachable at all; attribute names starting with ``_`` are never looked up.
Sizes are capped (huge powers, repetitions, shifts and loops are refused).
"""
from __future__ import annotations

import ast
import functools
import math
import operator
import string
from contextlib import contextmanager
from typing import Any, Callable, Iterator, Mapping, Sequence, Union, cast

from urdf_lint.expansion import traced


class UnsafeExpression(Exception):
    pass


_MAX_POW_BITS = 1 << 16        # refuse integer powers whose result exceeds ~65k bits
_MAX_SEQ = 10_000_000          # refuse building strings/lists longer than this
_MAX_STEPS = 2_000_000         # evaluation steps per expression (loops, comprehensions)

_STR_METHODS = frozenset({
    "capitalize", "casefold", "center", "count", "endswith", "expandtabs", "find", "format",
    "index", "isalnum", "isalpha", "isascii", "isdecimal", "isdigit", "isidentifier", "islower",
    "isnumeric", "isspace", "istitle", "isupper", "join", "ljust", "lower", "lstrip",
    "partition", "removeprefix", "removesuffix", "replace", "rfind", "rindex", "rjust",
    "rpartition", "rsplit", "rstrip", "split", "splitlines", "startswith", "strip", "swapcase",
    "title", "upper", "zfill"})
_LIST_METHODS = frozenset({"append", "clear", "copy", "count", "extend", "index", "insert",
                           "pop", "remove", "reverse", "sort"})
_DICT_METHODS = frozenset({"clear", "copy", "get", "items", "keys", "pop", "setdefault",
                           "update", "values"})
# namespaces are shared by every model a worker expands: only reading is allowed
_NAMESPACE_METHODS = frozenset({"copy", "get", "items", "keys", "values"})
_SET_METHODS = frozenset({"add", "copy", "difference", "discard", "intersection", "isdisjoint",
                          "issubset", "issuperset", "pop", "remove", "symmetric_difference",
                          "union", "update"})
_TUPLE_METHODS = frozenset({"count", "index"})
_NUM_ATTRS = frozenset({"real", "imag", "conjugate", "is_integer", "as_integer_ratio",
                        "bit_length", "numerator", "denominator"})

_BIN: dict[type[ast.operator], Callable[[Any, Any], Any]] = {
    ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
    ast.Div: operator.truediv, ast.FloorDiv: operator.floordiv, ast.Mod: operator.mod,
    ast.Pow: operator.pow, ast.LShift: operator.lshift, ast.RShift: operator.rshift,
    ast.BitAnd: operator.and_, ast.BitOr: operator.or_, ast.BitXor: operator.xor}
_UN: dict[type[ast.unaryop], Callable[[Any], Any]] = {
    ast.UAdd: operator.pos, ast.USub: operator.neg, ast.Not: operator.not_,
    ast.Invert: operator.invert}
_CMP: dict[type[ast.cmpop], Callable[[Any, Any], Any]] = {
    ast.Eq: operator.eq, ast.NotEq: operator.ne, ast.Lt: operator.lt, ast.LtE: operator.le,
    ast.Gt: operator.gt, ast.GtE: operator.ge, ast.Is: operator.is_,
    ast.IsNot: operator.is_not, ast.In: lambda a, b: a in b,
    ast.NotIn: lambda a, b: a not in b}

_SAFE_BUILTINS = {
    "abs": abs, "all": all, "any": any, "bool": bool, "chr": chr, "complex": complex,
    "dict": dict, "divmod": divmod, "enumerate": enumerate, "filter": filter, "float": float,
    "frozenset": frozenset, "hash": hash, "int": int, "isinstance": isinstance,
    "issubclass": issubclass, "len": len, "list": list, "map": map, "max": max, "min": min,
    "ord": ord, "pow": pow, "range": range, "repr": repr, "reversed": reversed, "round": round,
    "set": set, "slice": slice, "sorted": sorted, "str": str, "sum": sum, "tuple": tuple,
    "zip": zip,
}
# never reachable from an expression: install_xacro_symbols removes them from xacro's namespaces
DENIED = (type, vars, getattr, setattr, delattr, eval, exec, compile, open, __import__, globals,
          locals, dir, object, super, classmethod, staticmethod, property, memoryview,
          bytearray, breakpoint, input, help, id, iter, next, callable, hasattr)
_DENIED_IDS = frozenset(id(f) for f in DENIED)

# id -> object, held by strong reference so that an id can never be reused by another object
ALLOWED: dict[int, object] = {}


def _allow(obj: object) -> None:
    if id(obj) in _DENIED_IDS:
        raise ValueError(f"{obj!r} may never be allowed")
    ALLOWED[id(obj)] = obj


for _f in _SAFE_BUILTINS.values():
    _allow(_f)
for _k, _f in math.__dict__.items():
    if not _k.startswith("_") and callable(_f):
        _allow(_f)


# the numeric functions whose result is computed from their argument: a YAML value passed
# through one keeps its source (expansion.traced), marked derived unless it is the same number
_NUMERIC_IDS = frozenset([id(float), id(int), id(round), id(abs)] + [
    id(f) for k, f in math.__dict__.items() if not k.startswith("_") and callable(f)])


def _keep_trace(fn: object, args: Sequence[Any], result: Any) -> Any:
    if type(result) not in (float, int):
        return result
    for a in args:
        src = traced.source_of(a)
        if src is not None:
            same = fn in (float, int) and result == a and not src[1]
            return traced.rewrap(result, src[0], not same)
    return result


class SafeCallable:
    """Marks a callable made by this module as callable from expressions.

    Calls through it check their arguments too, so an allowed builtin that calls it (``map``,
    ``sorted``) cannot smuggle a foreign callable in."""
    __slots__ = ("_fn", "_name")

    def __init__(self, fn: Callable[..., Any], name: str) -> None:
        self._fn = fn
        self._name = name

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        _check_args(args, kwargs)
        return self._fn(*args, **kwargs)

    def __repr__(self) -> str:
        return f"<function {self._name}>"


_value_types: tuple[type[Any], ...] = (str, int, float, complex, bool, list, tuple, dict, set, frozenset,
                       range, slice, type(None))
_namespace_types: tuple[type[Any], ...] = ()
_yaml_dict_types: tuple[type[Any], ...] = ()

_policy = {"max_steps": _MAX_STEPS}
_removed: set[str] = set()   # names install_xacro_symbols took out of xacro's namespaces


def is_allowed_callable(fn: object) -> bool:
    return isinstance(fn, (SafeCallable, _Lambda)) or ALLOWED.get(id(fn)) is fn


def _check_args(args: Sequence[Any], kwargs: Mapping[str, Any]) -> None:
    for a in args:
        if callable(a) and not is_allowed_callable(a):
            raise UnsafeExpression(f"passing {_name_of(a)} to a function is not allowed")
    for a in kwargs.values():
        if callable(a) and not is_allowed_callable(a):
            raise UnsafeExpression(f"passing {_name_of(a)} to a function is not allowed")


def _name_of(fn: object) -> str:
    n = getattr(fn, "__name__", None)
    return n if isinstance(n, str) else type(fn).__name__


@contextmanager
def policy(p: object) -> Iterator[None]:
    """Evaluate with ``p`` (``{"max_steps": n}``; None: the defaults) for the time of the block."""
    saved = dict(_policy)
    if p:
        _policy.update(cast("Mapping[str, int]", p))
    try:
        yield
    finally:
        _policy.clear()
        _policy.update(saved)


def install_xacro_symbols(global_symbols: dict[str, Any]) -> None:
    """Make xacro's expression namespaces safe: drop the introspection builtins xacro exposes
    (``python.type``, ``python.vars``) and allow everything callable that remains, by identity."""
    global _namespace_types, _yaml_dict_types, _value_types
    import xacro
    _namespace_types = (xacro.Table,)
    _yaml_dict_types = (xacro.YamlDictWrapper,)
    if xacro.YamlListWrapper not in _value_types:
        _value_types = _value_types + (xacro.YamlListWrapper, xacro.YamlDictWrapper)

    def walk(d: dict[str, Any]) -> None:
        for k, v in list(dict.items(d)):
            if isinstance(v, xacro.Table):
                walk(v)
            elif id(v) in _DENIED_IDS:
                dict.__delitem__(d, k)
                _removed.add(k)
            elif callable(v):
                _allow(v)
    walk(global_symbols)
    _allow(xacro.YamlDictWrapper)


class _SafeFormatter(string.Formatter):
    def get_field(self, field_name: str, args: Sequence[Any],
                  kwargs: Mapping[str, Any]) -> Any:
        for part in field_name.replace("[", ".").split("."):
            if part.startswith("_"):
                raise UnsafeExpression(f"format field '{field_name}' is not allowed")
        obj, used = super().get_field(field_name, args, kwargs)
        if not isinstance(obj, _value_types + _namespace_types):
            raise UnsafeExpression(f"format field '{field_name}' reaches a non-value object")
        return obj, used


_FORMATTER = _SafeFormatter()


def _safe_format(s: str) -> SafeCallable:
    return SafeCallable(functools.partial(_FORMATTER.format, s), "str.format")


class _Lambda:
    __slots__ = ("node", "ev", "scope")

    def __init__(self, node: ast.Lambda, ev: Evaluator, scope: _Scope) -> None:
        self.node, self.ev, self.scope = node, ev, scope

    def __call__(self, *args: Any) -> Any:
        params = [a.arg for a in self.node.args.args]
        if len(args) != len(params):
            raise TypeError(f"lambda takes {len(params)} arguments ({len(args)} given)")
        return self.ev.eval(self.node.body, dict(zip(params, args, strict=True)), parent=self.scope)


class _Scope:
    __slots__ = ("vars", "parent")

    def __init__(self, vars: dict[str, Any], parent: _Scope | None) -> None:
        self.vars, self.parent = vars, parent


def _method(obj: object, a: str) -> SafeCallable:
    return SafeCallable(getattr(obj, a), f"{type(obj).__name__}.{a}")


def _gate(value: Any, what: str) -> Any:
    """Whatever an expression reads (a name, an attribute, an item) must be a value, a namespace
    or an allowed callable; anything else is refused before it can be used."""
    if callable(value) and not is_allowed_callable(value):
        raise UnsafeExpression(f"{what} is not available in xacro expressions")
    return value


# the comprehension nodes (:meth:`Evaluator._ev_comprehension`)
_Comprehension = Union[ast.ListComp, ast.SetComp, ast.GeneratorExp, ast.DictComp]


class Evaluator:
    def __init__(self, lookup: Callable[[str], Any]) -> None:
        self.lookup = lookup  # name -> value, raises KeyError
        self.steps = 0

    def tick(self) -> None:
        self.steps += 1
        if self.steps > _policy["max_steps"]:
            raise UnsafeExpression("expression too expensive (evaluation step limit reached)")

    def name(self, n: str, scope: _Scope | None) -> Any:
        while scope is not None:
            if n in scope.vars:
                return scope.vars[n]
            scope = scope.parent
        if n.startswith("__"):
            raise UnsafeExpression(f"use of invalid name '{n}'")
        try:
            value = self.lookup(n)
        except KeyError:
            raise NameError(f"name '{n}' is not defined") from None
        return _gate(value, f"'{n}'")

    def eval(self, node: ast.expr, vars: dict[str, Any] | None = None,
             parent: _Scope | None = None) -> Any:
        return self._ev(node, _Scope(vars or {}, parent))

    # -- attribute / call gates --------------------------------------------------------------
    def attr(self, obj: Any, a: str) -> Any:
        if a.startswith("_"):
            raise UnsafeExpression(f"access to attribute '{a}' is not allowed")
        if _namespace_types and isinstance(obj, _namespace_types):
            if a in _NAMESPACE_METHODS:
                return _method(obj, a)
            if a in _DICT_METHODS:
                raise UnsafeExpression(f"namespaces are read-only ('{a}' is not allowed)")
            try:
                return _gate(obj[a], f"'{a}'")
            except KeyError:
                if a in _removed:
                    raise UnsafeExpression(f"'{a}' is not available in xacro expressions "
                                           "(urdf-lint refuses introspection builtins)") from None
                raise NameError(f"name '{a}' is not defined") from None
        if _yaml_dict_types and isinstance(obj, _yaml_dict_types):
            if a in _DICT_METHODS:
                return _method(obj, a)
            return _gate(obj[a], f"'{a}'")
        if isinstance(obj, str) and a in _STR_METHODS:
            if a == "format":
                return _safe_format(obj)
            return _method(obj, a)
        if isinstance(obj, list) and a in _LIST_METHODS:
            return _method(obj, a)
        if isinstance(obj, dict) and a in _DICT_METHODS:
            return _method(obj, a)
        if isinstance(obj, (set, frozenset)) and a in _SET_METHODS:
            return _method(obj, a)
        if isinstance(obj, tuple) and a in _TUPLE_METHODS:
            return _method(obj, a)
        if isinstance(obj, (int, float, complex)) and a in _NUM_ATTRS:
            v = getattr(obj, a)
            return SafeCallable(v, f"{type(obj).__name__}.{a}") if callable(v) else v
        raise UnsafeExpression(f"attribute '{a}' of a {type(obj).__name__} value is not allowed")

    def call(self, fn: Any, args: Sequence[Any], kwargs: Mapping[str, Any]) -> Any:
        if not is_allowed_callable(fn):
            raise UnsafeExpression(f"calling {_name_of(fn)} is not allowed")
        _check_args(args, kwargs)
        if fn is range or fn is list or fn is tuple or fn is set:
            result: Any = fn(*args, **kwargs)
            if fn is not range and len(result) > _MAX_SEQ:
                raise UnsafeExpression("sequence too large")
            return result
        if id(fn) in _NUMERIC_IDS and args:   # radians(v['j1']): the result keeps v's YAML line
            return _keep_trace(fn, args, fn(*args, **kwargs))
        return fn(*args, **kwargs)

    def binop(self, op: type[ast.operator], a: Any, b: Any) -> Any:
        if op is ast.Pow and isinstance(a, int) and isinstance(b, int) and not isinstance(a, bool):
            if b > 0 and abs(a) > 1 and a.bit_length() * b > _MAX_POW_BITS:
                raise UnsafeExpression(f"integer power too large ({a}**{b})")
        if op is ast.Mult:
            for s, n in ((a, b), (b, a)):
                if isinstance(s, (str, list, tuple, bytes)) and isinstance(n, int) \
                        and len(s) * n > _MAX_SEQ:
                    raise UnsafeExpression("repetition too large")
        if op is ast.LShift and isinstance(b, int) and b > _MAX_POW_BITS:
            raise UnsafeExpression("shift too large")
        if op is ast.Mod and isinstance(a, str):
            return a % b  # %-formatting only looks keys up, it cannot reach attributes
        return _BIN[op](a, b)

    # -- the walk ----------------------------------------------------------------------------
    def _ev(self, n: ast.expr, sc: _Scope) -> Any:
        """Evaluate node ``n``: one handler per allowed node type (``_NODES``, matched by exact
        type); any other node is refused."""
        self.tick()
        t = type(n)
        if t is ast.Constant:       # the commonest nodes skip the table lookup
            return n.value   # type: ignore[attr-defined]  # t is type(n): an ast.Constant
        if t is ast.Name:
            return self.name(n.id, sc)   # type: ignore[attr-defined]  # an ast.Name
        handler = _NODES.get(t)
        if handler is None:
            raise UnsafeExpression(f"{t.__name__} is not allowed in xacro expressions")
        return handler(self, n, sc)

    def _ev_binop(self, n: ast.BinOp, sc: _Scope) -> Any:
        return self.binop(type(n.op), self._ev(n.left, sc), self._ev(n.right, sc))

    def _ev_unaryop(self, n: ast.UnaryOp, sc: _Scope) -> Any:
        return _UN[type(n.op)](self._ev(n.operand, sc))

    def _ev_boolop(self, n: ast.BoolOp, sc: _Scope) -> Any:
        if isinstance(n.op, ast.And):
            v = True
            for x in n.values:
                v = self._ev(x, sc)
                if not v:
                    return v
            return v
        v = False
        for x in n.values:
            v = self._ev(x, sc)
            if v:
                return v
        return v

    def _ev_compare(self, n: ast.Compare, sc: _Scope) -> bool:
        left = self._ev(n.left, sc)
        for op, c in zip(n.ops, n.comparators, strict=True):
            right = self._ev(c, sc)
            if not _CMP[type(op)](left, right):
                return False
            left = right
        return True

    def _ev_ifexp(self, n: ast.IfExp, sc: _Scope) -> Any:
        return self._ev(n.body, sc) if self._ev(n.test, sc) else self._ev(n.orelse, sc)

    def _ev_attribute(self, n: ast.Attribute, sc: _Scope) -> Any:
        return self.attr(self._ev(n.value, sc), n.attr)

    def _ev_subscript(self, n: ast.Subscript, sc: _Scope) -> Any:
        obj = self._ev(n.value, sc)
        key = self._ev(n.slice, sc)
        if not isinstance(obj, _value_types + _namespace_types):
            raise UnsafeExpression(f"indexing a {type(obj).__name__} is not allowed")
        if isinstance(obj, _namespace_types) and isinstance(key, str) and key.startswith("_"):
            raise UnsafeExpression(f"access to '{key}' is not allowed")
        return _gate(obj[key], "that item")

    def _ev_slice(self, n: ast.Slice, sc: _Scope) -> slice:
        return slice(*(self._ev(x, sc) if x is not None else None
                       for x in (n.lower, n.upper, n.step)))

    def _ev_call(self, n: ast.Call, sc: _Scope) -> Any:
        fn = self._ev(n.func, sc)
        args = self._items(n.args, sc)
        kwargs: dict[str, Any] = {}
        for k in n.keywords:
            if k.arg is None:
                kwargs.update(self._ev(k.value, sc))
            else:
                kwargs[k.arg] = self._ev(k.value, sc)
        return self.call(fn, args, kwargs)

    def _items(self, nodes: Sequence[ast.expr], sc: _Scope) -> list[Any]:
        """The values of ``nodes`` (call arguments, display elements), ``*x`` spread in."""
        items: list[Any] = []
        for e in nodes:
            if isinstance(e, ast.Starred):
                items.extend(self._ev(e.value, sc))
            else:
                items.append(self._ev(e, sc))
        return items

    def _ev_list(self, n: ast.List, sc: _Scope) -> list[Any]:
        return self._items(n.elts, sc)

    def _ev_tuple(self, n: ast.Tuple, sc: _Scope) -> tuple[Any, ...]:
        return tuple(self._items(n.elts, sc))

    def _ev_set(self, n: ast.Set, sc: _Scope) -> set[Any]:
        return set(self._items(n.elts, sc))

    def _ev_dict(self, n: ast.Dict, sc: _Scope) -> dict[Any, Any]:
        d: dict[Any, Any] = {}
        for k, v in zip(n.keys, n.values, strict=True):
            if k is None:
                d.update(self._ev(v, sc))
            else:
                d[self._ev(k, sc)] = self._ev(v, sc)
        return d

    def _ev_comprehension(self, n: _Comprehension, sc: _Scope) -> Any:
        out: list[Any] = []
        self._comp(n.generators, 0, _Scope({}, sc), n, out)
        return _COMPREHENSIONS[type(n)](out)

    def _ev_joinedstr(self, n: ast.JoinedStr, sc: _Scope) -> str:
        parts: list[Any] = []
        for v in n.values:
            parts.append(v.value if isinstance(v, ast.Constant) else self._ev(v, sc))
        return "".join(parts)

    def _ev_formattedvalue(self, n: ast.FormattedValue, sc: _Scope) -> str:
        v = self._ev(n.value, sc)
        if n.conversion == ord("r"):
            v = repr(v)
        elif n.conversion == ord("s"):
            v = str(v)
        elif n.conversion == ord("a"):
            v = ascii(v)
        spec = self._ev(n.format_spec, sc) if n.format_spec is not None else ""
        return format(v, spec)

    def _ev_lambda(self, n: ast.Lambda, sc: _Scope) -> _Lambda:
        a = n.args
        if a.vararg or a.kwarg or a.kwonlyargs or a.defaults or a.posonlyargs:
            raise UnsafeExpression("only simple lambdas are supported")
        return _Lambda(n, self, sc)

    def _comp(self, gens: Sequence[ast.comprehension], i: int, sc: _Scope,
              node: _Comprehension, out: list[Any]) -> None:
        if i == len(gens):
            self.tick()
            if isinstance(node, ast.DictComp):
                out.append((self._ev(node.key, sc), self._ev(node.value, sc)))
            else:
                out.append(self._ev(node.elt, sc))
            if len(out) > _MAX_SEQ:
                raise UnsafeExpression("comprehension too large")
            return
        g = gens[i]
        for item in self._ev(g.iter, sc):
            self.tick()
            inner = _Scope({}, sc)
            self._assign(g.target, item, inner)
            if all(self._ev(c, inner) for c in g.ifs):
                self._comp(gens, i + 1, inner, node, out)

    def _assign(self, target: ast.expr, value: Any, sc: _Scope) -> None:
        if isinstance(target, ast.Name):
            sc.vars[target.id] = value
        elif isinstance(target, (ast.Tuple, ast.List)):
            values = list(value)
            if len(values) != len(target.elts):
                raise ValueError("cannot unpack")
            for t, v in zip(target.elts, values, strict=True):
                self._assign(t, v, sc)
        else:
            raise UnsafeExpression("unsupported comprehension target")


# the node types an expression may contain (besides Constant and Name, which _ev handles
# first), each with its handler; a node of any other type is refused
_NODES: dict[type[ast.expr], Callable[[Evaluator, Any, _Scope], Any]] = {
    ast.BinOp: Evaluator._ev_binop, ast.UnaryOp: Evaluator._ev_unaryop,
    ast.BoolOp: Evaluator._ev_boolop, ast.Compare: Evaluator._ev_compare,
    ast.IfExp: Evaluator._ev_ifexp, ast.Attribute: Evaluator._ev_attribute,
    ast.Subscript: Evaluator._ev_subscript, ast.Slice: Evaluator._ev_slice,
    ast.Call: Evaluator._ev_call, ast.List: Evaluator._ev_list, ast.Tuple: Evaluator._ev_tuple,
    ast.Set: Evaluator._ev_set, ast.Dict: Evaluator._ev_dict,
    ast.ListComp: Evaluator._ev_comprehension, ast.SetComp: Evaluator._ev_comprehension,
    ast.GeneratorExp: Evaluator._ev_comprehension, ast.DictComp: Evaluator._ev_comprehension,
    ast.JoinedStr: Evaluator._ev_joinedstr, ast.FormattedValue: Evaluator._ev_formattedvalue,
    ast.Lambda: Evaluator._ev_lambda,
}
# what each comprehension builds from its items (a generator expression: an iterator over them)
_COMPREHENSIONS: dict[type[ast.expr], Callable[[list[Any]], Any]] = {
    ast.ListComp: lambda out: out, ast.SetComp: set, ast.DictComp: dict, ast.GeneratorExp: iter}


@functools.lru_cache(maxsize=8192)
def _parse(expr: str) -> ast.expr:
    """Expressions repeat (every macro call evaluates its body again); the AST is read-only."""
    return ast.parse(expr.strip(), mode="eval").body


def evaluate(expr: str, lookup: Callable[[str], Any]) -> Any:
    return Evaluator(lookup).eval(_parse(expr))


def xacro_safe_eval(expr: str, globals: Any, locals: Any = None) -> Any:
    """Drop-in for ``xacro.safe_eval``: names resolve through xacro's symbol Table."""
    if locals is not None:
        def lookup(name: str) -> Any:
            try:
                return locals[name]
            except KeyError:
                return globals[name]
    else:
        lookup = globals.__getitem__
    return evaluate(expr, lookup)


def substitution_eval(s: str, context: dict[str, Any]) -> str:
    """Drop-in for ``xacro.substitution_args._eval`` (``$(eval ...)``)."""
    from xacro import substitution_args as sa
    if "arg" not in context:
        context["arg"] = {}

    functions = {
        "arg": SafeCallable(lambda name: sa.convert_value(sa._eval_arg(name, args=context["arg"]),
                                                          "auto"), "arg"),
        "dirname": SafeCallable(lambda: sa._eval_dirname(context["filename"]), "dirname"),
    }
    for k, v in sa._eval_dict.items():
        if k.startswith("_"):
            continue
        if callable(v) and not is_allowed_callable(v):
            v = SafeCallable(v, k)  # find/env/optenv: our hooks
        functions[k] = v

    def lookup(name: str) -> Any:
        if name in functions:
            return functions[name]
        if name in context["arg"]:
            return sa.convert_value(context["arg"][name], "auto")
        if name in _SAFE_BUILTINS:
            return _SAFE_BUILTINS[name]
        raise KeyError(name)

    if s.find("__") >= 0:
        raise sa.SubstitutionException("$(eval ...) may not contain double underscore expressions")
    return str(evaluate(s, lookup))
