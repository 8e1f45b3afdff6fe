"""Source locations: where in the xacro sources an expanded element came from."""
from __future__ import annotations

import os
import re
from typing import Any, Iterator, NamedTuple

from urdf_lint.core.tree import find_workspace_cached, inside


class Loc(NamedTuple):
    file: str
    line: int
    col: int

    def format(self, base: str | None = None) -> str:
        return f"{display_path(self.file, base)}:{self.line}:{self.col}"


class Origin(NamedTuple):
    """The source of one expanded element.

    ``chain`` holds the macro call sites that led to it, outermost first (each a ``Loc``).
    """
    file: str
    line: int
    col: int
    chain: tuple[Any, ...] = ()

    @property
    def loc(self) -> Loc:
        return Loc(self.file, self.line, self.col)

    def format(self, base: str | None = None) -> str:
        return f"{display_path(self.file, base)}:{self.line}:{self.col}"

    def place(self, base: str | None = None) -> str:
        """Where a message names this element: ``robot.urdf.xacro:7``, and when a macro wrote
        it, the call that did (``arm.xacro:7, called from robot.urdf.xacro:18``): two elements
        one macro line wrote differ only there."""
        at = f"{display_path(self.file, base)}:{self.line}"
        return f"{at}, {self.format_chain(base)}" if self.chain else at

    def format_chain(self, base: str | None = None) -> str:
        """``called from arm.xacro:22 < robot.urdf.xacro:17`` (innermost call first)."""
        if not self.chain:
            return ""
        return "called from " + " < ".join(
            f"{display_path(c[0], base)}:{c[1]}" for c in reversed(self.chain))


_displayed: dict[tuple[str, str], str] = {}


def display_path(path: str, base: str | None = None) -> str:
    """A path as reports show it: relative to ``base`` (default: the working directory) when
    it lies below it; with ``..`` when it lies elsewhere in the git repository or colcon
    workspace that holds ``base`` (a sibling package, a mesh folder above): the same text on
    every checkout, so baselines and CI logs do not depend on where the repository is. Only
    a file outside all of them (``/opt/ros/...``) keeps its absolute path.
    Remembered per (path, base): a report names the same few files thousands of times."""
    if not path:
        return "<unknown>"
    base = base or os.getcwd()
    key = (path, base)
    shown = _displayed.get(key)
    if shown is None:
        try:
            rel = os.path.relpath(path, base)
        except ValueError:
            rel = ".."
        if rel.startswith("..") and not inside(os.path.abspath(path), project_root(base)):
            shown = path
        else:
            shown = rel
        if len(_displayed) > 50000:
            _displayed.clear()
        _displayed[key] = shown
    return shown


CONFIG_SUFFIXES = (".srdf", ".srdf.xacro", ".yaml", ".yml")


def related_label(path: str) -> str:
    """What a finding's related location is: the robot element it is about (its xacro line),
    or a line of another configuration file (UL717: the SRDF group a MoveIt controller
    serves)."""
    return "related configuration line" if path.endswith(CONFIG_SUFFIXES) else "robot element"


def label_base(entry: str) -> str:
    """What file names in a recording's labels are relative to: the folder holding the
    entry's package (so labels read ``ur_description/urdf/ur5e.xacro``), else the entry's
    folder; never a path of the machine that made it."""
    d = os.path.dirname(os.path.abspath(entry))
    probe = d
    while True:
        if os.path.isfile(os.path.join(probe, "package.xml")):
            return os.path.dirname(probe)
        up = os.path.dirname(probe)
        if up == probe:
            return d
        probe = up


def relative_label(path: str) -> str:
    """``path`` relative to :func:`label_base` of itself (for summary.md and labels)."""
    return os.path.relpath(path, label_base(path))


_PICTURE_SUFFIXES = (".urdf.xacro", ".xacro", ".urdf")


