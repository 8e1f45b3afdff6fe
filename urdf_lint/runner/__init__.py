"""``urdf_lint.runner``: forked, sandboxed, limited worker processes and their scheduler; handed a
Handler, it knows neither lint nor render; results come back as plain data (:mod:`.wire`), never
pickle.

May import: ``discovery``, ``config``, ``report``, ``core`` (the rooms below it, less the
ones the contract "runner" forbids, ``[tool.importlinter]`` in pyproject.toml; never a room above).
"""
