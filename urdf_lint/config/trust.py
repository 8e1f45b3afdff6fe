"""The linted repository cannot loosen the guarantees.

A repository's own config (``pyproject.toml`` / ``urdf-lint.toml``) is as untrusted as its
descriptions: a pull request can change both. :func:`apply` runs on the loaded settings, after
the config is read and before anything is linted, and keeps every key that could widen what a
description may read, where results go, or how much of the machine a run may take, to what
the *user* asked for:

* ``env-allow``, ``cache-dir`` and ``jobs`` from the repository's config are ignored;
* ``package-paths`` that point outside the repository are ignored (inside it they are kept);
* ``timeout`` and ``memory-mb`` may only tighten the defaults;

each with a note on stderr, unless the same setting is given on the command line or the user
passes ``--trust-config``. Keys that only choose what is reported and how severely (``select``,
``ignore``, ``severity``, ``targets``) are the repository's to set: they widen nothing a
description may read or a run may take. Numeric limits are always clamped to sane ranges, trusted or not.

The paths a run writes or reads as data -- a models entry's ``output`` and ``mesh-base``, and
``baseline`` -- must, from the repository's own config, resolve inside the repository with no
symlinked component (:func:`confine_paths`): otherwise the run stops with a config error
naming the key and the file:line, unless the setting is given on the command line or the user
passes ``--trust-config``.
"""
from __future__ import annotations

import os
from typing import Any

from urdf_lint.config.schema import Config
from urdf_lint.core.tree import inside

CLAMP = {"timeout": (0.5, 600.0), "memory-mb": (128, 65536), "jobs": (1, 64)}


def _inside(f: str, p: str) -> bool:
    return inside(os.path.realpath(f), os.path.realpath(p))


def _clamp(value: float, key: str) -> float:
    lo, hi = CLAMP[key]
    return min(max(value, lo), hi)


def config_root(cfg: Config, repo: str) -> str:
    """The folder the paths of ``cfg`` must stay in: the repository, or the config's own
    folder when the config lies above it (no git: the linted folder is the repository, and a
    config above it is not the repository's own)."""
    top = os.path.realpath(repo)
    folder = os.path.dirname(os.path.realpath(cfg.path)) if cfg.path else top
    return top if inside(folder, top) else folder


def confine_paths(cfg: Config, repo: str, given: set[Any]) -> None:
    """Raise a located :class:`ConfigError` when a path key of the repository's own config
    (``output``, ``mesh-base``, ``baseline``) leaves the repository or goes through a
    symlink; keys in ``given`` (set on the command line) are the user's and not checked."""
    from urdf_lint.config.schema import ConfigError, _line_of, _shown
    from pathlib import Path
    raw = cfg.raw or {}
    if not cfg.path:
        return
    folder = os.path.dirname(os.path.realpath(cfg.path))
    top = config_root(cfg, repo)
    found: list[Any] = []
    if "baseline" not in given and isinstance(raw.get("baseline"), str):
        found.append(("baseline", raw["baseline"]))
    for m in raw.get("models") or ():
        if isinstance(m, dict):
            found += [(k, m[k]) for k in ("output", "mesh-base") if isinstance(m.get(k), str)]
    for key, value in found:
        p = os.path.normpath(os.path.join(folder, os.path.expanduser(value)))
        why = None
        if not inside(p, top):
            why = "is outside the repository"
        else:
            from urdf_lint.core.fsbound import first_symlink
            link = first_symlink(p, top)
            if link is not None:
                why = f"goes through the symlink {os.path.relpath(link, top)!r}"
        if why:
            from urdf_lint.core.escape import escape_text
            raise ConfigError(
                f"{_shown(cfg.path)}{_line_of(Path(cfg.path), key)}: {key} = "
                f"{escape_text(repr(value))} {why} (a repository's own config may name only "
                f"paths inside it: pass it on the command line or use --trust-config)")


def apply(cfg: Config, repo: str, trusted: bool = False,
          given: frozenset[str] | set[str] = frozenset()) -> list[str]:
    """Make ``cfg`` safe to use; return the notes to show. Run it before the command line's
    settings are applied on top (they are the user's, not the repository's); ``given`` are
    the keys set on the command line."""
    notes: list[str] = []
    if not trusted:
        confine_paths(cfg, repo, set(given))
    raw = cfg.raw or {}
    where = os.path.basename(cfg.path) if cfg.path else "the config"
    default = Config()
    why = "a repository's own config cannot loosen urdf-lint's guarantees"
    hint = "pass it on the command line or use --trust-config"

    def note(key: str, what: str) -> None:
        notes.append(f"note: ignored {key!r} from {where} ({what}; {why}: {hint})")

    if not trusted:
        if raw.get("env-allow"):
            note("env-allow", "it lets descriptions read environment variables")
            cfg.env_allow = []
        if raw.get("cache-dir"):
            note("cache-dir", "it moves where results are written and read")
            cfg.cache_dir = None
        if raw.get("jobs") is not None:
            note("jobs", "it sets how many processes a run starts")
            cfg.jobs = None
        if "timeout" in raw and cfg.timeout > default.timeout:
            note("timeout", f"{cfg.timeout:g} s is above the default {default.timeout:g} s")
            cfg.timeout = default.timeout
        if "memory-mb" in raw and cfg.memory_mb > default.memory_mb:
            note("memory-mb", f"{cfg.memory_mb} MiB is above the default {default.memory_mb} MiB")
            cfg.memory_mb = default.memory_mb
        if raw.get("package-paths"):
            kept = {}
            for name, d in cfg.package_paths.items():
                if _inside(d, repo):
                    kept[name] = d
                else:
                    note("package-paths", f"{name} = {d} is outside the repository")
            cfg.package_paths = kept
    clamp(cfg)
    return notes


def clamp(cfg: Config) -> None:
    """Numeric limits within sane ranges, wherever they came from."""
    try:
        cfg.timeout = float(_clamp(float(cfg.timeout), "timeout"))
        cfg.memory_mb = int(_clamp(int(cfg.memory_mb), "memory-mb"))
        if cfg.jobs is not None:
            cfg.jobs = int(_clamp(int(cfg.jobs), "jobs"))
    except (TypeError, ValueError):
        from urdf_lint.config.schema import ConfigError
        raise ConfigError("'timeout', 'memory-mb' and 'jobs' must be numbers") from None
