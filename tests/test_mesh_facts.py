"""Mesh facts are typed (:class:`urdf_lint.meshes.facts.MeshFacts`, ``MassFacts``): the rules
read attributes, not a dict by string key."""
from __future__ import annotations

import pytest

from urdf_lint.engine.lint import Context
from urdf_lint.meshes import resolve as meshes
from urdf_lint.meshes.facts import MassFacts, MeshFacts


def test_the_context_gives_typed_facts_of_a_real_mesh_once_per_model(corpus):
    path = str(corpus / "robot_properties_fingers" / "meshes" / "finger_padding.stl")
    ctx = Context({}, None)
    f = ctx.mesh_facts(path)
    rec = meshes.mesh_facts(path)
    assert isinstance(f, MeshFacts) and f.ok and f.error == "" and f.finite
    assert (f.vertices, f.faces) == (rec["vertices"], rec["faces"]) and f.faces > 0
    assert f.bounds == (tuple(rec["bounds"][0]), tuple(rec["bounds"][1]))
    assert f.broken_refs == ()
    assert ctx.mesh_facts(path) is f                   # looked up once per model
    m = ctx.mass_facts(path)
    mrec = meshes.mass_facts(path)
    assert isinstance(m, MassFacts) and m.ok and m.volume == pytest.approx(mrec["volume"])
    assert m.first == tuple(mrec["first"]) and len(m.second) == 3 and m.hull == mrec["hull"]
    assert ctx.mass_facts(path) is m


def test_empty_and_unloadable_meshes_have_typed_facts_saying_so(tmp_path):
    empty = tmp_path / "pointer.stl"     # a Git LFS pointer checked out as the mesh: empty
    empty.write_text("version https://git-lfs.github.com/spec/v1\noid sha256:00\nsize 12\n")
    broken = tmp_path / "broken.dae"
    broken.write_text("<COLLADA><library_geometries><geometry")
    ctx = Context({}, None)
    f = ctx.mesh_facts(str(empty))
    assert f.ok and f.vertices == 0 and f.bounds is None
    f = ctx.mesh_facts(str(broken))
    assert not f.ok and f.error and f.bounds is None and f.vertices == 0
    assert ctx.mass_facts(str(empty)) == ctx.mass_facts(str(broken)) == MassFacts(False)


def test_a_job_changes_no_module_global_and_an_environment_failure_is_not_cached(
        tmp_path, monkeypatch):
    """The run's mesh state (confinement, cache folder, render run, environment failures)
    lives in the Context's MeshStore: linting a model rebinds no global of the mesh module,
    and a mesh the environment refused (here: out of memory) makes the result uncacheable."""
    from conftest import make_package
    from urdf_lint.core.jobs import LintJob, LintSettings
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.meshes import readers
    from urdf_lint.rules._meshes import TETRA_STL
    from urdf_lint.run.worker import process_job
    pkg = make_package(tmp_path, "p", {
        "meshes/part.stl": TETRA_STL,
        "urdf/r.urdf": '<robot name="r"><link name="a"><visual><geometry><mesh '
                       'filename="package://p/meshes/part.stl"/></geometry></visual></link></robot>'})
    settings = LintSettings(resolver=PackageResolver.build([str(pkg)]).to_dict(),
                            selected=("UL404",), mesh_cache_dir=str(tmp_path / "cache"))
    job = LintJob(str(pkg / "urdf" / "r.urdf"), kind="urdf")

    def no_memory(*a, **k):
        raise MemoryError("no memory")
    monkeypatch.setattr(readers, "binary_stl_triangles", no_memory)
    before = {k: v for k, v in vars(meshes).items() if not k.startswith("__")}
    report = process_job(job, settings)
    after = {k: v for k, v in vars(meshes).items() if not k.startswith("__")}
    assert [k for k in set(before) | set(after) if before.get(k) is not after.get(k)] == []
    [p] = [p for p in report.problems if p.code == "UL404"]
    assert "ran out of memory" in p.message
    assert not report.cacheable
    monkeypatch.undo()
    assert process_job(job, settings).cacheable     # measured now: an ordinary result
