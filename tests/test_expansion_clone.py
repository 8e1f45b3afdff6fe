"""Macro bodies cloned by urdf_lint.expansion.clone: minidom's clone, node for node, and the
same expansion (text, source lines, macro chains, values) as with minidom's cloneNode."""
from __future__ import annotations

import dataclasses
from xml.dom import minidom

import pytest

from conftest import corpus_entries
from urdf_lint.expansion import clone, expand

MACROS = b"""<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro" xmlns:gz="http://gazebosim.org/schema">
  <!-- a comment before the macro -->
  <xacro:macro name="leg" params="prefix *origin **extra len:=0.5">
    <!-- a comment in the body -->
    <link name="${prefix}_leg" gz:kind="leg">
      <visual><geometry><box size="0.1 0.1 ${len}"/></geometry></visual>
      <xacro:insert_block name="extra"/>
    </link>
    <joint name="${prefix}_joint" type="fixed">
      <parent link="base"/><child link="${prefix}_leg"/>
      <xacro:insert_block name="origin"/>
    </joint>
    <gazebo><![CDATA[<plugin> raw & text </plugin>]]></gazebo>
    <?pi some data?>
    text between <b>elements</b> and after
  </xacro:macro>
  <xacro:macro name="two" params="p">
    <xacro:leg prefix="${p}a"><origin xyz="0 0 1"/><inertial/></xacro:leg>
    <xacro:leg prefix="${p}b" len="1"><origin xyz="0 1 0"/><inertial/></xacro:leg>
  </xacro:macro>
  <link name="base"/>
  <xacro:two p="x"/>
  <xacro:two p="y"/>
</robot>
"""


def _bodies(data: bytes, path: str):
    """The macro elements of a parsed document, stamped as the expansion stamps them."""
    doc = expand.parse_bytes(data, path)
    return doc, doc.getElementsByTagName("xacro:macro")


def test_a_macro_bodys_clone_is_minidoms_node_for_node():
    doc, bodies = _bodies(MACROS, "/r/m.xacro")
    assert len(bodies) == 2
    for body in bodies:
        for mark in (False, True):          # before and after the template marks
            if mark:
                expand._mark_template(body)
            want = minidom.Element.cloneNode(body, True)
            got = clone.clone_tree(body, doc)
            assert clone.same_tree(want, got)
            assert want.toxml() == got.toxml()
    assert clone.usable(bodies[0])


def test_same_tree_tells_apart_what_a_reader_would_see():
    """The check that guards the fast clone is not blind: each kind of difference fails it."""
    doc, bodies = _bodies(MACROS, "/r/m.xacro")
    body = bodies[0]

    def changed(edit):
        c = clone.clone_tree(body, doc)
        edit(c)
        return clone.same_tree(minidom.Element.cloneNode(body, True), c)

    assert not changed(lambda c: c.getElementsByTagName("link")[0].setAttribute("name", "x"))
    assert not changed(lambda c: c.getElementsByTagName("link")[0].removeAttribute("gz:kind"))
    assert not changed(lambda c: c.getElementsByTagName("box")[0].setUserData(expand.KEY, None, None))
    assert not changed(lambda c: c.removeChild(c.lastChild))
    assert not changed(lambda c: setattr(c.getElementsByTagName("joint")[0], "nextSibling", None))
    link = body.getElementsByTagName("link")[0]       # attribute order
    a, b = clone.clone_tree(body, doc), minidom.Element.cloneNode(body, True)
    la = a.getElementsByTagName("link")[0]
    la._attrs = dict(reversed(list(la._attrs.items())))
    assert len(link._attrs) == 2 and not clone.same_tree(b, a)


def _expand(path, args=None, resolver=None, fast=True, parse_cache=True):
    saved = expand.FAST_CLONE, expand.PARSE_CACHE
    expand.FAST_CLONE, expand.PARSE_CACHE = fast, parse_cache
    try:
        return expand.expand_file(path, args or {}, resolver)
    finally:
        expand.FAST_CLONE, expand.PARSE_CACHE = saved


def _same_expansion(a, b):
    return dataclasses.asdict(a) == dataclasses.asdict(b)


def _expand_counting(path):
    """(the fast expansion of ``path``, the name of each macro body clone_tree cloned)."""
    calls = []
    real = clone.clone_tree

    def counting(node, doc, parent=None, restamp=None):
        if parent is None and restamp is None:
            calls.append(node.getAttribute("name"))
        return real(node, doc, parent, restamp)

    clone.clone_tree = counting
    try:
        return _expand(path), calls
    finally:
        clone.clone_tree = real


