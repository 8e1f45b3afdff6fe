"""The xacro project's own test inputs (../shared/corpus/peer-tests/xacro): each wrapper document
of upstream's test suite, written to disk beside the data files, must expand to the upstream
expectation, and to the same bytes as stock xacro (or fail where stock fails).

Skipped: nothing needs ROS itself. ``test_print_location`` only checks what xacro prints to
stderr (we capture xacro's messages as findings instead), so only its output ``<a/>`` is checked.
"""
from __future__ import annotations

import math
import os
import re
import shutil

import pytest
from lxml import etree

from conftest import CORPUS
from stock_xacro import stock_xacro

PEER = CORPUS / "peer-tests" / "xacro"
X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


@pytest.fixture(scope="module")
def peer(tmp_path_factory):
    if not PEER.is_dir():
        pytest.skip("peer-tests are not present")
    d = tmp_path_factory.mktemp("peer") / "xacro"
    shutil.copytree(PEER, d)
    return d


def expand_both(peer, name, doc, args=None, monkeypatch=None):
    """(ours, stock) for a wrapper document written to test/<name>, cwd = test/ as upstream."""
    from urdf_lint.expansion import expand_file
    from urdf_lint.discovery.packages import PackageResolver
    test = peer / "test"
    f = test / name
    f.write_text(doc)
    res = PackageResolver.build([peer], extra_roots=[peer])
    old = os.getcwd()
    os.chdir(test)
    try:
        ours = expand_file(name, args or {}, res, display_name=name)
        rc, out, err = stock_xacro(name, args or {}, res.scanned, cwd=str(test))
    finally:
        os.chdir(old)
    if rc == 0:
        assert ours.error is None, ours.error
        assert ours.xml == out
    else:
        assert ours.error is not None, f"stock failed ({err.strip()[-200:]}) but we did not"
    return ours


def body(xml):
    """Children of the root, serialised without whitespace or comments."""
    root = etree.fromstring(xml.encode(), etree.XMLParser(remove_blank_text=True, remove_comments=True))
    return "".join(etree.tostring(c, encoding="unicode") for c in root), root


def test_include_forms(peer):
    for doc in ['<xacro:include filename="include1.xml"/>',
                '<xacro:property name="file" value="include1.xml"/><xacro:include filename="${file}"/>',
                '<xacro:include filename="./include1.xml"/>']:
        got = expand_both(peer, "w_include.xacro", f"<a {X}>{doc}</a>")
        assert body(got.xml)[0] == "<inc1/>"


@pytest.mark.parametrize("pattern", ["include*.xml", "include?.xml", "include[1-2].xml"])
def test_include_glob(peer, pattern):
    got = expand_both(peer, "w_glob.xacro", f'<a {X}><xacro:include filename="{pattern}"/></a>')
    assert body(got.xml)[0] == "<inc1/><inc2/>"


def test_include_recursive(peer):
    got = expand_both(peer, "w_rec.xacro", f'<a {X}><xacro:include filename="subdir/include-recursive.xacro"/></a>')
    assert body(got.xml)[0] == "<subdir_inc1/><subdir_inc1/><inc1/>"


def test_include_from_macro(peer):
    doc = (f'<a {X}><xacro:macro name="foo" params="file:=include1.xml"><xacro:include filename="${{file}}"/></xacro:macro>'
           '<xacro:foo/><xacro:foo file="${xacro.abs_filename(\'include1.xml\')}"/>'
           '<xacro:include filename="subdir/foo.xacro"/><xacro:foo file="$(cwd)/subdir/include1.xml"/></a>')
    got = expand_both(peer, "w_macro_inc.xacro", doc)
    assert body(got.xml)[0] == "<inc1/><inc1/><subdir_inc1/><subdir_inc1/>"


def test_include_with_namespace(peer):
    doc = (f'<a {X}><xacro:property name="var" value="main"/>'
           '<xacro:include filename="include1.xacro" ns="A"/><xacro:include filename="include2.xacro" ns="B"/>'
           '<xacro:A.foo/><xacro:B.foo/><main var="${var}" A="${2*A.var}" B="${B.var+1}"/></a>')
    got = expand_both(peer, "w_ns.xacro", doc)
    assert body(got.xml)[0] == '<inc1/><inc2/><main A="2" B="3" var="main"/>'  # xacro sorts attributes


def test_namespace_propagation(peer):
    doc = f'<a {X}><xacro:include filename="include3.xacro" ns="C"/><xacro:C.foo/></a>'
    got = expand_both(peer, "w_nsprop.xacro", doc)
    assert body(got.xml)[0] == '<inc3 included="inner"/><inner/>'


