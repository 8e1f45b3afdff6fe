"""``remove_comment``: the fix of an unused suppression comment (made by
:func:`urdf_lint.fix.fixes.remove_comment`, never requested by a rule). A comment is not part
of the robot: the expanded robot does not change."""
from __future__ import annotations

from urdf_lint.fix.kinds import Expect, FixKind, Site
from urdf_lint.fix.request import Request
from urdf_lint.core.edits import Edit


class RemoveComment(FixKind):
    name = "remove_comment"
    expectation = "none"

    def resolve(self, site: Site) -> tuple[Edit, ...]:
        raise NotImplementedError("made by urdf_lint.fix.fixes.remove_comment")

    def expect(self, req: "Request", index: int) -> tuple[Expect, ...]:
        return (("none", 0, "", ""),)
