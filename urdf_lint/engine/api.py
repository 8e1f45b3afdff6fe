"""Small helpers shared by rules: number parsing and "did you mean"."""
from __future__ import annotations

import difflib
import math
from collections.abc import Iterable


def number(s):
    """A finite float from an attribute value, or None."""
    if s is None:
        return None
    try:
        v = float(s.strip())
    except (ValueError, AttributeError):
        return None
    return v if math.isfinite(v) else None


def numbers(s, n=None):
    """A list of finite floats from a whitespace-separated value (None if any is bad)."""
    if s is None:
        return None
    parts = s.split()
    if n is not None and len(parts) != n:
        return None
    out = []
    for p in parts:
        v = number(p)
        if v is None:
            return None
        out.append(v)
    return out


def did_you_mean(word: str, candidates: Iterable[str]) -> str:
    m = difflib.get_close_matches(word, list(candidates), n=1, cutoff=0.6)
    return f" (did you mean '{m[0]}'?)" if m else ""


CLEAR_MARGIN = 0.15


def single_candidate(word, candidates, cutoff=0.6):
    """The one close match of ``word`` among ``candidates`` (None when there are none or
    several): what a "did you mean" fix may apply. With a ``cutoff`` above 0.6 (references),
    a second candidate a "did you mean" would consider (similarity 0.6) within
    ``CLEAR_MARGIN`` of the first makes two: 'left_finger'
    (0.79 to left_finger_joint, 0.67 to left_inner_joint) is not fixed, 'bse_link' (0.94 to
    base_link, 0.63 to arm_link) is."""
    m = difflib.get_close_matches(word, list(candidates), n=2, cutoff=min(cutoff, 0.6))
    if not m:
        return None
    r = [difflib.SequenceMatcher(None, word, c).ratio() for c in m]
    if r[0] < cutoff or (len(m) == 2 and (cutoff <= 0.6 or r[1] > r[0] - CLEAR_MARGIN)):
        return None
    return m[0]


def reference_fixes(broken, candidates, taken=()):
    """{(element, attr): fix request} for broken references ``broken`` (``(element, attr,
    name)``) that have one close candidate (similarity 0.75) which no other reference of the
    same kind already names and no other broken reference would take too."""
    from urdf_lint.fix.fixes import set_attrs
    guess = {(el, a): single_candidate(n, candidates, 0.75) for el, a, n in broken}
    counts: dict = {}
    for g in guess.values():
        counts[g] = counts.get(g, 0) + 1
    return {k: set_attrs({k[1]: g}, f"point the reference at '{g}'")
            for k, g in guess.items() if g and counts[g] == 1 and g not in set(taken)}


def fmt(v):
    """Short, readable number."""
    return f"{v:g}"


def top(model, tag):
    return [e for e in model.root if e.tag == tag]
