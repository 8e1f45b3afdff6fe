"""Discovery: which files under the linted paths are candidate models, with which xacro args,
and which package roots they may read from."""
from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

from .jobs import LintJob
from .packages import PackageResolver, iter_files
from .vcs import git_root

if TYPE_CHECKING:  # pragma: no cover
    from .config import Config


def start_dir(paths) -> str:
    """The folder a run starts from: the first path, or its folder when it is a file."""
    first = os.path.abspath(paths[0] if paths else ".")
    return first if os.path.isdir(first) else os.path.dirname(first)


def inside(f: str, p: str) -> bool:
    """Is path ``f`` the folder ``p`` or below it?"""
    return f == p or f.startswith(p.rstrip(os.sep) + os.sep)


def build_resolver(paths, cfg: "Config", cli_packages: dict | None = None) -> PackageResolver:
    """The package roots of a run (:func:`urdf_lint.packages.discover_roots`): the packages,
    the git repository and the colcon workspace holding the linted paths; never the working
    directory by itself, and nothing above the linted paths without git (fail closed)."""
    from .packages import discover_roots
    start = start_dir(paths) if paths else os.getcwd()
    scan, extra_roots = discover_roots(paths or [start], git_root(start))
    explicit = dict(cfg.package_paths)
    explicit.update(cli_packages or {})
    return PackageResolver.build(scan, explicit=explicit, extra_roots=extra_roots)


def _kind(f: str) -> str:
    return "urdf" if f.endswith(".urdf") else "xacro"


def discover(paths, cfg: "Config") -> list[LintJob]:
    """Every candidate model file under the paths, with the arg sets to expand it with."""
    configured = {m.path: m.arg_sets for m in cfg.models}
    jobs, seen = [], set()
    for p in paths:
        p = os.path.abspath(p)
        for f in iter_files(Path(p), suffixes=(".urdf", ".xacro")):
            f = os.path.realpath(f) if not os.path.islink(f) else os.path.abspath(f)
            # an exclude does not apply below a path that is itself excluded and named explicitly
            if f in seen or (cfg.is_excluded(f) and not cfg.is_excluded(p)):
                continue
            seen.add(f)
            if f in configured:
                for args in configured[f]:
                    jobs.append(LintJob(f, dict(args), _kind(f), explicit=True))
            else:
                jobs.append(LintJob(f, {}, _kind(f), explicit=p == f))
    # configured models inside the linted paths that the walk did not reach
    for f, arg_sets in configured.items():
        if f in seen or not any(inside(f, os.path.abspath(p)) for p in paths):
            continue
        for args in arg_sets:
            jobs.append(LintJob(f, dict(args), _kind(f), explicit=True))
    return jobs
