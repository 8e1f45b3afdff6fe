"""Workspaces: the colcon/catkin workspace around the linted paths, and its packages.

A workspace is a folder with a ``src/`` folder holding packages (often one git repository
each: ``ws/src/robot_description``, ``ws/src/robot_meshes``, ...). It is found upward from the
linted paths; its ``src/`` is indexed for ``package.xml`` files, skipping folders marked with
``COLCON_IGNORE``, ``CATKIN_IGNORE`` or ``AMENT_IGNORE``, and so is its install space
(``install/share/NAME/package.xml``, or ``install/NAME/share/NAME/package.xml``). Every
workspace folder is also a confinement root: files may be read from it.
"""
from __future__ import annotations

import os
from pathlib import Path
from typing import Iterable, Iterator

from urdf_lint.core.tree import MAX_DEPTH, walk_packages
from urdf_lint.core.tree import find_workspace  # noqa: F401 - part of this API
from urdf_lint.core.tree import find_workspace_cached as _find_workspace_cached
from urdf_lint.discovery.folders import ignored  # noqa: F401 - part of this API
from urdf_lint.discovery.packages import package_name


def _install_packages(install: Path) -> Iterator[Path]:
    """``share/NAME/package.xml`` of a merged or isolated install space."""
    from urdf_lint.core import fsbound
    for share in [install / "share", *fsbound.glob_paths(install, "*/share")]:
        if share.is_dir():
            yield from fsbound.glob_paths(share, "*/package.xml")


def index(workspace: str) -> dict[str, str]:
    """Package name -> folder for a workspace: its sources first, then its install space."""
    ws = Path(workspace)
    out: dict[str, str] = {}
    for pxml in [*walk_packages(ws / "src", MAX_DEPTH), *_install_packages(ws / "install")]:
        name = package_name(pxml)
        if name and name not in out:
            out[name] = str(pxml.parent.resolve())
    return out


def workspace_roots(paths: Iterable[str]) -> list[str]:
    """The workspace folders around the linted paths: confinement roots as well as places
    packages are found."""
    out: list[str] = []
    dirs = {os.path.abspath(p if os.path.isdir(p) else os.path.dirname(os.path.abspath(p)))
            for p in paths or ["."]}
    for p in sorted(dirs):
        ws = _find_workspace_cached(p)
        if ws and ws not in out:
            out.append(os.path.realpath(ws))
    return out


def install_share_packages(top: str) -> dict[str, str]:
    """``share/NAME/package.xml`` below ``top`` (an install layout being linted), which the
    package scan skips (it never walks into install/ folders)."""
    out: dict[str, str] = {}
    t = Path(top)
    from urdf_lint.core import fsbound
    for share in [t / "share", t / "install" / "share", *fsbound.glob_paths(t, "install/*/share")]:
        if share.is_dir():
            for pxml in fsbound.glob_paths(share, "*/package.xml"):
                name = package_name(pxml)
                if name and name not in out:
                    out[name] = str(pxml.parent.resolve())
    return out


def _package_holding(p: str, up: int = 4) -> str:
    """The folder of the package that holds ``p`` (the nearest ``package.xml`` above it, at
    most ``up`` levels up), else ``p``'s folder: a file is beside what its package is beside."""
    start = d = os.path.abspath(p if os.path.isdir(p) else os.path.dirname(p))
    for _ in range(up + 1):
        if os.path.isfile(os.path.join(d, "package.xml")):
            return d
        parent = os.path.dirname(d)
        if parent == d:
            break
        d = parent
    return start


def beside(name: str, paths: Iterable[str], depth: int = 2) -> str | None:
    """The folder holding the ``package.xml`` of package ``name`` beside the linted ``paths``
    (in the parent folders of their packages, ``depth`` levels down: a file's package, a folder
    that is a package or lies in one), for a ``--package-path`` hint: such a
    folder is not a root by itself (outside git and a workspace, the working directory is not
    searched), but the user can name it."""
    seen = set()
    for p in paths:
        top = os.path.dirname(_package_holding(p))
        if top in seen:
            continue
        seen.add(top)
        for pxml in walk_packages(Path(top), depth):
            if package_name(pxml) == name:
                return str(pxml.parent)
    return None
