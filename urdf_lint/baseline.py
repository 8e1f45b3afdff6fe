"""``--baseline``: adopt urdf-lint on a repository with existing findings.

A baseline records each finding by code, file (relative to the baseline's folder) and message,
not by line, so unrelated edits that move lines do not resurrect old findings.
"""
from __future__ import annotations

import json
import os
from collections import Counter

from . import fsbound
from .errors import UsageError
from .locations import display_path


class BaselineError(UsageError):
    """A baseline file that cannot be read or written (exit 2)."""


def _key(f, base):
    return (f.code, os.path.relpath(f.file, base), f.message)


def write_baseline(path, findings, write_base=None) -> int:
    """Record ``findings`` in ``path`` (written below ``write_base``, by default its own
    folder: :func:`urdf_lint.fsbound.write_bytes`); returns how many were recorded."""
    base = os.path.dirname(os.path.abspath(path))
    items = [{"code": c, "file": fl, "message": m} for c, fl, m in sorted(_key(f, base) for f in findings)]
    try:
        fsbound.write_text(path, json.dumps({"version": 1, "findings": items}, indent=1),
                           write_base or base)
    except OSError as e:
        raise BaselineError(f"cannot write baseline {_shown(path)}: {_why(e)}") from None
    return len(items)


def _shown(path) -> str:
    from .report.escape import escape_text
    return escape_text(display_path(path))


def _why(e: OSError) -> str:
    from .report.escape import escape_text
    return escape_text(str(getattr(e, "why", None) or e.strerror or e))


def filter_baseline(path, findings):
    base = os.path.dirname(os.path.abspath(path))
    try:   # a regular file (never a device or FIFO), bounded
        data = json.loads(fsbound.read_bytes(path, max_bytes=fsbound.MAX_DATA_BYTES))
        known = Counter((i["code"], i["file"], i["message"]) for i in data["findings"])
    except OSError as e:
        raise BaselineError(f"cannot read baseline {_shown(path)}: {_why(e)}") from None
    except (ValueError, KeyError, TypeError, RecursionError) as e:
        raise BaselineError(f"{_shown(path)} is not a urdf-lint baseline "
                            f"({type(e).__name__}); make one with --write-baseline") from None
    out = []
    for f in findings:
        k = _key(f, base)
        if known[k] > 0:
            known[k] -= 1
        else:
            out.append(f)
    return out
