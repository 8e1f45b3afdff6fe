"""The formatter's proof from the changed file alone (urdf_lint/formatting/inert.py, issue 27).

Every case lays a real file out with the formatter and checks what ``proven`` says against
xacro itself: the model is expanded with the file as it was and as laid out, and the two
robots compared as the proof compares them. A layout proved from the file must expand to the
same robot; each kind of layout it refuses is shown to change a robot, so the rule is needed."""
from __future__ import annotations

import re

import pytest

from conftest import run_cli
from urdf_lint.formatting.inert import proven
from urdf_lint.formatting.layout import format_source, read_document

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def _robot(tmp_path, files: dict, entry: str = "m.urdf.xacro"):
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.expansion import expand_file
    from urdf_lint.run.format import canonical_robot
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    res = expand_file(str(tmp_path / entry), {}, build_resolver([str(tmp_path)],
                                                                 load_config(None)))
    assert res.error is None, res.error
    return canonical_robot(res.xml)


def _case(tmp_path, main: str, lib: str):
    """(what proven says of lib's layout, whether the robot is the same once it is laid out)."""
    new = format_source(lib.encode()).decode()
    assert new != lib
    why = proven(read_document(lib.encode()), read_document(new.encode()))
    before = _robot(tmp_path, {"m.urdf.xacro": main, "lib.xacro": lib})
    after = _robot(tmp_path, {"m.urdf.xacro": main, "lib.xacro": new})
    return why, before == after


MAIN = (f'<robot name="m" {X}>\n  <xacro:include filename="lib.xacro"/>\n  <link name="l"/>\n'
        '  <gazebo><plugin name="p" filename="x.so"><robotNamespace>/r</robotNamespace>'
        '</plugin></gazebo>\n  <xacro:arm/>\n</robot>\n')


def test_whitespace_inside_elements_of_a_macro_body_is_proved_and_is_the_same_robot(tmp_path):
    # (next to the xacro:property the text nodes stay where they are, of one line each)
    lib = (f'<robot {X}>\n  <xacro:macro name="arm">\n    <link name="a"> <visual><geometry>'
           '<box size="1 1 1"/></geometry>   </visual> <xacro:property name="p" value="1"/> '
           '<collision>\n\n\n<geometry><box size="1 1 1"/></geometry></collision> </link>\n'
           '    <joint name="j" type="fixed">   <parent link="l"/> <child link="a"/> </joint>\n'
           '  </xacro:macro>\n</robot>\n')
    why, same = _case(tmp_path, MAIN, lib)
    assert same and why is None, why


def test_text_of_an_xacro_if_alone_in_an_element_is_not_proved(tmp_path):
    # xacro writes an element's single text child in line (<e>/arm</e>), more children one a
    # line: the new whitespace around the xacro:if puts the text on a line of its own
    lib = (f'<robot {X}>\n  <xacro:macro name="arm"><link name="a"/><gazebo><plugin name="q" '
           'filename="y.so"><robotNamespace><xacro:if value="1">/arm</xacro:if>'
           '</robotNamespace></plugin></gazebo></xacro:macro>\n</robot>\n')
    why, same = _case(tmp_path, MAIN, lib)
    assert not same and why is not None and "robotNamespace" in why, why


@pytest.mark.parametrize("body, proved", [
    # the body is spliced where the macro is called: here alone into an element, whose
    # single text child xacro writes in line, more children one a line
    ('<xacro:if value="1">/x</xacro:if>', False),
    # two text nodes around the xacro:if: wherever the body lands, the element has more than
    # one child, and xacro writes such an element without its whitespace-only text (this pins
    # that behaviour of xacro's writer, which the proof relies on)
    (' <xacro:if value="1">/x</xacro:if> ', True),
])
def test_whitespace_directly_in_a_macro_body_without_elements(tmp_path, body, proved):
    main = MAIN.replace("<robotNamespace>/r</robotNamespace>",
                        "<robotNamespace><xacro:t/></robotNamespace>")
    lib = (f'<robot {X}>\n  <xacro:macro name="arm"><link name="a"/></xacro:macro>\n'
           f'  <xacro:macro name="t">{body}</xacro:macro>\n</robot>\n')
    why, same = _case(tmp_path, main, lib)
    assert same == proved and (why is None) == proved, why
    assert proved or "xacro:macro" in why


