"""``urdf_lint.discovery``: which files are models and fragments, the include graph, packages,
workspaces, generated outputs, git and what a change touches.

May import: ``config``, ``report``, ``core`` (the rooms below it, ``[tool.importlinter]`` in
pyproject.toml; never a room above).
"""
