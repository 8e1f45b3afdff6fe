"""What the real consumers did with each defect class: the verdicts recorded by the consumer
harness (``bench/consumers/harness.py``, issue 38) in ``verdicts.json`` beside this module,
shipped in the wheel. A rule's help (``urdf-lint rule CODE``) cites them as its evidence, and
``tests/test_consumer_verdicts.py`` checks every rule's per-target severity against them.

The file: ``consumers`` (name -> {target, version} or {target, unavailable}), ``mutants``
(defect class -> {codes, verdicts: consumer -> base -> {v, msg}}), ``corpus`` (model ->
consumer -> verdict), ``measured`` (the date). A verdict is ``.`` (loads), ``R`` (rejects),
``C`` (crashes or hangs) or ``W`` (loads a different robot than the one written).
"""
from __future__ import annotations

import functools
import json
from pathlib import Path
from typing import Any

from urdf_lint.core import fsbound

FILE = Path(__file__).with_name("verdicts.json")
SAYS = {".": "loads it", "R": "rejects it", "C": "crashes on it",
        "W": "loads a different robot"}


@functools.lru_cache(maxsize=1)
def load() -> dict[str, Any]:
    """The recorded verdicts ({} when the file is absent: a source checkout before a run)."""
    try:
        data: dict[str, Any] = json.loads(fsbound.read_text(FILE))
        return data
    except FileNotFoundError:
        return {}


def evidence(code: str) -> list[str]:
    """One line per defect class the rule ``code`` reports: each consumer's verdict (with its
    version) on that class's mutant of the probe robot, and the target it is measured for."""
    data = load()
    consumers = data.get("consumers", {})
    out = []
    for name, row in sorted(data.get("mutants", {}).items()):
        if code not in row.get("codes", ()):
            continue
        said = []
        for c, by_base in sorted(row.get("verdicts", {}).items()):
            info = consumers.get(c, {})
            v = by_base.get("probe") or next(iter(by_base.values()), None)
            if not v or "version" not in info:
                continue
            msg = f" ({v['msg'][:80]})" if v.get("msg") and v["v"] in "RC" else ""
            said.append(f"{c} {info['version']} [{info['target']}] {SAYS.get(v['v'], v['v'])}"
                        f"{msg}")
        if said:
            out.append(f"{name}: " + "; ".join(said))
    return out
