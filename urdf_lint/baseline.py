"""``--baseline``: adopt urdf-lint on a repository with existing findings.

A baseline records each finding by code, file (relative to the baseline's folder) and message,
not by line, so unrelated edits that move lines do not resurrect old findings.
"""
from __future__ import annotations

import json
import os
from collections import Counter

from .atomic import atomic_write
from .errors import UsageError
from .locations import display_path


class BaselineError(UsageError):
    """A baseline file that cannot be read or written (exit 2)."""


def _key(f, base):
    return (f.code, os.path.relpath(f.file, base), f.message)


def write_baseline(path, findings) -> int:
    """Record ``findings`` in ``path``; returns how many were recorded."""
    base = os.path.dirname(os.path.abspath(path))
    items = [{"code": c, "file": fl, "message": m} for c, fl, m in sorted(_key(f, base) for f in findings)]
    try:
        atomic_write(path, json.dumps({"version": 1, "findings": items}, indent=1))
    except OSError as e:
        raise BaselineError(f"cannot write baseline {path}: {e.strerror or e}") from None
    return len(items)


def filter_baseline(path, findings):
    base = os.path.dirname(os.path.abspath(path))
    try:
        with open(path, encoding="utf-8") as fh:
            data = json.load(fh)
        known = Counter((i["code"], i["file"], i["message"]) for i in data["findings"])
    except OSError as e:
        raise BaselineError(f"cannot read baseline {display_path(path)}: "
                            f"{e.strerror or e}") from None
    except (ValueError, KeyError, TypeError) as e:
        raise BaselineError(f"{display_path(path)} is not a urdf-lint baseline ({e}); "
                            "make one with --write-baseline") from None
    out = []
    for f in findings:
        k = _key(f, base)
        if known[k] > 0:
            known[k] -= 1
        else:
            out.append(f)
    return out
