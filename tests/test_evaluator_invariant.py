"""The evaluator invariant (SECURITY.md): an expression can only ever hold values, read-only
namespaces and allowed callables, and every call checks its callee and its callable arguments.

Tested by enumeration (every name reachable from xacro's namespaces, every attribute of every
allowed type), by the reproducers of the escape that was found, and by generated expressions
built from the reachable names."""
from __future__ import annotations

import os
import textwrap

import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

import xacro
import xacro.substitution_args as sa

from urdf_lint.expansion import safe_eval
from urdf_lint.expansion import expand
from urdf_lint.discovery.packages import PackageResolver
from urdf_lint.expansion.safe_eval import UnsafeExpression, is_allowed_callable

expand._install_hooks()
G = xacro._global_symbols


def walk_namespace(ns, prefix=""):
    for k, v in dict.items(ns):
        name = f"{prefix}{k}"
        yield name, v
        if isinstance(v, xacro.Table):
            yield from walk_namespace(v, name + ".")


def ev(expr):
    return xacro.safe_eval(expr, xacro.Table(G))


# -- enumeration ------------------------------------------------------------------------------
def test_every_name_reachable_from_the_namespaces_is_a_value_a_namespace_or_allowed():
    names = dict(walk_namespace(G))
    assert "python.list" in names and "math.sin" in names and "xacro.load_yaml" in names
    for name, v in names.items():
        if isinstance(v, xacro.Table):
            continue
        if callable(v):
            assert is_allowed_callable(v), name
        else:
            assert isinstance(v, (bool, int, float, str)), (name, type(v))
    denied_ids = {id(f) for f in safe_eval.DENIED}
    assert not [n for n, v in names.items() if id(v) in denied_ids]
    assert "python.type" not in names and "python.vars" not in names


def test_every_eval_substitution_name_is_allowed():
    ctx = {"arg": {"x": "1"}, "filename": "/tmp/r.xacro"}
    callables = [k for k, v in sa._eval_dict.items() if not k.startswith("_") and callable(v)]
    assert {"find", "env", "optenv", "sin"} <= set(callables)
    for k in callables + ["arg", "dirname"]:
        # reading the name passes the gate: it is allowed or wrapped in the marker type
        assert safe_eval.substitution_eval(f"1 if {k} else 0", ctx) == "1", k
    for bad in ("arg.func", "find.func", "sin.real"):
        with pytest.raises(UnsafeExpression):
            safe_eval.substitution_eval(bad, ctx)


def test_the_allowed_table_holds_its_objects():
    """Ids are compared against a table that keeps its objects alive: an id cannot be reused."""
    for i, obj in safe_eval.ALLOWED.items():
        assert id(obj) == i
    assert not set(safe_eval.ALLOWED) & {id(f) for f in safe_eval.DENIED}


SAMPLES = {
    "str": "ab", "int": 3, "float": 1.5, "complex": 1j, "bool": True, "list": [1, 2],
    "tuple": (1, 2), "dict": {"a": 1}, "set": {1}, "frozenset": frozenset({1}), "range": range(2),
    "none": None, "yaml_dict": xacro.YamlDictWrapper({"a": 1}), "yaml_list": xacro.YamlListWrapper([1]),
    "namespace": G["math"],
}


@pytest.mark.parametrize("kind", sorted(SAMPLES))
def test_every_attribute_of_every_value_type(kind):
    """Each attribute is either refused, or gives a value or a marked callable."""
    obj = SAMPLES[kind]
    e = safe_eval.Evaluator(lambda n: (_ for _ in ()).throw(KeyError(n)))
    allowed = []
    for a in sorted(set(dir(obj)) | {"update", "pop", "clear", "setdefault"}):
        try:
            v = e.attr(obj, a)
        except (UnsafeExpression, NameError, AttributeError):
            continue
        assert not a.startswith("_"), (kind, a)
        if callable(v):
            assert isinstance(v, safe_eval.SafeCallable) or is_allowed_callable(v), (kind, a)
        allowed.append(a)
    if kind == "namespace":
        assert not {"update", "pop", "clear", "setdefault"} & set(allowed)
        assert {"get", "keys", "items", "values", "copy"} <= set(allowed)
    if kind in ("none", "range"):
        assert allowed == []


# -- the escape that was found (issue #15) ----------------------------------------------------
ESCAPES = [
    "python.list(map(python.type, [xacro]))",
    "python.type('X', (python.dict,), {})",
    "python['type']",
    "python.vars(xacro)",
    "sorted([3, 1], key=python.type)",
    "python.sorted([3, 1], key=python.vars)",
    "[3, 1].sort(key=python.type)",
    "max([1], key=python.type)",
    "list(map(python.map, [python.type], [[1]]))",
    "math.update({'pi': 3})",
    "python.update(type=1)",
    "xacro.clear()",
    "math.setdefault('x', 1)",
    "''.__class__",
    "'{0.__class__}'.format(1)",
    "(1).real.__class__",
    "[x for x in python.values() if not python.isinstance(x, python.int)][0].__self__",
]


