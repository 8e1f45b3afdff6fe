"""``check --fix`` / ``--diff``: fixes written into the xacro source where the value is written.

Each case is a small ROS package; the assertions are the exact diff bytes, the finding gone after
``--fix``, a second ``--fix`` that changes nothing, and stock xacro's expansion of the fixed
source equal to stock xacro's expansion of the hand-fixed source.
"""
from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from conftest import make_package, run_cli, run_main
from support.stock_xacro import stock_xacro

HEAD = '<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
LINKS = '  <link name="a"/><link name="b"/>\n'


def joint(limit: str) -> str:
    return ('  <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/>'
            '<axis xyz="0 0 1"/>\n'
            f'    {limit}\n  </joint>\n')


def findings(pkg, *extra):
    p = run_main("check", pkg, "--format", "json", "--no-cache", "--isolated", *extra)
    assert p.returncode in (0, 1), p.stderr
    return json.loads(p.stdout)["findings"]


def codes(pkg):
    return sorted((f["code"], f["message"]) for f in findings(pkg))


def fix_and_check(pkg: Path, code: str, expected_diff: str, hand_fixed: dict,
                  entry="urdf/robot.urdf.xacro", args=None):
    """--diff shows exactly ``expected_diff``; --fix removes the finding and nothing else;
    a second --fix changes nothing; stock xacro of the fixed source == of the hand-fixed one."""
    before = codes(pkg)
    assert any(c == code for c, _ in before), before
    d = run_main("check", ".", "--diff", "--no-cache", "--isolated", cwd=pkg)
    assert d.returncode == 1, d.stderr
    assert d.stdout == expected_diff
    snapshot = {p: p.read_bytes() for p in pkg.rglob("*") if p.is_file()}
    f = run_main("check", ".", "--fix", "--no-cache", "--isolated", cwd=pkg)
    assert "Fixed 1 finding" in f.stderr, f.stderr
    after = codes(pkg)
    assert [c for c in after if c[0] == code] == [], after
    assert set(after) <= set(before)            # nothing introduced
    again = {p: p.read_bytes() for p in pkg.rglob("*") if p.is_file()}
    g = run_main("check", ".", "--fix", "--no-cache", "--isolated", cwd=pkg)
    assert "Fixed 0 findings" in g.stderr
    assert {p: p.read_bytes() for p in pkg.rglob("*") if p.is_file()} == again
    assert again != snapshot
    # stock xacro: the fixed source expands to what the hand-fixed source does
    rc, fixed_urdf, err = stock_xacro(str(pkg / entry), args or {}, {pkg.name: pkg})
    assert rc == 0, err
    ref = pkg.parent / "hand_fixed"
    shutil.copytree(pkg, ref)
    for rel, text in hand_fixed.items():
        (ref / rel).write_bytes(text if isinstance(text, bytes) else text.encode())
    rc, want, err = stock_xacro(str(ref / entry), args or {}, {pkg.name: ref})
    assert rc == 0, err
    body = lambda u: u[u.index("<robot"):]   # noqa: E731 - the header names the file
    assert body(fixed_urdf) == body(want)


def test_literal_in_element(tmp_path):
    src = HEAD + LINKS + joint('<limit lower="2.1" upper="-2.1" effort="1" velocity="1"/>') + "</robot>\n"
    pkg = make_package(tmp_path, "lit", {"urdf/robot.urdf.xacro": src})
    fix_and_check(pkg, "UL302", (
        "--- a/urdf/robot.urdf.xacro\n+++ b/urdf/robot.urdf.xacro\n@@ -2,6 +2,6 @@\n"
        ' <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '   <link name="a"/><link name="b"/>\n'
        '   <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>\n'
        '-    <limit lower="2.1" upper="-2.1" effort="1" velocity="1"/>\n'
        '+    <limit lower="-2.1" upper="2.1" effort="1" velocity="1"/>\n'
        "   </joint>\n </robot>\n"),
        {"urdf/robot.urdf.xacro": src.replace('lower="2.1" upper="-2.1"', 'lower="-2.1" upper="2.1"')})


def test_property_in_another_file(tmp_path):
    props = HEAD + '  <xacro:property name="lo" value="1.5"/>\n  <xacro:property name="hi" value="-0.5"/>\n</robot>\n'
    src = (HEAD + '  <xacro:include filename="$(find prop)/urdf/props.xacro"/>\n' + LINKS
           + joint('<limit lower="${lo}" upper="${hi}" effort="1" velocity="1"/>') + "</robot>\n")
    pkg = make_package(tmp_path, "prop", {"urdf/robot.urdf.xacro": src, "urdf/props.xacro": props})
    fix_and_check(pkg, "UL302", (
        "--- a/urdf/props.xacro\n+++ b/urdf/props.xacro\n@@ -1,5 +1,5 @@\n"
        ' <?xml version="1.0"?>\n <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '-  <xacro:property name="lo" value="1.5"/>\n-  <xacro:property name="hi" value="-0.5"/>\n'
        '+  <xacro:property name="lo" value="-0.5"/>\n+  <xacro:property name="hi" value="1.5"/>\n'
        " </robot>\n"),
        {"urdf/props.xacro": props.replace('"1.5"', '"X"').replace('"-0.5"', '"1.5"').replace('"X"', '"-0.5"')})


