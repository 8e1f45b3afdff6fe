"""``urdf-lint format`` (issue 27): the layout rules on pinned inputs, what is kept byte for
byte, the guard, the CLI's exit codes and config, the proof on the expanded robots (a layout
that would change a robot is refused), and the whole corpus formatted in a copy."""
from __future__ import annotations

import codecs
import os
import re
import shutil
from pathlib import Path

import pytest

from conftest import CORPUS, run_cli
from urdf_lint.formatting.layout import FormatError, Refused, Style, format_source

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def fmt(text: str, **style) -> str:
    out = format_source(text.encode("utf-8"), Style(**style)).decode("utf-8")
    assert format_source(out.encode("utf-8"), Style(**style)).decode("utf-8") == out, \
        "not idempotent"
    return out


# -- the layout rules -----------------------------------------------------------------------------
def test_one_element_per_line_children_indented_empty_self_closed():
    src = ('<robot name="r"><link   name = "a" ></link><joint name="j" type="fixed">'
           '<parent link="a" /><child link="b"/></joint></robot>')
    assert fmt(src) == ('<robot name="r">\n'
                        '  <link name="a"/>\n'
                        '  <joint name="j" type="fixed">\n'
                        '    <parent link="a"/>\n'
                        '    <child link="b"/>\n'
                        '  </joint>\n'
                        '</robot>\n')
    assert fmt(src, indent=4).splitlines()[2] == '    <joint name="j" type="fixed">'


def test_blank_line_runs_collapse_to_one_and_go_after_a_start_tag():
    src = '<robot name="r">\n\n\n  <link name="a"/>\n\n\n\n  <link name="b"/>\n\n</robot>\n'
    assert fmt(src) == '<robot name="r">\n  <link name="a"/>\n\n  <link name="b"/>\n</robot>\n'


def test_whitespace_only_structural_elements_are_self_closed_others_kept():
    src = ('<robot name="r">\n  <link name="a">\n  </link>\n'
           '  <gazebo><robotNamespace>  </robotNamespace></gazebo>\n</robot>')
    out = fmt(src)
    assert '  <link name="a"/>\n' in out
    assert "<robotNamespace>  </robotNamespace>" in out   # its text is read: kept


def test_long_start_tags_wrap_one_attribute_per_line():
    src = ('<robot name="r"><inertia ixx="0.0001234" ixy="0" ixz="0" iyy="0.0001234" iyz="0" '
           'izz="0.0001234"/></robot>')
    assert fmt(src, line_length=60) == ('<robot name="r">\n'
                                        '  <inertia ixx="0.0001234"\n'
                                        '           ixy="0"\n'
                                        '           ixz="0"\n'
                                        '           iyy="0.0001234"\n'
                                        '           iyz="0"\n'
                                        '           izz="0.0001234"/>\n'
                                        '</robot>\n')
    assert fmt(src).count("\n") == 3                       # fits in 100
    long_name = "xacro:a_macro_with_a_really_long_name_for_testing"
    out = fmt(f'<robot {X}><{long_name} prefix="left_" parent="base_link"/></robot>',
              line_length=60)
    assert f"  <{long_name}\n      prefix=\"left_\"\n      parent=\"base_link\"/>\n" in out


def test_canonical_attribute_order_name_first_then_the_schema():
    src = ('<robot name="r"><joint type="fixed" name="j"><origin rpy="0 0 1" xyz="1 0 0"/>'
           '<limit velocity="1" effort="2" upper="3" lower="-3" extra="x"/></joint></robot>')
    out = fmt(src, attribute_order="canonical")
    assert '<joint name="j" type="fixed">' in out
    assert '<origin xyz="1 0 0" rpy="0 0 1"/>' in out
    assert '<limit lower="-3" upper="3" effort="2" velocity="1" extra="x"/>' in out
    assert '<joint type="fixed" name="j">' in fmt(src)      # default: kept as written


# -- what is kept ---------------------------------------------------------------------------------
SPACED = ('<?xml version="1.0"?>\n<robot name="r">\n'
          '  <link name="a" />\n'
          '  <link name="b"></link>\n'
          '  <joint name="j" type="fixed">\n'
          '    <parent link="a" />\n'
          '    <child link="b"/>\n'
          '  </joint>\n'
          '</robot>\n')


