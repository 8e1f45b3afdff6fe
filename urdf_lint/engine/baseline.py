"""``--baseline``: adopt urdf-lint on a repository with existing findings.

A baseline (version 2) records each finding by

* its code,
* its file, relative to the baseline's folder,
* the identity of the source element it is at: the tags and ``name`` attributes from the root
  of the file down to it (``robot[r2d2]/xacro:macro[leg]/joint[${prefix}_leg_joint]/limit``),
  read from the source, not the line number,
* a fingerprint of its message with paths made relative to the baseline's folder and numbers
  replaced (``lower 2.1 > upper -2.1`` and ``first defined at x.urdf:14`` match after an edit
  above them),

so the same repository checked out elsewhere (another developer, CI), reindented, or edited
above a finding still matches. The message is kept too, for people reading the file.
Version 1 files (code, file, message) still load: their entries match any element, and a note
says how to rewrite them.
"""
from __future__ import annotations

import bisect
import json
import os
import re
from collections import Counter
from typing import TYPE_CHECKING, Any, Callable, Iterable, Iterator

from urdf_lint.core import fsbound
from urdf_lint.core.errors import UsageError
from urdf_lint.core.locations import display_path, portable

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.core.findings import Problem

VERSION = 2
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


class BaselineError(UsageError):
    """A baseline file that cannot be read or written (exit 2)."""


def normalized(message: str, base: str) -> str:
    """The message with its paths relative to ``base`` and every number replaced by ``#``."""
    return _NUMBER.sub("#", portable(message, base))


def fingerprint(message: str, base: str) -> str:
    import hashlib   # (only baselines need it: not every run's start-up)
    return hashlib.sha256(normalized(message, base).encode()).hexdigest()[:16]


class _Elements:
    """The identity of the source element at a finding's line and column, per file (each file
    parsed once)."""

    def __init__(self) -> None:
        self._files: dict[str, tuple[list[tuple[int, int]], list[str]]] = {}

    def identity(self, path: str, line: int, col: int) -> str:
        got = self._files.get(path)
        if got is None:
            starts = _element_starts(path)
            got = self._files[path] = ([pos for pos, _ in starts], [i for _, i in starts])
        positions, idents = got
        # the last element that starts at or before (line, col)
        k = bisect.bisect_right(positions, (line, col))
        return idents[k - 1] if k else ""


def _element_starts(path: str) -> list[tuple[tuple[int, int], str]]:
    """``[((line, col), identity)]`` of every element of an XML file, in document order;
    empty for a file that is not XML (YAML, a mesh) or cannot be read."""
    if not path.endswith((".xacro", ".urdf", ".xml")):
        return []
    from lxml import etree
    try:
        data = fsbound.read_bytes(path)
        root = etree.fromstring(data, etree.XMLParser(recover=True, resolve_entities=False,
                                                      no_network=True, huge_tree=False))
    except (OSError, etree.LxmlError, ValueError):
        return []
    if root is None:
        return []
    lines = data.decode("utf-8", "replace").splitlines()
    tag_cols: dict[int, list[int]] = {}   # line -> the columns (1-based) where start tags begin on it
    out: list[tuple[tuple[int, int], str]] = []
    idents: dict[Any, str] = {}
    for el in root.iter():
        if not isinstance(el.tag, str):
            continue
        line = el.sourceline or 0
        if line not in tag_cols:
            text = lines[line - 1] if 0 < line <= len(lines) else ""
            tag_cols[line] = [m.start() + 1 for m in re.finditer(r"<(?![/!?])", text)]
        cols = tag_cols[line]
        col = cols.pop(0) if cols else 1
        q = etree.QName(el)
        prefix = el.prefix + ":" if el.prefix else ""
        name = el.get("name")
        own = prefix + q.localname + (f"[{name}]" if name is not None else "")
        parent = el.getparent()
        ident = (idents[parent] + "/" if parent is not None and parent in idents else "") + own
        idents[el] = ident
        out.append(((line, col), ident))
    out.sort(key=lambda x: x[0])
    return out


def _entries(findings: Iterable[Problem], base: str) -> Iterator[dict[str, str]]:
    elements = _Elements()
    real = os.path.realpath(base)
    for f in findings:
        yield {"code": f.code,
               # both sides real: a checkout under a symlinked folder gives the same key
               "file": os.path.relpath(os.path.realpath(f.file), real) if f.file else "",
               "element": elements.identity(f.file, f.line, f.col) if f.file else "",
               "fingerprint": fingerprint(f.message, base),
               "message": portable(f.message, base)}


def write_baseline(path: str, findings: Iterable[Problem], write_base: str | None = None) -> int:
    """Record ``findings`` in ``path`` (written below ``write_base``, by default its own
    folder: :func:`urdf_lint.core.fsbound.write_bytes`); returns how many were recorded."""
    base = os.path.dirname(os.path.abspath(path))
    items = sorted(_entries(findings, base),
                   key=lambda e: (e["file"], e["code"], e["element"], e["fingerprint"]))
    try:
        fsbound.write_text(path, json.dumps({"version": VERSION, "findings": items}, indent=1)
                           + "\n", write_base or base)
    except OSError as e:
        raise BaselineError(f"cannot write baseline {_shown(path)}: {_why(e)}") from None
    return len(items)


def _shown(path: str) -> str:
    from urdf_lint.core.escape import escape_text
    return escape_text(display_path(path))


def _why(e: OSError) -> str:
    from urdf_lint.core.escape import escape_text
    return escape_text(str(getattr(e, "why", None) or e.strerror or e))


def filter_baseline(path: str, findings: list[Problem],
                    note: Callable[[str], object] | None = None) -> list[Problem]:
    """The findings not recorded in the baseline ``path``. ``note`` (a callable) hears that an
    old (version 1) file should be rewritten."""
    base = os.path.dirname(os.path.abspath(path))
    try:   # a regular file (never a device or FIFO), bounded
        data = json.loads(fsbound.read_bytes(path, max_bytes=fsbound.MAX_DATA_BYTES))
        version = data.get("version", 1)
        exact: Counter[tuple[str, str, str, str]] = Counter()
        loose: Counter[tuple[str, str, str]] = Counter()
        for i in data["findings"]:
            if version >= 2:
                exact[(i["code"], i["file"], i["element"], i["fingerprint"])] += 1
            else:   # version 1: matched on code, file and message, at any element
                loose[(i["code"], i["file"], fingerprint(i["message"], base))] += 1
    except OSError as e:
        raise BaselineError(f"cannot read baseline {_shown(path)}: {_why(e)}") from None
    except (ValueError, KeyError, TypeError, AttributeError, RecursionError) as e:
        raise BaselineError(f"{_shown(path)} is not a urdf-lint baseline "
                            f"({type(e).__name__}); make one with --write-baseline") from None
    if version > VERSION:
        raise BaselineError(f"{_shown(path)} is a version {version} baseline, newer than "
                            f"this urdf-lint reads ({VERSION}); update urdf-lint")
    if version < 2 and note is not None:
        note(f"note: {_shown(path)} is an old (version 1) baseline, matched by message "
             f"only; rewrite it with --write-baseline {_shown(path)}")
    out = []
    for f, entry in zip(findings, _entries(findings, base), strict=True):
        k = (entry["code"], entry["file"], entry["element"], entry["fingerprint"])
        lk = (entry["code"], entry["file"], entry["fingerprint"])
        if exact[k] > 0:
            exact[k] -= 1
        elif loose[lk] > 0:
            loose[lk] -= 1
        else:
            out.append(f)
    return out
