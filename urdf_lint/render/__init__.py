"""``urdf_lint.render``: snapshots: the CPU rasteriser, the scene from an expanded robot, rerun
recordings and the joint sweep.

May import: ``rules``, ``engine``, ``fix``, ``meshes``, ``expansion``, ``runner``,
``discovery``, ``config``, ``report``, ``core`` (the rooms below it, ``[tool.importlinter]`` in
pyproject.toml; never a room above).
"""
