"""Result cache, like ruff's: ``.urdf_lint_cache/`` at the repository root.

A model's entry is keyed on the tool version, the entry file, its args and the lint settings
(selected rules, options, package map, env allow-list). It is valid only while every file the
model read (xacro, YAML, meshes) still has the content it had, every file that was looked
for and missing is still missing, and every variable ``$(optenv)`` looked up outside the
allow-list is still set, or still unset, as it was (``ModelReport.env``). Stat data (size,
mtime) short-cuts the content hash. A corrupt or foreign entry is ignored.

The cache cannot lie (issue 15):

* every entry is signed (HMAC-SHA256) with a key kept outside the repository, in the user's
  cache folder (``$XDG_CACHE_HOME/urdf-lint/key``, created 0600): an entry committed to the
  repository, or written by anyone without the key, is ignored;
* a cache folder that git tracks, or that is a symlink, is refused (the run goes on uncached);
* the digests recorded are those of the bytes the worker actually read, with the file's stat
  taken before the read (:func:`file_record`), so a file edited during a run can never have
  the old result cached against its new content.
"""
from __future__ import annotations

import functools
import json
import os
import stat as _st
from pathlib import Path
from typing import TYPE_CHECKING, Any, Iterable, Sequence

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.config.schema import Config
    from urdf_lint.discovery.packages import PackageResolver
    from urdf_lint.meshes.store import FactsStore

from urdf_lint import __version__
from urdf_lint.core import fsbound, signing
from urdf_lint.discovery.discover import start_dir
from urdf_lint.core.hashing import blake2b, file_digest, file_record, memo_digest, read_regular, stat_key
from urdf_lint.core.jobs import (JobKey, LintJob, LintSettings, ModelReport, env_unchanged,
                                  job_key)
from urdf_lint.core.cachedir import ensure as ensure_cache_dir
from urdf_lint.discovery.vcs import git_root, repo_root

# bump when the stored record changes shape (4: signed, digests of what was read;
# 5: missing YAML files recorded as missing; 6: problems carry their fix; 7: the sources
# holding suppression comments, and folders read as files recorded as missing; 8: results of
# the stream-read mesh facts, a mesh refused by the memory limit is never cached; 14: the
# $(optenv) variables looked up and whether they were set)
RECORD_FORMAT = 15
MAX_COST_S = 3600.0    # the most a model's recorded seconds may say (more: not a cost)


def seconds(value: Any) -> float | None:
    """``value`` as a model's cost in seconds: a number above 0 and at most
    :data:`MAX_COST_S`; None for anything else."""
    if isinstance(value, (int, float)) and not isinstance(value, bool) \
            and 0 < value <= MAX_COST_S:
        return float(value)
    return None


def _recorded(site: str | None = None) -> dict[str, tuple[str, int]]:
    """Real path -> (sha256, size) of each module that pip's RECORD of the installed wheel
    lists; empty for an editable install or a source tree (their RECORD lists no module).
    Read from the ``urdf_lint-*.dist-info`` folder beside the package, as
    ``importlib.metadata`` finds it, without importing that (~11 ms, most of the cost of
    :func:`build_id` on every run)."""
    import csv
    import urdf_lint
    from urdf_lint.core import fsbound
    site = site or os.path.dirname(os.path.dirname(os.path.realpath(urdf_lint.__file__)))
    try:
        infos = sorted(n for n in fsbound.list_dir(site)
                       if n.startswith("urdf_lint-") and n.endswith(".dist-info"))
    except OSError:
        return {}
    mine = f"urdf_lint-{__version__}.dist-info"
    if not infos:
        return {}
    data = fsbound.read_regular(os.path.join(site, mine if mine in infos else infos[0],
                                             "RECORD"), MAX_RECORD_BYTES)
    out = {}
    for row in csv.reader((data or b"").decode("utf-8", "replace").splitlines()):
        if len(row) < 3 or not row[0].endswith(".py") or "=" not in row[1]:
            continue
        try:
            size = int(row[2])
        except ValueError:
            continue
        out[os.path.realpath(os.path.join(site, row[0]))] = (row[1].partition("=")[2], size)
    return out


MAX_RECORD_BYTES = 4 << 20


@functools.lru_cache(maxsize=None)
def build_id() -> str:
    """urdf-lint's version and a digest of its own code as installed (every module's path
    and size, and its content's hash from the wheel's RECORD, or else its modification
    time): a result cached by other code is not reused, also when an install from a newer
    commit keeps the version number, and two installs of one wheel agree (a CI job that
    installs afresh each run keeps its cache: the GitHub Action). ~2 ms: stats only."""
    import urdf_lint
    import urdf_lint.rules as rules
    from urdf_lint.core import fsbound
    recorded = _recorded()
    files = []
    for top in [*urdf_lint.__path__, *rules.__path__]:
        real = os.path.realpath(top)
        for rel, size, mtime in fsbound.stat_files(top, ".py"):
            known = recorded.get(os.path.join(real, rel))
            files.append([rel, size, known[0] if known and known[1] == size else mtime])
    digest = blake2b(json.dumps(files).encode(), digest_size=8).hexdigest()
    return f"{__version__}+{digest}"