def test_the_root_of_an_included_file_without_elements_is_not_proved(tmp_path):
    # the root's children are spliced where it is included: here alone into an element
    main = MAIN.replace("<robotNamespace>/r</robotNamespace>",
                        '<robotNamespace><xacro:include filename="lib2.xacro"/></robotNamespace>')
    (tmp_path / "lib2.xacro").write_text(f'<robot {X}><xacro:if value="1">/x</xacro:if></robot>')
    lib = f'<robot {X}><xacro:macro name="arm"><link name="a"/></xacro:macro></robot>\n'
    before = _robot(tmp_path, {"m.urdf.xacro": main, "lib.xacro": lib})
    lib2 = (tmp_path / "lib2.xacro").read_bytes()
    new = format_source(lib2)
    assert "<robot>" in (proven(read_document(lib2), read_document(new)) or "")
    (tmp_path / "lib2.xacro").write_bytes(new)
    assert _robot(tmp_path, {"m.urdf.xacro": main}) != before


def test_whitespace_whose_shape_xacro_reads_next_to_its_elements_is_not_proved(tmp_path):
    # after an xacro element that something precedes, xacro inserts one shared "\n\n" text
    # node, moving it from where it was: here out of an element in another file, whose text
    # is then written in line instead of on a line of its own
    main = (f'<robot name="m" {X}>\n  <link name="l"/>\n  <gazebo><plugin name="p" '
            'filename="x.so"><robotNamespace>/r<xacro:property name="z" value="1"/>'
            '<xacro:property name="z2" value="1"/></robotNamespace></plugin></gazebo>'
            '<xacro:include filename="lib.xacro"/></robot>\n')   # (the last one it moves)
    lib = f'<robot {X}><link name="k"><xacro:property name="a" value="1"/></link></robot>\n'
    why, same = _case(tmp_path, main, lib)
    assert not same and why is not None and "shape" in why, why


def test_a_changed_attribute_order_is_left_to_the_expansion():
    from urdf_lint.formatting.layout import Style
    old = f'<robot {X}><link type="x" name="a">  <visual/></link></robot>\n'.encode()
    new = format_source(old, Style(attribute_order="canonical"))
    assert b'<link name="a" type="x">' in new
    assert "differs" in (proven(read_document(old), read_document(new)) or "")


def test_format_proves_from_the_file_and_expands_only_for_the_rest(tmp_path):
    from conftest import make_package
    lib = (f'<robot {X}>\n<xacro:macro name="arm"><link name="a"><visual>   <geometry>'
           '<box size="1 1 1"/></geometry></visual></link></xacro:macro>\n</robot>\n')
    main = MAIN.replace("<robotNamespace>/r</robotNamespace>",
                        "<robotNamespace><xacro:t/></robotNamespace>")
    t = '<xacro:macro name="t"><xacro:if value="1">/x</xacro:if></xacro:macro>'
    pkg = make_package(tmp_path, "p", {"urdf/m.urdf.xacro": main, "urdf/lib.xacro": lib,
                                       "urdf/t.xacro": f'<robot {X}>{t}</robot>\n'})
    (pkg / "urdf" / "m.urdf.xacro").write_text(main.replace(
        '<link name="l"/>', '<link name="l"/>\n  <xacro:include filename="t.xacro"/>'))
    p = run_cli("format", pkg, cwd=pkg)
    assert p.returncode == 0, p.stderr
    # lib.xacro is proved by itself; t.xacro's macro body is not, nor the root of m.urdf.xacro
    # (its <gazebo> on lines of its own): the models are expanded for them, and left alone
    # (together: the model reads both); lib.xacro is not refused with them
    assert "urdf/t.xacro: left alone: formatting would change the robot" in p.stderr, p.stderr
    assert "urdf/m.urdf.xacro: left alone: formatting would change the robot" in p.stderr
    assert re.search(r"1 file\(s\) reformatted, 0 file\(s\) left unchanged, 2 file\(s\) left "
                     r"alone \(1 proved from the file itself, [1-9]\d* model\(s\) expanded", p.stderr)
    assert (pkg / "urdf" / "lib.xacro").read_text() == format_source(lib.encode()).decode()


