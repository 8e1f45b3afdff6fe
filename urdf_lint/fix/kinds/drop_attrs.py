"""``drop_attrs``: remove attributes (with the blank before each) from the element's start
tag."""
from __future__ import annotations

from typing import Iterable

from urdf_lint.fix.fixes import Element, Request, written
from urdf_lint.fix.kinds import FixKind, Site
from urdf_lint.core.edits import Edit


def drop_attrs(names: Iterable[str], description: str, safe: bool = False) -> Request:
    """Remove attributes (with the blank before each) from the element's start tag."""
    return DropAttrs.request(changes=tuple((n, "") for n in names), description=description,
                             safe=safe)


REQUESTS = (drop_attrs,)


class DropAttrs(FixKind):
    name = "drop_attrs"
    expectation = "drop"

    def resolve(self, site: Site) -> tuple[Edit, ...]:
        origin, data, tag = site.origin, site.data, site.tag
        edits = []
        for name, _ in site.req.changes:
            a = written(tag, name, origin)
            start = a.name_start
            while start > 0 and data[start - 1:start] in (b" ", b"\t"):
                start -= 1
            if data[start - 1:start] in (b"\n", b"\r"):   # first on its line: keep the indentation
                start = a.name_start
                end = a.value_end + 1
                while data[end:end + 1] in (b" ", b"\t"):
                    end += 1
            else:
                end = a.value_end + 1
            edits.append(Edit(origin.file, start, end, ""))
        return tuple(edits)

    def apply(self, el: Element, attr: str, value: str) -> bool:
        el.attrib.pop(attr, None)
        return True
