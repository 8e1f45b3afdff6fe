"""Result cache, like ruff's: ``.urdf_lint_cache/`` at the repository root.

A model's entry is keyed on the tool version, the entry file, its args and the lint settings
(selected rules, options, package map, env allow-list). It is valid only while every file the
model read (xacro, YAML, meshes) still has the content it had, and every file that was looked
for and missing is still missing. Stat data (size, mtime) short-cuts the content hash. A corrupt
or foreign entry is ignored.
"""
from __future__ import annotations

import hashlib
import json
import os
import shutil
from pathlib import Path

from . import __version__
from .discovery import start_dir
from .hashing import file_digest
from .jobs import LintJob, LintSettings, ModelReport
from .cachedir import ensure as ensure_cache_dir
from .vcs import git_root

# bump when the stored record changes shape (3: missing YAML files recorded as missing)
RECORD_FORMAT = 3


def _stat(path):
    try:
        st = os.stat(path)
    except OSError:
        return None
    return [st.st_size, st.st_mtime_ns]


class Cache:
    def __init__(self, directory: str):
        self.dir = str(directory)
        self._writes = 0
        self._marked = False

    @classmethod
    def for_paths(cls, paths, cfg) -> "Cache":
        if os.environ.get("URDF_LINT_CACHE_DIR"):
            return cls(os.environ["URDF_LINT_CACHE_DIR"])
        if cfg.cache_dir:
            return cls(os.path.join(cfg.root, cfg.cache_dir))
        # at git's work tree root; outside git under the working directory, never inside a
        # linted folder that is not the working directory
        top = git_root(start_dir(paths))
        return cls(os.path.join(top or os.getcwd(), ".urdf_lint_cache"))

    def _key(self, job: LintJob, settings: LintSettings) -> str:
        blob = json.dumps([__version__, RECORD_FORMAT, job.entry, sorted(job.args.items()),
                           job.kind, bool(job.explicit), job.output, job.mesh_base,
                           settings.cache_key()], sort_keys=True)
        return hashlib.blake2b(blob.encode(), digest_size=20).hexdigest()

    def _path(self, key) -> Path:
        return Path(self.dir, "results", key[:2], key + ".json")

    def get(self, job: LintJob, settings: LintSettings) -> ModelReport | None:
        p = self._path(self._key(job, settings))
        try:
            rec = json.loads(p.read_text(encoding="utf-8"))
            if rec.get("version") != __version__ or not isinstance(rec.get("deps"), dict):
                return None
            for path, (stat, digest) in rec["deps"].items():
                now = _stat(path)
                if now is None:
                    return None
                if now != stat and file_digest(path) != digest:
                    return None
            for path in rec.get("missing", []):
                if os.path.exists(path):
                    return None
            return ModelReport.from_record(job, rec["result"])
        except (OSError, ValueError, KeyError, TypeError, AttributeError, IndexError):
            return None

    def put(self, job: LintJob, settings: LintSettings, result: ModelReport):
        deps = {}
        for d in result.deps:
            st = _stat(d)
            dig = file_digest(d)
            if st is None or dig is None:
                continue
            deps[d] = [st, dig]
        rec = {"version": __version__, "deps": deps, "missing": list(result.missing),
               "result": result.to_record()}
        p = self._path(self._key(job, settings))
        try:
            self._ensure()
            p.parent.mkdir(parents=True, exist_ok=True)
            tmp = p.with_suffix(f".tmp{os.getpid()}")
            tmp.write_text(json.dumps(rec), encoding="utf-8")
            os.replace(tmp, p)
            self._writes += 1
        except OSError:
            pass

    def _ensure(self):
        if not self._marked:
            ensure_cache_dir(self.dir)
            self._marked = True

    def clear(self) -> str | None:
        if os.path.isdir(self.dir):
            shutil.rmtree(self.dir, ignore_errors=True)
            return self.dir
        return None
