"""Content hashes of files (the cache and the mesh-facts cache key on them)."""
from __future__ import annotations

import hashlib


def file_digest(path: str) -> str | None:
    """A 128-bit BLAKE2b hex digest of the file's bytes, or None when it cannot be read."""
    h = hashlib.blake2b(digest_size=16)
    try:
        with open(path, "rb") as f:
            for chunk in iter(lambda: f.read(1 << 20), b""):
                h.update(chunk)
    except OSError:
        return None
    return h.hexdigest()
