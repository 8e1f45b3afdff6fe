"""Which models a set of changed files affects, through the dependency graph expansion records
(every xacro, YAML, mesh and texture a model read). The changed files come from
:func:`urdf_lint.discovery.vcs.changed_files` (``--changed-since``) or from pre-commit (``hook``)."""
from __future__ import annotations

import os
from collections.abc import Iterable
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.core.jobs import ModelReport


def _real(f: str, folders: dict[str, str] | None = None) -> str:
    """realpath of a file that may be gone (its folder resolved). ``folders``: the real paths
    of folders resolved before (a run's models share most of their folders: resolving each
    folder once, not once per file under it, saves a stat of every folder above it per file)."""
    if os.path.exists(f):
        d, name = os.path.split(f)
        if folders is None or name in ("", ".", "..") or os.path.islink(f):
            return os.path.realpath(f)
    else:
        d, name = os.path.dirname(f), os.path.basename(f)
        if folders is None:
            return os.path.join(os.path.realpath(d), name)
    real = folders.get(d)
    if real is None:
        real = folders[d] = os.path.realpath(d)
    return os.path.join(real, name)


def affected(models: Iterable["ModelReport"], files: Iterable[str]
             ) -> tuple[list["ModelReport"], list[str]]:
    """(models whose recorded inputs intersect ``files``, files no model uses). A model's
    inputs are its entry, every file it read and every file it looked for and did not find,
    so a deleted or renamed-away include, YAML file or mesh re-lints the models that used it."""
    folders: dict[str, str] = {}
    done: dict[str, str] = {}

    def real_of(f: str) -> str:
        r = done.get(f)
        if r is None:
            r = done[f] = _real(f, folders)
        return r
    real = {real_of(f) for f in files}
    hit: list["ModelReport"] = []
    used: set[str] = set()
    for m in models:
        deps = {real_of(d) for d in [*m.deps, *m.missing, m.entry]}
        inter = deps & real
        if inter:
            hit.append(m)
            used |= inter
    return hit, sorted(real - used)
