"""``rename_tag``: rename an element in its start tag and end tag at the element's origin (names
are always written literally)."""
from __future__ import annotations

from urdf_lint.fix.fixes import Element, NOT_FIXABLE, Refuse, Request, where
from urdf_lint.fix.kinds import FixKind, Site
from urdf_lint.core.edits import Edit
from urdf_lint.fix.sourceedit import end_tag_of


def rename_tag(old: str, new: str, safe: bool = True) -> Request:
    return RenameTag.request(changes=((old, new),), description=f"rename <{old}> to <{new}>",
                             safe=safe)


REQUESTS = (rename_tag,)


class RenameTag(FixKind):
    name = "rename_tag"

    def resolve(self, site: Site) -> tuple[Edit, ...]:
        origin, data, tag = site.origin, site.data, site.tag
        ((old, new),) = site.req.changes
        start = tag.name_end - len(old.encode())
        if tag.name != old:
            raise Refuse(f"{NOT_FIXABLE}: <{tag.name}> at {where(origin.file, origin.line)}")
        edits = [Edit(origin.file, start, tag.name_end, new)]
        if not tag.self_closing:
            end = end_tag_of(data, tag)
            if end is None:
                raise Refuse(f"{NOT_FIXABLE}: no end tag for <{old}> at "
                             f"{where(origin.file, origin.line)}")
            edits.append(Edit(origin.file, end + 2, end + 2 + len(old.encode()), new))
        return tuple(edits)

    def apply(self, el: Element, attr: str, value: str) -> bool:
        el.tag = value
        return True
