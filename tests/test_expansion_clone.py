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


def test_the_expansion_is_the_same_with_the_fast_clone(tmp_path):
    """Macros calling macros, blocks, comments, CDATA: the same text, origins, chains and
    values, and the fast clone did the cloning."""
    p = tmp_path / "m.urdf.xacro"
    p.write_bytes(MACROS)
    calls = []
    real = clone.clone_tree

    def counting(node, doc, parent=None):
        if parent is None:
            calls.append(node.getAttribute("name"))
        return real(node, doc, parent)

    clone.clone_tree = counting
    try:
        fast = _expand(str(p))
    finally:
        clone.clone_tree = real
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