__all__ = ["Cache", "file_digest", "file_record", "key_path"]


def key_path() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base, "urdf-lint", "key")


def _load_key(repo_dirs: Iterable[str] = ()) -> bytes | None:
    """The signing key, created on first use (0600, in a 0700 folder). None when it cannot
    be kept safely: then nothing is cached."""
    p = key_path()
    real = os.path.realpath(p.parent)
    if any(real == d or real.startswith(d.rstrip(os.sep) + os.sep) for d in
           (os.path.realpath(r) for r in repo_dirs if r)):
        return None  # a key inside the linted repository would be the repository's
    try:
        p.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        try:
            fd = os.open(p, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0),
                         0o600)
        except FileExistsError:
            pass
        else:
            with os.fdopen(fd, "wb") as f:
                f.write(os.urandom(32))
        fd = os.open(p, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0))
        with os.fdopen(fd, "rb") as f:
            st = os.fstat(f.fileno())
            if not _st.S_ISREG(st.st_mode) or (hasattr(os, "getuid") and st.st_uid != os.getuid()) \
                    or st.st_mode & 0o077:
                return None
            key = f.read(64)
        return key if len(key) >= 32 else None
    except OSError:
        return None


def _git_tracks(directory: str) -> bool:
    from urdf_lint.discovery.vcs import GitError, git
    try:
        return bool(git("ls-files", "--", ".", cwd=directory, timeout=10).strip())
    except GitError:
        return False  # no git, or not a work tree: nothing can be tracked


MAX_ENTRY_BYTES = 64 << 20


def _read_entry(p: str) -> bytes | None:
    """The bytes of a cache entry: a regular file (no symlink, device or FIFO), bounded."""
    return read_regular(p, MAX_ENTRY_BYTES, nofollow=True)


def facts_store(secret: bytes | None = None,
                repo_dirs: Iterable[str] = ()) -> "FactsStore | None":
    """The user's mesh facts store (:class:`urdf_lint.meshes.store.FactsStore`), signed with a
    key derived from the result cache's (``secret``, else loaded), registered for the workers
    this process forks; None when no key can be kept."""
    from urdf_lint.core.signing import derive
    from urdf_lint.meshes.store import KEY_PURPOSE, FactsStore, facts_dir, register
    secret = secret or _load_key(repo_dirs)
    if secret is None:
        return None
    store = FactsStore(facts_dir(), derive(secret, KEY_PURPOSE))
    register(store)
    return store


