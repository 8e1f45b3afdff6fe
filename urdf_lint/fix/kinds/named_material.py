"""``named_material`` (unsafe): replace inline ``<material>`` elements by
``<material name="name"/>`` and (``define``) define it once, after the ``<robot>`` tag of the
first one's file. Structural: verified by its findings alone."""
from __future__ import annotations

from typing import Iterable

from urdf_lint.fix.fixes import Element, NOT_FIXABLE, Refuse, Request, where
from urdf_lint.fix.kinds import Site, StructuralKind
from urdf_lint.core.edits import Edit
from urdf_lint.fix.sourceedit import end_tag_of, iter_start_tags, parse_start_tag, start_tag_at


def named_material(elements: Iterable[Element], name: str, rgba: str, define: bool) -> Request:
    """Unsafe: replace the inline ``<material>`` elements by ``<material name="name"/>`` and
    (``define``) define it once, after the ``<robot>`` tag of the first one's file."""
    return NamedMaterial.request(
        changes=(("name", name), ("rgba", rgba), ("define", "1" if define else "")),
        description=f"use one named material '{name}' for the inline colour {rgba}",
        safe=False, elements=tuple(elements))


REQUESTS = (named_material,)


class NamedMaterial(StructuralKind):
    name = "named_material"

    def resolve(self, site: Site) -> tuple[Edit, ...]:
        model, src, req = site.model, site.src, site.req
        opts = dict(req.changes)
        name, rgba = opts["name"], opts["rgba"]
        edits = []
        first = None
        for el in req.elements:
            o = model.origins.get(el)
            if o is None or o.chain:
                raise Refuse(f"{NOT_FIXABLE}: an inline colour is written in a macro "
                             f"({where(o.file, o.line) if o else '?'}) that may make other "
                             "colours")
            data = src.get(o.file)
            tag = start_tag_at(data, o.line, o.col)
            if tag is None or tag.name.rpartition(":")[2] != "material" or tag.self_closing:
                raise Refuse(f"{NOT_FIXABLE}: <material> not found at {where(o.file, o.line)}")
            end = end_tag_of(data, tag)
            if end is None:
                raise Refuse(f"{NOT_FIXABLE}: no </material> for {where(o.file, o.line)}")
            inner = data[tag.end:end]
            c = inner.find(b"<color")
            ctag = parse_start_tag(data, tag.end + c) if c >= 0 else None
            rgba_attr = ctag.attr("rgba") if ctag is not None else None
            if rgba_attr is None or "$" in rgba_attr.value \
                    or b"<texture" in inner:
                raise Refuse(f"{NOT_FIXABLE}: the colour at {where(o.file, o.line)} is not a "
                             "literal rgba")
            q = tag.attrs[0].quote if tag.attrs else '"'
            edits.append(Edit(o.file, tag.start, data.index(b">", end) + 1,
                              f"<material name={q}{name}{q}/>"))
            first = first or (o.file, data, q)
        if opts["define"] and first is not None:
            file, data, q = first
            robot = next(iter_start_tags(data, "robot"), None)
            if robot is None:
                raise Refuse(f"{NOT_FIXABLE}: no <robot> in {where(file)}")
            nl = data.find(b"\n", robot.end)
            eol = "\r\n" if nl > 0 and data[nl - 1:nl] == b"\r" else "\n"
            nxt = data[nl + 1:data.find(b"\n", nl + 1)] if nl >= 0 else b""
            indent = nxt[:len(nxt) - len(nxt.lstrip(b" \t"))].decode("utf-8") or "  "
            edits.append(Edit(file, robot.end, robot.end,
                              f"{eol}{indent}<material name={q}{name}{q}><color "
                              f"rgba={q}{rgba}{q}/></material>"))
        return tuple(edits)
