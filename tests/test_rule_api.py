"""The rule side of the engine: a rule yields :class:`urdf_lint.engine.api.Report` and imports
only ``urdf_lint.engine.api`` (and its own ``rules/_*.py`` helpers)."""
from __future__ import annotations

import ast
import types
import warnings
from pathlib import Path

import pytest
from lxml import etree

from urdf_lint.engine import registry
from urdf_lint.engine.api import Cause, Report, set_attrs
from urdf_lint.engine.model import Model

RULES_DIR = Path(__file__).resolve().parent.parent / "rules"
RULES = registry.load_rules()
TUPLE_WARNING = r"rule UL\d{3} yields a tuple"


def fake_rule(monkeypatch, code: str, check) -> None:
    """A rule ``code`` with ``check``, loaded beside the built-in rules for this test."""
    mod = types.ModuleType(f"urdf_lint.rules.{code.lower()}_fake")
    mod.__doc__ = "Fake.\n\nWhy: x.\n\nHow to fix: y.\n\nFix: safe."
    mod.CODE, mod.NAME, mod.SEVERITY, mod.FAIL, mod.PASS = code, "fake", "error", "<r/>", "<r/>"
    mod.check = check
    monkeypatch.setattr(registry, "_RULES", {**registry.load_rules(),
                                             code: registry.rule_from_module(mod)})


def _fake_rule(monkeypatch, check):
    fake_rule(monkeypatch, "UL997", check)
    return Model(entry="/r.urdf", args={}, root=etree.fromstring("<robot><link/></robot>"),
                 origins={}, deps=[])


def _run(model, internal):
    return [tuple(x[1:]) for x in registry.run_rules(
        "model", ["UL997"], {}, model, types.SimpleNamespace(), internal, with_fix=True,
        with_table=True)]


def test_a_report_and_the_old_tuple_give_the_same_problem_and_only_the_tuple_warns(monkeypatch):
    fix = set_attrs({"name": "a"}, "name it")
    cause = Cause("UL004", "package:x", "package 'x' is not found")
    table = {"mujoco": "warning"}
    reports = [Report("EL", "plain"), Report("EL", "lowered", severity="info"),
               Report("EL", "fixed", "warning", fix, table, cause)]
    tuples = [("EL", "plain"), ("EL", "lowered", "info"),
              ("EL", "fixed", "warning", table, fix, cause)]   # extras in any order, by type
    internal: list = []
    model = _fake_rule(monkeypatch, lambda m, ctx: iter(reports))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        from_reports = _run(model, internal)
    assert not [w for w in caught if issubclass(w.category, DeprecationWarning)]
    assert from_reports == [("EL", "plain", "", None, None, None),
                            ("EL", "lowered", "info", None, None, None),
                            ("EL", "fixed", "warning", fix, cause, table)]
    model = _fake_rule(monkeypatch, lambda m, ctx: iter(tuples))
    with pytest.warns(DeprecationWarning, match="rule UL997 yields a tuple") as caught:
        from_tuples = _run(model, internal)
    assert from_tuples == from_reports and not internal
    assert all("UL997" in str(w.message) for w in caught if w.category is DeprecationWarning)


def test_report_is_frozen():
    r = Report("EL", "m")
    with pytest.raises(AttributeError):
        r.message = "other"    # type: ignore[misc]
    assert (r.severity, r.fix, r.targets, r.cause) == (None, None, None, None)


@pytest.mark.parametrize("code", sorted(c for c, r in RULES.items() if r.check is not None
                                        and r.scope == "model"))
def test_every_built_in_rule_yields_reports(tmp_path, monkeypatch, code):
    """Each rule's FAIL example, linted in process, with the tuple warning an error: a rule that
    still yields a tuple crashes (an internal error) instead of reporting."""
    from test_rule_examples import _in_process
    with warnings.catch_warnings():
        warnings.filterwarnings("error", message=TUPLE_WARNING, category=DeprecationWarning)
        found, _ = _in_process(tmp_path, monkeypatch, RULES[code], RULES[code].fail)
    assert found, f"{code} did not fire on its FAIL example"


