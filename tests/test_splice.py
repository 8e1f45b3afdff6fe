"""The linear-time node replacement (urdf_lint/expansion/splice.py) gives stock xacro's bytes, on the shapes
that exercise it: many sibling macro calls, deep recursion through xacro:if, comments removed
before calls, insert_block (single and multi), includes and conditionals. The corpus byte-identity
test (test_expand_corpus.py) covers real robots; bench/bench_scaling.py measures the speed."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))
from bench_scaling import deep_robot, flat_robot  # noqa: E402
from stock_xacro import stock_xacro  # noqa: E402

from urdf_lint.expansion import splice  # noqa: E402
from urdf_lint.expansion import expand_file  # noqa: E402
from urdf_lint.discovery.packages import PackageResolver  # noqa: E402

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'

MIXED = f"""<?xml version="1.0"?>
<!-- top comment -->
<robot name="mixed" {X}>
  <xacro:include filename="parts.xacro"/>
  <xacro:macro name="wrap" params="n *first **rest">
    <!-- kept comment -->
    <link name="${{n}}"><xacro:insert_block name="first"/></link>
    <xacro:insert_block name="rest"/>
  </xacro:macro>
  <!-- removed before the call -->

  <!-- this one too -->
  <xacro:part n="a"/>
  <xacro:wrap n="b">
    <visual><geometry><box size="1 1 1"/></geometry></visual>
    <stuff><joint name="jb" type="fixed"><parent link="a"/><child link="b"/></joint></stuff>
  </xacro:wrap>
  <xacro:if value="true"><!-- in if --><link name="c"/>text<link name="d"/></xacro:if>
  <xacro:unless value="true"><link name="e"/></xacro:unless>
  <xacro:property name="p" value="1"/>
  <xacro:arg name="q" default="2"/>
  <link name="f${{p}}$(arg q)"><xacro:attribute name="x" value="1"/></link>
  <xacro:element xacro:name="link" name="g"/>
</robot>
"""
PARTS = f"""<?xml version="1.0"?>
<robot {X}>
  <!-- parts -->
  <xacro:macro name="part" params="n"><link name="${{n}}"/><!-- after --></xacro:macro>
</robot>
"""


@pytest.mark.parametrize("name,text", [
    ("flat.urdf.xacro", flat_robot(300)),
    ("deep.urdf.xacro", deep_robot(60)),
    ("mixed.urdf.xacro", MIXED),
])
def test_spliced_expansion_is_byte_identical_to_stock(tmp_path, name, text):
    pkg = tmp_path / "p"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>p</name></package>")
    (pkg / "urdf" / "parts.xacro").write_text(PARTS)
    f = pkg / "urdf" / name
    f.write_text(text)
    rc, out, err = stock_xacro(str(f), {}, {"p": str(pkg)}, cwd=str(pkg / "urdf"))
    assert rc == 0, err
    ours = expand_file(str(f), resolver=PackageResolver.build([str(pkg)], extra_roots=[str(pkg)]))
    assert ours.error is None, ours.error
    assert splice._orig, "the splice hooks are installed by the expansion"
    assert ours.xml == out


def _consistent(node):
    kids = node.childNodes
    for i, c in enumerate(kids):
        assert c.parentNode is node
        assert c.previousSibling is (kids[i - 1] if i else None)
        assert c.nextSibling is (kids[i + 1] if i + 1 < len(kids) else None)
        _consistent(c)


@pytest.mark.parametrize("content_only", [True, False])
@pytest.mark.parametrize("where", [0, 3, 6])
def test_replace_node_matches_minidom_edits(where, content_only):
    """The same edit through the splice and through xacro's own replace_node gives the same
    tree, with every parent/sibling pointer consistent."""
    from xml.dom import minidom
    from xacro import xmlutils

    src = "<r>" + "".join(f"<a{i}/>t{i}<!--c{i}-->" for i in range(3)) + "</r>"
    trees = []
    for fn in (splice.replace_node, xmlutils.replace_node):
        splice.reset()
        doc = minidom.parseString(src)
        root = doc.documentElement
        node = root.childNodes[where]
        by = minidom.parseString("<b>x<c/><!--k--><d/></b>").documentElement
        if not content_only:
            by.parentNode.removeChild(by)
        fn(node, by=by, content_only=content_only)
        _consistent(root)
        trees.append(root.toxml())
    assert trees[0] == trees[1]
