"""Content hashes of files (the cache and the mesh-facts cache key on them)."""
from __future__ import annotations

import os
import re
import stat as _st
from typing import Any, Protocol

try:   # BLAKE2 is built into CPython (keys of small blobs: no OpenSSL to load for them)
    from _blake2 import blake2b as blake2b   # (re-exported: the caches key on it)
except ImportError:   # pragma: no cover - another interpreter
    from hashlib import blake2b as blake2b

MAX_HASHED_BYTES = 2 << 30
LARGE_FROM_BYTES = 1 << 20
_large: Any = None


class Hash(Protocol):
    """What :func:`content_hash` gives (hashlib's hash objects, and BLAKE3's)."""
    def update(self, data: bytes | memoryview, /) -> Any: ...
    def hexdigest(self) -> str: ...


def content_hash(size: int) -> Hash:
    """A new hash for ``size`` bytes of file content. From 1 MiB on (meshes, most of what a
    cold run hashes, twice: the worker to find and key the mesh facts, the parent to vouch
    for them) BLAKE3, 3.5 times SHA-256's speed on this machine even with SHA-NI (4.0 vs
    1.1 GB/s, one thread); where its wheel is not installed, OpenSSL's SHA-256. Below,
    BLAKE2b, built in, so that a worker hashing only sources never loads either (~3 ms;
    ``expand``'s worker, tested). The choice depends on the content alone (its length), so a
    file always gets the same digest in one installation; another algorithm's digests only
    miss in a cache, never match."""
    global _large
    if size < LARGE_FROM_BYTES:
        return blake2b(digest_size=16)
    if _large is None:
        try:
            import blake3
            _large = blake3.blake3    # (one thread: the default)
        except ImportError:   # pragma: no cover - a platform without its wheel
            try:
                import _hashlib
                _large = _hashlib.openssl_sha256
            except ImportError:   # a Python built without OpenSSL
                import hashlib
                _large = hashlib.sha256
    h: Hash = _large()
    return h


def read_regular(path: str, max_bytes: int, nofollow: bool = False) -> bytes | None:
    """The bytes of a regular file of at most ``max_bytes`` (after symlinks, unless
    ``nofollow``), or None: it cannot be read, is larger, or is a device, FIFO or folder (it
    is opened without blocking, so a FIFO named as a file never hangs the run)."""
    from urdf_lint.core import fsbound
    return fsbound.read_regular(path, max_bytes, nofollow=nofollow)


def content_digest(data: bytes) -> str:
    """The 128-bit hex digest of bytes, as :func:`file_digest` gives it for a file holding
    them."""
    h = content_hash(len(data))
    h.update(data)
    return h.hexdigest()[:32]


def file_digest(path: str) -> str | None:
    """:func:`content_digest` of a regular file's bytes (None when it cannot be read or
    changes size while read, or for a device, FIFO, folder, or above 2 GiB: a symlink to
    /dev/zero must not hang the run or grow it without end)."""
    from urdf_lint.core import fsbound
    try:
        with fsbound.open_regular(path) as (f, st):
            if st.st_size > MAX_HASHED_BYTES:
                return None
            h = content_hash(st.st_size)
            left = st.st_size + 1
            # one buffer read into again and again (a new 1 MiB bytes object per chunk costs
            # a fifth of hashing a large mesh)
            buf = memoryview(bytearray(min(1 << 20, left)))
            reader: Any = f      # (a buffered reader: IO's stubs name no readinto)
            while True:
                n = reader.readinto(buf[:min(len(buf), left)])
                if not n:
                    break
                h.update(buf[:n])
                left -= n
                if left <= 0:
                    return None  # grew while read
            if left != 1:
                return None  # shrank while read
    except OSError:
        return None
    return h.hexdigest()[:32]


_memo: dict[tuple[Any, ...], str] = {}  # (path, dev, ino, size, mtime_ns) -> digest, this process only
MAX_MEMO = 100_000


def _memo_key(path: str) -> tuple[os.stat_result, tuple[Any, ...]]:
    """(stat, memo key) of a file now; raises OSError."""
    st = os.stat(path)
    return st, (path, st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns)


def _remember(key: tuple[Any, ...], digest: str) -> None:
    if len(_memo) >= MAX_MEMO:
        _memo.clear()
    _memo[key] = digest


def memo_digest(path: str) -> tuple[list[Any], str] | None:
    """([size, mtime_ns], digest) of a file, hashed once per file version in this process
    (the stat is taken before the read, as in :func:`file_record`). The mesh facts key on
    it, and a worker records every mesh a model read with it, so a mesh shared by many
    models is hashed once per worker, not once per model."""
    try:
        st, key = _memo_key(path)
    except OSError:
        return None
    digest = _memo.get(key)
    if digest is None:
        digest = file_digest(path)
        if digest is None:
            return None
        _remember(key, digest)
    return [st.st_size, st.st_mtime_ns], digest


def memo_entry(path: str) -> tuple[list[Any], str] | None:
    """([path, dev, ino, size, mtime_ns], digest) of a file this process hashed at the version
    it has now, else None (nothing is read): what the run's parent hands a worker with the
    facts of that file (:func:`known`), so the worker takes them without hashing it again."""
    try:
        _, key = _memo_key(path)
    except OSError:
        return None
    digest = _memo.get(key)
    return None if digest is None else (list(key), digest)


def known(key: Any, digest: Any) -> None:
    """Take the digest the run's parent computed of a file at version ``key``
    (:func:`memo_entry`): this process's :func:`memo_read` and :func:`memo_digest` give it
    while the file's stat still matches, without reading the file."""
    if isinstance(key, list | tuple) and len(key) == 5 and isinstance(key[0], str) \
            and all(type(x) is int for x in key[1:]) and isinstance(digest, str) \
            and _DIGEST.fullmatch(digest):
        k = tuple(key)
        if k not in _memo:
            _remember(k, digest)


_DIGEST = re.compile("[0-9a-f]{32}")


def memo_read(path: str, max_bytes: int) -> tuple[str, bytes | None] | None:
    """(digest, bytes) of a file hashed for the first time in this process and at most
    ``max_bytes`` long: it is read once, for the hash and for the caller (a mesh reader), and
    the digest is remembered like :func:`memo_digest`'s. A file hashed before, or a larger
    one: (digest, None). None when it cannot be read."""
    try:
        st, key = _memo_key(path)
    except OSError:
        return None
    if key not in _memo and _st.S_ISREG(st.st_mode) and st.st_size <= max_bytes:
        data = read_regular(path, max_bytes)
        if data is not None and len(data) == st.st_size:   # else changed: hashed again below
            digest = content_digest(data)
            _remember(key, digest)
            return digest, data
    got = memo_digest(path)
    return None if got is None else (got[1], None)


def stat_key(path: str) -> list[Any] | None:
    try:
        st = os.stat(path)
    except OSError:
        return None
    return [st.st_size, st.st_mtime_ns]


def file_record(path: str) -> list[Any] | None:
    """[stat, digest] of a file as read now: the stat is taken before the bytes are read, so a
    concurrent edit can only make the record stale, never wrong."""
    got = memo_digest(path)
    return None if got is None else [got[0], got[1]]


def read_recorded(path: str) -> tuple[bytes, list[Any]]:
    """(the bytes of ``path``, their record [stat before the read, digest of those bytes]):
    for a caller that needs the bytes themselves (raises OSError)."""
    from urdf_lint.core import fsbound
    before = os.stat(path)
    data = fsbound.read_bytes(path, max_bytes=MAX_HASHED_BYTES)
    return data, [[before.st_size, before.st_mtime_ns], content_digest(data)]
