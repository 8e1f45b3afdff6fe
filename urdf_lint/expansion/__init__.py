"""The xacro integration: expansion without ROS that knows where every output element came from.

* :mod:`.expand`: the hooks into the pinned xacro's internals and :func:`expand_file`;
* :mod:`.sourcemap`: the :class:`SourceMap` (file, line, col, chain per output element);
* :mod:`.errors`: the table of how xacro's failures map to codes.

Importing this package imports xacro; only the commands that expand pay for it.
"""
from __future__ import annotations

from .expand import Expansion, expand_file
from .sourcemap import SourceMap

__all__ = ["Expansion", "SourceMap", "expand_file"]
