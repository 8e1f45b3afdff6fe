"""Atomic file writes: write beside the target, then rename over it, so a reader (or a run
that is killed half-way) never sees a half-written report, cache entry or snapshot."""
from __future__ import annotations

import contextlib
import os


@contextlib.contextmanager
def atomic_path(path, suffix: str = ""):
    """Yield a temporary path beside ``path``; on success it replaces ``path``, on an
    exception it is removed. For writers that want a file name (``img.save``, rerun)."""
    path = os.fspath(path)
    tmp = f"{path}.tmp{os.getpid()}{suffix}"
    try:
        yield tmp
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(tmp)
        raise


@contextlib.contextmanager
def atomic_open(path, mode: str = "w", encoding: str | None = "utf-8"):
    """``open`` for writing whose result appears at ``path`` only when the block succeeds."""
    with atomic_path(path) as tmp:
        with open(tmp, mode, encoding=None if "b" in mode else encoding) as fh:
            yield fh


def atomic_write(path, data: str | bytes, encoding: str = "utf-8") -> None:
    """Write ``data`` (text or bytes) to ``path`` atomically."""
    with atomic_open(path, "wb" if isinstance(data, bytes) else "w", encoding) as fh:
        fh.write(data)


def atomic_rewrite(path, data: bytes) -> None:
    """Rewrite a source file in place (``check --fix``, ``--add-suppressions``), atomically:
    a symlink is followed, so the link stays a link and its target gets the new bytes, and
    the file keeps its mode."""
    path = os.path.realpath(path)
    with atomic_path(path) as tmp:
        with open(tmp, "wb") as fh:
            fh.write(data)
        with contextlib.suppress(OSError):
            os.chmod(tmp, os.stat(path).st_mode & 0o7777)


__all__ = ["atomic_path", "atomic_open", "atomic_write", "atomic_rewrite"]
