"""``urdf_lint.config``: the SCHEMA (every key's type, default, flag and trust rule; the docs' key
tables come from it), loading ``[tool.urdf-lint]``, what a repository may not loosen
(:mod:`.trust`) and the severity policy.

May import: ``report``, ``core`` (the rooms below it, ``[tool.importlinter]`` in pyproject.toml;
never a room above).
"""
