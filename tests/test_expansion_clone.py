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


def _expand(path, args=None, resolver=None, fast=True):
    saved = expand.FAST_CLONE
    expand.FAST_CLONE = fast
    try:
        return expand.expand_file(path, args or {}, resolver)
    finally:
        expand.FAST_CLONE = saved


def _same_expansion(a, b):
    return dataclasses.asdict(a) == dataclasses.asdict(b)


def _expand_counting(path):
    """(the fast expansion of ``path``, the name of each macro body clone_tree cloned)."""
    calls = []
    real = clone.clone_tree

    def counting(node, doc, parent=None):
        if parent is None:
            calls.append(node.getAttribute("name"))
        return real(node, doc, parent)

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
