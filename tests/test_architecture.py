"""The engine's shape: rooms by layer (import-linter contracts), no import cycles, every code is
a rule module and is raised through it."""
from __future__ import annotations

import ast
import re

import pytest

from conftest import REPO
from urdf_lint.engine.registry import load_rules

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
    assert "urdf_lint.run.pipeline" in graph and "urdf_lint.rules.ul302_limit_order" in graph
    assert "urdf_lint.discovery.discover" in graph["urdf_lint.run.pipeline"]    # the graph sees imports
    cycle = find_cycle(graph)
    assert cycle is None, " -> ".join(cycle)


def test_the_cycle_finder_finds_cycles():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None


# -- the layer contracts (import-linter; [tool.importlinter] in pyproject.toml) -------------------
def _installed_layout(tmp_path):
    """The package as installed (``rules/`` as ``urdf_lint.rules``), copied under ``tmp_path``:
    import-linter reads the files of the package it finds, and an editable install maps
    ``urdf_lint.rules`` to ``rules/`` without a folder inside ``urdf_lint/``."""
    import shutil
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc")
    shutil.copytree(PKG, tmp_path / "urdf_lint", ignore=ignore)
    shutil.copytree(RULES_DIR, tmp_path / "urdf_lint" / "rules", ignore=ignore)
    shutil.copy(REPO / "pyproject.toml", tmp_path / "pyproject.toml")
    return tmp_path


def _lint_imports(tree):
    import os
    import subprocess
    import sys
    exe = os.path.join(os.path.dirname(sys.executable), "lint-imports")
    if not os.path.exists(exe):
        pytest.skip("import-linter is not installed (pip install -e '.[test]')")
    env = {**os.environ, "PYTHONPATH": str(tree)}
    return subprocess.run([exe, "--config", str(tree / "pyproject.toml"), "--no-cache"],
                          cwd=tree, env=env, capture_output=True, text=True, timeout=120)


def test_the_layer_contracts_are_kept(tmp_path):
    p = _lint_imports(_installed_layout(tmp_path))
    assert p.returncode == 0, p.stdout + p.stderr
    assert "Contracts: 2 kept, 0 broken." in p.stdout, p.stdout


