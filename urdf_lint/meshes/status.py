"""How a mesh or texture reference resolved: an enum of its own, so that the rule API
(:mod:`urdf_lint.engine.api`) names it without importing the resolver."""
from __future__ import annotations

import enum


class MeshStatus(enum.Enum):
    """How a mesh or texture reference resolved (the UL4xx rules map these to codes)."""
    OK = "ok"                          # an existing file inside the package roots
    UNKNOWN_PACKAGE = "unknown-package"
    NOT_FOUND = "not-found"
    CASE_MISMATCH = "case-mismatch"    # exists only with different letter case
    OUTSIDE_ROOTS = "outside-roots"    # resolves outside the package roots: never read
