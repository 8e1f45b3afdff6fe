"""``urdf_lint.review``: ``urdf-lint diff``: both revisions linted, the robots compared element by
element (:mod:`.robotdiff`), the changes at the xacro lines that write them (:mod:`.run`).

May import: ``run``, ``render``, ``formatting``, ``rules``, ``engine``, ``fix``, ``meshes``,
``expansion``, ``runner``, ``discovery``, ``config``, ``report``, ``core`` (the rooms below it,
``[tool.importlinter]`` in pyproject.toml; never a room above).
"""
