"""Values that remember the YAML line they were read from.

``load_yaml`` returns its scalars as :class:`TracedFloat`, :class:`TracedInt` and
:class:`TracedStr`: subclasses of ``float``, ``int`` and ``str`` that print, compare, hash and
compute exactly as the plain values do (so the expansion stays byte-identical to stock xacro's)
and carry ``ul_from``: ``(file, line, col)`` of the scalar in the YAML file. They travel
through everything xacro does with a value: properties that hold a dict, a sub-dict or the
scalar itself, item and attribute access (``config[name]['limit']``, ``limits.lower``), macro
parameters and their defaults, lists. Arithmetic on a traced number keeps the trace, marked
``ul_derived`` (the value is computed from the YAML scalar, not written there: a fix must not
write it back). When an element's attribute evaluates to a traced value, the expansion records
where it came from (:func:`urdf_lint.expansion.expand` ``Expansion.values``), and a finding on
that attribute names the YAML line (``value from config/joint_limits.yaml:28``).
"""
from __future__ import annotations

from typing import Any, Callable

Loc = tuple[str, int, int]  # (file, line, col), 1-based


class _Traced:
    """What the three traced types share: the source and whether the value was computed."""
    ul_from: Loc | tuple[()] = ()
    ul_derived: bool = False


def _wrap(value: Any, loc: Loc | tuple[()], derived: bool) -> Any:
    if value is NotImplemented or isinstance(value, bool):
        return value
    if type(value) is float:
        out: Any = TracedFloat(value)
    elif type(value) is int:
        out = TracedInt(value)
    else:
        return value
    out.ul_from, out.ul_derived = loc, derived
    return out


def _arith(name: str, base: type) -> Callable[..., Any]:
    op = getattr(base, name)

    def method(self: Any, *other: Any) -> Any:
        return _wrap(op(self, *other), self.ul_from, True)
    method.__name__ = name
    return method


_OPS = ("__add__", "__radd__", "__sub__", "__rsub__", "__mul__", "__rmul__", "__truediv__",
        "__rtruediv__", "__floordiv__", "__rfloordiv__", "__mod__", "__rmod__", "__pow__",
        "__rpow__", "__neg__", "__pos__", "__abs__")


class TracedFloat(float, _Traced):
    """A float read from YAML (prints and computes as the float)."""


class TracedInt(int, _Traced):
    """An int read from YAML (prints and computes as the int)."""


class TracedStr(str, _Traced):
    """A string read from YAML (prints and compares as the string; its methods and
    concatenation give plain strings)."""


for _name in _OPS:
    setattr(TracedFloat, _name, _arith(_name, float))
    setattr(TracedInt, _name, _arith(_name, int))


def traced(value: Any, loc: Loc) -> Any:
    """``value`` (a YAML scalar as constructed) carrying ``loc``, or itself when it is of
    another type (bool, None, a date)."""
    if type(value) is str:
        out = TracedStr(value)
        out.ul_from = loc
        return out
    return _wrap(value, loc, False)


def rewrap(value: Any, loc: Loc, derived: bool) -> Any:
    """``value`` (a number a function computed from a traced one: ``radians(v)``) carrying
    ``loc``; derived unless it is that very number (``float(v)``)."""
    return _wrap(value, loc, derived)


def source_of(value: Any) -> tuple[Loc, bool] | None:
    """``((file, line, col), derived)`` of a traced value, else None."""
    loc = getattr(value, "ul_from", None) if isinstance(value, _Traced) else None
    return (loc, bool(getattr(value, "ul_derived", False))) if loc else None


def load(stream: Any, loader_cls: Any, file: str) -> Any:
    """``yaml.load(stream, Loader=loader_cls)`` with every scalar traced to its line in
    ``file``."""
    loader = loader_cls(stream)
    try:
        node = loader.get_single_node()
        if node is None:
            return None
        data = loader.construct_document(node)
        return _attach(loader, node, data, file)
    finally:
        loader.dispose()


_MERGE = "tag:yaml.org,2002:merge"


def _attach(loader: Any, node: Any, data: Any, file: str) -> Any:
    import yaml
    if isinstance(node, yaml.ScalarNode):
        return traced(data, (file, node.start_mark.line + 1, node.start_mark.column + 1))
    if isinstance(node, yaml.SequenceNode) and isinstance(data, list) and \
            len(node.value) == len(data):
        for i, n in enumerate(node.value):
            data[i] = _attach(loader, n, data[i], file)
    elif isinstance(node, yaml.MappingNode) and isinstance(data, dict):
        for knode, vnode in node.value:
            if not isinstance(knode, yaml.ScalarNode) or knode.tag == _MERGE:
                continue
            try:
                key = loader.construct_object(knode)
                if key in data:
                    data[key] = _attach(loader, vnode, data[key], file)
            except (yaml.YAMLError, TypeError):   # an unhashable or odd key: left untraced
                continue
    return data
