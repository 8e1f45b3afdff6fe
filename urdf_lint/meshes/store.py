"""The mesh state of one run: what the reads of mesh files are allowed and where they cache,
owned by the run's :class:`urdf_lint.engine.lint.Context` (one per model linted), never set in
module globals by the worker.

The memories of measured results (keyed by file content: valid for any run) stay in
:mod:`urdf_lint.meshes.resolve`; what changes from one run to the next is here."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable


@dataclass
class MeshStore:
    """``inside``: the resolver's test that a path is inside the package roots (texture and MTL
    references outside are never read; None: no confinement); ``cache_dir``: the folder whose
    ``meshes/`` holds the measured facts and texture scans (None: memory only);
    ``keep_loaded``: a render run, whose renderer draws the meshes the rules measured (they are
    measured on the loaded trimesh and kept); ``env_failures``: how many results this store's
    reads measured that depend on the environment (a memory limit, a refused read), which
    must not be cached."""
    inside: Callable[[str], bool] | None = None
    cache_dir: str | None = None
    keep_loaded: bool = False
    env_failures: int = 0
