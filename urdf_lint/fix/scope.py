"""Where a run's fixes may write: the linted paths (:func:`inside_paths`), and never a
generated URDF (:func:`not_in_generated`). Every run's end applies them (``check`` and the
editor alike), so this module is light: it needs nothing of the fix machinery, which a run whose
findings all come from the result cache never imports."""
from __future__ import annotations

import os
from typing import TYPE_CHECKING, Iterable

from urdf_lint.core.edits import NOT_FIXABLE, Fix

if TYPE_CHECKING:
    from urdf_lint.core.findings import Problem


OUTSIDE = "is outside the linted paths"
GENERATED = "fix the source and run urdf-lint generate"


def scope_refusal(fix: Fix | None) -> str:
    """Why :func:`inside_paths` or :func:`not_in_generated` refused ``fix`` (the file it would
    edit, and why that file is not edited), or "" when they did not: a run asked to fix says
    so, since the fix exists and another command line would apply it."""
    if fix is None or fix.applicable or not fix.refused.startswith(NOT_FIXABLE + ": "):
        return ""
    why = fix.refused[len(NOT_FIXABLE) + 2:]
    return why if why.endswith((OUTSIDE, GENERATED)) else ""


def inside(path: str, paths: Iterable[str], resolved: bool = False) -> bool:
    """Whether ``path`` (symlinks followed) is one of ``paths`` or below one of them
    (``resolved``: the ``paths`` are already real paths)."""
    from urdf_lint.core.tree import inside as below
    real = os.path.realpath(path)
    roots = paths if resolved else (os.path.realpath(p) for p in paths)
    return any(below(real, r) for r in roots)


def inside_paths(findings: Iterable["Problem"], paths: list[str],
                 generated: dict[str, str] | None = None) -> list["Problem"]:
    """The findings, with the fixes that would edit a file outside the linted ``paths`` (an
    installed package, a dependency elsewhere in the workspace) refused, and those that would
    edit a generated URDF (:func:`not_in_generated`)."""
    from urdf_lint.core.fsbound import write_roots
    from urdf_lint.core.locations import display_path
    from urdf_lint.discovery.discover import repository_root
    out = []
    # once, not once per edit; a named symlink out of the repository stands for nothing
    real_paths = write_roots(paths, repository_root(paths))
    known: dict[str, bool] = {}   # file -> inside? (once per file, not once per fix)
    for p in not_in_generated(findings, generated or {}):
        fx = p.fix
        if fx is not None and fx.applicable:
            for e in fx.edits:
                if e.file not in known:
                    known[e.file] = inside(e.file, real_paths, resolved=True)
            outside = [e.file for e in fx.edits if not known[e.file]]
            if outside:
                p = p.replace(fix=Fix(fx.description, fx.safe, (), f"{NOT_FIXABLE}: "
                                      f"{display_path(outside[0])} {OUTSIDE}"))
        out.append(p)
    return out


def not_in_generated(findings: Iterable["Problem"],
                     generated: dict[str, str]) -> list["Problem"]:
    """The findings, with the fixes that would edit a generated URDF (``generated``: output ->
    the xacro it comes from) refused: fixes go to sources only, safe or unsafe."""
    if not generated:
        return list(findings)
    from urdf_lint.core.locations import display_path
    outputs = {os.path.realpath(k): v for k, v in generated.items()}
    out = []
    for p in findings:
        fx = p.fix
        made = [e.file for e in fx.edits if os.path.realpath(e.file) in outputs] \
            if fx is not None and fx.applicable else []
        if made and fx is not None:
            src = outputs[os.path.realpath(made[0])]
            p = p.replace(fix=Fix(fx.description, fx.safe, (), f"{NOT_FIXABLE}: "
                                  f"{display_path(made[0])} is generated from "
                                  f"{display_path(src)}; {GENERATED}"))
        out.append(p)
    return out
