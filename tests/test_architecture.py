"""The engine's shape: no import cycles, every code is a rule module and is raised through it."""
from __future__ import annotations

import ast
import re
from pathlib import Path

from conftest import REPO
from urdf_lint.registry import load_rules

PKG = REPO / "urdf_lint"
RULES_DIR = REPO / "rules"


def _modules():
    """{dotted module name: path} for urdf_lint/ and rules/ (installed as urdf_lint.rules)."""
    out = {}
    for base, prefix in ((PKG, "urdf_lint"), (RULES_DIR, "urdf_lint.rules")):
        for p in sorted(base.rglob("*.py")):
            rel = p.relative_to(base).with_suffix("")
            parts = [x for x in rel.parts if x != "__init__"]
            if base is PKG and parts and parts[0] == "rules":
                continue
            out[".".join([prefix, *parts])] = p
    return out


def _is_type_checking(node):
    t = node.test
    return (isinstance(t, ast.Name) and t.id == "TYPE_CHECKING") or (
        isinstance(t, ast.Attribute) and t.attr == "TYPE_CHECKING")


def _imports(name, path, known):
    """Modules of ours that ``name`` imports anywhere (functions included), except under
    ``if TYPE_CHECKING:``."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    is_pkg = path.name == "__init__.py"
    here = name.split(".") if is_pkg else name.split(".")[:-1]
    found = set()

    def visit(node):
        if isinstance(node, ast.If) and _is_type_checking(node):
            for n in node.orelse:
                visit(n)
            return
        if isinstance(node, ast.Import):
            for a in node.names:
                found.add(a.name)
        elif isinstance(node, ast.ImportFrom):
            base = here[:len(here) - node.level + 1] if node.level else []
            mod = ".".join(base + ([node.module] if node.module else []))
            found.add(mod)
            for a in node.names:
                found.add(f"{mod}.{a.name}")
        for child in ast.iter_child_nodes(node):
            visit(child)
    visit(tree)
    # importing a.b.c imports a.b and a too (their __init__ runs)
    edges = set()
    for m in found:
        parts = m.split(".")
        for i in range(1, len(parts) + 1):
            cand = ".".join(parts[:i])
            if cand in known and cand != name:
                edges.add(cand)
    return edges


def import_graph():
    mods = _modules()
    return {name: _imports(name, path, mods) for name, path in mods.items()}


def find_cycle(graph):
    state, stack = {}, []

    def dfs(n):
        state[n] = 1
        stack.append(n)
        for m in sorted(graph.get(n, ())):
            # a package's __init__ importing its own submodules is how packages work
            if m.startswith(n + "."):
                continue
            if state.get(m) == 1:
                return stack[stack.index(m):] + [m]
            if state.get(m) is None:
                c = dfs(m)
                if c:
                    return c
        stack.pop()
        state[n] = 2
        return None
    for n in sorted(graph):
        if state.get(n) is None:
            c = dfs(n)
            if c:
                return c
    return None


def test_the_import_graph_is_acyclic():
    graph = import_graph()
    assert "urdf_lint.pipeline" in graph and "urdf_lint.rules.ul302_limit_order" in graph
    assert "urdf_lint.discovery" in graph["urdf_lint.pipeline"]    # the graph sees imports
    cycle = find_cycle(graph)
    assert cycle is None, " -> ".join(cycle)


def test_the_cycle_finder_finds_cycles():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None


CODE_LITERAL = re.compile(r"UL\d{3}")


def test_the_engine_names_no_code_literally():
    """Codes are raised through their rule module (``rule.CODE``), never as a string."""
    offenders = []
    for name, path in _modules().items():
        if name.startswith("urdf_lint.rules"):
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) \
                    and CODE_LITERAL.fullmatch(node.value):
                offenders.append(f"{path.relative_to(REPO)}:{node.lineno}: {node.value!r}")
    assert not offenders, "\n".join(offenders)


def test_every_code_without_a_check_is_raised_through_its_module():
    engine = "\n".join(p.read_text(encoding="utf-8") for n, p in _modules().items()
                       if not n.startswith("urdf_lint.rules"))
    for code, r in load_rules().items():
        if r.check is not None:
            assert r.origin == "rule", code
            continue
        assert r.origin in ("expansion", "engine"), f"{code}: no check() and no ORIGIN"
        leaf = r.module.rsplit(".", 1)[1]
        assert re.search(rf"\b{leaf}\b", engine), f"{code} ({leaf}) is raised nowhere"


def test_scopes():
    rules = load_rules()
    assert rules["UL106"].scope == "run" and rules["UL106"].check is not None
    assert all(r.scope in ("model", "run") for r in rules.values())