def test_plain_lint_imports_at_the_root_runs_the_contracts():
    """A contributor types ``lint-imports`` in the checkout: the contracts run there too (it
    stopped at "No matches for ignored import ..." and "Missing layer", rules/ being outside
    urdf_lint/ in an editable install)."""
    import os
    import subprocess
    import sys
    exe = os.path.join(os.path.dirname(sys.executable), "lint-imports")
    if not os.path.exists(exe):
        pytest.skip("import-linter is not installed (pip install -e '.[test]')")
    p = subprocess.run([exe, "--no-cache"], cwd=REPO, capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "Contracts: 2 kept, 0 broken." in p.stdout, p.stdout


def test_an_upward_import_breaks_the_layer_contract(tmp_path):
    """The contracts see an import inside a function too: a lower room (core) importing a
    higher one (cli) is reported with its line, and the runner importing the engine breaks its
    own contract."""
    tree = _installed_layout(tmp_path)
    with open(tree / "urdf_lint" / "core" / "escape.py", "a", encoding="utf-8") as f:
        f.write("\n\ndef _upward():\n    from urdf_lint.cli import main  # noqa: F401\n")
    with open(tree / "urdf_lint" / "runner" / "forked.py", "a", encoding="utf-8") as f:
        f.write("\n\ndef _knows_lint():\n    from urdf_lint.engine import model  # noqa: F401\n")
    p = _lint_imports(tree)
    assert p.returncode != 0, p.stdout
    assert "urdf_lint.core.escape -> urdf_lint.cli.main" in p.stdout, p.stdout
    assert "urdf_lint.runner.forked -> urdf_lint.engine.model" in p.stdout, p.stdout
    assert "0 kept, 2 broken" in p.stdout, p.stdout
def _too_complex(source, label):
    """``label:line name rank(complexity)`` for every block radon grades E or F in ``source``
    (functions, methods and classes, as ``radon cc -n E`` lists them)."""
    from radon.complexity import cc_rank, cc_visit
    return [f"{label}:{b.lineno} {b.fullname} {cc_rank(b.complexity)}({b.complexity})"
            for b in cc_visit(source) if cc_rank(b.complexity) in "EF"]


def test_no_function_is_above_radon_grade_d():
    """Every function, method and class in urdf_lint/ and rules/ at radon grade D or better
    (cli/ and config/ included: none of theirs is above D)."""
    pytest.importorskip("radon")
    found = []
    for path in sorted([*PKG.rglob("*.py"), *RULES_DIR.rglob("*.py")]):
        found += _too_complex(path.read_text(encoding="utf-8"), path.relative_to(REPO).as_posix())
    assert not found, "split these (radon grade E or F):\n" + "\n".join(found)


def test_the_complexity_check_finds_a_complex_function():
    pytest.importorskip("radon")
    branches = "".join(f"    if x == {i}:\n        return {i}\n" for i in range(40))
    assert _too_complex(f"def f(x):\n{branches}    return -1\n", "m.py") == ["m.py:1 f F(41)"]
    assert _too_complex("def g(x):\n    return x\n", "m.py") == []


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


# -- the typed data -------------------------------------------------------------------------------
def test_problem_and_report_cross_the_pipe_and_the_cache():
    import json
    import pickle
    from urdf_lint.core.findings import Problem
    from urdf_lint.core.jobs import LintJob, ModelReport, Status
    from urdf_lint.core.locations import Origin
    p = Problem.at("UL302", "lower > upper", ("/r/arm.xacro", 14, 7, [["/r/robot.xacro", 7, 3]]),
                   ["joint", "elbow"])
    assert p.origin == Origin("/r/arm.xacro", 14, 7, (("/r/robot.xacro", 7, 3),))
    assert p.target == ("joint", "elbow") and (p.file, p.line, p.col) == ("/r/arm.xacro", 14, 7)
    assert pickle.loads(pickle.dumps(p)) == p
    job = LintJob("/r/robot.xacro", {"side": "left"})
    rep = ModelReport(job.entry, job.args, Status.MODEL, deps=[job.entry], problems=[p],
                      name="r", name_origin=Origin("/r/robot.xacro", 1, 1), links=3)
    assert pickle.loads(pickle.dumps(rep)) == rep
    back = ModelReport.from_record(job, json.loads(json.dumps(rep.to_record())))
    assert back.problems == [p] and back.cached and back.links == 3 and back.status is Status.MODEL
    assert json.dumps({"status": Status.FAILED}) == '{"status": "failed"}'
    assert rep.label.endswith("robot.xacro [side:=left]")
    import dataclasses
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.code = "UL001"


def test_source_map_alignment_is_strict():
    from lxml import etree
    from urdf_lint.expansion.sourcemap import SourceMap
    from urdf_lint.engine.model import model_from_xml
    stamps = [("/f.xacro", 1, 1, ()), None, ("/f.xacro", 3, 5, (("/g.xacro", 2, 3),))]
    sm = SourceMap.from_stamps(stamps)
    assert len(sm) == 3 and sm[1] == sm[0] and sm[2].chain == (("/g.xacro", 2, 3),)
    xml = '<robot name="r"><link name="a"/><link name="b"/></robot>'
    m = model_from_xml("/f.xacro", {}, xml, sm, ["/f.xacro"])
    assert m.origin(m.links["b"]).line == 3
    with pytest.raises(ValueError):
        model_from_xml("/f.xacro", {}, xml, SourceMap(sm.origins[:2]), ["/f.xacro"])
    with pytest.raises(ValueError):
        sm.align(etree.fromstring("<a><b/><c/><d/></a>").iter())


def test_error_table_maps_xacro_failures_to_rule_modules():
    import xacro
    import xacro.substitution_args as subst
    from urdf_lint.expansion import errors
    rules = load_rules()
    for row in errors.ERROR_TABLE:
        if row.rule is not None:
            assert rules[row.rule.CODE].origin == "expansion", row.rule.CODE
    here = ("/r/robot.xacro", 5, 3, ())
    p = errors.problem_for(errors.XmlSyntaxError("XML syntax error: x", "/r/a.xacro", 2, 4,
                                                 (("/r/robot.xacro", 9, 3),)), here)
    assert (p.code, p.file, p.line, p.col, p.chain) == \
        ("UL001", "/r/a.xacro", 2, 4, (("/r/robot.xacro", 9, 3),))
    p = errors.problem_for(xacro.XacroException("x", exc=subst.ArgException("side")), here)
    assert p.code == "UL005" and "'side'" in p.message and p.line == 5
    p = errors.problem_for(xacro.XacroException("boom"), here, ["inner", "outer"])
    assert p.code == "UL002" and p.message == "boom (in macro 'inner' < 'outer')"
    p = errors.problem_for(RecursionError("deep"), here)
    assert p.code == "UL904"
    from urdf_lint.rules import ul902_outside_roots
    p = errors.problem_for(errors.RefusedInput("no", ul902_outside_roots), here)
    assert (p.code, p.line) == ("UL902", 5)


def test_policy_is_one_matcher():
    from urdf_lint.config.policy import Policy, code_matches
    assert code_matches("UL3", "UL302") and code_matches("limit-order", "UL302", "limit-order")
    assert code_matches("ALL", "UL302") and not code_matches("UL30", "UL401")
    pol = Policy(select=("UL",), ignore=("UL3",), severity={"UL3": "warning", "UL302": "info"},
                 per_file_ignores={"legacy/*.xacro": ["UL6"]}, root="/repo")
    assert pol.is_selected("UL101") and not pol.is_selected("UL302")
    assert Policy(select=("UL302",), ignore=("UL3",)).is_selected("UL302")   # more specific wins
    assert pol.severity_of("UL302", "limit-order", "error") == "info"
    assert pol.severity_of("UL303", "x", "error") == "warning"
    assert pol.severity_of("UL101", "x", "error") == "error"
    assert pol.ignored_for_file("UL601", "missing-inertial", "/repo/legacy/a.xacro")
    assert not pol.ignored_for_file("UL601", "missing-inertial", "/repo/urdf/a.xacro")


def test_a_plain_rule_module_still_loads():
    """Backward compatible rule API: CODE/NAME/SEVERITY/FAIL/PASS and check(model, ctx)."""
    import types
    from urdf_lint.engine.registry import rule_from_module
    mod = types.ModuleType("urdf_lint.rules.ul999_plain")
    mod.__doc__ = "Something.\n\nWhy: x.\n\nHow to fix: y."
    mod.CODE, mod.NAME, mod.SEVERITY = "UL999", "plain", "warning"
    mod.FAIL, mod.PASS = "<robot/>", "<robot/>"
    mod.check = lambda model, ctx: iter(())
    r = rule_from_module(mod)
    assert (r.scope, r.origin, r.fail_at, r.check) == ("model", "rule", (), mod.check)
    del mod.check
    with pytest.raises(RuntimeError):
        rule_from_module(mod)     # neither check() nor ORIGIN


def test_mesh_resolution_is_a_status_that_rules_map_to_codes(tmp_path):
    from conftest import make_package
    from urdf_lint.meshes.resolve import MeshStatus, resolve
    from urdf_lint.engine.model import Model
    from urdf_lint.discovery.packages import PackageResolver
    from lxml import etree
    pkg = make_package(tmp_path, "p", {"meshes/part.stl": "solid x\nendsolid x\n"})
    res = PackageResolver.build([tmp_path], extra_roots=[tmp_path])
    model = Model(entry=str(pkg / "r.urdf"), args={}, root=etree.fromstring("<robot/>"),
                  origins={}, deps=[], resolver=res)
    cases = {"package://p/meshes/part.stl": MeshStatus.OK,
             "package://p/meshes/Part.STL": MeshStatus.CASE_MISMATCH,
             "package://p/meshes/none.stl": MeshStatus.NOT_FOUND,
             "package://nopkg/x.stl": MeshStatus.UNKNOWN_PACKAGE,
             "file:///etc/hostname": MeshStatus.OUTSIDE_ROOTS}
    for uri, status in cases.items():
        ref = resolve(model, uri)
        assert ref.status is status, (uri, ref)
        assert (ref.problem is None) == (status is MeshStatus.OK)


def test_settings_are_typed():
    import dataclasses
    from urdf_lint.core.jobs import LintSettings
    s = LintSettings(resolver={"scanned": {}}, selected=("UL302",), mesh_cache_dir="/c")
    assert s.selected == ("UL302",) and s.mesh_cache_dir == "/c" and s.render_dir is None
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.selected = ()
    assert dataclasses.replace(s, keep_model=True).keep_model


def test_a_rule_may_choose_the_severity_of_one_problem(monkeypatch):
    """check() may yield (element, message, severity); configured overrides still win."""
    import types
    from lxml import etree
    from urdf_lint.engine import registry
    from urdf_lint.core.findings import Problem
    from urdf_lint.engine.model import Model
    from urdf_lint.run.finish import with_policy as _with_policy
    from urdf_lint.config.policy import Policy
    mod = types.ModuleType("urdf_lint.rules.ul998_fake")
    mod.__doc__ = "Fake.\n\nWhy: x.\n\nHow to fix: y."
    mod.CODE, mod.NAME, mod.SEVERITY, mod.FAIL, mod.PASS = "UL998", "fake", "error", "<r/>", "<r/>"
    mod.check = lambda model, ctx: iter([(model.root, "lowered", "info"), (model.root, "plain")])
    monkeypatch.setattr(registry, "_RULES", {**registry.load_rules(),
                                             "UL998": registry.rule_from_module(mod)})
    model = Model(entry="/r.urdf", args={}, root=etree.fromstring("<robot><link/></robot>"),
                  origins={}, deps=[])
    got = [(msg, sev) for _, _, msg, sev in
           registry.run_rules("model", ["UL998"], {}, model, types.SimpleNamespace(), [])]
    assert got == [("lowered", "info"), ("plain", "")]
    probs = [Problem.at("UL998", m, ("/r.urdf", 1, 1), severity=s) for m, s in got]
    assert Problem.from_record(probs[0].to_record()).severity == "info"
    assert [p.severity for p in _with_policy(probs, "r", Policy())] == ["info", "error"]
    assert [p.severity for p in _with_policy(probs, "r", Policy(severity={"UL998": "warning"}))] \
        == ["warning", "warning"]


def _module_aliases(tree):
    """Names bound to imported modules at any level of ``tree`` (``import x``, ``import x as
    y``, ``from . import x``)."""
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names |= {(a.asname or a.name).split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module in (
                "os", "sys", "importlib"):
            names |= {a.asname or a.name for a in node.names}
    return names


def test_no_module_of_ours_rebinds_another_modules_names():
    """Issue 22: the sandbox swapped a stub into ``dataclasses``' view of ``inspect`` while
    importing ``landlock``, which crashed every Python but 3.11. Assigning to an attribute of
    an imported module (``dataclasses.inspect = ...``, ``setattr(mod, ...)``) changes another
    module's behaviour for everyone in the process: not allowed anywhere in the product."""
    # (module, target prefix): why it is not a patch of another module's behaviour
    allowed = {
        # the pinned xacro (pyproject: xacro==2.1.1) is hooked by design, inside one expansion
        ("urdf_lint.expansion.expand", "xacro."): "xacro is pinned to be hooked",
        ("urdf_lint.expansion.expand", "_subst."): "xacro's substitution_args, likewise",
        ("urdf_lint.expansion.splice", "xacro."): "likewise",
        # xacro prints to the streams: captured for one expansion, then restored
        ("urdf_lint.expansion.expand", "sys.stdout"): "capture, restored",
        ("urdf_lint.expansion.expand", "sys.stderr"): "capture, restored",
        # a worker process's own interpreter setting (the worker is ours alone)
        ("urdf_lint.runner.pool", "sys.dont_write_bytecode"): "the worker's own process",
    }
    found = []
    for name, path in _modules().items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        aliases = _module_aliases(tree)
        for node in ast.walk(tree):
            targets = []
            if isinstance(node, (ast.Assign, ast.AugAssign, ast.AnnAssign)):
                targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            elif isinstance(node, ast.Call) and isinstance(node.func, ast.Name) \
                    and node.func.id in ("setattr", "delattr") and node.args \
                    and isinstance(node.args[0], ast.Name) and node.args[0].id in aliases:
                found.append(f"{name}:{node.lineno} {node.func.id}({node.args[0].id}, ...)")
            for t in targets:
                if isinstance(t, ast.Attribute) and isinstance(t.value, ast.Name) \
                        and t.value.id in aliases and t.value.id != "self" \
                        and not any(name == m and ast.unparse(t).startswith(prefix)
                                    for m, prefix in allowed):
                    found.append(f"{name}:{node.lineno} {ast.unparse(t)} = ...")
    assert not found, "a module of ours rebinds another module's names:\n" + "\n".join(found)


def test_the_standard_library_is_untouched_by_the_sandbox_probe():
    """The sandbox probe (``landlock`` imported, as ``check`` and ``doctor`` do) leaves
    ``dataclasses`` and ``inspect`` as the standard library has them: a dataclass defined after
    it still gets its generated docstring with the signature."""
    import subprocess
    import sys
    code = (
        "import sys, dataclasses, urdf_lint, urdf_lint.runner.sandbox as s\n"
        "s.landlock_status()\n"
        "import inspect\n"
        "assert type(sys.modules['inspect']).__name__ == 'module', type(sys.modules['inspect'])\n"
        "assert dataclasses.inspect is inspect\n"
        "@dataclasses.dataclass\n"
        "class P:\n"
        "    x: int = 1\n"
        "print(P.__doc__)\n")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == "P(x: int = 1)", p.stdout


def test_one_git_runner(tmp_path):
    """git is run in one place, :func:`urdf_lint.discovery.vcs.git`: text or bytes out, and every
    failure (not a work tree, no git at all) one GitError with git's message."""
    offenders = []
    for name, path in _modules().items():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.List) and node.elts and isinstance(node.elts[0], ast.Constant) \
                    and node.elts[0].value == "git" and name != "urdf_lint.discovery.vcs":
                offenders.append(f"{path.relative_to(REPO)}:{node.lineno}")
    assert not offenders, "git run outside discovery/vcs.py:\n" + "\n".join(offenders)
    import os
    from urdf_lint.discovery.vcs import GitError, git
    assert git("--version", cwd=str(tmp_path)).startswith("git version")
    assert git("--version", cwd=str(tmp_path), binary=True).startswith(b"git version")
    with pytest.raises(GitError, match="not a git repository"):
        git("rev-parse", "--show-toplevel", cwd=str(tmp_path))
    old = os.environ["PATH"]
    os.environ["PATH"] = str(tmp_path)     # no git on the PATH
    try:
        with pytest.raises(GitError):
            git("--version", cwd=str(tmp_path))
    finally:
        os.environ["PATH"] = old


def test_rooms_below_the_rules_name_real_rules():
    """Below the rules a code is named by its rule module (``RuleName("ul904_resource_limit")``,
    urdf_lint.core.codes), never imported: every such name is a rule module of rules/ and its
    code is the module's CODE; every rule file is named by its code."""
    from urdf_lint.core.codes import RuleName
    rules = load_rules()
    by_leaf = {r.module.rsplit(".", 1)[1]: code for code, r in rules.items()}
    assert all(RuleName(leaf).CODE == code for leaf, code in by_leaf.items() if leaf.startswith("ul"))
    named = []
    for name, path in _modules().items():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) \
                    and node.func.id == "RuleName":
                assert node.args and isinstance(node.args[0], ast.Constant), \
                    f"{path.relative_to(REPO)}:{node.lineno}: a RuleName of a literal module name"
                named.append((node.args[0].value, f"{path.relative_to(REPO)}:{node.lineno}"))
    assert len(named) >= 15, named
    unknown = [f"{where}: {leaf}" for leaf, where in named if leaf not in by_leaf]
    assert not unknown, "no such rule module:\n" + "\n".join(unknown)
    with pytest.raises(ValueError):
        RuleName("resource_limit")


