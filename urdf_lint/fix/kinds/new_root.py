"""``new_root`` (unsafe): a massless root link joined by a fixed joint, inserted before the link
that the reported element (its ``<inertial>``) belongs to. Structural: verified by its findings
alone."""
from __future__ import annotations

from urdf_lint.fix.fixes import NOT_FIXABLE, Refuse, Request, where
from urdf_lint.fix.kinds import Site, StructuralKind
from urdf_lint.core.edits import Edit


def new_root(description: str, suffix: str = "_root") -> Request:
    """Unsafe: a massless root link joined by a fixed joint, inserted before the link that
    the reported element (its ``<inertial>``) belongs to."""
    return NewRoot.request(changes=(("suffix", suffix),), description=description, safe=False,
                           on_parent=True)


REQUESTS = (new_root,)


class NewRoot(StructuralKind):
    name = "new_root"

    def resolve(self, site: Site) -> tuple[Edit, ...]:
        model, link, origin, data, tag = site.model, site.el, site.origin, site.data, site.tag
        ((_, suffix),) = site.req.changes
        if origin.chain:
            raise Refuse(f"{NOT_FIXABLE}: the root link is written in a macro "
                         f"({where(origin.file, origin.line)}) that may make other links too")
        name = tag.attr("name")
        if name is None:
            raise Refuse(f"{NOT_FIXABLE}: the link's name is not written at "
                         f"{where(origin.file, origin.line)}")
        new = link.get("name") + suffix
        if new in model.links or new + "_joint" in model.joints:
            raise Refuse(f"{NOT_FIXABLE}: '{new}' already exists")
        raw = name.raw
        q = name.quote
        line_start = data.rfind(b"\n", 0, tag.start) + 1
        before = data[line_start:tag.start]
        eol = "\r\n" if data.find(b"\r\n", tag.start) == data.find(b"\n", tag.start) - 1 else "\n"
        block = (f"<link name={q}{raw}{suffix}{q}/>", f"<joint name={q}{raw}{suffix}_joint{q} "
                 f"type={q}fixed{q}><parent link={q}{raw}{suffix}{q}/><child link={q}{raw}{q}/>"
                 "</joint>")
        if not before.strip():
            indent = before.decode("utf-8")
            text = "".join(f"{indent}{b}{eol}" for b in block)
            return (Edit(origin.file, line_start, line_start, text),)
        return (Edit(origin.file, tag.start, tag.start, "".join(block)),)