def test_property_scope_parent_namespaced(peer):
    doc = (f'<a {X}><xacro:property name="prop" value="root"/>'
           '<xacro:include filename="A.xacro" ns="A"/>'
           '<a before="${prop}" a="${A.prop}" b="${A.B.prop}"/><xacro:A.B.set/><a after="${prop}"/></a>')
    got = expand_both(peer, "w_scope.xacro", doc)
    # A.xacro itself emits <A prop="B"/>: A.prop was set from A.B with scope="parent"
    assert body(got.xml)[0] == '<A prop="B"/><a a="B" b="b" before="root"/><a after="macro"/>'


@pytest.mark.parametrize("kind", ["inc1", "inc2"])
def test_yaml_support(peer, kind):
    doc = (f'<a {X}><xacro:arg name="type" default="{kind}"/>'
           '<xacro:property name="settings" value="${xacro.load_yaml(\'settings.yaml\')}"/>'
           '<xacro:property name="type" value="$(arg type)"/>'
           '<xacro:include filename="${settings.arms[type].file}"/>'
           '<xacro:call macro="${settings.arms[type].macro}"/>'
           '<port p="${settings.arms.inc2.props.port + 1}" has="${\'arms\' in settings}"/></a>')
    got = expand_both(peer, "w_yaml.xacro", doc)
    assert body(got.xml)[0] == f'<{kind}/><port has="True" p="4243"/>'


def test_yaml_missing_key_must_fail(peer):
    doc = f'<a {X}><xacro:property name="s" value="${{xacro.load_yaml(\'settings.yaml\')}}"/><x v="${{s.baz}}"/></a>'
    got = expand_both(peer, "w_yaml_bad.xacro", doc)
    assert got.error.code == "UL002" and "baz" in got.error.message


def test_yaml_lists(peer):
    doc = (f'<a {X}><xacro:property name="l" value="${{xacro.load_yaml(\'list.yaml\')}}"/>'
           '${l[0][1]} ${l[1][0]} ${l[2].a.A} ${l[2].a.B[0]} ${l[2].a.B[1]} ${l[2].b[0]}'
           '<xacro:property name="l2" value="${xacro.load_yaml(\'list2.yaml\')}"/>'
           '<b v="${[2*item.val.x for item in l2]}"/></a>')
    got = expand_both(peer, "w_list.xacro", doc)
    root = etree.fromstring(got.xml.encode())
    assert root.text.split() == ["A2", "B1", "1", "2", "3", "4"]
    assert root.find("b").get("v") == "[2, 4]"


def test_yaml_unit_constructors(peer):
    doc = (f'<a {X}><xacro:property name="c" value="${{xacro.load_yaml(\'constructors.yaml\')}}"/>'
           '<v a="${c.a}" b="${c.b}" c="${c.c}"/></a>')
    got = expand_both(peer, "w_units.xacro", doc)
    v = etree.fromstring(got.xml.encode()).find("v")
    assert math.isclose(float(v.get("a")), math.pi) and math.isclose(float(v.get("b")), math.pi / 2)
    assert v.get("c") == "42"


def test_noetic_unit_constructors(peer):
    shutil.copy(peer / "test-noetic" / "constructors.yaml", peer / "test" / "constructors_noetic.yaml")
    doc = (f'<a {X}><xacro:property name="c" value="${{xacro.load_yaml(\'constructors_noetic.yaml\')}}"/>'
           '<v n="${c.no_tag}" angles="${c.angles}" lengths="${c.lengths}"/></a>')
    got = expand_both(peer, "w_units2.xacro", doc)
    v = etree.fromstring(got.xml.encode()).find("v")
    assert v.get("n") == "42"
    assert [round(float(x), 9) for x in re.findall(r"[-\d.e]+", v.get("angles"))] == [round(math.pi, 9)] * 2
    assert [float(x) for x in re.findall(r"[-\d.e]+", v.get("lengths"))] == [25.0] * 4


@pytest.mark.parametrize("name", ["constructors_bad1.yaml", "constructors_bad2.yaml"])
def test_unit_constructors_with_code_must_fail(peer, name):
    doc = f'<a {X}><xacro:property name="c" value="${{xacro.load_yaml(\'{name}\')}}"/><v a="${{c}}"/></a>'
    got = expand_both(peer, "w_bad_units.xacro", doc)
    assert got.error is not None


def test_broken_include(peer):
    got = expand_both(peer, "w_broken.xacro", f'<a {X}><xacro:include filename="broken.xacro"/></a>')
    assert got.error.code == "UL001" and got.error.file.endswith("broken.xacro")


