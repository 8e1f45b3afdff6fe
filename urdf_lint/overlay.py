"""Unsaved editor buffers read in place of the files on disk (``urdf-lint server``).

The language server lints what the user sees, not what was last saved. The buffers travel
with the job (``LintJob.overlay``: ``(path, bytes)`` pairs) to the sandboxed worker, which
installs them here for the job's duration (:func:`using`); every read of a source file the
expansion, the lint and the fixes make (includes, ``xacro.load_yaml``, the entry, suppression
comments, fix sources) asks :func:`get` first. The confinement checks run before the lookup,
on the same path, so a buffer is only ever read where the file it stands for could be: the
overlay never widens what a worker may read, and no temporary file is written anywhere.
"""
from __future__ import annotations

import os
from contextlib import contextmanager

_files: dict[str, bytes] = {}


def _key(path: str) -> str:
    return os.path.realpath(path)


@contextmanager
def using(pairs):
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


def get(path) -> bytes | None:
    """The buffer standing for ``path``, or None (read the file)."""
    if not _files:
        return None
    return _files.get(_key(os.fspath(path)))


def read(path) -> bytes:
    """The buffer for ``path`` or the file's bytes (raises OSError like ``open``)."""
    got = get(path)
    if got is not None:
        return got
    with open(path, "rb") as f:
        return f.read()


def record(data: bytes) -> list:
    """The cache record of a buffer (no stat: it was never written; such a result is not
    cached)."""
    from .hashing import content_digest
    return [[len(data), -1], content_digest(data)]
