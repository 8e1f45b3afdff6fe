"""The shape of a source tree, for every room that walks or shows one (config, discovery, the
paths core shows): the folders never walked, colcon's ignore markers, whether a path is a folder
or below it, and the colcon/catkin workspace around a folder (a folder with a ``src/`` folder
holding packages)."""
from __future__ import annotations

import contextlib
import functools
import os
from collections.abc import Iterator
from pathlib import Path

SKIP_DIRS = {".git", ".hg", ".svn", "node_modules", ".venv", "venv", "__pycache__", "build",
             "install", "log", ".urdf_lint_cache", ".tox", ".mypy_cache", ".pytest_cache"}
IGNORE_MARKERS = ("COLCON_IGNORE", "CATKIN_IGNORE", "AMENT_IGNORE")
# how far below a workspace's src/ packages are looked for (src/repo/group/package)
MAX_DEPTH = 4


_real_paths: dict[str, str] | None = None   # within paths_fixed(): path -> its real path


@contextlib.contextmanager
def paths_fixed() -> Iterator[None]:
    """One lint job: a path whose real path was asked for gets the same answer again, without
    walking its symlinks again (the roots test asks per include, mesh, texture and finding's
    source). A job's files do not move under it, and the answers end with it: a symlink
    changed between two jobs, or two edits in the language server, is seen."""
    global _real_paths
    saved, _real_paths = _real_paths, {}
    try:
        yield
    finally:
        _real_paths = saved


def real_path(path: str | os.PathLike[str]) -> str:
    """``os.path.realpath(path)``, remembered within :func:`paths_fixed`."""
    memo = _real_paths
    if memo is None:
        return os.path.realpath(path)
    key = os.fspath(path)
    got = memo.get(key)
    if got is None:
        got = memo[key] = os.path.realpath(key)
    return got


def inside(f: str, p: str) -> bool:
    """Is path ``f`` the folder ``p`` or below it? (strings, as written: resolve first)"""
    return f == p or f.startswith(p.rstrip(os.sep) + os.sep)


def find_workspace(path: str) -> str | None:
    """The nearest folder at or above ``path`` whose ``src/`` holds ``path`` (or that is
    ``path``) and holds at least one package."""
    p = Path(os.path.abspath(path))
    if p.is_file():
        p = p.parent
    home = Path.home().resolve()
    for d in [p, *p.parents]:
        if d == home or d == Path(d.anchor):
            break
        src = d / "src"
        if src.is_dir() and (d == p or _inside(p, src)) and _has_package(src):
            return str(d)
    return None


@functools.lru_cache(maxsize=1024)
def find_workspace_cached(d: str) -> str | None:
    return find_workspace(d)


def _inside(p: Path, top: Path) -> bool:
    try:
        p.relative_to(top)
        return True
    except ValueError:
        return False


def _has_package(src: Path) -> bool:
    for _ in walk_packages(src, MAX_DEPTH):
        return True
    return False


def walk_packages(top: Path, depth: int) -> Iterator[Path]:
    """Every ``package.xml`` under ``top`` (not below a package, not in ignored folders)."""
    from urdf_lint.core import fsbound
    try:
        names = fsbound.list_dir(top)
    except OSError:
        return
    if any(m in names for m in IGNORE_MARKERS):
        return
    if "package.xml" in names:
        yield top / "package.xml"
        return
    if depth <= 0:
        return
    for n in sorted(names):
        if n in SKIP_DIRS or n.startswith("."):
            continue
        d = top / n
        if d.is_dir() and not d.is_symlink():
            yield from walk_packages(d, depth - 1)