def picture_name(rel_entry: str, args: dict[str, Any] | None = None, key: str | None = None) -> str:
    """The file name stem of a model's pictures and recording, the same for ``render`` and
    ``diff``: readable (the entry's path relative to the repository, folders joined by
    ``__``, no suffix, then its args) and unique: a short hash of the model's key (that path
    as is, suffix included, or ``key``, and every arg) tells apart the models the readable
    part confuses (``p/urdf/arm.urdf`` and ``p/urdf_arm.urdf``; ``X.xacro`` and ``X.urdf``).
    The callers still check a run's names for a collision before writing."""
    import hashlib
    import json
    rel = rel_entry.replace(os.sep, "/")
    ident = json.dumps([key or rel, sorted((str(k), str(v)) for k, v in (args or {}).items())])
    digest = hashlib.blake2b(ident.encode("utf-8", "surrogatepass"), digest_size=5).hexdigest()
    stem = next((rel[: -len(s)] for s in _PICTURE_SUFFIXES if rel.endswith(s)), rel)
    stem = stem.replace("/", "__")
    if args:
        stem += "__" + "_".join(f"{k}-{v}" for k, v in sorted(args.items()))
    stem = "".join(c if c.isascii() and (c.isalnum() or c in "_-.@") else "_" for c in stem)
    return f"{stem[:120]}-{digest}"


def snapshot_name(entry: str, args: dict[str, Any] | None, base: str | None) -> str:
    """:func:`picture_name` of the model ``entry`` (absolute) with ``args``, named relative
    to ``base`` (the repository; None: the working folder); outside it relative to its
    package's folder, hashed with its whole path (no path of this machine in the name)."""
    rel = os.path.relpath(entry, base)
    if rel.startswith(".."):
        return picture_name(relative_label(entry), args, key=os.path.abspath(entry))
    return picture_name(rel, args)


def clashing_names(named: dict[Any, str]) -> dict[str, list[Any]]:
    """{name: sorted models} of every name that two different models would get (``named``:
    model -> name), so that neither is written under it."""
    by: dict[str, set[Any]] = {}
    for model, name in named.items():
        by.setdefault(name, set()).add(model)
    return {n: sorted(ms) for n, ms in by.items() if len(ms) > 1}


_roots: dict[str, str] = {}


def project_root(base: str) -> str:
    """The widest folder whose files are shown relative to ``base``: the colcon workspace
    holding ``base``, else the top of its git work tree, else ``base``. Found by looking at
    the folders above (no git call: workers, in their sandbox, show paths too)."""
    base = os.path.abspath(base)
    top = _roots.get(base)
    if top is None:
        top = base
        for d in [base, *_parents(base)]:
            if os.path.lexists(os.path.join(d, ".git")):
                top = d
                break
        try:
            ws = find_workspace_cached(base)
        except (OSError, ValueError):   # a folder the sandbox may not list
            ws = None
        if ws and inside(top, ws):
            top = ws
        _roots[base] = top
    return top


def _parents(d: str) -> Iterator[str]:
    while True:
        up = os.path.dirname(d)
        if up == d:
            return
        yield up
        d = up


# an absolute path inside a message ("looked for /home/.../meshes/x.stl"), up to the first
# character that ends a path in the messages' wording
_PATH_TAIL = r"(?=[/\s'\"(),;:\]]|$)[^\s'\"(),;:\]]*"


def portable(text: str, base: str | None = None) -> str:
    """``text`` (a finding's message) with every absolute path below the project root of
    ``base`` (default: the working directory) shown as :func:`display_path` shows it."""
    if not text or os.sep not in text:
        return text
    base = base or os.getcwd()
    top = project_root(base)
    if len(top) <= 1:
        return text
    for root in {top, os.path.realpath(top)}:
        if root in text:
            text = re.sub(re.escape(root) + _PATH_TAIL,
                          lambda m: display_path(m.group(0), base), text)
    return text