def test_macro_parameter(tmp_path):
    parts = (HEAD + '  <xacro:macro name="hinge" params="name lower upper">\n'
             '    <joint name="${name}" type="revolute"><parent link="a"/><child link="b"/>\n'
             '      <axis xyz="0 0 1"/><limit lower="${lower}" upper="${upper}" effort="1" velocity="1"/>\n'
             '    </joint>\n  </xacro:macro>\n</robot>\n')
    src = (HEAD + '  <xacro:include filename="parts.xacro"/>\n' + LINKS
           + '  <xacro:hinge name="elbow" lower="0.3" upper="-0.3"/>\n</robot>\n')
    pkg = make_package(tmp_path, "mac", {"urdf/robot.urdf.xacro": src, "urdf/parts.xacro": parts})
    fix_and_check(pkg, "UL302", (
        "--- a/urdf/robot.urdf.xacro\n+++ b/urdf/robot.urdf.xacro\n@@ -2,5 +2,5 @@\n"
        ' <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '   <xacro:include filename="parts.xacro"/>\n   <link name="a"/><link name="b"/>\n'
        '-  <xacro:hinge name="elbow" lower="0.3" upper="-0.3"/>\n'
        '+  <xacro:hinge name="elbow" lower="-0.3" upper="0.3"/>\n </robot>\n'),
        {"urdf/robot.urdf.xacro": src.replace('lower="0.3" upper="-0.3"', 'lower="-0.3" upper="0.3"')})


def test_yaml_scalar(tmp_path):
    yml = "# joint limits\nelbow:\n  lower: 1.2   # rad\n  upper: -1.2\n"
    src = (HEAD + '  <xacro:property name="lim" value="${load_yaml(\'limits.yaml\')}"/>\n' + LINKS
           + joint('<limit lower="${lim[\'elbow\'][\'lower\']}" upper="${lim.elbow.upper}" '
                   'effort="1" velocity="1"/>') + "</robot>\n")
    pkg = make_package(tmp_path, "yml", {"urdf/robot.urdf.xacro": src, "urdf/limits.yaml": yml})
    fix_and_check(pkg, "UL302", (
        "--- a/urdf/limits.yaml\n+++ b/urdf/limits.yaml\n@@ -1,4 +1,4 @@\n"
        " # joint limits\n elbow:\n-  lower: 1.2   # rad\n-  upper: -1.2\n"
        "+  lower: -1.2   # rad\n+  upper: 1.2\n"),
        {"urdf/limits.yaml": "# joint limits\nelbow:\n  lower: -1.2   # rad\n  upper: 1.2\n"})


def test_expression_is_refused_with_its_location(tmp_path):
    src = (HEAD + '  <xacro:property name="lo" value="1"/>\n' + LINKS
           + joint('<limit lower="${lo*2}" upper="-2" effort="1" velocity="1"/>') + "</robot>\n")
    pkg = make_package(tmp_path, "expr", {"urdf/robot.urdf.xacro": src})
    p = run_main("check", ".", "--format", "json", "--no-cache", "--isolated", cwd=pkg)
    (f,) = [f for f in json.loads(p.stdout)["findings"] if f["code"] == "UL302"]
    assert f["fix"] == {"description": "swap lower and upper", "applicability": "safe",
                        "refused": "not fixable automatically: the value comes from the "
                                   "expression at urdf/robot.urdf.xacro:6"}
    d = run_main("check", ".", "--diff", "--no-cache", "--isolated", cwd=pkg)
    assert d.stdout == "" and d.returncode == 0
    before = (pkg / "urdf/robot.urdf.xacro").read_bytes()
    run_main("check", ".", "--fix", "--no-cache", "--isolated", cwd=pkg)
    assert (pkg / "urdf/robot.urdf.xacro").read_bytes() == before


def test_no_fix_keeps_json_unchanged(tmp_path):
    src = HEAD + LINKS + joint('<limit lower="0" upper="1" effort="-1" velocity="1"/>') + "</robot>\n"
    pkg = make_package(tmp_path, "nofix", {"urdf/robot.urdf.xacro": src})
    fs = findings(pkg)
    assert fs and all("fix" not in f for f in fs)
    assert all(set(f) == {"code", "name", "severity", "message", "file", "line", "col", "chain",
                          "models"} for f in fs)


def test_fix_shared_with_a_model_it_would_break_is_rolled_back(tmp_path):
    """`lo` is shared by two robots; swapping it is right for A (inverted) and wrong for B."""
    common = HEAD + '  <xacro:property name="lo" value="1"/>\n</robot>\n'
    def robot(hi):
        return (HEAD + '  <xacro:include filename="common.xacro"/>\n'
                f'  <xacro:property name="hi" value="{hi}"/>\n' + LINKS
                + joint('<limit lower="${lo}" upper="${hi}" effort="1" velocity="1"/>') + "</robot>\n")
    pkg = make_package(tmp_path, "shared", {"urdf/common.xacro": common,
                                            "urdf/a.urdf.xacro": robot("-1"),
                                            "urdf/b.urdf.xacro": robot("3")})
    snapshot = {p: p.read_bytes() for p in pkg.rglob("*") if p.is_file()}
    f = run_main("check", ".", "--fix", "--no-cache", "--isolated", cwd=pkg)
    assert "UL302 fix rolled back: the edited source is also used by urdf/b.urdf.xacro, where " \
           "the fix is wrong" in f.stderr, f.stderr
    assert "Fixed 0 findings" in f.stderr
    assert {p: p.read_bytes() for p in pkg.rglob("*") if p.is_file()} == snapshot
    assert any(c == "UL302" for c, _ in codes(pkg))


def test_crlf_tabs_non_ascii_and_comments_survive(tmp_path):
    src = ('<?xml version="1.0" encoding="UTF-8"?>\r\n<!-- bras articulé — ß -->\r\n'
           '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\r\n'
           '\t<link name="a"/><link name="b"/>\r\n'
           '\t<joint name="coude_é" type="revolute"><parent link="a"/><child link="b"/>'
           '<axis xyz="0 0 1"/>\r\n'
           "\t\t<limit  effort='1'\tlower='2'\r\n\t\t\tupper = '-2' velocity=\"1\"><!-- été --></limit>\r\n"
           '\t</joint>\r\n</robot>\r\n').encode("utf-8")
    pkg = make_package(tmp_path, "crlf", {"urdf/robot.urdf.xacro": src})
    run_main("check", ".", "--fix", "--no-cache", "--isolated", cwd=pkg)
    out = (pkg / "urdf/robot.urdf.xacro").read_bytes()
    assert out == src.replace(b"lower='2'", b"lower='-2'").replace(b"upper = '-2'", b"upper = '2'")
    assert not [c for c, _ in codes(pkg) if c == "UL302"]


