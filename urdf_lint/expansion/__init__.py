"""The xacro integration: expansion without ROS that knows where every output element came from.

* :mod:`.expand`: the hooks into the pinned xacro's internals and :func:`expand_file`;
* :mod:`.sourcemap`: the :class:`SourceMap` (file, line, col, chain per output element);
* :mod:`.clone`: macro bodies cloned field by field (xacro clones one per call), checked once
  per process against minidom's clone;
* :mod:`.errors`: the table of how xacro's failures map to codes.

Importing :mod:`.expand` (``expand_file``, ``Expansion``) imports xacro, so it is loaded on
first use: a cached run, and code that only needs the source-map type, never pay for it.

May import: ``runner``, ``discovery``, ``config``, ``report``, ``core`` (the rooms below it,
``[tool.importlinter]`` in pyproject.toml; never a room above).
"""
from __future__ import annotations

from typing import Any

from urdf_lint.core import lazy
from urdf_lint.expansion.sourcemap import SourceMap

# before xacro is imported (by .expand or .errors): PyYAML loads when a model first reads YAML
lazy.defer("yaml")

__all__ = ["Expansion", "SourceMap", "expand_file"]


def __getattr__(name: str) -> Any:
    if name in ("Expansion", "expand_file"):
        from urdf_lint.expansion import expand
        return getattr(expand, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
