"""``urdf_lint.preview``: the 3D page: ``urdf-lint preview`` (a local, read-only server of the
expanded robot, its meshes and its findings) and the self-contained review page that
``diff --html`` writes, with the vendored three.js and urdf-loader bundle (``static/``).

May import: ``review``, ``run``, ``render``, ``formatting``, ``rules``, ``engine``, ``fix``,
``meshes``, ``expansion``, ``runner``, ``discovery``, ``config``, ``report``, ``core`` (the
rooms below it, ``[tool.importlinter]`` in pyproject.toml; never a room above).
"""