def test_axis_and_colour_fixes(tmp_path):
    src = (HEAD + '  <material name="orange"><color rgba="255 128 0 1"/></material>\n'
           '  <link name="a"><visual><geometry><box size="1 1 1"/></geometry>'
           '<material name="orange"/></visual></link><link name="b"/>\n'
           '  <joint name="j" type="continuous"><parent link="a"/><child link="b"/>'
           '<axis xyz="0 0 2"/></joint>\n</robot>\n')
    pkg = make_package(tmp_path, "ax", {"urdf/robot.urdf.xacro": src})
    f = run_main("check", ".", "--fix", "--no-cache", "--isolated", cwd=pkg)
    assert "Fixed 2 findings" in f.stderr, f.stderr
    assert (pkg / "urdf/robot.urdf.xacro").read_text() == src.replace(
        'rgba="255 128 0 1"', 'rgba="1 0.502 0 1"').replace('xyz="0 0 2"', 'xyz="0 0 1"')
    assert not [c for c, _ in codes(pkg) if c in ("UL208", "UL307")]


def test_fix_options_are_checked(tmp_path):
    p = run_main("check", ".", "--unsafe-fixes", "--isolated", cwd=tmp_path)
    assert p.returncode == 2 and "--unsafe-fixes needs --fix or --diff" in p.stderr


def test_typo_and_reference_fixes(tmp_path):
    """Names with one "did you mean" candidate, renamed in the source (start and end tags)."""
    src = ('<?xml version="1.0"?>\n<robot name="r">\n'
           '  <material name="orange"><color rgba="1 0.5 0 1"/></material>\n'
           '  <link name="base_link"><visual><orgin xyz="0 0 1"></orgin><geometry>'
           '<cylinder raduis="1" length="2"/></geometry><material name="ornage"/></visual></link>\n'
           '  <link name="arm_link"/><link name="tip"/>\n'
           '  <joint name="shoulder_joint" type="revolute"><parent link="base_link"/>'
           '<child link="arm_link"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" '
           'velocity="1"/>\n    <safety_controller soft_lower="-0.5" soft_upper_limit="0.5" '
           'k_velocity="1"/></joint>\n'
           '  <joint name="tip_joint" type="continuous"><parent link="arm_link"/>'
           '<child link="tip"/><mimic joint="shoulder_jiont"/></joint>\n'
           '  <transmission name="t"><type>transmission_interface/SimpleTransmission</type>\n'
           '    <joint name="shoulder_jont"><hardwareInterface>x</hardwareInterface></joint>\n'
           '  </transmission>\n  <gazebo reference="bse_link"/>\n</robot>\n')
    pkg = make_package(tmp_path, "typo", {"urdf/robot.urdf": src})
    before = codes(pkg)
    f = run_main("check", ".", "--fix", "--no-cache", "--isolated", cwd=pkg)
    assert "Fixed 7 findings" in f.stderr, f.stderr
    want = (src.replace("<orgin xyz", "<origin xyz").replace("</orgin>", "</origin>")
            .replace("raduis", "radius").replace("ornage", "orange")
            .replace("soft_lower=", "soft_lower_limit=").replace("shoulder_jiont", "shoulder_joint")
            .replace("shoulder_jont", "shoulder_joint").replace("bse_link", "base_link"))
    assert (pkg / "urdf/robot.urdf").read_text() == want
    after = codes(pkg)
    assert not [c for c in after if c[0] in ("UL209", "UL210", "UL308", "UL502", "UL701",
                                            "UL703")], after
    assert set(after) <= set(before)


def test_ambiguous_candidates_are_not_fixed(tmp_path):
    """Two close candidates (iyx: ixy or iyz), or the candidate already present: no fix."""
    src = ('<?xml version="1.0"?>\n<robot name="r">\n  <link name="a"><inertial><mass value="1"/>'
           '<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0" iyx="0"/></inertial></link>\n'
           '</robot>\n')
    pkg = make_package(tmp_path, "amb", {"urdf/robot.urdf": src})
    fs = [f for f in findings(pkg) if f["code"] == "UL210"]
    assert fs and all("fix" not in f for f in fs)


def test_unused_suppression_comment_is_removed(tmp_path):
    src = ('<?xml version="1.0"?>\r\n<robot name="r">\r\n'
           '  <!-- urdf-lint: disable-next UL302 -->\r\n'
           '  <link name="a"/>  <!-- urdf-lint: disable-next UL103 --> <!-- kept -->\r\n'
           '  <link name="b"/>\r\n</robot>\r\n')
    pkg = make_package(tmp_path, "sup", {"urdf/robot.urdf": src.encode()})
    assert [c for c, _ in codes(pkg)].count("UL009") == 2
    f = run_main("check", ".", "--fix", "--no-cache", "--isolated", cwd=pkg)
    assert "Fixed 2 findings" in f.stderr, f.stderr
    assert (pkg / "urdf/robot.urdf").read_bytes() == (
        '<?xml version="1.0"?>\r\n<robot name="r">\r\n'
        '  <link name="a"/>   <!-- kept -->\r\n'
        '  <link name="b"/>\r\n</robot>\r\n').encode()
    assert "UL009" not in [c for c, _ in codes(pkg)]


