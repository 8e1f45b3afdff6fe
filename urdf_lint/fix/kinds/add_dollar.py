"""``add_dollar``: turn the literal ``{name}`` of each of some names in an attribute into
``${name}``. The new value is whatever xacro makes of it: verification lets that attribute take
any value."""
from __future__ import annotations

import re
from typing import Sequence

from urdf_lint.fix.fixes import Element, NOT_FIXABLE, Refuse, Request, where, written
from urdf_lint.fix.kinds import Expect, FixKind, Site
from urdf_lint.core.edits import Edit

ANY = "\ue000any"   # a private-use marker: "this attribute may take any value"


def add_dollar(attr: str, names: Sequence[str], safe: bool = True) -> Request:
    """Turn the literal ``{name}`` of each of ``names`` in ``attr`` into ``${name}``."""
    return AddDollar.request(changes=((attr, ",".join(names)),), safe=safe,
                             description="add the missing '$' of "
                             + ", ".join("${" + n + "}" for n in names))


REQUESTS = (add_dollar,)


class AddDollar(FixKind):
    name = "add_dollar"
    expectation = "any"

    def resolve(self, site: Site) -> tuple[Edit, ...]:
        origin = site.origin
        ((attr, names),) = site.req.changes
        a = written(site.tag, attr, origin)
        raw = a.raw
        for n in names.split(","):
            raw, k = re.subn(r"(?<![$}]){" + re.escape(n) + "}", "${" + n + "}", raw)
            if not k:
                raise Refuse(f"{NOT_FIXABLE}: '{{{n}}}' is not written at "
                             f"{where(origin.file, origin.line)}")
        return (Edit(origin.file, a.value_start, a.value_end, raw),)

    def expect(self, req: Request, index: int) -> tuple[Expect, ...]:
        return (("any", index, req.changes[0][0], ""),)

    def apply(self, el: Element, attr: str, value: str) -> bool:
        el.set(attr, ANY)
        return True
