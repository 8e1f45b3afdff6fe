"""The source map of an expansion: where in the xacro sources each output element came from.

While xacro parses a file, our expat builder stamps every element with
``(file, line, col, chain, template)`` through minidom *user data* (key :data:`KEY`), which is
invisible to xacro and copied to clones by a ``NODE_CLONED`` handler. A macro body being
instantiated gets the chain of call sites that produced it. After expansion, the output
document's elements are read in document order into a :class:`SourceMap`: one
:class:`~urdf_lint.core.locations.Origin` per element, so element *i* of the output (counting the
root, elements only, as ``lxml``'s ``root.iter(tag=etree.Element)`` does) came from
``source_map[i]``:

* ``file``, ``line``, ``col``: the start tag in the xacro source (1-based; ``col`` counts
  characters as expat does, plus one);
* ``chain``: the macro call sites that led to it, outermost first, each ``(file, line, col)``;
  empty for an element written directly in a file (also one reached through includes).

It is like sqlfluff's ``TemplatedFile`` slice map, at element rather than character grain.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Iterable, Iterator, Sequence, overload

from urdf_lint.core.locations import Origin

KEY = "urdf_lint.origin"   # the minidom user-data key of an element's stamp


@dataclass(frozen=True)
class SourceMap(Sequence["Origin | None"]):
    """One :class:`Origin` per output element, in document order (None only before the first
    stamped element, which never happens for a parsed document)."""
    origins: tuple[Origin | None, ...] = ()

    @classmethod
    def from_stamps(cls, stamps: Iterable[Sequence[Any] | None]) -> "SourceMap":
        """From the ``(file, line, col, chain, ...)`` stamps of the output elements (None for
        an element without one: it takes the origin of the element before it)."""
        out: list[Origin | None] = []
        last: Origin | None = None
        for s in stamps:
            if s is not None:
                last = Origin(s[0], s[1], s[2], tuple(tuple(c) for c in s[3]))
            out.append(last)
        return cls(tuple(out))

    def align(self, elements: Iterable[Any]) -> dict[Any, Origin]:
        """{element: Origin} for the output elements in document order. The counts must agree:
        a mismatch would silently shift every location, so it raises ``ValueError``."""
        return {el: o for el, o in zip(elements, self.origins, strict=True) if o is not None}

    def __len__(self) -> int:
        return len(self.origins)

    @overload
    def __getitem__(self, i: int) -> Origin | None: ...

    @overload
    def __getitem__(self, i: slice) -> tuple[Origin | None, ...]: ...

    def __getitem__(self, i: int | slice) -> Origin | None | tuple[Origin | None, ...]:
        return self.origins[i]

    def __iter__(self) -> Iterator[Origin | None]:
        return iter(self.origins)


def as_source_map(origins: Sequence[Any]) -> SourceMap:
    return origins if isinstance(origins, SourceMap) else SourceMap.from_stamps(origins)