def test_missing_dollar_in_a_macro(tmp_path):
    parts = (HEAD + '  <xacro:macro name="arm" params="prefix">\n'
             '    <link name="${prefix}base"/>\n    <link name="{prefix}tool"/>\n'
             '    <joint name="${prefix}j" type="fixed"><parent link="${prefix}base"/>'
             '<child link="${prefix}tool"/></joint>\n  </xacro:macro>\n</robot>\n')
    src = (HEAD + '  <xacro:include filename="parts.xacro"/>\n  <link name="world"/>\n'
           '  <xacro:arm prefix="left_"/>\n  <xacro:arm prefix="right_"/>\n'
           '  <joint name="l" type="fixed"><parent link="world"/><child link="left_base"/></joint>\n'
           '  <joint name="r" type="fixed"><parent link="world"/><child link="right_base"/></joint>\n'
           '</robot>\n')
    pkg = make_package(tmp_path, "dollar", {"urdf/robot.urdf.xacro": src, "urdf/parts.xacro": parts})
    fix_and_check(pkg, "UL212", (
        "--- a/urdf/parts.xacro\n+++ b/urdf/parts.xacro\n@@ -2,7 +2,7 @@\n"
        ' <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '   <xacro:macro name="arm" params="prefix">\n     <link name="${prefix}base"/>\n'
        '-    <link name="{prefix}tool"/>\n+    <link name="${prefix}tool"/>\n'
        '     <joint name="${prefix}j" type="fixed"><parent link="${prefix}base"/>'
        '<child link="${prefix}tool"/></joint>\n   </xacro:macro>\n </robot>\n'),
        {"urdf/parts.xacro": parts.replace('"{prefix}tool"', '"${prefix}tool"')})


def test_json_and_sarif_carry_the_fix(tmp_path):
    src = HEAD + LINKS + joint('<limit lower="2.1" upper="-2.1" effort="1" velocity="1"/>') + "</robot>\n"
    pkg = make_package(tmp_path, "sarif", {"urdf/robot.urdf.xacro": src})
    data = src.encode()
    lo, hi = data.index(b'"2.1"') + 1, data.index(b'"-2.1"') + 1
    p = run_main("check", ".", "--format", "json", "--no-cache", "--isolated", cwd=pkg)
    (f,) = [f for f in json.loads(p.stdout)["findings"] if f["code"] == "UL302"]
    assert f["fix"] == {"description": "swap lower and upper", "applicability": "safe", "edits": [
        {"file": "urdf/robot.urdf.xacro", "start": lo, "end": lo + 3, "text": "-2.1"},
        {"file": "urdf/robot.urdf.xacro", "start": hi, "end": hi + 4, "text": "2.1"}]}
    p = run_main("check", ".", "--format", "sarif", "--no-cache", "--isolated", cwd=pkg)
    (r,) = [r for r in json.loads(p.stdout)["runs"][0]["results"] if r["ruleId"] == "UL302"]
    assert r["fixes"] == [{"description": {"text": "swap lower and upper"}, "artifactChanges": [
        {"artifactLocation": {"uri": "urdf/robot.urdf.xacro"}, "replacements": [
            {"deletedRegion": {"byteOffset": lo, "byteLength": 3}, "insertedContent": {"text": "-2.1"}},
            {"deletedRegion": {"byteOffset": hi, "byteLength": 4}, "insertedContent": {"text": "2.1"}}]}]}]


def test_add_suppressions(tmp_path):
    src = ('<?xml version="1.0"?>\r\n<robot name="r">\r\n  <link name="a"/><link name="b"/>\r\n'
           '\t<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
           '<axis xyz="0 0 2"/>\r\n\t\t<limit lower="1" upper="-1" effort="1" velocity="1"/>\r\n'
           '\t</joint>\r\n</robot>\r\n')
    pkg = make_package(tmp_path, "adopt", {"urdf/robot.urdf": src.encode()})
    before = codes(pkg)
    assert sorted(c for c, _ in before) == ["UL302", "UL307", "UL601"]
    p = run_main("check", ".", "--add-suppressions", "--no-cache", "--isolated", cwd=pkg)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "Added 3 suppression comments in 1 file" in p.stderr
    assert (pkg / "urdf/robot.urdf").read_bytes() == (
        '<?xml version="1.0"?>\r\n<robot name="r">\r\n'
        '  <!-- urdf-lint: disable-next UL601 -->\r\n'
        '  <link name="a"/><link name="b"/>\r\n'
        '\t<!-- urdf-lint: disable-next UL307 -->\r\n'
        '\t<joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 2"/>\r\n'
        '\t\t<!-- urdf-lint: disable-next UL302 -->\r\n'
        '\t\t<limit lower="1" upper="-1" effort="1" velocity="1"/>\r\n\t</joint>\r\n</robot>\r\n'
    ).encode()
    assert codes(pkg) == []


def test_corpus_round_trip(tmp_path, corpus, corpus_report):
    """--fix --unsafe-fixes on a copy of the whole corpus: every changed model still expands
    with stock xacro, no finding is introduced, and a second run changes nothing."""
    from collections import Counter
    from urdf_lint.discovery.packages import PackageResolver
    copy = tmp_path / "corpus"
    shutil.copytree(corpus, copy)
    def run(*extra):
        p = run_cli("check", ".", "--format", "json", "--no-cache", "-j", "2", *extra, cwd=copy,
                    timeout=900)
        assert p.returncode in (0, 1), p.stderr
        return json.loads(p.stdout), p.stderr
    before = corpus_report    # `run()` on the original: the same findings (cwd-relative)
    after, err = run("--fix", "--unsafe-fixes")
    fixed = int(err.rsplit("Fixed ", 1)[1].split()[0])
    changed = sorted(str(p.relative_to(copy)) for p in copy.rglob("*")
                     if p.is_file() and p.read_bytes() != (corpus / p.relative_to(copy)).read_bytes())
    key = lambda f: (f["code"], f["file"], f["message"])   # noqa: E731
    b, a = Counter(map(key, before["findings"])), Counter(map(key, after["findings"]))
    assert not (a - b), f"introduced: {a - b}"
    removed = Counter(k[0] for k in (b - a).elements())
    print("findings removed per code:", dict(sorted(removed.items())), "files changed:", changed)
    assert sum(removed.values()) >= fixed >= 1   # a fix may also clear a finding it caused
    assert bool(changed) == bool(fixed)
    scanned = PackageResolver.build([copy], extra_roots=[copy]).scanned
    scanned_orig = PackageResolver.build([corpus], extra_roots=[corpus]).scanned
    entries = {m["entry"]: m["args"] for m in after["models"] if m["status"] == "model"}
    todo = set()
    for rel in changed:     # the changed model itself, or the models of a changed library's package
        todo |= {rel} if rel in entries else {e for e in entries if e.startswith(rel.split("/")[0] + "/")}
    for entry in sorted(todo):
        args = entries[entry]
        # as stock xacro expanded the original (a few peer-test files fail on purpose)
        rc0, _, err0 = stock_xacro(str(corpus / entry), args, scanned_orig, cwd=str(corpus))
        rc, _, err1 = stock_xacro(str(copy / entry), args, scanned, cwd=str(copy))
        assert (rc, err1.replace(str(copy), "")) == (rc0, err0.replace(str(corpus), ""))
    from lxml import etree
    for rel in changed:                       # and every changed file is still well-formed XML
        if rel.endswith((".urdf", ".xacro")):
            etree.parse(str(copy / rel))
    state = {p: p.read_bytes() for p in copy.rglob("*") if p.is_file()}
    again, err = run("--fix", "--unsafe-fixes")
    assert "Fixed 0 findings" in err
    assert {p: p.read_bytes() for p in copy.rglob("*") if p.is_file()} == state


