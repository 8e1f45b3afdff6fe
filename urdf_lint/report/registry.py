"""The registry of output formats: every module of :mod:`urdf_lint.report` that defines a
:class:`~urdf_lint.report.base.BaseFormatter` subclass with a ``name``."""
from __future__ import annotations

import importlib
import os
import sys

import urdf_lint.report as _package
from urdf_lint.report.base import BaseFormatter, ReportOptions

__all__ = ["BaseFormatter", "ReportOptions", "formats", "names", "write", "use_color"]

_FORMATS: dict | None = None


def formats() -> dict:
    """name -> formatter class, for every format module in this package."""
    global _FORMATS
    if _FORMATS is None:
        from urdf_lint.engine.registry import submodule_names
        found = {}
        for name in submodule_names(_package.__path__):
            if name in ("base", "registry"):
                continue
            mod = importlib.import_module(f"{_package.__name__}.{name}")
            for obj in vars(mod).values():
                if (isinstance(obj, type) and issubclass(obj, BaseFormatter)
                        and obj is not BaseFormatter and obj.__module__ == mod.__name__
                        and obj.name):
                    if obj.name in found:
                        raise RuntimeError(f"duplicate output format {obj.name!r}")
                    found[obj.name] = obj
        order = ["text", "concise", "json", "sarif", "github", "junit"]
        _FORMATS = dict(sorted(found.items(), key=lambda kv: (
            order.index(kv[0]) if kv[0] in order else len(order), kv[0])))
    return _FORMATS


def names() -> tuple:
    return tuple(formats())


def use_color(mode: str = "auto", stream=None) -> bool:
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
        return stream.isatty()
    except (AttributeError, ValueError):
        return False


def write(result, fmt, stream=None, statistics=False, color=None, **options):
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
