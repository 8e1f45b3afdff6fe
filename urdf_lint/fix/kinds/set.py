"""``set``: new values for attributes of the expanded element, written where each value's literal
is: the element itself, the macro call's argument, the ``xacro:property`` or the YAML scalar
(:func:`urdf_lint.fix.fixes.trace`)."""
from __future__ import annotations

from urdf_lint.fix.fixes import (Element, NOT_FIXABLE, Refuse, Request, same_value, trace, traced_scalar,
                                 where, written, yaml_text, YamlScalar, unit_literal)
from urdf_lint.fix.kinds import FixKind, Site
from urdf_lint.core.edits import Edit
from urdf_lint.fix.sourceedit import Attr, escape


def set_attrs(changes: dict[str, str], description: str, safe: bool = True,
              on_parent: bool = False) -> Request:
    return SetAttrs.request(changes=tuple(changes.items()), description=description,
                            safe=safe, on_parent=on_parent)


REQUESTS = (set_attrs,)


class SetAttrs(FixKind):
    name = "set"

    def resolve(self, site: Site) -> tuple[Edit, ...]:
        el, origin, data, tag, src = site.el, site.origin, site.data, site.tag, site.src
        edits = []
        for attr, new in site.req.changes:
            a = written(tag, attr, origin)
            try:
                file, lit = trace(src, origin.file, data, a, tuple(origin.chain), 0)
            except Refuse:   # the expansion saw it come from a YAML scalar: that literal
                found = traced_scalar(site.model, src, el, attr)
                if found is None:
                    raise
                file, lit = found
            if isinstance(lit, YamlScalar) and lit.tag:   # !degrees 370.0: a number in a unit
                edits.append(Edit(file, lit.value_start, lit.value_end,
                                  yaml_text(unit_literal(lit, el.get(attr), new), lit)))
                continue
            if not same_value(lit.value, el.get(attr)):
                raise Refuse(f"{NOT_FIXABLE}: the literal at {where(file)} "
                             f"({lit.value!r}) is not the expanded value {el.get(attr)!r}")
            edits.append(Edit(file, lit.value_start, lit.value_end, escape(new, lit.quote))
                         if isinstance(lit, Attr) else
                         Edit(file, lit.value_start, lit.value_end, yaml_text(new, lit)))
        if len({(e.file, e.start) for e in edits}) != len(edits):
            raise Refuse(f"{NOT_FIXABLE}: two of the values come from the same literal")
        return tuple(edits)

    def apply(self, el: Element, attr: str, value: str) -> bool:
        el.set(attr, value)
        return True

    def traced(self, req: Request) -> tuple[str, ...]:
        return tuple(a for a, _ in req.changes)
