"""The last result of a whole ``check`` run, reused when nothing it depends on changed.

A warm run of a description repository finds every model unchanged: without this, it still
walks the folders, looks up one cache entry per model, merges, suppresses and applies the
policy again (~80 ms on the corpus). The run memo keeps the run's final result, and checks:

* the key: urdf-lint's version, the working directory (messages name paths relative to it),
  the paths, the whole configuration after the command line, the package roots and the
  settings the workers would get (selected rules, options, ``env-allow`` values);
* every input any model read (the stat the worker took before reading it), every file a
  model looked for and did not find, and every folder discovery walked (a file added or
  removed changes its folder's mtime);
* every variable a model's ``$(optenv)`` looked up outside the allow-list is still set, or
  still unset (``ModelReport.env``).

A run whose inputs or folders changed within the last seconds is not remembered (a coarse
file-system clock could hide an edit made in the same tick), nor one with internal errors or
results that depended on the machine (limits). The memo is signed like the cache entries.
Plain ``check`` runs only: ``--changed-since``, the hook, ``--fix``, ``--render`` and ``diff``
take the usual path.
"""
from __future__ import annotations

import json
import os
import time
from typing import TYPE_CHECKING

from urdf_lint.core.findings import Problem
from urdf_lint.core.hashing import blake2b, stat_key
from urdf_lint.core.jobs import LintJob, ModelReport, env_unchanged

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.run.cache import Cache

FORMAT = 8
RACY_S = 2.0   # inputs changed this recently are not trusted to show a later change


class RunMemo:
    def __init__(self, cache: "Cache", paths, cfg, resolver, settings):
        from urdf_lint.run.cache import build_id
        blob = json.dumps([build_id(), FORMAT, os.getcwd(), [os.path.abspath(p) for p in paths],
                           repr(cfg), resolver.to_dict(), settings.cache_key()],
                          sort_keys=True, default=str)
        key = blake2b(blob.encode(), digest_size=20).hexdigest()
        self.cache = cache
        self.path = os.path.join(cache.dir, "runs", key + ".json")
        self.started = time.time_ns()   # (before discovery: what changes later is not trusted)

    def load(self) -> dict | None:
        """The fields of the last identical run's ``CheckResult``, or None."""
        if self.cache.refused:
            return None
        try:
            blob = self.cache.read_signed(self.path)
            if blob is None:
                return None
            # what the result depends on first: a changed input stops before the result is read
            head, _, body = blob.partition(b"\n")
            rec = json.loads(head)
            if rec.get("format") != FORMAT:
                return None
            for path, stat in rec["inputs"]:
                if stat_key(path) != stat:
                    return None
            for path in rec["missing"]:
                if os.path.isfile(path):   # (as the cache: a folder read as a file stays missing)
                    return None
            for path, mtime in rec["folders"]:
                if _mtime(path) != mtime:
                    return None
            if not env_unchanged(rec.get("env") or {}):
                return None
            rec = json.loads(body)
            return {"models": [_report(m) for m in rec["models"]],
                    "skipped": [_report(m) for m in rec["skipped"]],
                    "findings": [Problem.from_row(r) for r in rec["findings"]],
                    "fragments": dict(rec["fragments"]), "generated": dict(rec["generated"])}
        except (OSError, ValueError, KeyError, TypeError, AttributeError, IndexError):
            return None

    def store(self, out, results: list, folders: list) -> None:
        """Remember ``out`` (a ``pipeline.CheckResult``) with what its ``results`` read."""
        if self.cache.refused or out.internal or \
                any(r.internal or not r.cacheable for r in results):
            return
        inputs: dict = {}
        missing: set = set()
        env: dict = {}
        for r in results:
            env.update(r.env)
            for d in r.deps:
                if d not in inputs:
                    rec = r.digests.get(d)   # (the cache filled them in, or refused the result)
                    if rec is None:
                        return
                    inputs[d] = rec[0]
            missing.update(r.missing)
        seen = []
        for f in folders:
            m = _mtime(f)
            if m is None:
                return
            seen.append((f, m))
        # an input or folder changed since shortly before the run began may have changed
        # after it was read or listed (a file added while the run went on): not remembered
        limit = self.started - int(RACY_S * 1e9)
        if any(stat[1] >= limit for stat in inputs.values()) or any(m >= limit for _, m in seen):
            return
        _prune(os.path.dirname(self.path))
        head = {"format": FORMAT, "inputs": sorted(inputs.items()), "missing": sorted(missing),
                "folders": seen, "env": env}
        body = {"models": [_report_record(r) for r in out.models],
                "skipped": [_report_record(r) for r in out.skipped],
                "findings": [p.to_row() for p in out.findings],
                "fragments": out.fragments, "generated": out.generated}
        # two lines of JSON (json.dumps writes no raw newline), signed together
        blob = (json.dumps(head) + "\n" + json.dumps(body)).encode("utf-8")
        self.cache.write_signed(self.path, blob)


KEEP = 8   # memos kept (one per distinct command line and config); the oldest go


def _prune(folder: str) -> None:
    from urdf_lint.core import fsbound
    try:
        entries = sorted(fsbound.scan_dir(folder),
                         key=lambda e: e.stat(follow_symlinks=False).st_mtime_ns)
    except OSError:
        return
    for e in entries[:max(0, len(entries) - KEEP + 1)]:
        fsbound.remove(e.path, folder)


def _mtime(path: str) -> int | None:
    try:
        return os.stat(path).st_mtime_ns
    except OSError:
        return None


def _report_record(r: ModelReport) -> dict:
    # a reused run's models carry no raw problems: what they found is in the run's findings
    # (merged, suppressed, with the policy applied), which is all a plain check reports
    rec = r.to_record()
    rec["problems"] = []
    return {"entry": r.entry, "args": r.args, "record": rec}


def _report(d: dict) -> ModelReport:
    r = ModelReport.from_record(LintJob(d["entry"], dict(d["args"])), d["record"])
    r.cached = True
    return r
