"""Fix kinds are classes, one file each in urdf_lint/fix/kinds/ (auto-discovered): a rule with a
new kind of fix touches two files, the rule and the kind."""
from __future__ import annotations

import pytest

from urdf_lint.engine import api
from urdf_lint.fix import kinds

BUILT_IN = {"set", "drop_attrs", "rename_attr", "rename_tag", "add_dollar", "named_material",
            "new_root", "remove_comment", "rename_at"}


def test_the_built_in_kinds_are_discovered_and_their_requests_are_in_the_api():
    found = kinds.kinds()
    assert set(found) == BUILT_IN
    assert all(isinstance(k, kinds.FixKind) and k.name == n for n, k in found.items())
    reqs = kinds.requests()
    assert set(reqs) == {"set_attrs", "drop_attrs", "rename_attr", "rename_tag", "add_dollar",
                         "named_material", "new_root", "rename_at"}
    for name, fn in reqs.items():
        assert getattr(api, name) is fn
    assert api.set_attrs({"a": "1"}, "d").kind == "set"
    assert api.rename_tag("a", "b").kind == "rename_tag"
    assert api.drop_attrs(["a"], "d").kind == "drop_attrs"
    # the records of expected results keep their names (they are stored in the cache)
    assert {n: (k.expectation or k.name) for n, k in found.items()} == {
        "set": "set", "drop_attrs": "drop", "rename_attr": "rename_attr",
        "rename_tag": "rename_tag", "add_dollar": "any", "named_material": "structural",
        "new_root": "structural", "remove_comment": "none", "rename_at": "rename_at"}
    with pytest.raises(AttributeError):
        api.no_such_request   # noqa: B018


def test_a_kinds_request_names_the_kind_once_and_the_old_positional_form_warns():
    """A kind builds its requests by keyword (``Kind.request(changes=..., description=...)``:
    the kind's name is its class's ``name``, written once); a third-party rule's positional
    ``Request(changes, description, safe, kind)`` still works for one release, with a
    DeprecationWarning, and builds the same request."""
    import warnings
    from urdf_lint.fix.fixes import Request
    from urdf_lint.fix.kinds.rename_attr import RenameAttr
    new = RenameAttr.request(changes=(("a", "b"),), description="d", safe=False)
    assert (new.kind, new.changes, new.safe, new.on_parent) == ("rename_attr", (("a", "b"),),
                                                                 False, False)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert api.rename_attr("a", "b", safe=False).kind == "rename_attr"   # no warning
        assert Request(changes=(("a", "b"),), description="d", safe=False,
                       kind="rename_attr") == new
    with pytest.warns(DeprecationWarning, match="by position is deprecated"):
        old = Request((("a", "b"),), "d", False, "rename_attr")
    assert old == new
    with pytest.raises(TypeError, match="multiple values for argument 'description'"), \
            pytest.warns(DeprecationWarning):
        Request((("a", "b"),), "d", description="e")
    for name, k in kinds.kinds().items():
        if name != "remove_comment":
            assert k.request(changes=(), description="d").kind == name


KIND = '''
"""``upper_value``: upper-case an attribute's literal value (a test's kind)."""
from urdf_lint.fix.fixes import NOT_FIXABLE, Refuse, written
from urdf_lint.fix.kinds import FixKind
from urdf_lint.core.edits import Edit


def upper_value(attr, description):
    return UpperValue.request(changes=((attr, ""),), description=description)


REQUESTS = (upper_value,)


class UpperValue(FixKind):
    name = "upper_value"

    def resolve(self, site):
        ((attr, _),) = site.req.changes
        a = written(site.tag, attr, site.origin)
        if "$" in a.value:
            raise Refuse(f"{NOT_FIXABLE}: an expression")
        return (Edit(site.origin.file, a.value_start, a.value_end, a.value.upper()),)

    def apply(self, el, attr, value):
        el.set(attr, el.get(attr).upper())
        return True
'''