CONT = ('<?xml version="1.0"?>\n<robot name="r">\n  <link name="a"/><link name="w"/>\n'
        '  <joint name="axle" type="continuous"><parent link="a"/><child link="w"/>'
        '<axis xyz="0 1 0"/>\n    <limit lower="-3.14" upper="3.14" effort="10" velocity="10"/>\n'
        '  </joint>\n</robot>\n')


def test_unsafe_fixes_need_the_flag_continuous_limits_dropped(tmp_path):
    pkg = make_package(tmp_path, "cont", {"urdf/robot.urdf": CONT})
    f = run_main("check", ".", "--fix", "--no-cache", "--isolated", cwd=pkg)
    assert "Fixed 0 findings" in f.stderr and (pkg / "urdf/robot.urdf").read_text() == CONT
    f = run_main("check", ".", "--fix", "--unsafe-fixes", "--no-cache", "--isolated", cwd=pkg)
    assert "Fixed 1 finding" in f.stderr, f.stderr
    assert (pkg / "urdf/robot.urdf").read_text() == CONT.replace(
        '<limit lower="-3.14" upper="3.14" effort', '<limit effort')
    assert "UL305" not in [c for c, _ in codes(pkg)]


def test_continuous_limits_made_revolute_by_option(tmp_path):
    pkg = make_package(tmp_path, "rev", {
        "urdf/robot.urdf": CONT,
        "urdf-lint.toml": '[rule-options.UL305]\nfix = "revolute"\n'})
    f = run_main("check", ".", "--fix", "--unsafe-fixes", "--no-cache", cwd=pkg)
    assert "Fixed 1 finding" in f.stderr, f.stderr
    assert (pkg / "urdf/robot.urdf").read_text() == CONT.replace('"continuous"', '"revolute"')


def test_root_inertial_gets_a_massless_root(tmp_path):
    src = ('<?xml version="1.0"?>\r\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\r\n'
           '\t<xacro:property name="base" value="base_link"/>\r\n'
           '\t<link name="${base}"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" '
           'iyy="1" iyz="0" izz="1"/></inertial></link>\r\n\t<link name="arm"/>\r\n'
           '\t<joint name="j" type="fixed"><parent link="${base}"/><child link="arm"/></joint>\r\n'
           '</robot>\r\n')
    pkg = make_package(tmp_path, "root", {"urdf/robot.urdf.xacro": src.encode()})
    f = run_main("check", ".", "--fix", "--unsafe-fixes", "--no-cache", "--isolated", cwd=pkg)
    assert "Fixed 1 finding" in f.stderr, f.stderr
    fixed = src.replace('\t<link name="${base}">', '\t<link name="${base}_root"/>\r\n'
                        '\t<joint name="${base}_root_joint" type="fixed"><parent link="${base}_root"/>'
                        '<child link="${base}"/></joint>\r\n\t<link name="${base}">')
    assert (pkg / "urdf/robot.urdf.xacro").read_bytes() == fixed.encode()
    assert "UL604" not in [c for c, _ in codes(pkg)]
    rc, out, err = stock_xacro(str(pkg / "urdf/robot.urdf.xacro"), {}, {"root": pkg})
    assert rc == 0 and '<link name="base_link_root"/>' in out and \
        '<parent link="base_link_root"/>' in out, err


def test_repeated_inline_colour_becomes_one_named_material(tmp_path):
    vis = '<visual><geometry><box size="1 1 1"/></geometry><material name="{n}">\n      <color rgba="0 0 1 1"/>\n    </material></visual>'
    src = ('<?xml version="1.0"?>\n<robot name="r">\n'
           + "".join(f'  <link name="{k}">{vis.format(n=n)}</link>\n'
                     for k, n in (("a", "blue"), ("b", "m2"), ("c", "blue")))
           + '  <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>\n'
           '  <joint name="j2" type="fixed"><parent link="a"/><child link="c"/></joint>\n</robot>\n')
    pkg = make_package(tmp_path, "mat", {"urdf/robot.urdf": src})
    assert "UL504" in [c for c, _ in codes(pkg)]
    f = run_main("check", ".", "--fix", "--unsafe-fixes", "--no-cache", "--isolated", cwd=pkg)
    assert "Fixed 1 finding" in f.stderr, f.stderr
    ref = '<visual><geometry><box size="1 1 1"/></geometry><material name="blue"/></visual>'
    assert (pkg / "urdf/robot.urdf").read_text() == (
        '<?xml version="1.0"?>\n<robot name="r">\n'
        '  <material name="blue"><color rgba="0 0 1 1"/></material>\n'
        + "".join(f'  <link name="{k}">{ref}</link>\n' for k in "abc")
        + '  <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>\n'
        '  <joint name="j2" type="fixed"><parent link="a"/><child link="c"/></joint>\n</robot>\n')
    after = codes(pkg)
    assert "UL504" not in [c for c, _ in after]


