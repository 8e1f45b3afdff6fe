"""git, the only version control urdf-lint talks to: the work tree root and changed files."""
from __future__ import annotations

import functools
import os
import subprocess


class GitError(Exception):
    pass


def _git(*args: str, cwd: str, timeout: float = 60) -> str:
    try:
        p = subprocess.run(["git", *args], cwd=cwd, capture_output=True, text=True,
                           timeout=timeout)
    except (OSError, subprocess.SubprocessError) as e:
        raise GitError(str(e)) from None
    if p.returncode != 0:
        raise GitError(p.stderr.strip() or f"git {' '.join(args)} failed")
    return p.stdout


def git_root(start: str) -> str | None:
    """The top of the git work tree holding ``start``, or None outside git."""
    return _git_root(os.path.abspath(start))


@functools.lru_cache(maxsize=16)  # asked by config trust, roots and the cache: one git call
def _git_root(start: str) -> str | None:
    try:
        top = _git("rev-parse", "--show-toplevel", cwd=start, timeout=5).strip()
    except GitError:
        return None
    return top or None


def repo_root(start: str) -> str:
    """The git work tree holding ``start``, or ``start`` itself outside git."""
    return git_root(start) or os.path.abspath(start)


def changed_files(ref: str, cwd: str) -> set[str]:
    """Files changed since ``ref`` (committed, staged, unstaged and untracked), absolute."""
    top = _git("rev-parse", "--show-toplevel", cwd=cwd).strip()
    names = _git("diff", "--name-only", "--no-renames", ref, cwd=cwd).splitlines()
    names += _git("ls-files", "--others", "--exclude-standard", cwd=cwd).splitlines()
    return {os.path.realpath(os.path.join(top, n)) for n in names if n}
