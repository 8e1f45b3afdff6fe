"""Where in a config file a ``[[models]]`` entry sets each xacro arg: the line a person edits when
a value that comes from a passed arg is wrong (a finding's ``value_from``).

``tomllib`` keeps no positions, so the text is scanned: the entry's header (or, for an inline
``models = [...]`` array, the array), then, after its ``args`` key or ``args`` sub-table, each
``NAME =``. When a name appears once per arg set that sets it (``args = [{x = 1}, {x = 2}]``,
``[[...models.args]]`` tables), the n-th appearance belongs to the n-th such set; otherwise every
set points at the first. A name that cannot be found has no place (the finding then names the
element's own line, as before)."""
from __future__ import annotations

import functools
import re
from typing import Any

Place = tuple[str, int, int]            # (file, line, column), 1-based


def _header(line: str, pyproject: bool) -> tuple[bool, bool] | None:
    """(is a [[models]] entry header, is a sub-table of the entry) of a table header line, or
    None when ``line`` is not a header."""
    s = line.strip()
    if not s.startswith("["):
        return None
    name = re.sub(r"\s+", "", s.strip("[]").split("#")[0]).replace('"', "").replace("'", "")
    if pyproject:
        if not name.startswith("tool.urdf-lint."):
            return (False, False)
        name = name[len("tool.urdf-lint."):]
    entry = s.startswith("[[") and name == "models"
    return (entry, name.startswith("models."))


@functools.lru_cache(maxsize=4)
def _entries(text: str, pyproject: bool) -> tuple[list[str], list[int]]:
    """(the lines of a config text, the index of each ``[[models]]`` header): scanned once per
    text, not once per entry (a config listing a hundred models)."""
    lines = text.splitlines()
    return lines, [i for i, ln in enumerate(lines) if (_header(ln, pyproject) or (False,))[0]]


def arg_places(file: str, text: str, entry: int, arg_sets: list[dict[str, Any]]
               ) -> list[dict[str, Place]]:
    """Per arg set of the ``entry``-th ``[[models]]`` entry of the config ``text``, the place of
    each arg it sets."""
    pyproject = file.endswith("pyproject.toml")
    lines, starts = _entries(text, pyproject)
    if entry < len(starts):
        lo, hi = starts[entry] + 1, len(lines)
        for i in range(lo, len(lines)):
            h = _header(lines[i], pyproject)
            if h is not None and not h[1]:
                hi = i
                break
    else:   # an inline ``models = [...]`` array: the scan cannot tell entries apart reliably
        return [{} for _ in arg_sets]
    args_at = next((i for i in range(lo, hi) if re.match(r"\s*[\"']?args[\"']?\s*=", lines[i])
                    or (_header(lines[i], pyproject) or (False, False))[1]), None)
    if args_at is None:
        return [{} for _ in arg_sets]
    places: list[dict[str, Place]] = [{} for _ in arg_sets]
    for name in sorted({n for s in arg_sets for n in s}):
        key = re.compile(r"(?:^|[{,\s])([\"']?)" + re.escape(name) + r"\1\s*=")
        found: list[Place] = []
        for i in range(args_at, hi):
            code = lines[i].split("#")[0] if '"' not in lines[i] else lines[i]
            if i == args_at and not code.lstrip().startswith("["):
                code = code.split("=", 1)[1] if "=" in code else ""
                off = len(lines[i].split("=", 1)[0]) + 1
            else:
                off = 0
            for m in key.finditer(code):
                found.append((file, i + 1, off + m.start(1) + 1))
        if not found:
            continue
        having = [j for j, s in enumerate(arg_sets) if name in s]
        for k, j in enumerate(having):
            places[j][name] = found[k] if len(found) >= len(having) else found[0]
    return places
