"""``--fix`` remembers the fixes it rolled back, so the next run does not write and roll back
the same edit again (rewriting sources, re-linting twice) while nothing it depends on changed.

A rolled-back fix is remembered under a key made of its code, its edits (file, byte range,
text), the fixes tried with it that edit the same files (their codes and edits: a swap of two
limits may verify only beside the swap of the soft limits written from the same values, which
another rule, or a run selecting it, adds) and the content digests of every input of every model
that reads an edited file (and the files those models looked for and did not find). The
verification that rolled it back depends on nothing else, so while the key is the same the
outcome is the same: the fix is reported as not applied, with the earlier reason. Any change to
those makes a new key, and the fix is tried again. The memory is a signed file in the cache
folder (``--no-cache``: none).
"""
from __future__ import annotations

import hashlib
import json
import os
from typing import TYPE_CHECKING, Iterable

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.core.findings import Problem
    from urdf_lint.core.jobs import ModelReport
    from urdf_lint.run.cache import Cache

FILE = "fix-rollbacks.json"
MAX_ENTRIES = 2000


def _edits(p: "Problem") -> list[tuple[str, int, int, str]]:
    return sorted((e.file, e.start, e.end, e.text) for e in p.fix.edits) if p.fix else []


def fix_key(p: "Problem", models: Iterable["ModelReport"],
            tried: Iterable["Problem"] = ()) -> str | None:
    """The key of ``p``'s fix in the run whose models are ``models`` and whose fixes tried
    together are ``tried`` (``p``'s own among them or not); None when an input's digest is
    unknown (then nothing is remembered)."""
    fx = p.fix
    if fx is None or not fx.edits:
        return None
    edited = {e.file for e in fx.edits}
    mine = _edits(p)
    beside = sorted({(q.code, json.dumps(_edits(q))) for q in tried
                     if (q.code, _edits(q)) != (p.code, mine)
                     and edited & {f for f, *_ in _edits(q)}})
    inputs: dict[str, str] = {}
    missing: set[str] = set()
    for m in models:
        if not edited & {m.entry, *m.deps}:
            continue
        for d in {m.entry, *m.deps}:
            rec = (m.digests or {}).get(d)
            if not rec:
                return None
            inputs[d] = rec[1]
        missing.update(m.missing or ())
    if not inputs:
        return None
    blob = json.dumps([p.code, mine, beside, sorted(inputs.items()), sorted(missing)])
    return hashlib.sha256(blob.encode()).hexdigest()


class FixMemo:
    """The rolled-back fixes of earlier runs (key -> reason), kept in the cache folder."""

    def __init__(self, cache: "Cache") -> None:
        self.cache = cache
        self.path = os.path.join(cache.dir, FILE)
        self.entries: dict[str, str] = {}
        self.changed = False
        blob = cache.read_signed(self.path) if os.path.isfile(self.path) else None
        if blob:
            try:
                data = json.loads(blob)
                if isinstance(data, dict):
                    self.entries = {str(k): str(v) for k, v in data.items()}
            except ValueError:
                self.entries = {}

    def reason(self, key: str | None) -> str | None:
        return self.entries.get(key) if key else None

    def remember(self, key: str | None, reason: str) -> None:
        if key:
            self.entries.pop(key, None)
            self.entries[key] = reason
            self.changed = True

    def save(self) -> None:
        if self.changed:
            kept = dict(list(self.entries.items())[-MAX_ENTRIES:])
            self.cache.write_signed(self.path, json.dumps(kept).encode())
