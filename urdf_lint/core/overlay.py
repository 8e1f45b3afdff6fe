"""Unsaved editor buffers read in place of the files on disk (``urdf-lint server``).

The language server lints what the user sees, not what was last saved. The buffers travel
with the job (``LintJob.overlay``: ``(path, bytes)`` pairs) to the sandboxed worker, which
installs them here for the job's duration (:func:`using`); every read of a source file the
expansion, the lint and the fixes make (includes, ``xacro.load_yaml``, the entry, suppression
comments, fix sources) goes through ``fsbound.read_bytes``, which asks :func:`get` first,
after the same roots check (and the expansion's own confinement check before it), so a
buffer is only ever read where the file it stands for could be: the overlay never widens what
a worker may read, and no temporary file is written anywhere. ``urdf-lint format`` hands its
layouts being proved to the workers the same way.
"""
from __future__ import annotations

import os
from contextlib import contextmanager
from typing import Iterable, Iterator

_files: dict[str, bytes] = {}


def _key(path: str) -> str:
    return os.path.realpath(path)


@contextmanager
def using(pairs: dict[str, bytes] | Iterable[tuple[str, bytes]] | None) -> Iterator[None]:
    """Read ``pairs`` (``(path, bytes)``, or a dict) in place of those files until the block
    ends (nested uses add to the outer ones)."""
    items = pairs.items() if isinstance(pairs, dict) else pairs
    saved = dict(_files)
    for path, data in items or ():
        _files[_key(path)] = bytes(data)
    try:
        yield
    finally:
        _files.clear()
        _files.update(saved)


def active() -> bool:
    return bool(_files)


def get(path: str | os.PathLike[str]) -> bytes | None:
    """The buffer standing for ``path``, or None (read the file)."""
    if not _files:
        return None
    return _files.get(_key(os.fspath(path)))