def test_an_unchanged_file_is_proved():
    doc = read_document(f'<robot {X}><link name="a"/></robot>'.encode())
    assert proven(doc, doc) is None


COLOURS = (f'<?xml version="1.0"?>\n<robot {X}>\n\n  <!-- yellow -->\n'
           '  <xacro:property name="yellow"   value="0.96 0.76 0.13 1.0" />\n'
           '  <!-- white -->\n  <xacro:property name="white" value="0.86 0.85 0.81 1.0" />\n\n\n'
           '  <xacro:macro name="arm"><link name="a"><visual><geometry><box size="1 1 1"/>'
           '</geometry><material name="y"><color rgba="${yellow}"/></material></visual></link>'
           '</xacro:macro>\n</robot>\n')


def test_reads_quietly_wants_two_nodes_that_reach_the_robot_next_to_xacro_elements():
    from urdf_lint.formatting.inert import reads_quietly
    quiet = f'<robot {X}>\n  <link name="a"/>\n  <xacro:property name="p" value="1"/>\n</robot>'
    assert reads_quietly(read_document(quiet.encode()))
    assert reads_quietly(read_document(COLOURS.encode()))
    for loud in (f'<robot {X}><link name="a"/><xacro:property name="p" value="1"/></robot>',
                 f'<robot {X}>\n<link name="k"><xacro:property name="a" value="1"/></link></robot>',
                 f'<robot {X}>\n<link name="k"> <xacro:if value="1"/></link></robot>'):
        assert not reads_quietly(read_document(loud.encode())), loud
    # xacro:attribute and insert_block do not read the text before them
    assert reads_quietly(read_document(
        f'<robot {X}><link name="k"><xacro:attribute name="n" value="1"/></link></robot>'.encode()))


def test_a_new_shape_next_to_xacro_elements_is_proved_when_every_file_reads_quietly(tmp_path):
    # a blank line after <robot> removed before a comment and an xacro:property (xacro then
    # removes that comment, and moves its "\n\n" node, differently): every file of the model
    # holds two nodes that reach the robot wherever xacro reads, so it writes the same robot
    from conftest import make_package
    main = MAIN.replace('<xacro:include filename="lib.xacro"/>',
                        '<xacro:include filename="lib.xacro"/>\n  <link name="m"/>')
    pkg = make_package(tmp_path, "p", {"urdf/m.urdf.xacro": main, "urdf/lib.xacro": COLOURS})
    lib = pkg / "urdf" / "lib.xacro"
    new = format_source(COLOURS.encode())
    assert proven(read_document(COLOURS.encode()), read_document(new)) is not None
    assert proven(read_document(COLOURS.encode()), read_document(new), quiet_reads=True) is None
    before = _robot(pkg / "urdf", {})
    p = run_cli("format", "urdf/lib.xacro", cwd=pkg)
    assert p.returncode == 0 and "1 file(s) reformatted" in p.stderr, p.stderr
    assert "(1 proved from the file itself, 0 model(s) expanded" in p.stderr, p.stderr
    assert lib.read_bytes() == new
    assert _robot(pkg / "urdf", {}) == before


