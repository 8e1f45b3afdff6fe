"""Modules imported at start-up by code we do not own but used by few runs, loaded on first use.

* xacro's ``substitution_args`` imports PyYAML at module level for ``load_yaml`` and
  ``$(arg)`` of type yaml: ~24 ms (its reader compiles a large character-class regex), a
  sixth of ``urdf-lint expand`` on a small model that reads no YAML.
* ``landlock`` imports ``platform`` (~2.5 ms) to word an error message.

:func:`defer` puts a placeholder module under the name. ``import NAME`` binds the placeholder
(the import system reads only its ``__spec__``); the first other attribute looked up on it
imports the real module, and the placeholder takes on its namespace, so code holding either
object sees the same functions and classes.

Only in urdf-lint's own process: :func:`defer` does nothing until the command enables it
(:func:`enable`, first thing in :func:`urdf_lint.cli.main.main`; the workers it forks inherit
it). A program that imports urdf-lint's modules as a library never gets a placeholder in its
``sys.modules``. (``importlib.util.LazyLoader`` cannot do this job: a second ``import yaml``
reads the module's ``__spec__``, which loads a lazily loaded module at once.)
"""
from __future__ import annotations

import sys
import types
from typing import Any


_enabled = False


def enable() -> None:
    """Let :func:`defer` defer, in this process (the command's) and the workers it forks."""
    global _enabled
    _enabled = True


class _Deferred(types.ModuleType):
    def __getattr__(self, attr: str) -> Any:
        # called only for names not (yet) in the placeholder's namespace; ``__path__`` is what
        # ``from NAME import x`` probes on a module that is not a package (it has none: the
        # placeholder of a package has its own). Any other name loads the module, dunders too
        # (``yaml.__with_libyaml__`` must say what the real module says).
        if attr == "__path__":
            raise AttributeError(attr)
        real = _load(self)
        return getattr(real, attr)


def _load(placeholder: types.ModuleType) -> types.ModuleType:
    name = placeholder.__name__
    if sys.modules.get(name) is placeholder:
        del sys.modules[name]
    import importlib
    try:
        real = importlib.import_module(name)
    except BaseException:
        sys.modules.setdefault(name, placeholder)
        raise
    placeholder.__dict__.update(real.__dict__)
    return real


def load(name: str) -> None:
    """Import a deferred module now (a parent about to fork workers that will all use it)."""
    module = sys.modules.get(name)
    if isinstance(module, _Deferred):
        _load(module)


def defer(name: str) -> None:
    """Bind ``name`` to a placeholder, unless it is imported already or cannot be found, or
    deferring is not enabled (urdf-lint imported as a library)."""
    if not _enabled or name in sys.modules:
        return
    import importlib.util
    try:
        spec = importlib.util.find_spec(name)
    except (ImportError, ValueError):
        return
    if spec is None:
        return
    placeholder = _Deferred(name)
    placeholder.__spec__ = spec
    placeholder.__file__ = spec.origin
    if spec.submodule_search_locations is not None:
        placeholder.__path__ = list(spec.submodule_search_locations)
    sys.modules[name] = placeholder
