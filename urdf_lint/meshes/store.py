"""The mesh state of one run: what the reads of mesh files are allowed and where their facts
are kept, owned by the run's :class:`urdf_lint.engine.lint.Context` (one per model linted), never
set in module globals by the worker.

The facts of a mesh depend on its bytes only. They are kept across runs, repositories and
front ends in the user's cache (:class:`FactsStore`, ``$XDG_CACHE_HOME/urdf-lint/mesh-facts/``),
keyed on the content digest and signed like the result cache (:mod:`urdf_lint.core.signing`).
Only the parent process writes it: a worker (sandboxed, the store read-only to it) reads the
entries it can verify and sends what it measured back with its report
(:attr:`MeshStore.measured`); the parent hashes each mesh itself and stores the facts under
its own digest (:meth:`FactsStore.accept`), so a worker cannot file facts under content it
did not measure."""
from __future__ import annotations

import json
import os
import re
from dataclasses import dataclass, field
from typing import Any, Callable, Iterable, Iterator

from urdf_lint.core import fsbound

MAX_STORE_BYTES = 64 << 20       # the store's bound: the oldest entries go beyond it
MAX_ENTRY_BYTES = 1 << 20        # a facts record is a few hundred bytes
ENTRY_NAME = re.compile(r"^[a-z]+[0-9]+-[0-9a-f]{16,128}$")   # {prefix}-{content digest}
KEY_PURPOSE = "mesh-facts"

# the keys of the stores the parent opened (:func:`register`), by folder: a forked worker
# inherits them and verifies the entries it reads; it never writes the store
_keys: dict[str, bytes] = {}


def facts_dir() -> str:
    """The store's folder in the user's cache (beside the signing key of the result cache)."""
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "urdf-lint", "mesh-facts")


@dataclass
class FactsStore:
    """The persistent mesh facts: one signed JSON entry per ``{prefix}-{digest}`` (a prefix
    per kind of fact and version of its measurement) in ``dir``, at most ``max_bytes`` in all."""
    dir: str
    secret: bytes
    max_bytes: int = MAX_STORE_BYTES

    def _path(self, name: str) -> str:
        return os.path.join(self.dir, name + ".json")

    def get(self, name: str) -> dict[str, Any] | None:
        """The record stored under ``name``, if this user's key signed it there; else None
        (absent, forged, changed, copied from another name: the caller measures again)."""
        data = fsbound.read_regular(self._path(name), MAX_ENTRY_BYTES, nofollow=True)
        if data is None:
            return None
        from urdf_lint.core import signing   # (hashlib: only once a store is read)
        blob = signing.verified(self.secret, name + ".json", data)
        if blob is None:
            return None
        try:
            rec = json.loads(blob)
        except (ValueError, RecursionError):
            return None
        return rec if isinstance(rec, dict) and "ok" in rec else None

    def put(self, name: str, record: dict[str, Any]) -> bool:
        """Store ``record`` under ``name`` (the parent only). False when it could not."""
        blob = json.dumps(record).encode("utf-8")
        if not ENTRY_NAME.match(name) or len(blob) > MAX_ENTRY_BYTES:
            return False
        try:
            from urdf_lint.core.cachedir import ensure
            ensure(self.dir)       # CACHEDIR.TAG: backup tools skip it
            from urdf_lint.core import signing
            fsbound.write_bytes(self._path(name), signing.signed(self.secret, name + ".json",
                                                                 blob), self.dir)
            return True
        except OSError:
            return False

    def accept(self, measured: Iterable[list[Any]], inside: Callable[[str], bool] | None = None,
               digest_of: Callable[[str], str | None] | None = None) -> int:
        """Store what workers measured (:attr:`MeshStore.measured`: [name, path, digest,
        record]) whose mesh this process hashes to the same digest (``digest_of``; a path
        outside ``inside`` is not read); then keep the store within its bound. How many
        entries were written."""
        written = 0
        for name, _, record in verified(measured, inside, digest_of):
            written += self.put(name, record)
        if written:
            self.evict()
        return written

    def entries(self) -> list[tuple[float, int, str]]:
        """(mtime, size, path) of every entry."""
        out: list[tuple[float, int, str]] = []
        try:
            listing = fsbound.scan_dir(self.dir)
        except OSError:
            return out
        for e in listing:
            if e.name.endswith(".json"):
                try:
                    st = e.stat(follow_symlinks=False)
                except OSError:
                    continue
                out.append((st.st_mtime, st.st_size, e.path))
        return out

    def evict(self) -> int:
        """Remove the oldest entries until the store is within ``max_bytes``; how many."""
        found = sorted(self.entries())
        total = sum(size for _, size, _ in found)
        removed = 0
        for _, size, path in found:
            if total <= self.max_bytes:
                break
            if not fsbound.remove(path, self.dir):
                continue
            total -= size
            removed += 1
        return removed

    def clear(self) -> str | None:
        """Empty the store (``urdf-lint clean``): the folder removed, if there was one."""
        if os.path.isdir(self.dir) and not os.path.islink(self.dir):
            fsbound.remove_tree(self.dir)
            return self.dir
        return None


def verified(measured: Iterable[list[Any]], inside: Callable[[str], bool] | None = None,
             digest_of: Callable[[str], str | None] | None = None
             ) -> Iterator[tuple[str, str, dict[str, Any]]]:
    """(name, path, record) of what workers measured (:attr:`MeshStore.measured`: [name,
    path, digest, record]) whose mesh this process hashes to the digest the name carries
    (``digest_of``, memoized per file version; a path outside ``inside`` is not read)."""
    digest_of = digest_of or _digest_of
    for item in measured:
        try:
            name, path, digest, record = item
        except (TypeError, ValueError):
            continue
        if not (isinstance(name, str) and isinstance(path, str) and isinstance(digest, str)
                and isinstance(record, dict) and ENTRY_NAME.match(name)
                and name.endswith("-" + digest)):
            continue
        if inside is not None and not inside(path):
            continue
        if digest_of(path) != digest:     # changed since, or not what the worker says
            continue
        yield name, path, record


def _digest_of(path: str) -> str | None:
    from urdf_lint.core.hashing import memo_digest
    got = memo_digest(path)
    return None if got is None else got[1]


def register(store: FactsStore) -> None:
    """Make ``store`` readable by the runs of this process and of the workers it forks later
    (a worker's :class:`MeshStore` names its folder, ``LintSettings.mesh_cache_dir``)."""
    _keys[store.dir] = store.secret


def opened(directory: str | None) -> FactsStore | None:
    """The store registered for ``directory`` (None: no store, or not registered here)."""
    secret = _keys.get(directory) if directory else None
    return None if secret is None or directory is None else FactsStore(directory, secret)


@dataclass
class MeshStore:
    """``inside``: the resolver's test that a path is inside the package roots (texture and MTL
    references outside are never read; None: no confinement); ``cache_dir``: the folder of the
    run's :class:`FactsStore` (None: memory only; read only where it was :func:`register` ed);
    ``keep_loaded``: a render run, whose renderer draws the meshes the rules measured (they are
    measured on the loaded trimesh and kept); ``env_failures``: how many results this store's
    reads measured that depend on the environment (a memory limit, a refused read), which
    must not be cached; ``measured``: the facts measured here and not found in the store
    ([name, path, digest, record], plain values), for the parent to store."""
    inside: Callable[[str], bool] | None = None
    cache_dir: str | None = None
    keep_loaded: bool = False
    env_failures: int = 0
    measured: list[list[Any]] = field(default_factory=list)

    def facts(self) -> FactsStore | None:
        return opened(self.cache_dir)
