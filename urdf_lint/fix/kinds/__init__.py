"""Fix kinds: one class per kind of fix a rule may request, one module per kind in this folder
(auto-discovered, like rules: adding a fix kind is adding one file here).

A kind (:class:`FixKind`) says, for a request of it (:class:`urdf_lint.fix.fixes.Request`):

* ``resolve``: the byte edits of the sources, traced from the element's start tag
  (:class:`Site`), or :class:`urdf_lint.fix.fixes.Refuse` with the reason;
* ``expect``: what the fix does to the expanded robot of the model that found it, recorded with
  the :class:`urdf_lint.fix.fixes.Fix` (``(expectation, element index, attr, value)``), and
  ``apply``, which replays one such record on the robot before fixing: ``urdf-lint check
  --fix`` compares the robot after fixing with that (:mod:`urdf_lint.fix.run`);
* ``traced``: the attributes whose values the finding's ``value_from`` traces.

The functions a rule calls to request a kind (``set_attrs``, ``rename_tag``, ...) are defined
in the kind's module and named in its ``REQUESTS``; :mod:`urdf_lint.engine.api` re-exports
them all, so that a rule with a new kind of fix touches two files: the rule and the kind.
"""
from __future__ import annotations

import importlib
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, ClassVar

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.core.locations import Origin
    from urdf_lint.fix.fixes import Request, _Sources
    from urdf_lint.core.edits import Edit
    from urdf_lint.fix.sourceedit import StartTag

Expect = tuple[str, int, str, str]   # (expectation, element index, attr | old name, value | new)


@dataclass(frozen=True)
class Site:
    """Where a request is resolved: the expanded element (``el``; its parent for an
    ``on_parent`` request), its origin, the bytes of its source file and its start tag there."""
    model: Any
    el: Any
    origin: "Origin"
    data: bytes
    tag: "StartTag"
    req: "Request"
    src: "_Sources"


class FixKind:
    """One kind of fix. Subclasses set ``name`` (the request's ``kind``) and define
    ``resolve``; ``expectation`` names their expected results when they differ from ``name``
    (kinds that share one share its ``apply``)."""
    name: ClassVar[str] = ""
    expectation: ClassVar[str] = ""

    @classmethod
    def request(cls, *, changes: tuple[tuple[str, str], ...], description: str,
                safe: bool = True, on_parent: bool = False,
                elements: tuple[Any, ...] = ()) -> "Request":
        """A request of this kind (its ``kind`` is this class's ``name``): what the kind's
        request function (``set_attrs``, ...) returns."""
        from urdf_lint.fix.request import Request
        return Request(changes=changes, description=description, safe=safe, kind=cls.name,
                       on_parent=on_parent, elements=elements)

    def resolve(self, site: Site) -> tuple["Edit", ...]:
        raise NotImplementedError

    def expect(self, req: "Request", index: int) -> tuple[Expect, ...]:
        """The records of what the fix does to element ``index`` of the expanded robot (by
        default one per change: the attribute and its new value)."""
        return tuple((self.expectation or self.name, index, a, v) for a, v in req.changes)

    def apply(self, el: Any, attr: str, value: str) -> bool:   # el: an lxml element
        """Replay one expected record on ``el`` of the robot before fixing; False when the
        change cannot be predicted (a structural fix: its findings decide alone)."""
        return True

    def traced(self, req: "Request") -> tuple[str, ...]:
        """The attributes whose source (``value_from``) the finding names: none by default."""
        return ()


class StructuralKind(FixKind):
    """A fix that changes the robot's structure: verified by its findings alone."""
    expectation: ClassVar[str] = "structural"

    def expect(self, req: "Request", index: int) -> tuple[Expect, ...]:
        return (("structural", index, "", ""),)

    def apply(self, el: Any, attr: str, value: str) -> bool:   # el: an lxml element
        return False


_KINDS: dict[str, FixKind] = {}
_EXPECTATIONS: dict[str, FixKind] = {}
_REQUESTS: dict[str, Callable[..., "Request"]] = {}


def _load() -> None:
    if _KINDS:
        return
    from urdf_lint.core import fsbound
    kinds: dict[str, FixKind] = {}
    requests: dict[str, Callable[..., "Request"]] = {}
    names = {fn[:-3] for folder in __path__ for fn in fsbound.list_dir(folder)
             if fn.endswith(".py") and not fn.startswith("_")}
    for name in sorted(names):
        mod = importlib.import_module(f"{__name__}.{name}")
        for obj in vars(mod).values():
            if isinstance(obj, type) and issubclass(obj, FixKind) and obj.name \
                    and obj.__module__ == mod.__name__:
                if obj.name in kinds:
                    raise RuntimeError(f"fix kind {obj.name!r} is defined twice "
                                       f"({mod.__name__} and {type(kinds[obj.name]).__module__})")
                kinds[obj.name] = obj()
        for fn in getattr(mod, "REQUESTS", ()):
            requests[fn.__name__] = fn
    expectations: dict[str, FixKind] = {}
    for k in kinds.values():
        expectations.setdefault(k.expectation or k.name, k)
    _REQUESTS.update(requests)
    _EXPECTATIONS.update(expectations)
    _KINDS.update(kinds)


def reload() -> None:
    """Discover the kinds again (after a folder was added to this package's ``__path__``)."""
    for d in (_KINDS, _EXPECTATIONS, _REQUESTS):
        d.clear()
    _load()


def kind(name: str) -> FixKind:
    """The fix kind of a request's ``kind`` (KeyError when there is none)."""
    _load()
    return _KINDS[name]


def expectation(name: str) -> FixKind | None:
    """The fix kind whose expected results are recorded as ``name`` (None: unknown)."""
    _load()
    return _EXPECTATIONS.get(name)


def kinds() -> dict[str, FixKind]:
    _load()
    return dict(_KINDS)


def requests() -> dict[str, Callable[..., "Request"]]:
    """{name: function} of the request functions of every kind (``REQUESTS``)."""
    _load()
    return dict(_REQUESTS)
