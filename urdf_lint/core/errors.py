"""Errors that end a run with exit code 2 and one line on stderr (no traceback)."""
from __future__ import annotations


class UsageError(Exception):
    """A bad command line, path or input file named by the user."""
