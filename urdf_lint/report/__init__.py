"""Output formats, one module per format in this package; adding a format is adding one file.

Each module defines a subclass of :class:`urdf_lint.report.base.BaseFormatter` with a ``name``;
:func:`formats` finds them, and the CLI's ``--output-format`` choices come from there.

JSON schema (``--format json``), version 1::

    {
      "version": 1, "tool": "urdf-lint", "tool_version": "0.1.0",
      "models": [{"entry": str, "args": {str: str}, "name": str, "status": "model"|"failed",
                  "cached": bool (result reused from .urdf_lint_cache),
                  "links": int, "joints": int, "meshes": int}],
      "findings": [{"code": "UL302", "name": "limit-order", "severity": "error"|"warning"|"info",
                    "message": str, "file": str (relative to cwd; ``..`` inside its repository
                    or workspace), "line": int, "col": int,
                    "chain": [[file, line, col], ...]  (macro call sites, outermost first),
                    "models": [str, ...],
                    "fix": {"description": str, "applicability": "safe"|"unsafe",
                            "edits": [{"file": str, "start": int, "end": int, "text": str}]
                                     (byte ranges of the source, replaced by text)
                            | "refused": str (why it is not applied automatically)}
                           (only when the rule has a fix for this finding),
                    "severity_from": [str, ...] (the selected consumer targets that make it
                           this severe, urdf_lint.targets; only when one raised it)}],
                    "detail": str (what this instance is about, when the message is a root
                               cause's, e.g. the mesh URI of an unknown package; optional),
                    "value_from": [file, line, col] (where the value came from: a YAML scalar,
                                  a property defined elsewhere; optional),
                    "count": int, "instances": [{finding fields, "target": [kind, name]}, ...]
                             (when several elements, models or places are one finding: one per
                              source location and rule, or per root cause)}],
      "summary": {"models": int, "errors": int, "warnings": int, "info": int}
    }

With ``--statistics``, ``--format json`` prints ``[{"code", "name", "severity", "count"}]``.
"""
from __future__ import annotations

import importlib
import os
import sys

from .base import BaseFormatter, ReportOptions

__all__ = ["BaseFormatter", "ReportOptions", "formats", "names", "write", "use_color"]

_FORMATS: dict | None = None


def formats() -> dict:
    """name -> formatter class, for every format module in this package."""
    global _FORMATS
    if _FORMATS is None:
        from ..registry import submodule_names
        found = {}
        for name in submodule_names(__path__):
            if name == "base":
                continue
            mod = importlib.import_module(f"{__name__}.{name}")
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
