"""" (did you mean 'X'?)": the hint of every message about an unknown name (config keys, codes,
rule options, links a rule cannot find)."""
from __future__ import annotations

import difflib
from collections.abc import Iterable


def did_you_mean(word: str, candidates: Iterable[str]) -> str:
    m = difflib.get_close_matches(word, list(candidates), n=1, cutoff=0.6)
    return f" (did you mean '{m[0]}'?)" if m else ""
