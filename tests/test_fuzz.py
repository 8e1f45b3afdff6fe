"""Fuzz: mutate real models at the XML and expression level. The linter must never print a
traceback, never hang past its limit, and always exit 0, 1 or 2.

Bounded in CI; run longer with URDF_LINT_FUZZ_EXAMPLES=2000 .venv/bin/python -m pytest tests/test_fuzz.py
"""
from __future__ import annotations

import io
import os
import shutil
import time
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from conftest import CORPUS, DESCRIPTIONS

EXAMPLES = int(os.environ.get("URDF_LINT_FUZZ_EXAMPLES", "40"))

SEEDS = [DESCRIPTIONS / "r2d2_description/urdf/r2d2_macros.xacro",
         DESCRIPTIONS / "double_pendulum_description/urdf/double_pendulum.urdf.xacro"]
if (CORPUS / "urdf_tutorial").is_dir():
    SEEDS.append(CORPUS / "urdf_tutorial/urdf/08-macroed.urdf.xacro")
    SEEDS.append(CORPUS / "urdf_tutorial/urdf/07-physics.urdf")

SEED_TEXT = {p: p.read_text() for p in SEEDS}  # a snapshot: generation must not depend on disk

EXPRESSIONS = ["${1/0}", "${9**9**9}", "${'a'*10**9}", "${[1,2][5]}", "${undefined}", "${(}",
               "${xacro.load_yaml('/etc/passwd')}", "${''.__class__}", "$(arg nope)",
               "$(find nope)", "$(env HOME)", "${python.sum(python.range(10**4))}", "${-1e309}",
               "${float('nan')}", "${{'a': 1}['b']}", "${math.sqrt(-1)}", "${1 if True else}",
               "\x00", "&amp;", "]]>", "<!--", "${lambda: 0}", "${pi*2}", "${\"x\".join([])}"]
XML_BITS = ["<", ">", "/>", "</link>", "<link name=\"x\"/>", "<xacro:macro name=\"m\"/>",
            "<xacro:m/>", "<xacro:include filename=\"nope.xacro\"/>", "\"", "'", "=",
            "<joint name=\"j\" type=\"revolute\"/>", "<!DOCTYPE r>", "<?xml version=\"1.0\"?>"]


@st.composite
def mutated(draw):
    seed = draw(st.sampled_from(SEEDS))
    text = SEED_TEXT[seed]
    for _ in range(draw(st.integers(1, 4))):
        op = draw(st.sampled_from(["insert_expr", "insert_xml", "delete", "dup_line", "truncate",
                                   "swap_value"]))
        pos = draw(st.integers(0, max(0, len(text) - 1)))
        if op == "insert_expr":
            text = text[:pos] + draw(st.sampled_from(EXPRESSIONS)) + text[pos:]
        elif op == "insert_xml":
            text = text[:pos] + draw(st.sampled_from(XML_BITS)) + text[pos:]
        elif op == "delete":
            text = text[:pos] + text[pos + draw(st.integers(1, 40)):]
        elif op == "dup_line":
            lines = text.splitlines(keepends=True)
            if lines:
                i = draw(st.integers(0, len(lines) - 1))
                lines.insert(i, lines[i])
                text = "".join(lines)
        elif op == "truncate":
            text = text[:pos]
        else:
            i = text.find('="', pos)
            if i >= 0:
                j = text.find('"', i + 2)
                if j > 0:
                    text = text[:i + 2] + draw(st.sampled_from(EXPRESSIONS + ["", "0", "-1"])) + text[j:]
    return seed, text


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    d = tmp_path_factory.mktemp("fuzz")
    for src in {s.parent.parent for s in SEEDS}:
        shutil.copytree(src, d / src.name, dirs_exist_ok=True)
    return d


@settings(max_examples=EXAMPLES, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(case=mutated())
def test_never_crashes_or_hangs(workdir, case):
    from urdf_lint.cli.main import main
    seed, text = case
    target = workdir / seed.parent.parent.name / seed.parent.name / seed.name
    original = target.read_bytes()
    target.write_text(text)
    out, err = io.StringIO(), io.StringIO()
    t0 = time.monotonic()
    try:
        with redirect_stdout(out), redirect_stderr(err):
            rc = main(["check", str(target.parent.parent), "--no-cache", "--timeout", "10", "-j", "1"])
    finally:
        target.write_bytes(original)
    took = time.monotonic() - t0
    assert rc in (0, 1, 2)
    assert "Traceback" not in out.getvalue() + err.getvalue()
    assert "internal error" not in err.getvalue(), err.getvalue()
    assert took < 20
