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

Which key gets which treatment is the key's ``trust`` and ``clamp`` in the schema
(:data:`urdf_lint.config.schema.SCHEMA`); this module only applies them.

The paths a run writes or reads as data -- a models entry's ``output`` and ``mesh-base``, and
``baseline`` -- must, from the repository's own config, resolve inside the repository with no
symlinked component (:func:`confine_paths`): otherwise the run stops with a config error
naming the key and the file:line, unless the setting is given on the command line or the user
passes ``--trust-config``.
"""
from __future__ import annotations

import os
from typing import Any

from urdf_lint.config.schema import SCHEMA, Config, Key, Number
from urdf_lint.core.tree import inside


def _inside(f: str, p: str) -> bool:
    return inside(os.path.realpath(f), os.path.realpath(p))


def keys_with(rule: str) -> tuple[Key, ...]:
    """The schema keys whose ``trust`` rule is ``rule``."""
    return tuple(k for k in SCHEMA if k.trust is not None and k.trust.rule == rule)


def _number(v: float) -> str:
    return f"{v:g}" if isinstance(v, float) else str(v)


def config_root(cfg: Config, repo: str) -> str:
    """The folder the paths of ``cfg`` must stay in: the repository, or the config's own
    folder when the config lies above it (no git: the linted folder is the repository, and a
    config above it is not the repository's own)."""
    top = os.path.realpath(repo)
    folder = os.path.dirname(os.path.realpath(cfg.path)) if cfg.path else top
    return top if inside(folder, top) else folder


def confine_paths(cfg: Config, repo: str, given: set[Any]) -> None:
    """Raise a located :class:`ConfigError` when a path key of the repository's own config
    (``output``, ``mesh-base``, ``srdf``, ``controllers``, ``joint-limits``, ``baseline``)
    leaves the repository or goes through a symlink; keys in ``given`` (set on the command
    line) are the user's and not checked."""
    from urdf_lint.config.schema import ConfigError, _line_of, _shown
    from pathlib import Path
    raw = cfg.raw or {}
    if not cfg.path:
        return
    folder = os.path.dirname(os.path.realpath(cfg.path))
    top = config_root(cfg, repo)
    found: list[tuple[str, Any]] = []
    for k in keys_with("confine"):
        assert k.trust is not None
        if not k.trust.fields and k.name not in given and isinstance(raw.get(k.name), str):
            found.append((k.name, raw[k.name]))
        for m in (raw.get(k.name) or ()) if k.trust.fields else ():
            if isinstance(m, dict):
                found += [(f, v) for f in k.trust.fields
                          for v in (m[f] if isinstance(m.get(f), list) else [m.get(f)])
                          if isinstance(v, str)]
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
        why = "a repository's own config cannot loosen urdf-lint's guarantees"
        hint = "pass it on the command line or use --trust-config"
        for key in SCHEMA:
            if key.trust is not None and raw.get(key.name) is not None:
                for what in _loosened(cfg, key, repo):
                    notes.append(f"note: ignored {key.name!r} from {where} ({what}; {why}: {hint})")
    clamp(cfg)
    return notes


def _loosened(cfg: Config, key: Key, repo: str) -> list[str]:
    """Undo what the repository's value of ``key`` loosens in ``cfg``; say what each was."""
    assert key.trust is not None
    rule, value = key.trust.rule, getattr(cfg, key.attr)
    if rule == "ignore" and cfg.raw.get(key.name):
        setattr(cfg, key.attr, key.default)
        return [key.trust.why]
    if rule == "at-most-default" and value > key.default:
        setattr(cfg, key.attr, key.default)
        unit = key.trust.unit
        return [f"{_number(value)} {unit} is above the default {_number(key.default)} {unit}"]
    if rule == "inside-repo":
        kept = {n: d for n, d in value.items() if _inside(d, repo)}
        setattr(cfg, key.attr, kept)
        return [f"{n} = {d} is outside the repository" for n, d in value.items() if n not in kept]
    return []


def clamp(cfg: Config) -> None:
    """Numeric limits within sane ranges, wherever they came from."""
    keys = [k for k in SCHEMA if k.clamp is not None]
    try:
        for k in keys:
            value = getattr(cfg, k.attr)
            if value is not None:
                kind = k.type.kind if isinstance(k.type, Number) else float
                lo, hi = k.clamp  # type: ignore[misc]
                setattr(cfg, k.attr, kind(min(max(kind(value), lo), hi)))
    except (TypeError, ValueError):
        from urdf_lint.config.schema import ConfigError
        names = [repr(k.name) for k in keys]
        raise ConfigError(f"{', '.join(names[:-1])} and {names[-1]} must be numbers") from None