def test_error_reporting_names_the_macros(peer):
    got = expand_both(peer, "w_raise.xacro", f'<a {X}><xacro:include filename="raise.xacro"/><xacro:outer/></a>')
    e = got.error
    assert e.code == "UL002" and "undefined" in e.message
    assert "'inner' < 'outer'" in e.message
    assert e.file.endswith("raise.xacro") and e.line == 2
    assert [os.path.basename(c[0]) for c in e.chain] == ["w_raise.xacro", "raise.xacro"]


def test_print_location_output(peer):
    got = expand_both(peer, "w_loc.xacro", f'<a {X}><xacro:macro name="scope"><xacro:include filename="location.xacro"/></xacro:macro><xacro:scope/></a>')
    text, root = body(got.xml)
    assert root.tag == "a" and text == "" and not (root.text or "").strip()  # the document is <a/>


def test_unicode(peer):
    got = expand_both(peer, "w_emoji.xacro", f'<a {X}><xacro:include filename="emoji.xacro"/></a>')
    assert "🍔" in got.xml


def test_cmake_args(peer):
    got = expand_both(peer, "test-xacro-cmake/w.xacro", (peer / "test/test-xacro-cmake/test.xacro").read_text(),
                      {"bar": "foo", "foo": "bar"})
    assert body(got.xml)[1].attrib == {"foo": "bar", "bar": "foo"}
    got = expand_both(peer, "test-xacro-cmake/w2.xacro", (peer / "test/test-xacro-cmake/test.xacro").read_text())
    assert got.error.code == "UL005"


def test_namespace_lifting(peer):
    got = expand_both(peer, "w_nslift.xacro", f'<a xmlns:a="http://a" {X}><xacro:macro name="m"><xacro:include filename="namespace.xml"/></xacro:macro><xacro:m/></a>')
    assert 'xmlns:b="http://www.ros.org/b"' in got.xml


def test_inline_behaviours(peer):
    missing = expand_both(peer, "w_m.xacro", f'<a {X}><xacro:include filename="nope.xml"/></a>')
    assert missing.error.code == "UL003"
    optional = expand_both(peer, "w_o.xacro", f'<a {X}><xacro:include filename="nope.xml" optional="True"/></a>')
    assert optional.error is None
    lazy = expand_both(peer, "w_if.xacro", f'<a {X}><xacro:if value="false"><xacro:include filename="$(find nonexistent_package)/x.xacro"/></xacro:if></a>')
    assert lazy.error is None
    for bad in ('<xacro:property name="a.b" value="1"/>', '<xacro:property name="__x" value="1"/>',
                "${xacro.fatal('stop')}"):
        assert expand_both(peer, "w_bad.xacro", f'<a {X}>{bad}</a>').error is not None
    ns = expand_both(peer, "w_tns.xacro", f'<a {X} xacro:targetNamespace="http://t"><b/></a>')
    assert 'xmlns="http://t"' in ns.xml


def _xml_matches(a, b):
    """Upstream's comparison: names and attributes (any order), whitespace-collapsed text,
    numbers within 1e-9; comments ignored."""
    def num(s):
        try:
            return [float(x) for x in s.split()]
        except ValueError:
            return None

    def same(x, y):
        if x == y:
            return True
        nx, ny = num(x), num(y)
        return nx is not None and ny is not None and len(nx) == len(ny) and \
            all(abs(p - q) <= 1e-9 for p, q in zip(nx, ny))
    if a.tag != b.tag or set(a.attrib) != set(b.attrib):
        return False
    if not all(same(a.get(k), b.get(k)) for k in a.attrib):
        return False
    if not same(" ".join((a.text or "").split()), " ".join((b.text or "").split())):
        return False
    ca = [c for c in a if isinstance(c.tag, str)]
    cb = [c for c in b if isinstance(c.tag, str)]
    return len(ca) == len(cb) and all(_xml_matches(x, y) for x, y in zip(ca, cb))


def test_pr2_golden(peer):
    from urdf_lint.expansion import expand_file
    from urdf_lint.discovery.packages import PackageResolver
    res = PackageResolver.build([peer], extra_roots=[peer])
    got = expand_file(str(peer / "test/robots/pr2/pr2.urdf.xacro"), {}, res)
    assert got.error is None, got.error
    parser = etree.XMLParser(remove_comments=True, remove_blank_text=True)
    ours = etree.fromstring(got.xml.encode(), parser)
    golden = etree.parse(str(peer / "test/robots/pr2/pr2_1.11.4.xml"), parser).getroot()
    assert _xml_matches(ours, golden)
    assert len(ours.findall("link")) == 95 and len(ours.findall("joint")) == 94
