"""Which models a set of changed files affects, through the dependency graph expansion records
(every xacro, YAML, mesh and texture a model read). The changed files come from
:func:`urdf_lint.vcs.changed_files` (``--changed-since``) or from pre-commit (``hook``)."""
from __future__ import annotations

import os

from .vcs import GitError, changed_files  # noqa: F401 - the names callers used to import here


def affected(models, files: set[str]):
    """(models whose inputs intersect ``files``, files no model uses)."""
    files = {os.path.realpath(f) for f in files}
    hit, used = [], set()
    for m in models:
        deps = {os.path.realpath(d) for d in m.deps} | {os.path.realpath(m.entry)}
        inter = deps & files
        if inter:
            hit.append(m)
            used |= inter
    return hit, sorted(files - used)
