"""The cache folder's markers: whoever creates ``.urdf_lint_cache/`` first (the result cache
or the mesh-facts cache, possibly in a worker) leaves a ``.gitignore`` (so ``git add -A``
never commits it) and a ``CACHEDIR.TAG`` (so backup tools skip it)."""
from __future__ import annotations

import os

GITIGNORE = "# Automatically created by urdf-lint.\n*\n"
CACHEDIR_TAG = "Signature: 8a477f597d28d172789f06886806bc55\n# urdf-lint cache\n"


_done: set[str] = set()


def ensure(directory: str) -> None:
    """Create ``directory`` if needed and make sure both markers are in it (once a process)."""
    if directory in _done and os.path.isdir(directory):
        return
    _done.add(directory)
    from urdf_lint.core import fsbound
    fsbound.make_own_dirs(directory)
    for name, text in ((".gitignore", GITIGNORE), ("CACHEDIR.TAG", CACHEDIR_TAG)):
        p = os.path.join(directory, name)
        if not os.path.exists(p):
            from urdf_lint.core import fsbound
            try:
                fsbound.write_text(p, text, directory)
            except OSError:
                pass