def test_self_closing_style_follows_the_files_majority():
    """A file that writes ``<a />`` (two of three self-closed tags) keeps that style: the
    empty ``<link name="b">`` and the minority ``<child link="b"/>`` become `` />``, the rest
    stays; a file formatted already in that style is unchanged (adopting ``format`` is no
    churn commit). ``compact`` and ``spaced`` choose it whatever the file writes."""
    out = fmt(SPACED)
    assert out == SPACED.replace('"b"></link>', '"b" />').replace('"b"/>', '"b" />'), out
    assert format_source(out.encode()) == out.encode()   # formatted already: unchanged
    assert fmt(SPACED, self_closing="compact").count(" />") == 0
    assert fmt(SPACED.replace(" />", "/>"), self_closing="spaced").count(" />") == 4
    assert fmt(SPACED.replace(" />", "/>")).count(" />") == 0   # most are compact


def test_self_closing_from_the_config_and_the_flag(tmp_path):
    from conftest import run_main
    f = tmp_path / "r.urdf"
    f.write_text(SPACED)
    (tmp_path / "urdf-lint.toml").write_text('[format]\nself-closing = "compact"\n')
    p = run_main("format", "--check", ".", cwd=tmp_path)
    assert p.returncode == 1 and "Would reformat: r.urdf" in p.stdout, (p.stdout, p.stderr)
    p = run_main("format", "--self-closing", "spaced", ".", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert f.read_text().count(" />") == 4
    p = run_main("format", "--self-closing", "tight", ".", cwd=tmp_path)
    assert p.returncode == 2 and "--self-closing" in p.stderr, p.stderr


def test_xacro_expressions_and_attribute_values_are_kept_byte_for_byte():
    src = (f'<robot name="r" {X}>\n<xacro:property name="p"   value="${{ a  >  b  and  c }}"/>'
           "<link name='${prefix}&amp;base'/>"
           '<xacro:macro name="m" params="a b\n       c:=${1+2} *origin"><link name="${ a }"/>'
           '</xacro:macro><e>  ${ x  *  2 }  $(arg   y)  </e></robot>')
    out = fmt(src)
    for piece in ['value="${ a  >  b  and  c }"', "name='${prefix}&amp;base'",
                  'params="a b\n       c:=${1+2} *origin"', "<e>  ${ x  *  2 }  $(arg   y)  </e>"]:
        assert piece in out


def test_text_mixed_content_cdata_pi_and_xml_space_are_kept():
    inner = ('<a>text <b>bold</b>  more</a><c><![CDATA[ <raw> ]]></c><?pi data?>'
             '<d xml:space="preserve">\n   <k/>  </d><n>\n  line\n</n>')
    out = fmt(f"<robot name='r'>{inner}</robot>")
    for piece in ["<a>text <b>bold</b>  more</a>", "<c><![CDATA[ <raw> ]]></c>", "<?pi data?>",
                  '<d xml:space="preserve">\n   <k/>  </d>', "<n>\n  line\n</n>"]:
        assert piece in out


def test_doctype_with_an_internal_subset_is_kept():
    src = ('<?xml version="1.0"?>\n<!DOCTYPE robot [\n  <!ENTITY w "0.1"> <!-- a > b -->\n]>\n'
           '<robot name="r"><link name="a"><e>&w;</e></link></robot>')
    out = fmt(src)
    assert out.startswith('<?xml version="1.0"?>\n<!DOCTYPE robot [\n  <!ENTITY w "0.1"> '
                          '<!-- a > b -->\n]>\n<robot name="r">\n  <link name="a">\n'
                          '    <e>&w;</e>\n')


def test_comments_stay_where_they_are():
    src = ('<?xml version="1.0"?>\n<!-- head -->\n<robot name="r"> <!-- on the robot line -->\n'
           '<link name="a"/>   <!-- after a -->\n<!-- own line\n   two -->\n<link name="b"/>\n'
           '</robot>\n<!-- tail -->')
    out = fmt(src)
    assert out == ('<?xml version="1.0"?>\n<!-- head -->\n'
                   '<robot name="r"> <!-- on the robot line -->\n'
                   '  <link name="a"/> <!-- after a -->\n  <!-- own line\n   two -->\n'
                   '  <link name="b"/>\n</robot>\n<!-- tail -->\n')
    assert out.count("<!--") == src.count("<!--")


def test_crlf_bom_declaration_and_encoding_are_kept():
    src = '<?xml version="1.0"?>\r\n<robot name="r">\r\n<link name="a"/>\r\n</robot>\r\n'
    data = codecs.BOM_UTF8 + src.encode()
    out = format_source(data)
    assert out == codecs.BOM_UTF8 + (b'<?xml version="1.0"?>\r\n<robot name="r">\r\n'
                                      b'  <link name="a"/>\r\n</robot>\r\n')
    latin = '<?xml version="1.0" encoding="ISO-8859-1"?>\n<robot name="r\xe9"><link name="a"/></robot>'
    out = format_source(latin.encode("latin-1"))
    assert out.decode("latin-1") == ('<?xml version="1.0" encoding="ISO-8859-1"?>\n'
                                     '<robot name="r\xe9">\n  <link name="a"/>\n</robot>\n')


def test_not_well_formed_is_a_located_error():
    with pytest.raises(FormatError) as e:
        format_source(b'<robot name="r">\n  <link name="a">\n</robot>\n')
    assert e.value.line == 3 and "not well-formed" in e.value.message


# -- suppression comments ------------------------------------------------------------------------
def test_suppression_comments_stay_attached_to_their_element():
    src = ('<robot name="r"><link name="a"/>\n<!-- urdf-lint: disable-next UL204 -->'
           '\n\n<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint></robot>')
    out = fmt(src)
    assert "  <!-- urdf-lint: disable-next UL204 -->\n  <joint name=\"j\"" in out
    from urdf_lint.engine.suppress import coverage
    assert [c[2] for c in coverage(src.encode())] == [c[2] for c in coverage(out.encode())]


def test_a_layout_that_would_change_what_a_suppression_covers_is_refused():
    # disable-next covers every element starting up to the end line of the next element: here
    # both links; once each link has its own line it would cover only the first
    src = ('<robot name="r">\n<!-- urdf-lint: disable-next UL204 --><link name="a"/>'
           '<link name="b"/>\n</robot>\n')
    with pytest.raises(Refused) as e:
        format_source(src.encode())
    assert "suppression comment at line 2" in e.value.reason


# -- the command ----------------------------------------------------------------------------------
UGLY = (f'<?xml version="1.0"?>\n<robot name="r" {X}>\n<xacro:property name="w" value="0.1"/>\n'
        '<link name="base"><visual><geometry><box size="${w} ${w} ${w}"/></geometry></visual></link>\n'
        '</robot>\n')


@pytest.fixture
def pkg(tmp_path):
    from conftest import make_package
    p = make_package(tmp_path, "fmt_pkg", {"urdf/r.urdf.xacro": UGLY})
    return p


def test_check_diff_and_write_exit_codes(pkg):
    f = pkg / "urdf" / "r.urdf.xacro"
    p = run_cli("format", "--check", pkg, cwd=pkg)
    assert p.returncode == 1 and "Would reformat: urdf/r.urdf.xacro" in p.stdout, p.stderr
    assert f.read_text() == UGLY
    p = run_cli("format", "--diff", pkg, cwd=pkg)
    assert p.returncode == 1 and "+    <visual>" in p.stdout and f.read_text() == UGLY
    p = run_cli("format", pkg, cwd=pkg)
    assert p.returncode == 0 and "1 file(s) reformatted" in p.stderr, p.stderr
    assert "(1 proved from the file itself, 0 model(s) expanded before and after)" in p.stderr
    assert "  <link name=\"base\">\n    <visual>\n" in f.read_text()
    p = run_cli("format", "--check", pkg, cwd=pkg)
    assert p.returncode == 0 and p.stdout == "", p.stdout
    (pkg / "urdf" / "broken.xacro").write_text("<robot>\n<link>\n</robot>\n")
    p = run_cli("format", "--check", pkg, cwd=pkg)
    assert p.returncode == 2 and "urdf/broken.xacro:3:" in p.stderr, p.stderr


def test_config_table_isolated_and_exclude(pkg):
    f = pkg / "urdf" / "r.urdf.xacro"
    (pkg / "pyproject.toml").write_text(
        '[tool.urdf-lint.format]\nindent = 4\nexclude = ["urdf/skip/*"]\n')
    (pkg / "urdf" / "skip").mkdir()
    (pkg / "urdf" / "skip" / "s.urdf").write_text('<robot name="s"><link name="a"/></robot>')
    p = run_cli("format", pkg, cwd=pkg)
    assert p.returncode == 0, p.stderr
    assert '\n    <link name="base">\n' in f.read_text()
    assert (pkg / "urdf" / "skip" / "s.urdf").read_text() == '<robot name="s"><link name="a"/></robot>'
    p = run_cli("format", "--check", pkg, cwd=pkg)
    assert p.returncode == 0 and p.stdout == "", p.stdout
    p = run_cli("format", "--isolated", "--check", pkg, cwd=pkg)   # no config: indent 2, no exclude
    assert p.returncode == 1 and p.stdout == ("Would reformat: urdf/r.urdf.xacro\n"
                                              "Would reformat: urdf/skip/s.urdf\n"), p.stdout
    (pkg / "pyproject.toml").write_text('[tool.urdf-lint.format]\nindnet = 4\n')
    p = run_cli("format", pkg, cwd=pkg)
    assert p.returncode == 2 and "format.indnet" in p.stderr and "did you mean 'indent'" in p.stderr
    p = run_cli("format", "--isolated", "--line-length", "zero", pkg, cwd=pkg)
    assert p.returncode == 2 and "--line-length" in p.stderr


NS_MACRO = (f'<robot {X}>\n<xacro:macro name="ns"><gazebo><plugin name="p" filename="x.so">'
            '<robotNamespace><xacro:if value="1">/arm</xacro:if></robotNamespace>'
            '</plugin></gazebo></xacro:macro>\n</robot>\n')


def test_a_layout_that_would_change_the_robot_is_refused(pkg):
    # the text of <robotNamespace> comes from an xacro:if inside it: laying the xacro:if out on
    # its own line would put the new whitespace into the expanded robot's text
    inc = NS_MACRO
    (pkg / "urdf" / "ns.xacro").write_text(inc)
    main = UGLY.replace("</robot>", '<xacro:include filename="ns.xacro"/><xacro:ns/>\n</robot>')
    (pkg / "urdf" / "r.urdf.xacro").write_text(main)
    p = run_cli("format", pkg, cwd=pkg)
    assert p.returncode == 0, p.stderr
    assert (pkg / "urdf" / "ns.xacro").read_text() == inc       # left alone
    assert "urdf/ns.xacro: left alone: formatting would change the robot" in p.stderr
    assert "<robotNamespace> differs" in p.stderr
    # the main file reads it too: left alone with it (it was proved together with it)
    assert (pkg / "urdf" / "r.urdf.xacro").read_text() == main
    assert "2 file(s) left alone" in p.stderr


# -- the corpus -----------------------------------------------------------------------------------
_DATA = (".stl", ".STL", ".dae", ".DAE", ".obj", ".OBJ", ".png", ".jpg", ".jpeg", ".mtl")


def _robots(root: Path) -> dict:
    """{(entry, args): canonical robot or the failure} of every xacro model under root."""
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver, discover_models
    from urdf_lint.expansion import expand_file
    from urdf_lint.run.format import canonical_robot
    cfg = load_config(None)
    resolver = build_resolver([str(root)], cfg)
    out = {}
    for job in discover_models([str(root)], cfg, resolver).jobs:
        if job.kind != "xacro":
            continue
        res = expand_file(job.entry, job.args, resolver)
        key = (os.path.relpath(job.entry, root), tuple(sorted(job.args.items())))
        out[key] = canonical_robot(res.xml) if res.error is None else res.error.code
    return out


def test_corpus_formats_without_changing_any_robot(tmp_path):
    if not (CORPUS / "MANIFEST.md").is_file():
        pytest.skip("../shared/corpus is not present")
    root = tmp_path / "corpus"
    shutil.copytree(CORPUS, root, ignore=shutil.ignore_patterns(*("*" + s for s in _DATA)))
    files = sorted(p for p in root.rglob("*") if p.suffix in (".urdf", ".xacro"))
    # the corpus has no file with a BOM: give one real CRLF file one (xacro reads it alike)
    crlf = next(f for f in files if b"\r\n" in f.read_bytes())
    crlf.write_bytes(codecs.BOM_UTF8 + crlf.read_bytes())
    before_bytes = {p: p.read_bytes() for p in files}
    robots_before = _robots(root)
    p = run_cli("format", root, cwd=root, timeout=900)
    m = re.search(r"(\d+) file\(s\) reformatted, (\d+) file\(s\) left unchanged", p.stderr)
    assert m, p.stderr
    errors = [ln for ln in p.stderr.splitlines() if ln.startswith("error:")]
    left_alone = [ln for ln in p.stderr.splitlines() if ": left alone: " in ln]
    print(f"\ncorpus: {m.group(1)} reformatted, {m.group(2)} unchanged, "
          f"{len(left_alone)} left alone, {len(errors)} not well-formed")
    for ln in left_alone + errors:
        print("  " + ln)
    # the only errors are the peer tests' deliberately malformed files
    assert all("peer-tests/" in ln and "not well-formed" in ln for ln in errors), errors
    changed = [f for f in files if f.read_bytes() != before_bytes[f]]
    assert len(changed) == int(m.group(1)) > 100
    for f in changed:
        old, new = before_bytes[f], f.read_bytes()
        assert new.count(b"<!--") == old.count(b"<!--"), f
        assert (b"\r\n" in old) == (b"\r\n" in new), f
        assert new.startswith(codecs.BOM_UTF8) == old.startswith(codecs.BOM_UTF8), f
        for expr in set(re.findall(rb"\$[{(][^}\)]*[})]", old)):
            assert new.count(expr) == old.count(expr), (f, expr)
    assert any(b"\r\n" in before_bytes[f] for f in changed)     # CRLF files are in the corpus
    assert crlf in changed and crlf.read_bytes().startswith(codecs.BOM_UTF8 + b"<")
    # a second pass changes nothing
    p = run_cli("format", "--check", root, cwd=root, timeout=900)
    assert "0 file(s) would be reformatted" in p.stderr and p.stdout == "", p.stdout
    # every model expands to the same robot
    robots_after = _robots(root)
    assert robots_after.keys() == robots_before.keys()
    differ = [k for k in robots_before if robots_before[k] != robots_after[k]]
    assert not differ, differ
    assert sum(1 for v in robots_before.values() if not isinstance(v, str)) > 100


def test_precommit_hook_entry_formats_the_files_it_is_given(pkg):
    import yaml
    from conftest import REPO
    hooks = {h["id"]: h for h in yaml.safe_load((REPO / ".pre-commit-hooks.yaml").read_text())}
    hook = hooks["urdf-lint-format"]
    assert hook["entry"] == "urdf-lint format" and hook.get("pass_filenames", True)
    assert re.search(hook["files"], "r.urdf.xacro") and not re.search(hook["files"], "a.yaml")
    other = pkg / "urdf" / "other.urdf"
    other.write_text('<robot name="o"><link name="a"/></robot>')
    p = run_cli(*hook["entry"].split()[1:], "urdf/r.urdf.xacro", cwd=pkg)   # as pre-commit runs it
    assert p.returncode == 0 and "1 file(s) reformatted" in p.stderr, p.stderr
    assert other.read_text() == '<robot name="o"><link name="a"/></robot>'   # not given: untouched


def test_the_proof_sees_models_the_config_excludes(pkg):
    (pkg / "urdf" / "ns.xacro").write_text(NS_MACRO)
    (pkg / "test").mkdir()
    (pkg / "test" / "t.urdf.xacro").write_text(
        f'<robot name="t" {X}><xacro:include filename="$(find fmt_pkg)/urdf/ns.xacro"/>'
        '<link name="a"/><xacro:ns/></robot>')
    (pkg / "urdf" / "r.urdf.xacro").write_text(UGLY.replace("<robot ", "<robot ", 1))
    (pkg / "pyproject.toml").write_text('[tool.urdf-lint]\nexclude = ["test/*"]\n')
    p = run_cli("format", "urdf/ns.xacro", cwd=pkg)
    assert p.returncode == 0, p.stderr
    assert (pkg / "urdf" / "ns.xacro").read_text() == NS_MACRO
    assert "left alone: formatting would change the robot test/t.urdf.xacro" in p.stderr, p.stderr