def test_the_run_scope_rule_yields_reports(tmp_path, monkeypatch):
    """UL106 (two robots of one name) through the run pipeline, with the warning an error."""
    from conftest import make_package
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import RunRequest, run_check
    pkg = make_package(tmp_path, "two", {"urdf/a.urdf": '<robot name="r"><link name="a"/></robot>',
                                         "urdf/b.urdf": '<robot name="r"><link name="b"/></robot>'})
    monkeypatch.chdir(pkg)
    cfg = load_config(None)
    cfg.select = ["UL106"]
    with warnings.catch_warnings():
        warnings.filterwarnings("error", message=TUPLE_WARNING, category=DeprecationWarning)
        res = run_check(RunRequest((".",), cfg, build_resolver(["."], cfg), in_process=True))
    assert not res.internal, res.internal
    assert [f.code for f in res.findings] == ["UL106", "UL106"]


# -- rules import only urdf_lint.engine.api ---------------------------------------------------
def foreign_imports(source: str) -> list[str]:
    """The urdf_lint modules a rule's source imports (at any depth) other than
    ``urdf_lint.engine.api`` and the private helpers ``urdf_lint.rules._*``."""
    out = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:          # relative: inside the rules package
                names = [f"urdf_lint.rules.{node.module}"] if node.module else \
                    [f"urdf_lint.rules.{a.name}" for a in node.names]
            else:
                names = [node.module or ""]
                if node.module in ("urdf_lint", "urdf_lint.rules", "urdf_lint.engine"):
                    names = [f"{node.module}.{a.name}" for a in node.names]
        else:
            continue
        for n in names:
            if n != "urdf_lint" and not n.startswith("urdf_lint."):
                continue
            if n == "urdf_lint.engine.api" or n.startswith("urdf_lint.rules._"):
                continue
            out.append(n)
    return out


def test_the_import_check_finds_what_it_must():
    assert foreign_imports("from urdf_lint.fix.fixes import set_attrs") == ["urdf_lint.fix.fixes"]
    assert foreign_imports("def check(m, c):\n    import urdf_lint.meshes.resolve\n") == \
        ["urdf_lint.meshes.resolve"]
    assert foreign_imports("from urdf_lint.rules import ul004_unknown_package") == \
        ["urdf_lint.rules.ul004_unknown_package"]
    assert foreign_imports("from urdf_lint.engine import api") == []
    assert foreign_imports("from . import ul212_missing_dollar") == \
        ["urdf_lint.rules.ul212_missing_dollar"]
    assert foreign_imports("from urdf_lint.engine.api import Report\n"
                           "from urdf_lint.rules._schema import urdf_iter\nimport os") == []


@pytest.mark.parametrize("path", sorted(RULES_DIR.glob("*.py")), ids=lambda p: p.name)
def test_rules_import_only_the_engine_api(path):
    assert foreign_imports(path.read_text(encoding="utf-8")) == [], \
        f"{path.name}: a rule imports only urdf_lint.engine.api (re-export what it needs there)"


