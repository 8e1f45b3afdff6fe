"""Which models a set of changed files affects, through the dependency graph expansion records
(every xacro, YAML, mesh and texture a model read). The changed files come from
:func:`urdf_lint.discovery.vcs.changed_files` (``--changed-since``) or from pre-commit (``hook``)."""
from __future__ import annotations

import os
from collections.abc import Iterable
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.core.jobs import ModelReport


def _real(f: str) -> str:
    """realpath of a file that may be gone (its folder resolved)."""
    if os.path.exists(f):
        return os.path.realpath(f)
    return os.path.join(os.path.realpath(os.path.dirname(f)), os.path.basename(f))


def affected(models: Iterable["ModelReport"], files: Iterable[str]
             ) -> tuple[list["ModelReport"], list[str]]:
    """(models whose recorded inputs intersect ``files``, files no model uses). A model's
    inputs are its entry, every file it read and every file it looked for and did not find,
    so a deleted or renamed-away include, YAML file or mesh re-lints the models that used it."""
    real = {_real(f) for f in files}
    hit: list["ModelReport"] = []
    used: set[str] = set()
    for m in models:
        deps = {_real(d) for d in [*m.deps, *m.missing, m.entry]}
        inter = deps & real
        if inter:
            hit.append(m)
            used |= inter
    return hit, sorted(real - used)
