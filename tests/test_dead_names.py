"""No dead names: vulture finds no unused function, class, method, attribute or variable in
the package and the rules, with scripts/vulture_whitelist.py naming what is reached by name
(entry points, plugin hooks, parser callbacks); the classes a registry finds in their folder
(formats, fix kinds) count as used. A name used only by the tests is not dead (vulture reads
the tests too): it is an API the tests pin."""
from __future__ import annotations

import pytest

from conftest import REPO

vulture = pytest.importorskip("vulture")

# The language server is being split into one module per LSP method (another change in
# flight); its names are checked once that lands.
SKIPPED = ("urdf_lint/lsp/",)


def found_by_registry() -> set[str]:
    """The classes a registry finds in their folder (output formats, diff formats, fix
    kinds): adding one is adding its file, never a line in the whitelist."""
    from urdf_lint.fix import kinds
    from urdf_lint.report import diff, registry
    return ({c.__name__ for c in registry.formats().values()}
            | {c.__name__ for c in diff.formats().values()}
            | {type(k).__name__ for k in kinds.kinds().values()})


def unused(paths: list[str]) -> list[str]:
    v = vulture.Vulture()
    v.scavenge(paths)
    registered = found_by_registry()
    return [f"{item.filename.relative_to(REPO)}:{item.first_lineno}: {item.message}"
            for item in v.get_unused_code(min_confidence=60)
            if (str(item.filename).startswith(str(REPO / "urdf_lint"))
                or str(item.filename).startswith(str(REPO / "rules")))
            and not (item.typ == "class" and item.name in registered)]


def test_no_dead_names_in_the_package_and_the_rules():
    found = unused([str(REPO / p) for p in ("urdf_lint", "rules", "tests", "scripts", "bench")]
                   + [str(REPO / "scripts" / "vulture_whitelist.py")])
    dead = [d for d in found if not d.startswith(SKIPPED)]
    assert dead == [], "\n".join(dead)


def test_the_check_finds_a_dead_name(tmp_path):
    (tmp_path / "m.py").write_text("def used():\n    return 1\n\n\ndef never_called():\n"
                                   "    return used()\n\n\nused()\n", encoding="utf-8")
    v = vulture.Vulture()
    v.scavenge([str(tmp_path)])
    assert [i.name for i in v.get_unused_code(min_confidence=60)] == ["never_called"]
