"""The source fix of a finding, as every layer sees it: byte :class:`Edit` s of source files
(:class:`Fix`), and :func:`combine` for a finding several models report. How a fix is made
(tracing a value to the line that wrote it, the fix kinds) is :mod:`urdf_lint.fix`."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

NOT_FIXABLE = "not fixable automatically"


@dataclass(frozen=True)
class Edit:
    """Replace bytes [start, end) of ``file`` with ``text`` (UTF-8)."""
    file: str
    start: int
    end: int
    text: str

    def to_dict(self) -> dict[str, Any]:
        return {"file": self.file, "start": self.start, "end": self.end, "text": self.text}


@dataclass(frozen=True)
class Fix:
    """A fix of one finding: byte edits of source files, or why there is none."""
    description: str
    safe: bool = True
    edits: tuple[Edit, ...] = ()
    refused: str = ""                                  # why it is not applied automatically
    # what the fix does to the expanded robot of the model that found it, for verification:
    # ((kind, element index, attr | old name, value | new name), ...); () for a structural fix
    expect: tuple[tuple[Any, ...], ...] = field(default=(), compare=False)

    @property
    def applicable(self) -> bool:
        return bool(self.edits) and not self.refused

    def to_dict(self) -> dict[str, Any]:
        from urdf_lint.core.locations import display_path
        d: dict[str, Any] = {"description": self.description,
             "applicability": "safe" if self.safe else "unsafe"}
        if self.refused:
            d["refused"] = self.refused
        else:
            d["edits"] = [dict(e.to_dict(), file=display_path(e.file)) for e in self.edits]
        return d

    def to_record(self) -> dict[str, Any]:
        return {"description": self.description, "safe": self.safe, "refused": self.refused,
                "edits": [e.to_dict() for e in self.edits],
                "expect": [list(x) for x in self.expect]}

    @classmethod
    def from_record(cls, d: dict[str, Any]) -> "Fix":
        return cls(d["description"], d["safe"], tuple(Edit(**e) for e in d["edits"]),
                   d.get("refused", ""), tuple(tuple(x) for x in d.get("expect", ())))


def combine(a: Fix, b: Fix, label_a: str = "", label_b: str = "") -> Fix:
    """One fix for a finding reported by several models or macro instances: the union of
    their edits when they agree, refused when they edit the same bytes differently."""
    if a.refused:
        return a
    if b.refused:
        return b
    if a.edits == b.edits:
        return a
    by_range = {(e.file, e.start, e.end): e.text for e in a.edits}
    for e in b.edits:
        t = by_range.get((e.file, e.start, e.end))
        if t is not None and t != e.text:
            who = f" ({label_a} and {label_b})" if label_a and label_b else ""
            return Fix(a.description, a.safe, (), f"{NOT_FIXABLE}: the models that use this "
                       f"line need different values{who}")
    edits = tuple(sorted(set(a.edits) | set(b.edits), key=lambda e: (e.file, e.start)))
    return Fix(a.description, a.safe and b.safe, edits, "")
