"""" (did you mean 'X'?)": the hint of every message about an unknown name (config keys, codes,
rule options, links a rule cannot find, command-line flags). difflib is imported only when a
name is unknown (~2 ms that a run without a mistake does not pay)."""
from __future__ import annotations

from collections.abc import Iterable


def close_matches(word: str, candidates: Iterable[str], n: int = 1,
                  cutoff: float = 0.6) -> list[str]:
    """``difflib.get_close_matches``: the best ``n`` of ``candidates`` at least ``cutoff``
    alike to ``word``."""
    import difflib
    return difflib.get_close_matches(word, list(candidates), n=n, cutoff=cutoff)


def did_you_mean(word: str, candidates: Iterable[str]) -> str:
    m = close_matches(word, candidates)
    return f" (did you mean '{m[0]}'?)" if m else ""
