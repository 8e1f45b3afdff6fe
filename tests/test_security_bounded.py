"""Linear work on untrusted input in the parent (issue 21, items 10 and 11): unknown-package
lookups and the suppression-comment scan. Each input is generated at a size where the quadratic
code took a minute or more (measured: 82 s and 57-60 s) and the linear code well under a
second; each run has a timeout of a few seconds."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import pytest

from conftest import make_package, run_cli

X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def test_unknown_package_lookups_are_memoised_with_one_index_of_ros_package_path(tmp_path):
    """1,000 ``$(find nopkgN)`` with a ROS_PACKAGE_PATH of 2,000 folders: one walk of the
    search path per run and a lookup per name (each miss walked it again: 82 s)."""
    rpp = tmp_path / "rpp"
    for i in range(2000):
        (rpp / f"d{i // 50}" / f"f{i}").mkdir(parents=True)
    make_package(rpp / "d0", "extpkg", {"urdf/m.xacro": f"<robot {X}/>\n"})
    includes = "".join(f'  <xacro:include filename="$(find nopkg{i})/x.xacro"/>\n'
                       for i in range(1000))
    repo = tmp_path / "repo"
    make_package(repo, "p", {"urdf/r.urdf.xacro":
                             f'<robot name="r" {X}>\n  <link name="a"/>\n'
                             '  <xacro:include filename="$(find extpkg)/urdf/m.xacro"/>\n'
                             f'{includes}</robot>\n'})
    t0 = time.monotonic()
    p = run_cli("check", ".", "--no-cache", "--format", "json", cwd=repo,
                env={"ROS_PACKAGE_PATH": str(rpp)}, timeout=20)
    took = time.monotonic() - t0
    assert p.returncode == 1, p.stderr
    found = json.loads(p.stdout)["findings"]
    # the package on the search path is found; the first unknown one stops the expansion
    assert [(f["code"], f["line"]) for f in found] == [("UL004", 4)], found
    assert "nopkg0" in found[0]["message"] and "ROS_PACKAGE_PATH (1 folder)" in found[0]["message"]
    assert took < 10, took


def _scan(path, timeout=5.0) -> tuple[int, float]:
    """(directives found, seconds) of the parent's scan of ``path``, in a process of its own."""
    code = ("import sys\nfrom urdf_lint.engine.suppress import parse_directives\n"
            "print(len(parse_directives(sys.argv[1])))\n")
    t0 = time.monotonic()
    p = subprocess.run([sys.executable, "-c", code, str(path)], capture_output=True, text=True,
                       timeout=timeout, env=dict(os.environ))
    assert p.returncode == 0, p.stderr
    return int(p.stdout), time.monotonic() - t0


@pytest.mark.parametrize("shape", ["unclosed", "closed-after-a-long-line"])
def test_the_suppression_scan_is_linear(tmp_path, shape):
    """600 kB of unclosed ``<!-- urdf-lint:`` (each opening searched the rest of the file for
    ``-->``: over 60 s), and 8,000 valid ``disable-next`` comments after a 3 MB line (each
    counted the lines from the top and scanned every element for the next one: 57 s)."""
    f = tmp_path / "r.urdf"
    if shape == "unclosed":
        f.write_text('<robot name="r">' + "<!-- urdf-lint:" * 40000 + "</robot>\n")
        expected = 0
    else:
        body = "".join(f'<!-- urdf-lint: disable-next UL101 -->\n<link name="l{i}"/>\n'
                       for i in range(8000))
        f.write_text('<robot name="r"><!-- ' + "x" * 3_000_000 + ' -->\n' + body + "</robot>\n")
        expected = 8000
    n, took = _scan(f)
    assert n == expected and took < 3, (n, took)


def test_the_scan_finds_what_the_pattern_finds():
    """The one-pass scan yields exactly what the directive pattern's ``finditer`` yields, on
    generated texts made of its pieces (unclosed, nested, ``-->`` inside the kind...)."""
    import random

    from urdf_lint.engine.suppress import _DIRECTIVE, _comments
    pieces = ["<!--", "-->", " ", "\n", "urdf-lint", "urdf_lint", ":", "disable", "-", "next",
              "UL1", ",", ">", "x", "--", "enable"]
    rnd = random.Random(21)
    for _ in range(5000):
        text = "".join(rnd.choice(pieces) for _ in range(rnd.randint(0, 30)))
        want = [(m.start(), m.end(), m.group(1), m.group(2)) for m in _DIRECTIVE.finditer(text)]
        assert list(_comments(text)) == want, text


def test_a_flood_of_unused_comments_is_linear(tmp_path):
    """20,000 unused ``disable-next`` comments: each is a UL009 with its removal fix, found
    from one read and one line table of the file (each read the file and counted its lines
    from the top again)."""
    line = "<!-- urdf-lint: disable-next UL101 -->\n"
    repo = tmp_path / "repo"
    make_package(repo, "p", {"urdf/r.urdf": '<?xml version="1.0"?>\n<robot name="r">\n'
                             '  <link name="a"/>\n' + line * 20000 + "</robot>\n"})
    t0 = time.monotonic()
    p = run_cli("check", ".", "--no-cache", "--format", "concise", cwd=repo, timeout=60)
    took = time.monotonic() - t0
    assert p.returncode == 0 and p.stdout.count("UL009") == 20000, p.stdout[-500:]
    assert took < 15, took
