"""The registry of output formats: every module of :mod:`urdf_lint.report` that defines a
:class:`~urdf_lint.report.base.BaseFormatter` subclass with a ``name``."""
from __future__ import annotations

import importlib
import os
import sys
from typing import IO, Any, Iterable, TypeVar

import urdf_lint.report as _package
from urdf_lint.report.base import BaseFormatter, Outcome, ReportOptions

__all__ = ["BaseFormatter", "ReportOptions", "discover", "formats", "names", "write", "use_color"]

_FORMATS: dict[str, type[BaseFormatter]] | None = None
_T = TypeVar("_T")


ORDER = ("text", "concise", "json", "sarif", "github", "junit")


def discover(package: str, paths: Iterable[str], base: type[_T],
             order: tuple[str, ...] = ()) -> dict[str, type[_T]]:
    """name -> class, for every ``base`` subclass with a ``name`` defined in a module of
    ``package`` (its folders ``paths``), those named in ``order`` first. ``check``'s formats
    and ``diff``'s (:mod:`urdf_lint.report.diff`) are found by it alike."""
    from urdf_lint.core.plugins import submodule_names
    found: dict[str, type[_T]] = {}
    for module in submodule_names(paths):
        if module in ("base", "registry"):
            continue
        mod = importlib.import_module(f"{package}.{module}")
        for obj in vars(mod).values():
            name = getattr(obj, "name", "")
            if (isinstance(obj, type) and issubclass(obj, base) and obj is not base
                    and obj.__module__ == mod.__name__ and name):
                if name in found:
                    raise RuntimeError(f"duplicate output format {name!r}")
                found[name] = obj
    return dict(sorted(found.items(), key=lambda kv: (
        order.index(kv[0]) if kv[0] in order else len(order), kv[0])))


def formats() -> dict[str, type[BaseFormatter]]:
    """name -> formatter class, for every format module in this package."""
    global _FORMATS
    if _FORMATS is None:
        _FORMATS = discover(_package.__name__, _package.__path__, BaseFormatter, ORDER)
    return _FORMATS


def names() -> tuple[str, ...]:
    return tuple(formats())


def use_color(mode: str = "auto", stream: IO[str] | None = None) -> bool:
    """``--color``: always, never, or auto (NO_COLOR, then FORCE_COLOR, then a terminal)."""
    if mode == "always":
        return True
    if mode == "never":
        return False
    if os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    stream = stream or sys.stdout
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False


def write(result: Outcome, fmt: str, stream: IO[str] | None = None, statistics: bool = False,
          color: bool | None = None, **options: Any) -> None:
    """Write ``result`` in format ``fmt``; with ``statistics`` only the counts per rule."""
    stream = stream or sys.stdout
    if color is None:
        color = use_color("auto", stream)
    opts = ReportOptions(color=color, **options)
    formatter = formats()[fmt](stream, opts)
    if statistics:
        formatter.statistics(result)
    else:
        formatter.write(result)
