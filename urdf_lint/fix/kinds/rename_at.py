"""``rename_at``: rename a name written on a line of a configuration file (an SRDF or YAML
line: a place no element of the robot has). Unsafe; verified by re-linting like every fix: the
finding must go and none may appear."""
from __future__ import annotations

import re

from urdf_lint.core.edits import Edit, Fix
from urdf_lint.core.locations import Origin
from urdf_lint.fix.fixes import NOT_FIXABLE, Refuse, Request
from urdf_lint.fix.kinds import Expect, FixKind, Site


def rename_at(old: str, new: str) -> Request:
    """The unsafe fix of a finding reported at a line of an SRDF or YAML file: the name ``old``
    written on that line, from the finding's column on, becomes ``new``."""
    return RenameAt.request(changes=((old, new),), safe=False,
                            description=f"rename '{old}' to '{new}'")


REQUESTS = (rename_at,)


class RenameAt(FixKind):
    name = "rename_at"

    def resolve(self, site: Site) -> tuple[Edit, ...]:
        raise Refuse(f"{NOT_FIXABLE}: rename_at edits a line of a configuration file, "
                     "not an element")

    def expect(self, req: Request, index: int) -> tuple[Expect, ...]:
        return ()   # the robot does not change: the configuration file does (its findings
                    # decide: the finding must go and none may appear)


def fix_at(at: Origin, data: bytes | None, req: Request) -> Fix | None:
    """The :class:`Fix` of a ``rename_at`` request for a finding at ``at`` (``data``: the bytes
    of ``at.file``), or None when the line does not hold the name (a name an expression
    builds)."""
    ((old, new),) = req.changes
    if data is None:
        return None
    lines = data.split(b"\n")
    if not 1 <= at.line <= len(lines):
        return None
    start = sum(len(x) + 1 for x in lines[:at.line - 1])
    line = lines[at.line - 1]
    name = re.escape(old.encode())
    col = max(at.col - 1, 0)
    # a quoted value first (an SRDF attribute: not the attribute of the same name), else a
    # plain YAML scalar or key
    m = re.compile(rb"(?<=[\"'])" + name + rb"(?=[\"'])").search(line, col) or \
        re.compile(rb"(?<![\w/.-])" + name + rb"(?![\w/.-]|\s*=)").search(line, col)
    if m is None:
        return None
    return Fix(req.description, safe=req.safe,
               edits=(Edit(at.file, start + m.start(), start + m.end(), new),))
