"""The output formats of ``urdf-lint diff``, one module per format in this package (a
:class:`~urdf_lint.report.diff.base.DiffFormatter` subclass with a ``name``), found like
``check``'s (:func:`urdf_lint.report.registry.discover`): adding a format is adding one file.
"""
from __future__ import annotations

import os
from typing import IO

from urdf_lint.report.diff.base import DiffFormatter, DiffOptions, DiffResult

__all__ = ["DiffFormatter", "DiffOptions", "DiffResult", "formats", "names", "write", "write_file"]

_FORMATS: dict[str, type[DiffFormatter]] | None = None
ORDER = ("text", "json", "markdown")


def formats() -> dict[str, type[DiffFormatter]]:
    """name -> formatter class, for every format module in this package."""
    global _FORMATS
    if _FORMATS is None:
        from urdf_lint.report.registry import discover
        _FORMATS = discover(__name__, __path__, DiffFormatter, ORDER)
    return _FORMATS


def names() -> tuple[str, ...]:
    return tuple(formats())


def write(result: DiffResult, fmt: str, stream: IO[str], options: DiffOptions | None = None) -> None:
    stream.write(formats()[fmt](options).render(result))


def write_file(result: DiffResult, fmt: str, path: str, base: str | None = None,
               options: DiffOptions | None = None) -> None:
    """The report in ``path``, atomically, written below ``base`` (by default its folder)."""
    from urdf_lint.core import fsbound
    with fsbound.open_write(path, base or os.path.dirname(os.path.abspath(path))) as f:
        write(result, fmt, f, options)