def test_files_outside_the_linted_paths_are_not_edited(tmp_path):
    """The property lives in another package of the workspace: linting only the robot's
    package fixes nothing there, and says which fix and why in the summary of --fix and
    --diff, not only "Fixed 0" (the real franka description's limits live in a YAML file
    beside its entry: `check fr3.urdf.xacro --fix` said nothing more); linting the workspace
    fixes it."""
    props = HEAD + '  <xacro:property name="lo" value="1.5"/>\n  <xacro:property name="hi" value="-0.5"/>\n</robot>\n'
    src = (HEAD + '  <xacro:include filename="$(find common)/urdf/props.xacro"/>\n' + LINKS
           + joint('<limit lower="${lo}" upper="${hi}" effort="1" velocity="1"/>') + "</robot>\n")
    ws = tmp_path / "ws" / "src"
    make_package(ws, "common", {"urdf/props.xacro": props})
    robot = make_package(ws, "robot", {"urdf/robot.urdf.xacro": src})
    p = run_main("check", "robot", "--fix", "--no-cache", "--isolated", "--package-path",
                f"common={ws / 'common'}", cwd=ws)
    why = ("robot/urdf/robot.urdf.xacro:6:5: UL302 fix not applied: common/urdf/props.xacro "
           "is outside the linted paths\n")
    assert why + "Fixed 0 findings in 0 files (3 remaining, 1 fix(es) not applied)." \
        in p.stderr, p.stderr
    p = run_main("check", "robot", "--diff", "--no-cache", "--isolated", "--package-path",
                 f"common={ws / 'common'}", cwd=ws)
    assert why + "Would fix 0 findings in 0 file(s)." in p.stderr, p.stderr
    assert (ws / "common/urdf/props.xacro").read_text() == props
    p = run_main("check", "robot", "--format", "json", "--no-cache", "--isolated",
                "--package-path", f"common={ws / 'common'}", cwd=ws)
    (f,) = [f for f in json.loads(p.stdout)["findings"] if f["code"] == "UL302"]
    assert f["fix"]["refused"] == ("not fixable automatically: common/urdf/props.xacro is "
                                   "outside the linted paths")
    p = run_main("check", ".", "--fix", "--no-cache", "--isolated", cwd=ws)
    assert "Fixed 1 finding" in p.stderr, p.stderr
    assert (ws / "common/urdf/props.xacro").read_text() != props
    assert (robot / "urdf/robot.urdf.xacro").read_text() == src



def test_a_refused_fix_of_a_shared_macro_is_named_once(tmp_path):
    """A macro outside the linted paths called three times gives one finding of three
    instances, and one fix at one place: the summary names it once and counts one, as the
    report counts the finding once (not three identical lines, nor "3 fix(es) not
    applied" beside "1 remaining")."""
    arm = ('<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
           '  <xacro:macro name="arm" params="prefix">\n'
           '    <link name="${prefix}link"/>\n'
           '    <joint name="${prefix}joint" type="revolute"><parent link="base"/>'
           '<child link="${prefix}link"/><axis xyz="0 0 1"/>\n'
           '      <limit lower="1" upper="-1" effort="1" velocity="1"/>\n'
           '    </joint>\n  </xacro:macro>\n</robot>\n')
    src = (HEAD + '  <xacro:include filename="$(find common)/urdf/arm.xacro"/>\n'
           '  <link name="base"/>\n' + "".join(f'  <xacro:arm prefix="{p}_"/>\n' for p in "lrm")
           + "</robot>\n")
    ws = tmp_path / "ws" / "src"
    make_package(ws, "common", {"urdf/arm.xacro": arm})
    make_package(ws, "robot", {"urdf/robot.urdf.xacro": src})
    why = ("common/urdf/arm.xacro:6:7: UL302 fix not applied: common/urdf/arm.xacro is outside "
           "the linted paths\n")
    for how, end in (("--fix", "Fixed 0 findings in 0 files (1 remaining, 1 fix(es) not "
                               "applied)."), ("--diff", "Would fix 0 findings in 0 file(s).")):
        p = run_main("check", "robot", how, "--select", "UL302", "--no-cache", "--isolated",
                     "--package-path", f"common={ws / 'common'}", cwd=ws)
        assert p.stderr.count("fix not applied") == 1 and why + end in p.stderr, p.stderr
    assert (ws / "common/urdf/arm.xacro").read_text() == arm

def test_start_tag_tokeniser_on_raw_bytes():
    from urdf_lint.core.edits import Edit
    from urdf_lint.fix.sourceedit import apply_edits, end_tag_of, escape, start_tag_at
    data = ('<robot>\r\n<!-- <link name="x"> -->\r\n\t<link  name = \'é&amp;"q\'\r\n'
            '\ttype="a&#x41;\tb"><link name="in"></link><!-- </link> --></link>\r\n'
            '</robot>\r\n').encode()
    tag = start_tag_at(data, 3, 2)            # col counts characters, as expat does
    assert tag.name == "link" and not tag.self_closing
    assert [(a.name, a.value, a.quote) for a in tag.attrs] == [
        ("name", 'é&"q', "'"), ("type", "aA b", '"')]
    end = end_tag_of(data, tag)
    assert data[end:end + 7] == b"</link>" and data[end - 16:end] == b"<!-- </link> -->"
    a = tag.attr("name")
    new = apply_edits(data, [Edit("f", a.value_start, a.value_end, escape("it's", "'"))])
    assert new == data.replace("é&amp;\"q".encode(), b"it&apos;s")


def test_fixes_survive_the_cache(tmp_path):
    src = HEAD + LINKS + joint('<limit lower="2.1" upper="-2.1" effort="1" velocity="1"/>') + "</robot>\n"
    pkg = make_package(tmp_path, "cached", {"urdf/robot.urdf.xacro": src})
    runs = [run_main("check", ".", "--format", "json", "--isolated", cwd=pkg) for _ in range(2)]
    cold, warm = (json.loads(r.stdout) for r in runs)
    assert [m["cached"] for m in warm["models"]] == [True]
    assert cold["findings"] == warm["findings"]
    assert any("edits" in f.get("fix", {}) for f in warm["findings"])


