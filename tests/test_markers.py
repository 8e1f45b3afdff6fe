"""The unit/e2e split (tests/conftest.py): every test has exactly one of the two markers, and
the rule that sets them reads what a test uses (the CLI as a subprocess, another program, the
corpus), through the helpers it calls, not a list of names."""
from __future__ import annotations

import importlib

from conftest import _uses_e2e, collected_items, kind_of


def _why(module: str, name: str):
    func = getattr(importlib.import_module(module), name)
    return _uses_e2e(func.__code__, func.__globals__, set())


def test_every_collected_test_is_unit_or_e2e(request):
    items = collected_items(request.config)
    assert request.node in items
    both_or_none = [i.nodeid for i in items
                    if any(i.iter_markers(name="unit")) == any(i.iter_markers(name="e2e"))]
    assert both_or_none == [], both_or_none
    for item in items:       # and the one it has is the rule's (a hand-set marker agrees)
        kind, why = kind_of(item)
        assert any(item.iter_markers(name=kind)), (item.nodeid, kind, why)


def test_the_rule_follows_what_a_test_uses():
    # run_cli, in the test itself and reached through a module-level helper (lint)
    assert _why("test_accuracy", "test_broken_demo_shows_every_class") == \
        "test_broken_demo_shows_every_class uses run_cli"
    assert _why("test_cache", "test_invalidation") == "run uses run_cli"
    # a subprocess of another program, reached through a helper of tests/support (stock xacro)
    assert _why("test_fixes", "fix_and_check") in ("stock_xacro uses executable",
                                                  "stock_xacro uses subprocess")
    # the corpus, by a module-level path under it (tests/test_recording.py's GRIPPER)
    assert _why("test_recording", "test_robotiq_mimic_joints_follow") == \
        "test_robotiq_mimic_joints_follow reads the corpus (GRIPPER)"
    # in process: the CLI's main() in this process (run_main), a tokeniser
    assert _why("test_fixes", "test_fix_options_are_checked") is None
    assert _why("test_accuracy", "test_negative_mass_is_always_an_error") is None
    assert _why("test_fixes", "test_start_tag_tokeniser_on_raw_bytes") is None


def test_the_whole_unit_half_runs_on_every_core_and_chosen_files_in_one_process():
    """``pytest -m unit`` with no paths (the inner loop) is spread over the machine's cores by
    pytest-xdist; ``-m e2e`` and a run of chosen files stay in one process."""
    import os
    import subprocess
    import sys
    import pytest
    from conftest import REPO
    pytest.importorskip("xdist")
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    if (cores or 1) < 2:
        pytest.skip("one core: xdist's auto is one worker")
    env = {k: v for k, v in os.environ.items() if k != "PYTEST_XDIST_AUTO_NUM_WORKERS"}

    def run(*args):     # (xdist does not distribute --collect-only: one quick test is run)
        p = subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider",
                            "-k", "test_the_rule_follows_what_a_test_uses", *args], cwd=REPO,
                           capture_output=True, text=True, env=env, timeout=300)
        assert p.returncode in (0, 5), p.stdout[-2000:] + p.stderr[-2000:]  # (5: none chosen)
        return p.stdout
    assert f"created: {cores}/{cores} workers" in run("-m", "unit")
    out = run("-m", "unit", "tests/test_markers.py")
    assert "1 passed" in out and "workers" not in out
    assert "workers" not in run("-m", "e2e")
