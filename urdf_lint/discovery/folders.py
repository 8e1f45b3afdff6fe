"""Folder helpers shared by package resolution and workspace detection (no imports from
either): colcon's ignore markers, and finding a folder by name for the unknown-package hint."""
from __future__ import annotations

import functools
import os
from pathlib import Path
from typing import Iterable

from urdf_lint.core.tree import IGNORE_MARKERS


def ignored(folder: str | os.PathLike[str], top: str | os.PathLike[str]) -> bool:
    """Is ``folder`` (at or below ``top``) in a folder marked COLCON_IGNORE/CATKIN_IGNORE?"""
    folder, top = os.fspath(os.path.abspath(folder)), os.fspath(os.path.abspath(top))
    while True:
        if _marked(folder):
            return True
        parent = os.path.dirname(folder)
        if folder == top or parent == folder or len(folder) <= len(top):
            return False
        folder = parent


@functools.lru_cache(maxsize=4096)
def _marked(folder: str) -> bool:
    return any(os.path.exists(os.path.join(folder, m)) for m in IGNORE_MARKERS)


def folder_named(name: str, tops: Iterable[str], skip: Iterable[str] = frozenset(),
                 depth: int = 5) -> str | None:
    """A folder called ``name`` below ``tops`` (breadth first, the first in sorted order), for
    the hint on an unknown package: ``--package-path NAME=DIR``. The folders are listed once
    per roots in a process (one index), so each further name is a lookup."""
    if not name or "/" in name or name in (".", ".."):
        return None
    return _folder_index(tuple(tops), frozenset(skip), depth).get(name)


@functools.lru_cache(maxsize=8)
def _folder_index(tops: tuple[str, ...], skip: frozenset[str], depth: int) -> dict[str, str]:
    """name -> the first folder of that name, breadth first below ``tops`` (hidden folders
    are neither named nor entered, ``skip`` ones are named but not entered)."""
    index: dict[str, str] = {}
    level = [Path(t) for t in tops if t and os.path.isdir(t)]
    seen = set()
    for _ in range(depth):
        nxt = []
        for d in level:
            from urdf_lint.core import fsbound
            for e in fsbound.scan_dir(d):
                if not e.is_dir(follow_symlinks=False) or e.name.startswith("."):
                    continue
                index.setdefault(e.name, os.path.abspath(e.path))
                if e.name in skip - {"install"} or e.path in seen:
                    continue
                seen.add(e.path)
                nxt.append(Path(e.path))
        level = nxt
    return index