def test_the_expansion_is_the_same_with_the_fast_clone(tmp_path):
    """Macros calling macros, blocks, comments, CDATA: the same text, origins, chains and
    values, and the fast clone did the cloning."""
    p = tmp_path / "m.urdf.xacro"
    p.write_bytes(MACROS)
    fast, calls = _expand_counting(str(p))
    slow = _expand(str(p), fast=False)
    assert fast.error is None and fast.xml.count("<link ") == 5
    assert sorted(calls) == ["leg"] * 4 + ["two"] * 2
    assert _same_expansion(fast, slow)
    # the chain of a link made by leg inside two: both calls
    chains = [o[3] for o in fast.origins if o is not None and len(o[3]) == 2]
    assert chains


@pytest.mark.parametrize("entry,args", corpus_entries()[::2] or [("-", {})])
def test_corpus_expansions_are_the_same_with_the_fast_clone(entry, args, corpus, corpus_resolver):
    path = str(corpus / entry)
    fast = _expand(path, args, corpus_resolver)
    slow = _expand(path, args, corpus_resolver, fast=False)
    assert _same_expansion(fast, slow), entry


X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
NESTED = f"""<?xml version="1.0"?>
<robot name="r" {X} xmlns:foo="http://foo">
  <xacro:include filename="parts.xacro"/>
  <xacro:macro name="outer" params="p" xmlns:bar="http://bar">
    <!-- outer -->
    <xacro:macro name="inner" params="q">
      <link name="${{p}}_${{q}}" bar:x="${{q}}" xml:lang="en"><?pi ${{q}}?><![CDATA[ <raw> ]]></link>
    </xacro:macro>
    <xacro:inner q="a"/>
    <xacro:call macro="inner" q="b"/>
    <xacro:element xacro:name="gen_${{p}}" k="${{p}}">
      <xacro:attribute name="foo:d" value="v${{p}}"/></xacro:element>
  </xacro:macro>
  <xacro:outer p="x"/>
  <xacro:outer p="y"/>
  <xacro:macro name="rd"><link name="rd1"/></xacro:macro>
  <xacro:rd/>
  <xacro:macro name="rd"><link name="rd2" xmlns:q="http://q" q:z="1"/></xacro:macro>
  <xacro:property name="mn" value="rd"/>
  <xacro:call macro="${{mn}}"/>
  <xacro:wrap><defs><xacro:macro name="fromblock" params="k"><link name="fb_${{k}}"/></xacro:macro>
    <xacro:fromblock k="1"/><xacro:part n="inblock"/></defs></xacro:wrap>
  <xacro:part n="top"/>
</robot>
"""
PARTS = f"""<?xml version="1.0"?>
<robot {X}>
  <xacro:macro name="part" params="n"><link name="part_${{n}}"><!-- c --></link></xacro:macro>
  <xacro:macro name="wrap" params="**b">
    <xacro:insert_block name="b"/><xacro:insert_block name="b"/></xacro:macro>
  <xacro:part n="inc"/>
</robot>
"""


def test_nested_redefined_dynamic_and_included_macros_expand_the_same(tmp_path):
    """Macros defined inside macros (their body is itself a fast clone), redefined, called by
    xacro:call, defined in a block, from an included file, with namespaces on the macro and in
    its body, xacro:element/attribute: the same expansion as with minidom's clone."""
    (tmp_path / "parts.xacro").write_text(PARTS)
    p = tmp_path / "n.urdf.xacro"
    p.write_text(NESTED)
    fast, calls = _expand_counting(str(p))
    slow = _expand(str(p), fast=False)
    assert fast.error is None, fast.error
    for name in ("x_a", "x_b", "y_a", "y_b", "rd1", "rd2", "fb_1", "part_inblock", "part_top"):
        assert f'name="{name}"' in fast.xml
    assert fast.xml.count('name="fb_1"') == 2 and 'foo:d="vy"' in fast.xml
    # the inner macro's body came from the outer's fast clone, and was fast-cloned in turn
    assert sorted(set(calls)) == ["fromblock", "inner", "outer", "part", "rd", "wrap"]
    assert calls.count("inner") == 4
    assert _same_expansion(fast, slow)
    chains = {len(o[3]) for o in fast.origins if o is not None}
    assert {0, 1, 2} <= chains


