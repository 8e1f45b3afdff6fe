"""Which models a set of changed files affects, through the dependency graph expansion records
(every xacro, YAML, mesh and texture a model read)."""
from __future__ import annotations

import os
import subprocess


class GitError(Exception):
    pass


def changed_files(ref: str, cwd: str) -> set[str]:
    """Files changed since ``ref`` (committed, staged, unstaged and untracked), absolute."""
    def git(*args):
        p = subprocess.run(["git", *args], cwd=cwd, capture_output=True, text=True, timeout=60)
        if p.returncode != 0:
            raise GitError(p.stderr.strip() or f"git {' '.join(args)} failed")
        return p.stdout
    top = git("rev-parse", "--show-toplevel").strip()
    names = git("diff", "--name-only", "--no-renames", ref).splitlines()
    names += git("ls-files", "--others", "--exclude-standard").splitlines()
    return {os.path.realpath(os.path.join(top, n)) for n in names if n}


def affected(models, files: set[str]):
    """(models whose inputs intersect ``files``, files no model uses)."""
    files = {os.path.realpath(f) for f in files}
    hit, used = [], set()
    for m in models:
        deps = {os.path.realpath(d) for d in m.deps} | {os.path.realpath(m.entry)}
        inter = deps & files
        if inter:
            hit.append(m)
            used |= inter
    return hit, sorted(files - used)
