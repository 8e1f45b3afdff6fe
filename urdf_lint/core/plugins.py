"""The modules of a plugin folder (rules, output formats, fix kinds), named without importing
them: every room that finds its plugins by file uses this."""
from __future__ import annotations

from collections.abc import Iterable


def submodule_names(paths: Iterable[str]) -> list[str]:
    """The public modules (``*.py`` not starting with ``_``) in a package's folders, sorted.
    (``pkgutil.iter_modules`` would import ``inspect``, ~7 ms, to name them.) None at all is
    an error: an install without its sources must not lint with no rules, or report nothing."""
    from urdf_lint.core import fsbound
    paths = list(paths)
    names: set[str] = set()
    for folder in paths:
        try:
            names.update(fn[:-3] for fn in fsbound.list_dir(folder)
                         if fn.endswith(".py") and not fn.startswith("_"))
        except OSError:
            continue
    if not names:
        raise RuntimeError(f"no modules in {', '.join(map(str, paths))}: urdf-lint is "
                           "installed without its sources (.py files)")
    return sorted(names)
