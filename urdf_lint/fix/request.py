"""A fix request: what a rule wants done to the expanded element (its own module, below both
:mod:`urdf_lint.fix.fixes` and :mod:`urdf_lint.fix.kinds`, which build and resolve it)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any


@dataclass(frozen=True, kw_only=True)
class Request:
    """What a rule wants done to the expanded element: ``kind`` names a fix kind
    (:mod:`urdf_lint.fix.kinds`: "set" with ``changes`` the new values of attributes,
    "rename_attr" / "rename_tag" with ((old, new),), ...); the rules make requests with the
    kinds' functions (``set_attrs``, ...), through :mod:`urdf_lint.engine.api`, and a kind's
    function builds its request with ``Kind.request(changes=..., description=...)``, which
    writes the kind's name (:meth:`urdf_lint.fix.kinds.FixKind.request`). Built by keyword;
    the positional form ``Request(changes, description, safe, kind, ...)`` of 0.x still works
    for one release, with a DeprecationWarning."""
    changes: tuple[tuple[str, str], ...]
    description: str
    safe: bool = True
    kind: str = "set"
    on_parent: bool = False      # the fix edits the parent of the element reported
    elements: tuple[Any, ...] = field(default=(), compare=False)   # more elements the fix edits


_REQUEST_FIELDS = ("changes", "description", "safe", "kind", "on_parent", "elements")
_keyword_init = Request.__init__


def _init_positional_deprecated(self: Request, *args: Any, **kw: Any) -> None:
    """Request's ``__init__``: keywords, or (deprecated) the old positional form."""
    if args:
        import warnings
        warnings.warn("Request(changes, description, safe, kind, ...) by position is "
                      "deprecated: build a request with its kind's request(changes=..., "
                      "description=...) (urdf_lint.fix.kinds.FixKind.request)",
                      DeprecationWarning, stacklevel=2)
        if len(args) > len(_REQUEST_FIELDS):
            raise TypeError(f"Request takes at most {len(_REQUEST_FIELDS)} positional "
                            f"arguments ({len(args)} given)")
        for name, value in zip(_REQUEST_FIELDS, args, strict=False):
            if name in kw:
                raise TypeError(f"Request got multiple values for argument {name!r}")
            kw[name] = value
    _keyword_init(self, **kw)


# mypy sees the keyword-only __init__ (new code must name the fields); the old form still runs
Request.__init__ = _init_positional_deprecated  # type: ignore[method-assign]
