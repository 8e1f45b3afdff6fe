"""The repository's scripts (``scripts/*.py``) as modules, for tests that call their functions
in process."""
from __future__ import annotations

import importlib.util
from pathlib import Path
from types import ModuleType

REPO = Path(__file__).resolve().parent.parent.parent


def load_script(name: str, repo: Path = REPO) -> ModuleType:
    """``scripts/NAME.py`` of ``repo``, loaded afresh (a module's own state is never shared
    between tests)."""
    spec = importlib.util.spec_from_file_location(f"script_{name}", repo / "scripts" / f"{name}.py")
    assert spec and spec.loader
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod
