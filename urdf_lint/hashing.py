"""Content hashes of files (the cache and the mesh-facts cache key on them)."""
from __future__ import annotations

import hashlib
import os
import stat as _st

MAX_HASHED_BYTES = 2 << 30


def file_digest(path: str) -> str | None:
    """A 128-bit BLAKE2b hex digest of a regular file's bytes (None when it cannot be read, or
    for a device, FIFO, folder, or above 2 GiB: a symlink to /dev/zero must not hang the run
    or grow it without end)."""
    h = hashlib.blake2b(digest_size=16)
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
        with os.fdopen(fd, "rb") as f:
            st = os.fstat(f.fileno())
            if not _st.S_ISREG(st.st_mode) or st.st_size > MAX_HASHED_BYTES:
                return None
            left = st.st_size + 1
            while True:
                chunk = f.read(min(1 << 20, left))
                if not chunk:
                    break
                h.update(chunk)
                left -= len(chunk)
                if left <= 0:
                    return None  # grew while read
    except OSError:
        return None
    return h.hexdigest()


def stat_key(path) -> list | None:
    try:
        st = os.stat(path)
    except OSError:
        return None
    return [st.st_size, st.st_mtime_ns]


def file_record(path: str, data: bytes | None = None) -> list | None:
    """[stat, digest] of a file as read now: the stat is taken before the bytes are read (or
    passed in as ``data``), so a concurrent edit can only make the record stale, never wrong."""
    before = stat_key(path)
    if before is None:
        return None
    if data is None:
        digest = file_digest(path)
    else:
        digest = hashlib.blake2b(data, digest_size=16).hexdigest()
    return None if digest is None else [before, digest]
