"""``urdf_lint.fix``: tracing a value to the place that wrote it, the fix requests and their kinds
(one class per kind in :mod:`.kinds`), the source edits, ``--add-suppressions`` and the memory
of rolled-back fixes.

May import: ``meshes``, ``expansion``, ``runner``, ``discovery``, ``config``, ``report``,
``core`` (the rooms below it, ``[tool.importlinter]`` in pyproject.toml; never a room above).
"""
