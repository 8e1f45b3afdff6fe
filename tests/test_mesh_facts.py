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