@pytest.mark.parametrize("expr", ESCAPES)
def test_escape_routes_are_refused(expr):
    with pytest.raises((UnsafeExpression, NameError, KeyError)):
        ev(expr)


def test_methods_cannot_smuggle_a_foreign_callable():
    key = safe_eval.SafeCallable(len, "len")
    assert ev("sorted(['bb', 'a'], key=python.len)") == ["a", "bb"]
    with pytest.raises(UnsafeExpression):
        key(print)  # a marked callable checks its arguments even when a builtin calls it


def _expand(tmp_path, name, body):
    pkg = tmp_path / "p"
    (pkg / "urdf").mkdir(parents=True, exist_ok=True)
    (pkg / "package.xml").write_text("<package><name>p</name></package>")
    f = pkg / "urdf" / name
    f.write_text(textwrap.dedent(body))
    resolver = PackageResolver.build([str(pkg)], extra_roots=[str(pkg)])
    return expand.expand_file(str(f), resolver=resolver)


X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def test_escape_in_a_real_expansion_is_a_located_unsafe_expression(tmp_path):
    r = _expand(tmp_path, "r.urdf.xacro", f"""\
        <robot name="r" {X}>
          <link name="${{python.list(map(python.type, [xacro]))}}"/>
        </robot>
        """)
    assert r.xml is None
    assert r.error.code == "UL903" and r.error.line == 2, r.error
    assert "NameSpace" not in r.error.message


def test_one_model_cannot_change_what_the_next_sees(tmp_path):
    """math.update(...) used to mutate the namespace shared by every model of a worker."""
    a = _expand(tmp_path, "a.urdf.xacro", f"""\
        <robot name="a" {X}><link name="${{math.update(pi=3)}}"/></robot>
        """)
    assert a.error and a.error.code == "UL903"
    b = _expand(tmp_path, "b.urdf.xacro", f"""\
        <robot name="b" {X}><link name="l${{math.pi}}"/></robot>
        """)
    assert b.error is None and 'name="l3.141592653589793"' in b.xml


def test_deprecated_global_sorted_is_checked(tmp_path):
    r = _expand(tmp_path, "r.urdf.xacro", f"""\
        <robot name="r" {X}><link name="${{sorted([2, 1], key=python.vars)}}"/></robot>
        """)
    assert r.error and r.error.code == "UL903"
    ok = _expand(tmp_path, "ok.urdf.xacro", f"""\
        <robot name="r" {X}><link name="${{sorted([2, 1])[0]}}"/></robot>
        """)
    assert ok.error is None and '<link name="1"/>' in ok.xml


# -- generated expressions from the reachable names -------------------------------------------
REACHABLE = sorted(n for n, _ in walk_namespace(G) if not n.startswith(("True", "False")))
ATTRS = sorted({a for o in SAMPLES.values() for a in dir(o)} | {"__class__", "__globals__",
                                                                "__self__", "mro", "update"})
ATOMS = ["1", "2.5", "'a_b'", "[1, 2]", "{'k': 1}", "(1,)", "xacro", "python", "math",
         "lambda x: x", "None"] + REACHABLE


def _exprs():
    atom = st.sampled_from(ATOMS)

    def extend(inner):
        return st.one_of(
            st.builds(lambda f, a: f"{f}({a})", inner, inner),
            st.builds(lambda f, a, b: f"{f}({a}, {b})", inner, inner, inner),
            st.builds(lambda o, a: f"({o}).{a}", inner, st.sampled_from(ATTRS)),
            st.builds(lambda o, k: f"({o})[{k}]", inner, inner),
            st.builds(lambda f, k, xs: f"{f}({xs}, key={k})",
                      st.sampled_from(["sorted", "max", "min", "python.sorted"]), inner, inner),
            st.builds(lambda f, g, xs: f"list({f}({g}, {xs}))",
                      st.sampled_from(["map", "filter", "python.map"]), inner, inner),
        )
    return st.recursive(atom, extend, max_leaves=6)


def _closed(v, depth=0):
    """A result holds nothing but values, namespaces and allowed callables."""
    if depth > 4:
        return True
    if callable(v):
        return is_allowed_callable(v)
    if isinstance(v, (list, tuple, set, frozenset)):
        return all(_closed(x, depth + 1) for x in v)
    if isinstance(v, dict):
        return all(_closed(x, depth + 1) for x in list(v.keys()) + list(v.values()))
    return True


@settings(max_examples=400, deadline=None, suppress_health_check=list(HealthCheck))
@given(_exprs())
def test_generated_expressions_stay_inside_the_allowed_set(expr):
    try:
        v = ev(expr)
    except Exception:  # noqa: BLE001 - refusals and ordinary errors are both fine
        return
    assert _closed(v), (expr, v)
    assert "pwned" not in os.listdir(".")