def test_pre_commit_fix_hook_fails_when_it_changed_files(tmp_path):
    """The urdf-lint-fix hook's entry: exit 1 when it fixed something (as formatters do), then
    0 once the sources are clean of errors."""
    import yaml
    from conftest import REPO
    hooks = {h["id"]: h for h in yaml.safe_load((REPO / ".pre-commit-hooks.yaml").read_text())}
    entry = hooks["urdf-lint-fix"]["entry"].split()
    assert entry[0] == "urdf-lint" and hooks["urdf-lint-fix"]["pass_filenames"] is False
    src = HEAD + LINKS + joint('<limit lower="2.1" upper="-2.1" effort="1" velocity="1"/>') + "</robot>\n"
    pkg = make_package(tmp_path, "hook", {"urdf/robot.urdf.xacro": src})
    first = run_main(*entry[1:], "--isolated", "--no-cache", cwd=pkg)
    assert first.returncode == 1 and "Fixed 1 finding" in first.stderr, first.stderr
    second = run_main(*entry[1:], "--isolated", "--no-cache", cwd=pkg)
    assert second.returncode == 0 and "Fixed 0 findings" in second.stderr, second.stderr


def _sources(kind, element, bad):
    """(files, the file and text the fix must change) for an element whose value ``bad`` is
    written: in the element, as a property in another file, as a macro argument, as a YAML
    scalar, or in an expression."""
    robot = HEAD + "{inc}" + LINKS + "{body}</robot>\n"
    if kind == "literal":
        return {"urdf/robot.urdf.xacro": robot.format(inc="", body=element.format(v=bad))}, \
            "urdf/robot.urdf.xacro"
    if kind == "property":
        return {"urdf/robot.urdf.xacro": robot.format(
                    inc='  <xacro:include filename="$(find {pkg})/urdf/props.xacro"/>\n',
                    body=element.format(v="${v}")),
                "urdf/props.xacro": HEAD + f'  <xacro:property name="v" value="{bad}"/>\n</robot>\n'}, \
            "urdf/props.xacro"
    if kind == "macro":
        return {"urdf/robot.urdf.xacro": robot.format(
                    inc='  <xacro:include filename="parts.xacro"/>\n', body=f'  <xacro:part v="{bad}"/>\n'),
                "urdf/parts.xacro": HEAD + '  <xacro:macro name="part" params="v">\n'
                + element.format(v="${v}") + "  </xacro:macro>\n</robot>\n"}, "urdf/robot.urdf.xacro"
    if kind == "yaml":
        return {"urdf/robot.urdf.xacro": robot.format(
                    inc='  <xacro:property name="cfg" value="${load_yaml(\'cfg.yaml\')}"/>\n',
                    body=element.format(v="${cfg['v']}")),
                "urdf/cfg.yaml": f"# values\nv: {bad}  # here\n"}, "urdf/cfg.yaml"
    return {"urdf/robot.urdf.xacro": robot.format(
        inc="", body=element.format(v=bad.rsplit(" ", 1)[0] + " ${" + bad.rsplit(" ", 1)[1] + "*1}"))}, None


AXIS = ('  <joint name="j" type="continuous"><parent link="a"/><child link="b"/>'
        '<axis xyz="{v}"/></joint>\n')
COLOUR = '  <material name="red"><color rgba="{v}"/></material>\n'


@pytest.mark.parametrize("kind", ["literal", "property", "macro", "yaml", "expression"])
@pytest.mark.parametrize("code,element,bad,good", [
    ("UL307", AXIS, "0 0 2", "0 0 1"), ("UL208", COLOUR, "0 255 0 1", "0 1 0 1")])
def test_fix_where_the_value_is_written(tmp_path, kind, code, element, bad, good):
    import difflib
    files, edited = _sources(kind, element, bad)
    name = f"p{code.lower()}{kind}"
    files = {k: v.replace("{pkg}", name) for k, v in files.items()}
    pkg = make_package(tmp_path, name, files)
    if edited is None:
        (f,) = [f for f in findings(pkg) if f["code"] == code]
        assert f["fix"]["refused"].startswith(
            "not fixable automatically: the value comes from the expression at "), f
        assert f["fix"]["refused"].endswith("/urdf/robot.urdf.xacro:4")   # the element's line
        return
    old = files[edited]
    # the one literal changes; a YAML file keeps its comments
    new = old.replace(f'"{bad}"', f'"{good}"') if edited.endswith(".xacro") else \
        old.replace(f"v: {bad}", f"v: {good}")
    assert new != old
    diff = "".join(difflib.unified_diff(old.splitlines(True), new.splitlines(True),
                                        f"a/{edited}", f"b/{edited}"))
    fix_and_check(pkg, code, diff, {edited: new})


def test_a_bad_fix_option_is_a_config_error(tmp_path):
    pkg = make_package(tmp_path, "badopt", {"urdf/robot.urdf": CONT,
                                            "urdf-lint.toml": '[rule-options.UL305]\nfix = "drop"\n'})
    p = run_main("check", ".", "--no-cache", cwd=pkg)
    assert p.returncode == 2
    assert "rule-options.UL305.fix must be one of 'drop-limits', 'revolute', not 'drop'" in p.stderr


