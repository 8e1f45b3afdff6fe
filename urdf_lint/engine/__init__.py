"""``urdf_lint.engine``: linting one model: the model aligned with its source (:mod:`.model`), the
rule registry (:mod:`.registry`, the one importer of the rules) and its docs (:mod:`.rulesdoc`),
suppressions, the baseline, and :mod:`.api`, the one module rules import.

May import: ``fix``, ``meshes``, ``expansion``, ``runner``, ``discovery``, ``config``,
``report``, ``core`` (the rooms below it, ``[tool.importlinter]`` in pyproject.toml; never a
room above).
"""
