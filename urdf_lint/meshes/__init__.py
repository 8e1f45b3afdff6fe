"""``urdf_lint.meshes``: finding mesh and texture files, reading them (STL, DAE, OBJ), the facts
measured of each (:class:`MeshFacts`) and the per-run store of them.

May import: ``runner``, ``discovery``, ``config``, ``report``, ``core`` (the rooms below it,
``[tool.importlinter]`` in pyproject.toml; never a room above).
"""