def test_a_new_shape_is_expanded_when_a_file_of_the_model_does_not_read_quietly(tmp_path):
    # the same change, with the model's main file holding an xacro element alone in text
    # (test_whitespace_whose_shape_xacro_reads_next_to_its_elements_is_not_proved): expanded,
    # and left alone as the robot changes
    from conftest import make_package
    main = (f'<robot name="m" {X}>\n  <link name="l"/>\n  <gazebo><plugin name="p" '
            'filename="x.so"><robotNamespace>/r<xacro:property name="z" value="1"/>'
            '<xacro:property name="z2" value="1"/></robotNamespace></plugin></gazebo>'
            '<xacro:include filename="lib.xacro"/></robot>\n')
    lib = (f'<robot {X}>\n<link name="k"><visual><geometry><box size="1 1 1"/></geometry>'
           '</visual><xacro:property name="a" value="1"/></link></robot>\n')
    new = format_source(lib.encode())   # (so xacro's "\n\n" node moves into <link>)
    assert proven(read_document(lib.encode()), read_document(new)) is not None
    assert proven(read_document(lib.encode()), read_document(new), quiet_reads=True) is None
    pkg = make_package(tmp_path, "p", {"urdf/m.urdf.xacro": main, "urdf/lib.xacro": lib})
    before = _robot(pkg / "urdf", {})
    (pkg / "urdf" / "lib.xacro").write_bytes(new)
    assert _robot(pkg / "urdf", {}) != before      # it would change the robot
    (pkg / "urdf" / "lib.xacro").write_text(lib)
    p = run_cli("format", "urdf/lib.xacro", cwd=pkg)
    assert p.returncode == 0, p.stderr
    assert "urdf/lib.xacro: left alone: formatting would change the robot" in p.stderr, p.stderr
    assert re.search(r"\(0 proved from the file itself, [1-9]\d* model\(s\) expanded", p.stderr)
    assert (pkg / "urdf" / "lib.xacro").read_text() == lib


@pytest.mark.parametrize("seed", [3])
def test_random_layouts_of_real_xacros_are_proved_soundly(tmp_path, seed):
    # xacro's own test inputs and a real description, every gap between two tags replaced by
    # one of several shapes (none, a space, blank lines, ...), or, in some files, by none at
    # all (where the new layout may change robots): formatted with the proof, and
    # every model expanded as it was and as written must be the same robot, whether its files
    # were proved from themselves or by expanding the models
    import random
    import shutil

    from conftest import CORPUS
    from test_format import _robots
    if not (CORPUS / "MANIFEST.md").is_file():
        pytest.skip("../shared/corpus is not present")
    rnd = random.Random(seed)
    shapes = [b"><", b"> <", b">\n<", b">\n\n<", b">\n\n\n  <", b">  \n <"]
    for part in ("peer-tests/xacro", "ur_description"):
        shutil.copytree(CORPUS / part, tmp_path / part,
                        ignore=shutil.ignore_patterns("*.stl", "*.dae", "*.STL", "*.DAE"))
    for f in sorted(tmp_path.rglob("*")):
        if f.suffix in (".urdf", ".xacro"):
            tight = rnd.random() < 0.3     # no whitespace at all: formatting it changes robots
            f.write_bytes(re.sub(rb">\s*<", lambda m, t=tight: b"><" if t else rnd.choice(shapes),
                                 f.read_bytes()))
    before = _robots(tmp_path)
    p = run_cli("format", ".", cwd=tmp_path, timeout=900)
    m = re.search(r"(\d+) file\(s\) reformatted.*\((\d+) proved from the file itself, (\d+) "
                  r"model\(s\) expanded", p.stderr)
    after = _robots(tmp_path)
    assert [k for k in before if before[k] != after[k]] == []
    assert m and int(m.group(1)) > 30 and int(m.group(2)) > 10 and int(m.group(3)) > 10, p.stderr
    assert "left alone: formatting would change the robot" in p.stderr   # the proof was needed
    assert sum(1 for v in before.values() if not isinstance(v, str)) > 40
