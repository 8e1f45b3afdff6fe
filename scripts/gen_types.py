"""The generated Python: what mypy and editors read of names made at run time.

* ``urdf_lint/config/schema.py``: the ``class Config`` block under ``TYPE_CHECKING``, the fields
  :func:`urdf_lint.config.schema.config_class` makes from ``SCHEMA`` at run time (adding a
  config key is one ``Key`` in the schema, then this);
* ``urdf_lint/engine/api.py``: the request function of every fix kind.

A fix kind is one file in ``urdf_lint/fix/kinds/`` naming its request functions in
``REQUESTS``; the rule API imports each by name, so that mypy and editors see it (no module
``__getattr__``). ``render(text)`` writes the block between ``# generated: requests`` and
``# end: requests`` from the kinds' sources (read, not imported: the AST of each module's
``REQUESTS = (...)``). ``scripts/gen_docs.py`` writes it; ``tests/test_rule_api.py`` fails while
it is stale.
"""
from __future__ import annotations

import ast
import re
import sys
import textwrap
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))   # this checkout's code
API = REPO / "urdf_lint" / "engine" / "api.py"
KINDS = REPO / "urdf_lint" / "fix" / "kinds"
_BLOCK = re.compile(r"(# generated: requests\n).*?(# end: requests\n)", re.S)


def requests(folder: Path = KINDS) -> list[tuple[str, str]]:
    """[(module, function)] of every kind's ``REQUESTS``, by module then as listed."""
    out = []
    for path in sorted(folder.glob("*.py")):
        if path.name.startswith("_"):
            continue
        for node in ast.parse(path.read_text(encoding="utf-8")).body:
            if isinstance(node, ast.Assign) and any(
                    isinstance(t, ast.Name) and t.id == "REQUESTS" for t in node.targets) \
                    and isinstance(node.value, (ast.Tuple, ast.List)):
                out += [(path.stem, e.id) for e in node.value.elts if isinstance(e, ast.Name)]
    return out


def block(folder: Path = KINDS) -> str:
    found = requests(folder)
    lines = [f"from urdf_lint.fix.kinds.{m} import {f} as {f}" for m, f in found]
    names = textwrap.fill(", ".join(f'"{f}"' for _, f in found), 88,
                          initial_indent="__all__ += [", subsequent_indent=" " * 12)
    return "\n".join(lines) + f"\n{names}]\n"


def render(text: str, folder: Path = KINDS) -> str:
    return _BLOCK.sub(lambda m: m.group(1) + block(folder) + m.group(2), text, count=1)


SCHEMA_PY = REPO / "urdf_lint" / "config" / "schema.py"
_CONFIG = re.compile(r"(    # generated: config .*?\n).*?(    # end: config\n)", re.S)


def config_block() -> str:
    """``class Config`` as mypy and editors read it: the fields :func:`config_class` makes
    at run time from the schema (imported: the schema is the source of truth)."""
    from urdf_lint.config import schema

    def own(name: str, annotation: str, default: object) -> str:
        value = f"field(default_factory={default.__name__})" if default in (dict, list) \
            else repr(default).replace("'", '"')
        return f"        {name}: {annotation} = {value}"
    lines = ["    @dataclass", "    class Config(_ConfigMethods):",
             '        """' + schema.CONFIG_DOC.replace("\n    ", "\n        ") + '"""']
    lines += [own(*f) for f in schema.OWN_FIELDS_FIRST]
    lines += [f'        {k.attr}: {k.annotation} = _default("{k.name}")' for k in schema.SCHEMA]
    lines += [own(*f) for f in schema.OWN_FIELDS_LAST]
    return "\n".join(lines) + "\n"


def render_config(text: str) -> str:
    return _CONFIG.sub(lambda m: m.group(1) + config_block() + m.group(2), text, count=1)


GENERATED = {"urdf_lint/engine/api.py": (API, render),
             "urdf_lint/config/schema.py": (SCHEMA_PY, render_config)}


def current() -> dict[str, bool]:
    """{file: whether it is as generated}."""
    return {name: rend(path.read_text(encoding="utf-8")) == path.read_text(encoding="utf-8")
            for name, (path, rend) in GENERATED.items()}


def write() -> list[str]:
    """Rewrite the generated parts; the files that changed."""
    changed = []
    for name, (path, rend) in GENERATED.items():
        old = path.read_text(encoding="utf-8")
        new = rend(old)
        if new != old:
            path.write_text(new, encoding="utf-8")
            changed.append(name)
    return changed


if __name__ == "__main__":
    print(", ".join(write()) or "up to date")
