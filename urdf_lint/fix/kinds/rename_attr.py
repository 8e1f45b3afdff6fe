"""``rename_attr``: rename an attribute where the element's start tag writes it (names are
always written literally)."""
from __future__ import annotations

from urdf_lint.fix.fixes import Element, NOT_FIXABLE, Refuse, Request, where
from urdf_lint.fix.kinds import FixKind, Site
from urdf_lint.core.edits import Edit


def rename_attr(old: str, new: str, safe: bool = True) -> Request:
    return RenameAttr.request(changes=((old, new),), safe=safe,
                              description=f"rename attribute '{old}' to '{new}'")


REQUESTS = (rename_attr,)


class RenameAttr(FixKind):
    name = "rename_attr"

    def resolve(self, site: Site) -> tuple[Edit, ...]:
        ((old, new),) = site.req.changes
        a = site.tag.attr(old)
        if a is None:
            raise Refuse(f"{NOT_FIXABLE}: attribute '{old}' is not written at "
                         f"{where(site.origin.file, site.origin.line)}")
        return (Edit(site.origin.file, a.name_start, a.name_start + len(old.encode()), new),)

    def apply(self, el: Element, attr: str, value: str) -> bool:
        v = el.attrib.pop(attr, None)
        if v is not None:
            el.set(value, v)
        return True
