"""``urdf_lint.formatting``: the xacro-aware layout of ``urdf-lint format`` (:mod:`.layout`) and
the proof from the file itself that a layout changes no robot (:mod:`.inert`).

May import: ``rules``, ``engine``, ``fix``, ``meshes``, ``expansion``, ``runner``,
``discovery``, ``config``, ``report``, ``core`` (the rooms below it, ``[tool.importlinter]`` in
pyproject.toml; never a room above).
"""