def test_every_package_folder_is_installed():
    """pyproject.toml lists the packages by hand (``rules/`` is installed as
    ``urdf_lint.rules``): a new room or sub-room missing from that list would be left out of
    the wheel, and the installed tool would fail where the checkout works."""
    from pyproject import pyproject as read_pyproject
    listed = set(read_pyproject()["tool"]["setuptools"]["packages"])
    found = {".".join(("urdf_lint", *p.parent.relative_to(PKG).parts))
             for p in PKG.rglob("__init__.py") if "__pycache__" not in p.parts}
    found.add("urdf_lint.rules")
    assert found == listed, f"not installed: {sorted(found - listed)}; stale: {sorted(listed - found)}"


# a room's private names stay in the room: no exception (the language server's workers are
# the runner's public WorkerPool, persistent)
PRIVATE_ACROSS_ROOMS_ALLOWED: set = set()


def _private_imports_across_rooms():
    import ast
    found = set()
    for f in sorted(PKG.rglob("*.py")):
        parts = f.relative_to(PKG).parts
        room = parts[0] if len(parts) > 1 else ""
        for n in ast.walk(ast.parse(f.read_text(encoding="utf-8"))):
            if isinstance(n, ast.ImportFrom) and (n.module or "").startswith("urdf_lint."):
                other = n.module.split(".")[1]
                found |= {(f.relative_to(REPO).as_posix(), n.module, a.name) for a in n.names
                          if a.name.startswith("_") and other != room}
    return found


def test_no_private_name_is_imported_across_rooms():
    """A room's ``_names`` are its own: another room imports only its public names (the run's
    end is run.finish's public functions, not four private ones of run.pipeline)."""
    assert _private_imports_across_rooms() <= PRIVATE_ACROSS_ROOMS_ALLOWED, \
        sorted(_private_imports_across_rooms() - PRIVATE_ACROSS_ROOMS_ALLOWED)