def _gen_types():
    import importlib.util
    from conftest import REPO
    spec = importlib.util.spec_from_file_location("gen_types", REPO / "scripts" / "gen_types.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _top_level_names(tree: ast.Module) -> set[str]:
    """The names a module binds unconditionally at its top level (not under an ``if``: not
    under ``TYPE_CHECKING``, not by a module ``__getattr__``)."""
    out = set()
    for node in tree.body:
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            out |= {(a.asname or a.name).split(".")[0] for a in node.names}
        elif isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            out.add(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            out |= {t.id for t in targets if isinstance(t, ast.Name)}
    return out


def test_every_name_of_the_rule_api_is_real_and_mypy_sees_the_requests():
    """mypy and editors see a module's real names, not what a module ``__getattr__`` returns:
    every name of ``engine.api.__all__`` and every built-in kind's request function is bound
    at the top of api.py, and the block of requests is the one scripts/gen_types.py writes."""
    from conftest import REPO
    from urdf_lint.engine import api
    from urdf_lint.fix import kinds
    path = REPO / "urdf_lint" / "engine" / "api.py"
    text = path.read_text(encoding="utf-8")
    bound = _top_level_names(ast.parse(text))
    assert set(api.__all__) <= bound, sorted(set(api.__all__) - bound)
    assert set(kinds.requests()) <= bound and set(kinds.requests()) <= set(api.__all__)
    assert "MeshStatus" in bound and api.MeshStatus.OK.value == "ok"
    gen = _gen_types()
    assert gen.render(text) == text, "api.py is stale: run python scripts/gen_docs.py"
    stale = text.replace("from urdf_lint.fix.kinds.set import set_attrs as set_attrs\n", "")
    assert stale != text and gen.render(stale) == text


def _foreign(el) -> bool:
    """The per-element definition the shared walk must agree with: namespaced, or below a
    free-form extension element."""
    from urdf_lint.rules._schema import FREE_FORM
    if el.tag.startswith("{") or ":" in el.tag:
        return True
    p = el.getparent()
    while p is not None:
        if p.tag in FREE_FORM:
            return True
        p = p.getparent()
    return False


_BLOCKS = """<robot name="r" xmlns:drake="http://drake.mit.edu">
  <!-- a comment --><link name="a"><visual><geometry><mesh filename="a.stl"/></geometry>
    </visual><sensor name="s"><camera><image width="1"/></camera><origin xyz="0 0 0"/></sensor>
  </link>
  <gazebo reference="a"><link name="sdf"><visual><geometry><mesh filename="b.dae"/></geometry>
    </visual></link><plugin name="p"><origin xyz="1"/></plugin></gazebo>
  <drake:joint name="d"><origin xyz="2 2 2"/><drake:child/></drake:joint>
  <transmission name="t"><joint name="j"><hardwareInterface>x</hardwareInterface></joint>
  </transmission>
  <ros2_control name="c"><joint name="j"><param name="p">1</param></joint></ros2_control>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/><origin xyz="0 0 0"/></joint>
  <link name="b"><collision><geometry><mesh filename="c.stl"/></geometry></collision></link>
</robot>"""


@pytest.mark.unit
def test_the_walk_rules_share_keeps_the_elements_no_ancestor_makes_foreign():
    """``checked_elements`` and ``urdf_iter`` come from one walk per model: they give what a
    look at every element's own tag and ancestors gives, in document order, on a document of
    every kind of extension block and on the seed and broken models."""
    from urdf_lint.rules._schema import checked_elements, urdf_iter
    roots = [etree.fromstring(_BLOCKS)]
    for f in sorted(Path(__file__).parent.parent.glob("descriptions/**/*.urdf")):
        try:   # (a broken model that is not XML has no tree to walk)
            roots.append(etree.parse(str(f), etree.XMLParser(resolve_entities=False)).getroot())
        except etree.XMLSyntaxError:
            continue
    assert len(roots) > 5
    for root in roots:
        model = Model(entry="/r.urdf", args={}, root=root, origins={}, deps=[])
        want = [el for el in root.iter() if isinstance(el.tag, str) and not _foreign(el)]
        assert list(checked_elements(model)) == want
        for tag in {el.tag for el in root.iter() if isinstance(el.tag, str)} | {"nothing"}:
            assert list(urdf_iter(model, tag)) == [el for el in root.iter(tag)
                                                   if not _foreign(el)], tag
        assert list(checked_elements(model)) == want      # (the second walk is the memo)
    first = roots[0]
    got = {el.get("name") or el.get("filename") or el.get("xyz") for el in
           checked_elements(Model(entry="/r.urdf", args={}, root=first, origins={}, deps=[]))}
    assert {"a", "a.stl", "s", "j", "b", "c.stl", "2 2 2"} <= got
    assert not got & {"sdf", "b.dae", "1", "p"}      # inside <gazebo>, <plugin>, <ros2_control>
