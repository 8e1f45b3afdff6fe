"""git, the only version control urdf-lint talks to: the work tree root and changed files."""
from __future__ import annotations

import functools
import os
import subprocess
from typing import Any, Iterator


class GitError(Exception):
    pass


def git(*args: str, cwd: str, timeout: float = 60, binary: bool = False) -> Any:
    """The one way urdf-lint runs git: its output (``str``, or ``bytes`` with ``binary``), or
    :class:`GitError` with git's message (no git, a time-out and a failing command alike)."""
    try:
        p = subprocess.run(["git", *args], cwd=cwd, capture_output=True, timeout=timeout)
    except (OSError, subprocess.SubprocessError) as e:
        raise GitError(str(e)) from None
    if p.returncode != 0:
        raise GitError(p.stderr.decode(errors="replace").strip() or f"git {' '.join(args)} failed")
    return p.stdout if binary else p.stdout.decode()


def git_root(start: str) -> str | None:
    """The top of the git work tree holding ``start``, or None outside git."""
    return _git_root(os.path.abspath(start))


@functools.lru_cache(maxsize=16)  # asked by config trust, roots and the cache: one git call
def _git_root(start: str) -> str | None:
    try:
        top = git("rev-parse", "--show-toplevel", cwd=start, timeout=5).strip()
    except GitError:
        return None
    return top or None


def repo_root(start: str) -> str:
    """The git work tree holding ``start``, or ``start`` itself outside git."""
    return git_root(start) or os.path.abspath(start)


def _name_status(out: str) -> Iterator[tuple[str, list[str]]]:
    """(status letter, paths) per entry of ``git diff --name-status -z`` output: a rename or
    copy has both the old and the new path."""
    parts = out.split("\0")
    i = 0
    while i < len(parts):
        status = parts[i]
        if not status:
            i += 1
            continue
        n = 2 if status[0] in "RC" else 1
        yield status[0], parts[i + 1:i + 1 + n]
        i += 1 + n


def changed_files(ref: str, cwd: str) -> set[str]:
    """Files changed since ``ref`` (committed, staged, unstaged and untracked), absolute;
    deleted files and the old names of renamed files included."""
    top = git("rev-parse", "--show-toplevel", cwd=cwd).strip()
    names = [p for _, paths in _name_status(git("diff", "--name-status", "-z", "-M", ref,
                                                 cwd=cwd)) for p in paths]
    names += git("ls-files", "--others", "--exclude-standard", cwd=cwd).splitlines()
    return {_absolute(top, n) for n in names if n}


def staged_removals(cwd: str) -> set[str]:
    """Files the index deletes or renames away (pre-commit passes only files that exist)."""
    top = git("rev-parse", "--show-toplevel", cwd=cwd).strip()
    out = git("diff", "--cached", "--name-status", "-z", "-M", cwd=cwd)
    return {_absolute(top, paths[0]) for status, paths in _name_status(out)
            if status in "DR" and paths}


def _absolute(top: str, name: str) -> str:
    """The absolute path of a repository-relative name (realpath of its folder: the file
    itself may be gone)."""
    p = os.path.join(top, name)
    return os.path.join(os.path.realpath(os.path.dirname(p)), os.path.basename(p))