@pytest.fixture
def upper_kind(tmp_path, monkeypatch):
    """A kind in a file of its own, in a folder added to the kinds package."""
    folder = tmp_path / "more_kinds"
    folder.mkdir()
    (folder / "upper_value.py").write_text(KIND, encoding="utf-8")
    monkeypatch.setattr(kinds, "__path__", [*kinds.__path__, str(folder)])
    kinds.reload()
    yield
    monkeypatch.undo()
    kinds.reload()
    api.__dict__.pop("upper_value", None)


def _upper_rule(model, ctx):
    """The rule: it imports the request from the api, nothing else."""
    for lk in model.root.iter("link"):
        if lk.get("name") != lk.get("name").upper():
            yield api.Report(lk, "link names are upper case here",
                             fix=api.upper_value("name", "upper-case the name"))


def _fix(tmp_path, monkeypatch, text):
    """``check --fix`` (in process) of one URDF holding ``text`` with the upper-case rule."""
    from conftest import make_package
    from test_rule_api import fake_rule
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.fix import run_fix
    fake_rule(monkeypatch, "UL996", _upper_rule)
    pkg = make_package(tmp_path, "upper", {"urdf/r.urdf": text})
    monkeypatch.chdir(pkg)
    cfg = load_config(None)
    cfg.select = ["UL996"]
    return run_fix(["."], cfg, build_resolver(["."], cfg), in_process=True), pkg / "urdf" / "r.urdf"


TEXT = '<robot name="r">\n  <link name="base"/>\n</robot>\n'


def test_a_new_fix_kind_is_one_file_and_check_fix_applies_and_verifies_it(
        upper_kind, tmp_path, monkeypatch):
    out, path = _fix(tmp_path, monkeypatch, TEXT)
    assert [p.code for p in out.applied] == ["UL996"] and not out.rolled_back, out.rolled_back
    assert out.applied[0].fix.expect == (("upper_value", 1, "name", ""),)
    assert path.read_text() == TEXT.replace("base", "BASE")
    assert not out.result.findings


def test_a_kind_whose_expected_result_is_wrong_is_rolled_back(upper_kind, tmp_path, monkeypatch):
    """The verification replays the kind's ``apply``: one that predicts another robot than the
    edit makes rolls the fix back (the expected result is the kind's, not a table elsewhere)."""
    monkeypatch.setattr(kinds.kind("upper_value"), "apply",
                        lambda el, attr, value: el.set(attr, "other") or True)
    out, path = _fix(tmp_path, monkeypatch, TEXT)
    assert not out.applied and [p.code for p, _ in out.rolled_back] == ["UL996"]
    assert "changes more" in out.rolled_back[0][1]
    assert path.read_text() == TEXT


def test_a_value_from_a_property_defined_twice_is_refused_naming_both(tmp_path, monkeypatch):
    """The ``set`` kind's trace through a property: defined twice, it names both places."""
    from conftest import make_package
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import RunRequest, run_check
    head = '<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
    src = (head + '  <xacro:property name="lo" value="3"/>\n'
           '  <xacro:include filename="$(find twice)/urdf/more.xacro"/>\n'
           '  <link name="a"/><link name="b"/>\n'
           '  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
           '<axis xyz="0 0 1"/><limit lower="${lo}" upper="-2" effort="1" velocity="1"/></joint>\n'
           '</robot>\n')
    more = head + '  <xacro:property name="lo" value="2"/>\n</robot>\n'
    pkg = make_package(tmp_path, "twice", {"urdf/robot.urdf.xacro": src, "urdf/more.xacro": more})
    monkeypatch.chdir(pkg)
    cfg = load_config(None)
    cfg.select = ["UL302"]
    res = run_check(RunRequest((".",), cfg, build_resolver(["."], cfg), in_process=True))
    assert not res.internal, res.internal
    (f,) = [f for f in res.findings if f.code == "UL302"]
    assert f.fix is not None and not f.fix.edits
    assert f.fix.refused == ("not fixable automatically: the value comes from the expression at "
                             "urdf/robot.urdf.xacro:6 (property 'lo' is defined 2 times: "
                             "urdf/more.xacro:3, urdf/robot.urdf.xacro:3)")
