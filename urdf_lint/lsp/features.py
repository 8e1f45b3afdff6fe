"""Navigation, hover, completion and symbols (registered on the server)."""
from __future__ import annotations


def register(server) -> None:
    pass
