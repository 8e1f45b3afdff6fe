"""``urdf_lint.core``: what every room shares: findings (Problem), locations, jobs (LintJob,
LintSettings, ModelReport), edits, targets, the file-system boundary (:mod:`.fsbound`), the one
escaper (:mod:`.escape`, :mod:`.emit`), signing and hashing.

May import: nothing of urdf_lint (the bottom room; ``[tool.importlinter]`` in pyproject.toml).
"""