# -- a file parsed again and again: copied from its second parse -------------------------------
def _same_parse(a, b) -> bool:
    """Whether documents ``a`` and ``b`` are alike node for node in everything the expansion
    reads: the XML declaration, classes, names, local names, namespaces, values, attributes
    (in order, with their text), user data, parent and sibling links, each node owned by its
    own document."""
    if (a.version, a.encoding, a.standalone, a.doctype) != (b.version, b.encoding,
                                                            b.standalone, b.doctype):
        return False

    def walk(x, doc):
        yield x, doc
        for k in x.childNodes:
            yield from walk(k, doc)
    na, nb = list(walk(a, a)), list(walk(b, b))
    if len(na) != len(nb):
        return False
    for (x, da), (y, db) in zip(na, nb, strict=True):
        if type(x) is not type(y) or (x is not da and (x.ownerDocument is not da
                                                        or y.ownerDocument is not db)):
            return False
        for f in ("nodeName", "nodeValue", "prefix", "namespaceURI", "localName", "_localName"):
            if getattr(x, f, None) != getattr(y, f, None):
                return False
        if getattr(x, "_user_data", None) != getattr(y, "_user_data", None):
            return False
        for link in ("parentNode", "previousSibling", "nextSibling"):
            px, py = getattr(x, link, None), getattr(y, link, None)
            ix = next((i for i, (n, _) in enumerate(na) if n is px), None)
            iy = next((i for i, (n, _) in enumerate(nb) if n is py), None)
            if ix != iy:
                return False
        if x.nodeType == x.ELEMENT_NODE:
            ax, ay = list((x._attrs or {}).items()), list((y._attrs or {}).items())
            if [(k, v.value, v.namespaceURI, v.prefix, v.localName, v.ownerElement is x)
                    for k, v in ax] != \
                    [(k, v.value, v.namespaceURI, v.prefix, v.localName, v.ownerElement is y)
                     for k, v in ay]:
                return False
            if list(x._attrsNS or {}) != list(y._attrsNS or {}):
                return False
    return True


def test_a_copied_parse_is_a_new_parse_node_for_node(tmp_path):
    """From the third parse of the same bytes on, the document is a copy of the second one,
    stamped with the including chain of the moment: the same document a new parse gives."""
    for name, data in (("m.xacro", MACROS), ("n.xacro", NESTED.encode()),
                       ("p.xacro", PARTS.encode()),
                       ("d.xacro", b'<?xml version="1.0" encoding="UTF-8" standalone="yes"?>'
                                   b'<?top pi?><!-- top --><robot name="x"/><!-- end -->')):
        path = str(tmp_path / name)
        expand._parsed.clear()
        chains = [((path, 1, 1),), (), (("/a", 2, 3), ("/b", 4, 5))]
        docs = [expand.parsed(data, path, c, "d" * 32) for c in chains]
        assert isinstance(expand._parsed[(path, "d" * 32)], tuple), "kept from the second parse"
        for doc, chain in zip(docs, chains, strict=True):
            assert _same_parse(doc, expand.parse_bytes(data, path, chain)), (name, chain)
        assert not _same_parse(docs[2], expand.parse_bytes(data, path, chains[0])), \
            "the chain is the copy's own"
        docs[2].documentElement.setAttribute("name", "changed")   # a copy: the kept one is not
        again = expand.parsed(data, path, (), "d" * 32)
        assert _same_parse(again, expand.parse_bytes(data, path, ()))


def test_a_document_with_a_doctype_is_parsed_every_time(tmp_path):
    p = tmp_path / "d.urdf.xacro"
    p.write_text('<?xml version="1.0"?><!DOCTYPE robot><robot name="r"><link name="a"/></robot>')
    expand._parsed.clear()
    runs = [_expand(str(p)) for _ in range(4)]
    assert all(_same_expansion(r, runs[0]) for r in runs)
    assert any("DOCTYPE" in str(n) for n in dataclasses.astuple(runs[3]))   # noted every time
    assert not any(isinstance(v, tuple) for v in expand._parsed.values())


@pytest.mark.parametrize("entry,args", corpus_entries()[1::2] or [("-", {})])
def test_corpus_expansions_are_the_same_with_copied_parses(entry, args, corpus, corpus_resolver):
    """Each of its files parsed twice already: the third expansion reads copies, and is the
    expansion of fresh parses (text, source lines, macro chains, values, notes)."""
    path = str(corpus / entry)
    expand._parsed.clear()
    copied = [_expand(path, args, corpus_resolver) for _ in range(3)][2]
    assert copied.error is not None or any(isinstance(v, tuple) for v in
                                           expand._parsed.values()), "nothing was copied"
    fresh = _expand(path, args, corpus_resolver, parse_cache=False)
    assert _same_expansion(copied, fresh), entry


def test_the_parse_cache_keeps_what_its_bound_says_of_a_file_of_tiny_elements(tmp_path,
                                                                            monkeypatch):
    """PARSED_BYTES bounds what the parse cache keeps at ~25 bytes of DOM per byte of source;
    a file of many tiny elements (``<a/>``: ~120 bytes of DOM per byte) must not keep five
    times that in a worker between its jobs (it counts against every later job's memory-mb)."""
    import gc
    import tracemalloc
    monkeypatch.setattr(expand, "PARSED_BYTES", 20_000)
    expand._parsed.clear()
    data = b"<robot name='r'>" + b"<a/>" * 4_500 + b"</robot>"     # (18 kB: under the bound)
    f = str(tmp_path / "tiny.xacro")
    tracemalloc.start()
    try:
        for _ in range(2):
            expand.parsed(data, f, (), "0" * 32)
        gc.collect()      # (the parses returned: cycles)
        kept = tracemalloc.get_traced_memory()[0]
    finally:
        tracemalloc.stop()
        expand._parsed.clear()
    assert kept <= 25 * 20_000 * 1.5, kept
