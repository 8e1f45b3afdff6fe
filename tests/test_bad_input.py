"""Bad input gives one located diagnostic, a non-zero exit and never a traceback."""
from __future__ import annotations

import pytest

from conftest import make_package, run_main

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'

CASES = {
    "malformed-xml": ({"urdf/r.urdf.xacro": f'<robot name="r" {X}>\n  <link name="a">\n</robot>\n'},
                      "UL001", "urdf/r.urdf.xacro:3:3"),
    "malformed-include": ({"urdf/r.urdf.xacro": f'<robot name="r" {X}>\n  <xacro:include filename="inc.xacro"/>\n  <link name="a"/>\n</robot>\n',
                           "urdf/inc.xacro": f'<robot {X}>\n\n   <oops\n</robot>\n'},
                          "UL001", "urdf/inc.xacro:4:1"),
    "missing-include": ({"urdf/r.urdf.xacro": f'<robot name="r" {X}>\n  <link name="a"/>\n  <xacro:include filename="nope.xacro"/>\n</robot>\n'},
                        "UL003", "urdf/r.urdf.xacro:3:3"),
    "undefined-macro": ({"urdf/r.urdf.xacro": f'<robot name="r" {X}>\n  <link name="a"/>\n\n    <xacro:no_such_macro x="1"/>\n</robot>\n'},
                        "UL002", "urdf/r.urdf.xacro:4:5"),
    "undefined-property": ({"urdf/r.urdf.xacro": f'<robot name="r" {X}>\n  <xacro:macro name="m">\n    <link name="${{nope}}"/>\n  </xacro:macro>\n  <xacro:m/>\n</robot>\n'},
                           "UL002", "urdf/r.urdf.xacro:3:5"),
    "bad-macro-parameter": ({"urdf/r.urdf.xacro": f'<robot name="r" {X}>\n  <xacro:macro name="m" params="a">\n    <link name="${{a}}"/>\n  </xacro:macro>\n  <xacro:m a="1" b="2"/>\n</robot>\n'},
                            "UL002", "urdf/r.urdf.xacro:5:3"),
    "unknown-package": ({"urdf/r.urdf.xacro": f'<robot name="r" {X}>\n  <xacro:include filename="$(find ghost_pkg)/x.xacro"/>\n  <link name="a"/>\n</robot>\n'},
                        "UL004", "urdf/r.urdf.xacro:2:3"),
    "required-arg": ({"urdf/r.urdf.xacro": f'<robot name="r" {X}>\n  <link name="$(arg link_name)"/>\n</robot>\n'},
                     "UL005", "urdf/r.urdf.xacro:2:3"),
    "not-xml": ({"urdf/r.urdf": b"\x89PNG\r\n\x1a\n\x00\x00garbage"}, "UL001", "urdf/r.urdf:1:1"),
    "empty-file": ({"urdf/r.urdf": ""}, "UL001", "urdf/r.urdf:1:1"),
    "empty-xacro": ({"urdf/r.urdf.xacro": ""}, "UL001", "urdf/r.urdf.xacro:1:1"),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_one_located_diagnostic(tmp_path, name):
    files, code, loc = CASES[name]
    pkg = make_package(tmp_path, "bad_pkg", files)
    p = run_main("check", ".", "--no-cache", cwd=pkg)
    assert p.returncode == 1, p.stdout + p.stderr
    diag = [ln for ln in p.stdout.splitlines() if ": UL" in ln]
    assert len(diag) == 1, p.stdout
    assert diag[0].startswith(f"{loc}: {code} "), diag[0]
    assert p.stderr == ""


def test_messages_name_the_culprit(tmp_path):
    pkg = make_package(tmp_path, "bad_pkg", CASES["unknown-package"][0])
    out = run_main("check", ".", "--no-cache", cwd=pkg).stdout
    assert "unknown package 'ghost_pkg'" in out and "package.xml under" in out
    pkg = make_package(tmp_path / "b", "bad_pkg", CASES["required-arg"][0])
    out = run_main("check", ".", "--no-cache", cwd=pkg).stdout
    assert "xacro arg 'link_name'" in out


def test_expand_command_reports_and_writes_nothing(tmp_path):
    pkg = make_package(tmp_path, "bad_pkg", CASES["missing-include"][0])
    out = tmp_path / "out" / "r.urdf"
    p = run_main("expand", pkg / "urdf/r.urdf.xacro", "-o", out)
    assert p.returncode == 1
    assert "UL003" in p.stderr and "r.urdf.xacro:3:3" in p.stderr
    assert not out.exists() and not out.parent.exists()


def test_usage_errors_exit_2(tmp_path):
    assert run_main("check", tmp_path / "does-not-exist").returncode == 2
    assert run_main("check", ".", "--select", "XX999", cwd=tmp_path).returncode == 2
    assert run_main("frobnicate").returncode == 2
    (tmp_path / "urdf-lint.toml").write_text("selcet = ['UL1']\n")
    p = run_main("check", ".", cwd=tmp_path)
    assert p.returncode == 2 and "unknown key" in p.stderr and "selcet" in p.stderr


def test_a_folder_named_in_another_encoding_is_linted_without_an_internal_error(tmp_path):
    """A repository folder whose name is not UTF-8 (Latin-1 bytes): its paths reach lxml
    (include graph, branch analysis), the expansion (``$(find)``, the output header compared
    with a generated URDF) and every output format. Each model gets its findings and the run
    its exit code; none is an internal error."""
    import os
    import shutil
    from conftest import DESCRIPTIONS
    top = os.path.join(os.fsencode(tmp_path), b"\xe9quipe_robots")
    src = DESCRIPTIONS / "broken" / "broken_robots"
    pkg = os.path.join(top, b"broken_robots")
    shutil.copytree(os.fsencode(src / "meshes"), os.path.join(pkg, b"meshes"))
    os.makedirs(os.path.join(pkg, b"urdf", b"generated"))
    for name in ("package.xml", "urdf/mesh_base.urdf.xacro", "urdf/generated/mesh_base.urdf",
                 "urdf/xrefs.urdf.xacro", "urdf/branches.urdf.xacro"):
        shutil.copy(os.fsencode(src / name), os.path.join(pkg, os.fsencode(name)))
    for fmt in ("json", "sarif", "text"):
        p = run_main("check", os.fsdecode(top), "--no-cache", "--format", fmt)
        assert p.returncode == 1, (fmt, p.stderr[-2000:])
        assert "internal error" not in p.stderr, (fmt, p.stderr[-2000:])
