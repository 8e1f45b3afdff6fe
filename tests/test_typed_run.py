"""The run side's typed hand-offs (issue 23, item 2): ``run_check`` takes one ``RunRequest``."""
from __future__ import annotations

import dataclasses
import inspect

import pytest

from conftest import make_package

ROBOT = ('<robot name="r"><link name="a"/><link name="b"/>'
         '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
         '<axis xyz="0 0 1"/><limit lower="1" upper="0" effort="1" velocity="1"/></joint>'
         '</robot>\n')


def test_run_check_takes_one_frozen_request(tmp_path, monkeypatch):
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import RunRequest, run_check
    assert list(inspect.signature(run_check).parameters) == ["request"]
    pkg = make_package(tmp_path, "p", {"urdf/r.urdf": ROBOT})
    monkeypatch.chdir(pkg)
    cfg = load_config(None)
    paths = ["."]
    request = RunRequest(paths, cfg, build_resolver(paths, cfg), in_process=True,
                         affected_by={str(pkg / "urdf/r.urdf")})
    paths.append("elsewhere")      # the request holds its own copy
    assert request.paths == (".",) and request.affected_by == frozenset({str(pkg / "urdf/r.urdf")})
    with pytest.raises(dataclasses.FrozenInstanceError):
        request.keep_models = True   # type: ignore[misc]
    result = run_check(request)
    assert ("UL302", 1) in [(f.code, f.line) for f in result.findings]
    assert [m.entry for m in result.models] == [str(pkg / "urdf/r.urdf")]
    # a variant is a replace of the same request: the robots come back with it
    kept = run_check(dataclasses.replace(request, keep_models=True))
    assert kept.models[0].kept_model is not None and result.models[0].kept_model is None


def test_limits_travel_in_the_settings_with_one_default(tmp_path):
    """``timeout``/``memory-mb`` reach the workers inside ``LintSettings`` (no caller passes
    them beside it), and their default is written once: the config schema's."""
    from urdf_lint.config.schema import KEYS, Config
    from urdf_lint.core.jobs import LintSettings
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.run.pipeline import settings_for, worker_settings
    from urdf_lint.run.worker import LINT, run_jobs
    from urdf_lint.runner.pool import WorkerPool
    from urdf_lint.runner.pool import run_jobs as pool_run_jobs
    resolver = PackageResolver.build([str(tmp_path)], extra_roots=[str(tmp_path)])
    cfg = Config(timeout=2.5, memory_mb=300)
    for s in (settings_for(cfg, resolver, None), worker_settings(cfg, resolver)):
        assert (s.timeout, s.memory_mb) == (2.5, 300)
    plain = LintSettings(resolver={})
    assert (plain.timeout, plain.memory_mb) == (Config().timeout, Config().memory_mb) == \
        (KEYS["timeout"].default, KEYS["memory-mb"].default)
    # (``costs``: what the models took before, which plans the workers; no limit)
    assert list(inspect.signature(run_jobs).parameters) == ["jobs", "settings", "jobs_n",
                                                            "costs"]
    assert list(inspect.signature(pool_run_jobs).parameters) == ["jobs", "settings", "handler",
                                                                 "jobs_n", "costs"]
    # one pool for check and the language server (persistent there): the limits are the
    # settings' too
    assert list(inspect.signature(WorkerPool).parameters) == ["settings", "handler", "size",
                                                              "persistent"]
    assert WorkerPool(dataclasses.replace(plain, timeout=4.0), LINT).timeout == 4.0


def test_the_expansion_state_is_passed_in_and_the_hooks_find_it_in_one_holder(tmp_path):
    """``expand_file`` makes an ``ExpansionState`` and sets it in ``expand.CURRENT`` for the
    time of the expansion only (the previous value back after, also after a failure); the
    module keeps no state of its own, and a hook that needs one refuses to run outside."""
    import contextvars

    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.expansion import expand
    X = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
    (tmp_path / "inc.xacro").write_text(f'<robot {X}><link name="b"/></robot>')
    (tmp_path / "r.urdf.xacro").write_text(
        f'<robot name="r" {X}>\n  <xacro:include filename="inc.xacro"/>\n'
        '  <link name="$(env URDF_LINT_NOT_ALLOWED)a"/>\n</robot>\n')
    (tmp_path / "bad.urdf.xacro").write_text(f'<robot name="r" {X}>\n  <xacro:nope/>\n</robot>\n')
    resolver = PackageResolver.build([str(tmp_path)], extra_roots=[str(tmp_path)])
    outer = expand.ExpansionState(resolver, ())

    def expand_both():
        good = expand.expand_file(str(tmp_path / "r.urdf.xacro"), resolver=resolver)
        bad = expand.expand_file(str(tmp_path / "bad.urdf.xacro"), resolver=resolver)
        return good, bad, expand.CURRENT.get()

    ctx = contextvars.copy_context()
    ctx.run(expand.CURRENT.set, outer)
    good, bad, after = ctx.run(expand_both)
    assert after is outer and outer.notes == [] and outer.deps == {}
    assert good.error is None and '<link name="b"/>' in (good.xml or "")
    assert good.deps == [str(tmp_path / "r.urdf.xacro"), str(tmp_path / "inc.xacro")]
    assert [(n.code, n.line) for n in good.notes] == [("UL901", 3)]
    assert bad.error is not None and bad.error.line == 2
    assert expand.CURRENT.get() is None and not hasattr(expand, "_state")
    with pytest.raises(RuntimeError, match="outside an expansion"):
        expand._hook_eval_find("p")