class Cache:
    def __init__(self, directory: str, repo: str | None = None) -> None:
        self.dir = str(directory)
        self.refused: str | None = None
        self._marked = False
        self._settings_key: tuple[LintSettings, str] | None = None   # (settings, its key part)
        self._resolver: tuple[LintSettings, "PackageResolver | None"] | None = None
        # job key -> the seconds its model took when last linted, from each record read,
        # reusable or not: what a run plans a re-linted model at (runner.pool.package_blocks)
        self.costs: dict[JobKey, float] = {}
        self._secret = _load_key([repo] if repo else [])
        if self._secret is None:
            self.refused = (f"no signing key could be kept at {key_path()} (outside the "
                            "repository, mode 0600)")
        elif os.path.islink(self.dir):
            self.refused = f"{self.dir} is a symlink"
        elif os.path.isdir(self.dir) and _git_tracks(self.dir):
            self.refused = f"{self.dir} holds files tracked by git"
        if self.refused:
            from urdf_lint.core.emit import say
            say(f"urdf-lint: note: not using the cache: {self.refused}")

    @classmethod
    def for_paths(cls, paths: Sequence[str], cfg: "Config") -> "Cache":
        repo = repo_root(start_dir(paths))
        if os.environ.get("URDF_LINT_CACHE_DIR"):
            return cls(os.environ["URDF_LINT_CACHE_DIR"], repo)
        if cfg.cache_dir:
            return cls(os.path.join(cfg.root, cfg.cache_dir), repo)
        # at git's work tree root; outside git under the working directory, never inside a
        # linted folder that is not the working directory
        top = git_root(start_dir(paths))
        return cls(os.path.join(top or os.getcwd(), ".urdf_lint_cache"), repo)

    def _key(self, job: LintJob, settings: LintSettings) -> str:
        memo = self._settings_key
        if memo is None or memo[0] is not settings:   # the run's settings, serialised once
            memo = self._settings_key = (settings, json.dumps(settings.cache_key(),
                                                              sort_keys=True))
        blob = json.dumps([build_id(), RECORD_FORMAT, job.entry, sorted(job.args.items()),
                           job.kind, bool(job.explicit), job.output, job.mesh_base,
                           list(job.outputs), list(job.untied),
                           [list(v) for v in job.variants],
                           [[n, list(p)] for n, p in job.arg_origins],
                           [list(c) for c in job.configs]]) + memo[1]
        return blake2b(blob.encode(), digest_size=20).hexdigest()

    def _path(self, key: str) -> str:
        return os.path.join(self.dir, "results", key[:2], key + ".json")

    def get(self, job: LintJob, settings: LintSettings,
            seen: dict[Any, Any] | None = None) -> ModelReport | None:
        """The cached report of ``job``, if every input it read is unchanged. ``seen`` (path ->
        stat) lets one pass over many jobs stat each shared input once (:meth:`get_many`)."""
        if self.refused:
            return None
        seen = {} if seen is None else seen
        p = self._path(self._key(job, settings))
        try:
            blob = self.read_signed(p)
            if blob is None:
                return None  # absent, or not written by this user's urdf-lint
            rec = json.loads(blob)
            self._cost_of(job, rec)
            if rec.get("version") != build_id() or not isinstance(rec.get("deps"), dict):
                return None
            deps = rec["deps"]
            for path, (stat, digest) in list(deps.items()):
                now = seen.get(path, False)
                if now is False:
                    now = seen[path] = stat_key(path)
                if now is None:
                    return None
                if now != stat:   # touched (a checkout, a copy): the same bytes will do
                    got = memo_digest(path)      # (hashed once for all the models sharing it)
                    if got is None or got[1] != digest:
                        return None
                    deps[path] = [got[0], digest]   # stat taken before the bytes were hashed
            for path in rec.get("missing", []):
                key = ("missing", path)
                appeared = seen.get(key)
                if appeared is None:
                    appeared = seen[key] = os.path.isfile(path)
                if appeared:   # a file looked for (or a folder read as one) appeared
                    return None
            report = ModelReport.from_record(job, rec["result"])
            if not env_unchanged(report.env):   # a variable $(optenv) read was set or unset
                return None
            report.digests = deps   # what it read, as it is now (the run memo keeps it)
            return report
        except (OSError, ValueError, KeyError, TypeError, AttributeError, IndexError):
            return None

    def _cost_of(self, job: LintJob, rec: Any) -> None:
        """Keep the seconds ``rec`` (a record :meth:`put` wrote) says ``job`` took."""
        took = seconds(rec.get("took")) if isinstance(rec, dict) else None
        if took is not None:
            self.costs[job_key(job)] = took

    def get_many(self, jobs: Iterable[LintJob],
                 settings: LintSettings) -> list[ModelReport | None]:
        """:meth:`get` for each job, in one pass: an input shared by many models (a macro
        file, a mesh) is looked at once. The inputs must not change during the pass."""
        seen: dict[Any, Any] = {}   # path or ("missing", path) -> what was seen
        return [self.get(job, settings, seen) for job in jobs]

    def put(self, job: LintJob, settings: LintSettings, result: ModelReport) -> None:
        """Store ``result``: its inputs' records end up in ``result.digests`` (what the run
        memo keeps), or ``result.cacheable`` turns False when it is not stored."""
        if self.refused:
            return
        deps = {}
        read = result.digests or {}
        roots = self._roots(settings)
        for d in result.deps:
            # the worker's record of what it read; a file it did not record is read here
            inside = roots is None or roots.is_inside(d)
            rec = (read.get(d) or file_record(d)) if inside else None
            if rec is None:   # a worker reporting a file outside the roots, or an input
                result.cacheable = False   # that vanished: nothing trustworthy to keep
                return
            deps[d] = rec
        result.digests = deps
        rec = {"version": build_id(), "deps": deps, "missing": list(result.missing),
               "result": result.to_record()}
        took = seconds(result.seconds)   # (what a worker says: checked like the rest)
        if took is not None:
            rec["took"] = round(took, 4)
        self.write_signed(self._path(self._key(job, settings)), json.dumps(rec).encode("utf-8"))

    def read_signed(self, path: str) -> bytes | None:
        """What :meth:`write_signed` wrote at ``path``, if this user's key signed it (a regular
        file, bounded); None otherwise."""
        data = _read_entry(path)
        if data is None:
            return None
        assert self._secret is not None
        return signing.verified(self._secret, os.path.basename(path), data)

    def write_signed(self, path: str, blob: bytes) -> bool:
        """Write ``blob`` under the cache folder, signed: the signature's line, then the bytes
        (read back with one parse). False when it could not be written."""
        try:
            self._ensure()
            assert self._secret is not None
            fsbound.write_bytes(path, signing.signed(self._secret, os.path.basename(path), blob),
                                self.dir, make_dirs=True)
            return True
        except OSError:
            return False

    def _roots(self, settings: LintSettings) -> "PackageResolver | None":
        """The run's resolver (for the roots check), built once per settings."""
        memo = self._resolver
        if memo is None or memo[0] is not settings:
            resolver = None
            if settings.resolver:
                from urdf_lint.discovery.packages import PackageResolver
                resolver = PackageResolver.from_dict(settings.resolver)
            memo = self._resolver = (settings, resolver)
        return memo[1]

    def _ensure(self) -> None:
        if not self._marked:
            ensure_cache_dir(self.dir)
            self._marked = True

    def clear(self) -> str | None:
        if os.path.isdir(self.dir):
            fsbound.remove_tree(self.dir)
            return self.dir
        return None