def test_a_macro_literal_that_needs_different_values_per_model_is_not_fixed(tmp_path):
    """The macro writes lower="2"; robot A passes upper -1, robot B upper -3: the swap needs
    lower=-1 for A and lower=-3 for B on the same bytes, so nothing is written."""
    parts = (HEAD + '  <xacro:macro name="hinge" params="upper">\n'
             '    <joint name="elbow" type="revolute"><parent link="a"/><child link="b"/>\n'
             '      <axis xyz="0 0 1"/><limit lower="2" upper="${upper}" effort="1" velocity="1"/>\n'
             '    </joint>\n  </xacro:macro>\n</robot>\n')
    def robot(up):
        return (HEAD + '  <xacro:include filename="parts.xacro"/>\n' + LINKS
                + f'  <xacro:hinge upper="{up}"/>\n</robot>\n')
    pkg = make_package(tmp_path, "perm", {"urdf/parts.xacro": parts, "urdf/a.urdf.xacro": robot("-1"),
                                          "urdf/b.urdf.xacro": robot("-3")})
    snapshot = {p: p.read_bytes() for p in pkg.rglob("*") if p.is_file()}
    f = run_main("check", ".", "--fix", "--no-cache", "--isolated", cwd=pkg)
    assert "Fixed 0 findings" in f.stderr, f.stderr
    assert "UL302 fix not applied: the models or macro calls that use urdf/parts.xacro need different values there ('-1' for urdf/a.urdf.xacro, '-3' for urdf/b.urdf.xacro)" in f.stderr, f.stderr
    assert {p: p.read_bytes() for p in pkg.rglob("*") if p.is_file()} == snapshot
    # the two robots' findings at the macro line are one finding with two instances
    (both,) = [f for f in findings(pkg) if f["code"] == "UL302"]
    assert both["count"] == 2 and len({i["message"] for i in both["instances"]}) == 2


def test_symlinked_source_stays_a_link(tmp_path):
    src = HEAD + LINKS + joint('<limit lower="2.1" upper="-2.1" effort="1" velocity="1"/>') + "</robot>\n"
    real = make_package(tmp_path, "real", {"urdf/robot.urdf.xacro": src})
    link = tmp_path / "ws"
    link.mkdir()
    (link / "robot.urdf.xacro").symlink_to(real / "urdf/robot.urdf.xacro")
    f = run_main("check", str(tmp_path), "--fix", "--no-cache", "--isolated", cwd=tmp_path)
    assert "Fixed" in f.stderr and (link / "robot.urdf.xacro").is_symlink()
    assert 'lower="-2.1" upper="2.1"' in (real / "urdf/robot.urdf.xacro").read_text()


def test_a_rolled_back_fix_is_not_retried_until_its_inputs_change(tmp_path):
    """--fix remembers a rollback (issue 22): the next run reports it without rewriting the
    sources; an edit to a file the models read makes it try again."""
    import os
    common = HEAD + '  <xacro:property name="lo" value="1"/>\n</robot>\n'

    def robot(hi, extra=""):
        return (HEAD + extra + '  <xacro:include filename="common.xacro"/>\n'
                f'  <xacro:property name="hi" value="{hi}"/>\n' + LINKS
                + joint('<limit lower="${lo}" upper="${hi}" effort="1" velocity="1"/>') + "</robot>\n")
    pkg = make_package(tmp_path, "shared", {"urdf/common.xacro": common,
                                            "urdf/a.urdf.xacro": robot("-1"),
                                            "urdf/b.urdf.xacro": robot("3")})
    cache = ["--cache-dir", str(tmp_path / "cache")]
    f = run_main("check", ".", "--fix", "--isolated", *cache, cwd=pkg)
    assert "UL302 fix rolled back: the edited source is also used by urdf/b.urdf.xacro" in f.stderr
    stamp = os.stat(pkg / "urdf/common.xacro").st_mtime_ns
    f = run_main("check", ".", "--fix", "--isolated", *cache, cwd=pkg)
    assert "fix rolled back" not in f.stderr, f.stderr
    assert ("UL302 fix not applied: rolled back on an earlier run (the edited source is also "
            "used by urdf/b.urdf.xacro") in f.stderr, f.stderr
    assert "not tried again until a file it depends on changes" in f.stderr
    assert os.stat(pkg / "urdf/common.xacro").st_mtime_ns == stamp   # not rewritten
    # an input of the models changes: tried (and rolled back) again
    (pkg / "urdf/b.urdf.xacro").write_text(robot("3", "  <!-- edited -->\n"))
    f = run_main("check", ".", "--fix", "--isolated", *cache, cwd=pkg)
    assert "UL302 fix rolled back: the edited source is also used by" in f.stderr, f.stderr


def test_a_fix_rolled_back_alone_is_tried_again_beside_the_fix_it_needs(tmp_path):
    """The soft limits are written from the same properties as the limits: the swap UL302
    asks for also changes the safety controller, so with UL302 alone it is rolled back; with
    UL306 selected too, its swap of the same values verifies beside it. The memory of the first
    run's rollback must not keep the second run from trying (the fixes tried together are part
    of what a rollback depended on)."""
    src = (HEAD + '  <xacro:property name="lo" value="2.0"/>\n'
           '  <xacro:property name="hi" value="-2.0"/>\n' + LINKS
           + joint('<limit lower="${lo}" upper="${hi}" effort="1" velocity="1"/>\n'
                   '    <safety_controller soft_lower_limit="${lo}" soft_upper_limit="${hi}" '
                   'k_position="1" k_velocity="1"/>') + "</robot>\n")
    pkg = make_package(tmp_path, "p", {"urdf/r.urdf.xacro": src})
    cache = ["--cache-dir", str(tmp_path / "cache")]
    f = run_main("check", ".", "--fix", "--isolated", "--select", "UL302", *cache, cwd=pkg)
    assert "UL302 fix rolled back: the fix changes more of" in f.stderr, f.stderr
    assert (pkg / "urdf/r.urdf.xacro").read_text() == src
    # the same run again: remembered, not tried
    f = run_main("check", ".", "--fix", "--isolated", "--select", "UL302", *cache, cwd=pkg)
    assert "UL302 fix not applied: rolled back on an earlier run" in f.stderr, f.stderr
    f = run_main("check", ".", "--fix", "--isolated", "--select", "UL302,UL306", *cache, cwd=pkg)
    assert "Fixed 2 findings in 1 file (0 remaining)" in f.stderr, f.stderr
    fixed = (pkg / "urdf/r.urdf.xacro").read_text()
    assert 'name="lo" value="-2.0"' in fixed and 'name="hi" value="2.0"' in fixed

