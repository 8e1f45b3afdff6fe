"""ROS package resolution without ROS.

One resolver serves expansion (``$(find)``, ``package://`` includes, ``load_yaml``), mesh
checks and rendering. It looks, in this order, at:

1. explicit ``package-paths`` (config or ``--package-path name=dir``);
2. ``package.xml`` files under the linted paths and the repository root (name from ``<name>``);
3. ``AMENT_PREFIX_PATH`` (the ament resource index);
4. ``ROS_PACKAGE_PATH``.

It also knows the *roots* that files may be read from: every package directory it found plus
the linted repository, and the packages of the environment's search path. Anything resolving
(after symlinks) outside the roots is refused.

A resolver is an immutable snapshot, built once per run (``build``) and handed as is to every
pass and worker: looking a package up never adds a root (SECURITY.md, "Roots"). A package
name is a name, never a path (:func:`valid_package_name`).
"""
from __future__ import annotations

import os
import re
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any, Callable

from urdf_lint.core.tree import SKIP_DIRS
from urdf_lint.core.tree import inside as inside   # (part of this API)
from urdf_lint.core.tree import real_path

_NAME_RE = re.compile(rb"<name>\s*([^<\s]+)\s*</name>")
# REP 144 (lower case letters, digits and underscores, starting with a letter), leniently:
# upper case, dashes and a leading digit or underscore, which catkin tolerates; never a path
# separator, a dot (so never '.' or '..'), a leading dash or anything absolute
_PACKAGE_NAME_RE = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_-]{0,199}")


def valid_package_name(name: str) -> bool:
    """Is ``name`` a ROS package name (not a path: ``$(find /abs)``, ``$(find ../x)``)?"""
    return isinstance(name, str) and _PACKAGE_NAME_RE.fullmatch(name) is not None


class PackageNotFound(Exception):
    def __init__(self, name: str, searched: list[str], folder: str | None = None) -> None:
        self.name = name
        self.searched = searched
        self.folder = folder
        where = "; ".join(searched) if searched else "nowhere (no package.xml found)"
        hint = (f"; a folder named '{name}' exists: pass --package-path {name}={folder}"
                if folder else "")
        if not name:   # package:///x or $(find ): a slash too many, or an empty name
            super().__init__("the package URI names no package ('package:///...' has one slash "
                             "too many: write package://NAME/path)")
            return
        super().__init__(f"unknown package '{name}' (searched: {where}){hint}")

    def again(self) -> "PackageNotFound":
        """The same miss, raised afresh (a memoised lookup)."""
        return PackageNotFound(self.name, self.searched, self.folder)


class InvalidPackageName(PackageNotFound):
    """A name that is no ROS package name (a path, ``..``): it resolves to nothing."""
    def __init__(self, name: str) -> None:
        shown = name if len(name) <= 80 else name[:80] + "..."
        Exception.__init__(self, f"'{shown}' is not a ROS package name (letters, digits, '_' "
                                 "and '-'; never a path): it names no package")
        self.name, self.searched, self.folder = name, [], None

    def again(self) -> "PackageNotFound":
        return InvalidPackageName(self.name)


class OutsideRoots(Exception):
    def __init__(self, path: str, what: str = "file") -> None:
        self.path = path
        super().__init__(f"{what} '{path}' resolves outside the package roots and the linted "
                         f"repository; it was not read")


def package_name(package_xml: Path) -> str | None:
    from urdf_lint.core import fsbound
    try:   # a regular file (never a FIFO or device) in its own folder, its first 64 KiB
        # (a committed package.xml -> /elsewhere is not read: not a package)
        data = fsbound.read_head(package_xml, 65536,
                                 [os.path.realpath(os.path.dirname(os.path.abspath(package_xml)))])
    except OSError:
        return None
    m = _NAME_RE.search(data)
    return m.group(1).decode("utf-8", "replace") if m else None


def iter_files(top: Path, suffixes: tuple[str, ...] | None = None, names: set[str] | None = None,
               folders: list[str] | None = None) -> Iterator[Path]:
    """Walk ``top`` (skipping build/VCS/venv folders), yielding files that match; each folder
    looked into is added to ``folders`` when given."""
    from urdf_lint.core import fsbound
    for f in fsbound.walk_files(top, suffixes, names, folders=folders,
                                skip=lambda d: d in SKIP_DIRS or d.startswith(".")):
        yield Path(f)


def _colcon_ignored(folder: Path, top: Path) -> bool:
    from urdf_lint.discovery.folders import ignored
    return ignored(folder, top)


@dataclass(frozen=True)
class PackageResolver:
    """Where each ROS package lives (named with ``--package-path``, or found by ``package.xml``)
    and which folders a run may read.

    Immutable (a frozen snapshot of one run's roots): the maps are read-only and the roots a
    tuple, so no lookup, pass or worker can widen what the others may read. The roots are
    ``roots`` plus the packages of ``AMENT_PREFIX_PATH`` and ``ROS_PACKAGE_PATH`` (as the
    parent saw them: workers run with a scrubbed environment, so the search path travels with
    the resolver); lookups, hits and misses alike, are memoised in ``_memo``, which only ever
    caches what the fields above already determine."""
    explicit: Mapping[str, Path] = field(default_factory=dict)
    scanned: Mapping[str, Path] = field(default_factory=dict)
    roots: tuple[Path, ...] = ()
    scanned_dirs: tuple[str, ...] = ()
    use_environment: bool = True
    env_paths: Mapping[str, Sequence[str]] = field(default_factory=dict)   # tuples once made
    _memo: dict[Any, Any] = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self) -> None:
        fixed = {"explicit": MappingProxyType({k: Path(v) for k, v in self.explicit.items()}),
                 "scanned": MappingProxyType({k: Path(v) for k, v in self.scanned.items()}),
                 "roots": tuple(Path(r) for r in self.roots),
                 "scanned_dirs": tuple(self.scanned_dirs),
                 "env_paths": MappingProxyType({k: tuple(v) for k, v in self.env_paths.items()})}
        for k, v in fixed.items():
            object.__setattr__(self, k, v)

    def __reduce__(self) -> tuple[Callable[[dict[str, Any]], PackageResolver],
                                  tuple[dict[str, Any]]]:   # (the read-only maps do not pickle as such)
        return (PackageResolver.from_dict, (self.to_dict(),))

    @classmethod
    def build(cls, scan_dirs: Iterable[str], explicit: dict[str, str] | None = None,
              extra_roots: Iterable[str] = (), use_environment: bool = True,
              packages: dict[str, str] | None = None) -> "PackageResolver":
        """``packages``: name -> folder found elsewhere (a workspace index), after the scan."""
        env_paths = environment_paths() if use_environment else {}
        explicit_paths = {name: Path(where).resolve() for name, where in (explicit or {}).items()}
        scanned: dict[str, Path] = {}
        scanned_dirs: list[str] = []
        seen = set()
        for d0 in scan_dirs:
            d = Path(d0).resolve()
            if d in seen or not d.exists():
                continue
            seen.add(d)
            if d.is_dir():   # (a linted file holds no package.xml: not a place to name)
                scanned_dirs.append(str(d))
            for pxml in iter_files(d, names={"package.xml"}):
                if _colcon_ignored(pxml.parent, d):
                    continue
                found = package_name(pxml)
                if found and found not in scanned:
                    scanned[found] = pxml.parent.resolve()
        for pkg, where in (packages or {}).items():
            scanned.setdefault(pkg, Path(where).resolve())
        roots = list(explicit_paths.values()) + list(scanned.values())
        roots += [Path(r).resolve() for r in extra_roots]
        return cls(explicit=explicit_paths, scanned=scanned, roots=tuple(sorted(set(roots), key=str)),
                   scanned_dirs=tuple(scanned_dirs), use_environment=use_environment,
                   env_paths=env_paths)

    # -- lookup ------------------------------------------------------------------------------
    def _from_environment(self, name: str) -> Path | None:
        if not self.use_environment:
            return None
        for prefix in self.env_paths.get("AMENT_PREFIX_PATH", ()):
            found = self._ament_share(prefix, name)
            if found is not None:
                return found
        return self._ros_packages()[0].get(name)

    def _ament_share(self, prefix: str, name: str) -> Path | None:
        """``prefix/share/NAME`` when the ament index of ``prefix`` lists ``NAME`` and the folder
        really is that child of the prefix (no symlink leading anywhere else)."""
        key = ("ament", prefix, name)
        if key not in self._memo:
            found = None
            share = self._real_share(prefix)
            if share is not None and valid_package_name(name):
                marker = os.path.join(prefix, "share", "ament_index", "resource_index",
                                      "packages", name)
                folder = os.path.join(prefix, "share", name)
                if os.path.lexists(marker) and os.path.isdir(folder) and \
                        os.path.realpath(folder) == os.path.join(share, name):
                    found = Path(share, name)
            self._memo[key] = found
        got: Path | None = self._memo[key]
        return got

    def _real_share(self, prefix: str) -> str | None:
        """The real ``share`` folder of an ament prefix, when it is inside the prefix."""
        key = ("share", prefix)
        if key not in self._memo:
            share = os.path.realpath(os.path.join(prefix, "share"))
            self._memo[key] = share if inside(share, os.path.realpath(prefix)) else None
        got: str | None = self._memo[key]
        return got

    def _ros_packages(self) -> tuple[dict[str, Path], frozenset[str]]:
        """(name -> folder, the set of folders) of every package under ``ROS_PACKAGE_PATH``:
        one walk per run (shared by the processes forked after it), however many lookups."""
        if "ros" not in self._memo:
            self._memo["ros"] = ros_package_index(self.env_paths.get("ROS_PACKAGE_PATH", ()))
        got: tuple[dict[str, Path], frozenset[str]] = self._memo["ros"]
        return got

    def find(self, name: str) -> Path:
        key = ("find", name)
        hit = self._memo.get(key)
        if hit is None:
            hit = self._memo[key] = self._lookup(name)
        if isinstance(hit, PackageNotFound):
            raise hit.again()
        return hit

    def _lookup(self, name: str) -> "Path | PackageNotFound":
        if not valid_package_name(name):
            return InvalidPackageName(str(name))
        if name in self.explicit:
            return self.explicit[name]
        if name in self.scanned:
            return self.scanned[name]
        found = self._from_environment(name)
        if found is not None:
            return found
        from urdf_lint.discovery.folders import folder_named
        if not name:
            return PackageNotFound("", [])
        return PackageNotFound(name, self.searched(),
                               folder_named(name, [str(r) for r in self.roots], SKIP_DIRS))

    def searched(self) -> list[str]:
        out = [f"--package-path/package-paths ({', '.join(sorted(self.explicit)) or 'none'})"]
        out += [f"package.xml under {d}" for d in self.scanned_dirs]
        if self.use_environment:  # never the values: messages carry no environment contents
            for var in ("AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH"):
                n = len(self.env_paths.get(var, ()))
                out.append(f"{var} ({n} folder{'s' if n != 1 else ''})" if n else f"{var} (unset)")
        return out

    # -- URIs --------------------------------------------------------------------------------
    def resolve_uri(self, uri: str, base_dir: str | os.PathLike[str] | None) -> Path:
        """Turn a mesh/include URI (``package://``, ``file://``, absolute, relative) into a path.

        Raises PackageNotFound for unknown packages. Does not check confinement or existence.
        """
        if uri.startswith("package://"):
            rest = uri[len("package://"):]
            name, _, rel = rest.partition("/")
            p = self.find(name) / rel
            return p if p.exists() else Path(self.installed(p)[0])
        if uri.startswith("file://"):
            return Path(uri[len("file://"):])
        p = Path(uri)
        if not p.is_absolute() and base_dir is not None:
            p = Path(base_dir) / p
        return p

    def installed(self, path: str | os.PathLike[str]) -> tuple[str, str | None]:
        """``(source path, the CMakeLists.txt that maps it)`` of a path below a package of the
        source tree that does not exist as written but that the package's build installs from
        another folder (:mod:`urdf_lint.discovery.installs`); ``(path, None)`` otherwise."""
        s = os.path.normpath(str(path))
        if os.path.exists(s):
            return s, None
        pkgs = [(n, str(r)) for n, r in (*self.explicit.items(), *self.scanned.items())
                if inside(s, str(r))]
        if not pkgs:
            return s, None
        name, root = max(pkgs, key=lambda p: len(p[1]))
        from urdf_lint.discovery.installs import source_of
        rel = os.path.relpath(s, root).replace(os.sep, "/")
        for cand in source_of(rel, self._install_rules(name, root)):
            p = os.path.normpath(os.path.join(root, cand))
            if inside(p, root) and os.path.exists(p):
                return p, os.path.join(root, "CMakeLists.txt")
        return s, None

    def _install_rules(self, name: str, root: str) -> list[tuple[str, str]]:
        key = ("install", root)
        if key not in self._memo:
            from urdf_lint.core import fsbound
            from urdf_lint.discovery.installs import MAX_CMAKE_BYTES, install_rules
            cmake = os.path.join(root, "CMakeLists.txt")
            try:
                text = fsbound.read_text(cmake, max_bytes=MAX_CMAKE_BYTES, errors="replace") \
                    if os.path.isfile(cmake) else ""
            except OSError:
                text = ""
            self._memo[key] = install_rules(text, name)
        rules: list[tuple[str, str]] = self._memo[key]
        return rules

    def is_inside(self, path: str | os.PathLike[str]) -> bool:
        real = real_path(path)
        # string prefixes of the normalised roots (what Path.relative_to tests, 20x cheaper)
        return any(inside(real, r) for r in map(str, self.roots)) or \
            self._environment_root(real) is not None

    def root_of(self, path: str | os.PathLike[str]) -> str | None:
        """The deepest root holding ``path`` as written (a normalised absolute path, before
        symlinks), or None. (Of two roots that both hold it the deeper is the longer string.)"""
        s = str(path)
        best = None
        for r in map(str, self.roots):
            if inside(s, r) and (best is None or len(r) > len(best)):
                best = r
        env = self._environment_root(s)
        if env is not None and (best is None or len(env) > len(best)):
            best = env
        return best

    def _environment_root(self, path: str) -> str | None:
        """The package of the environment's search path holding ``path`` (normalised), if any:
        ``prefix/share/NAME`` of an ament prefix, or a package under ``ROS_PACKAGE_PATH``."""
        if not self.use_environment or not self.env_paths:
            return None
        for prefix in self.env_paths.get("AMENT_PREFIX_PATH", ()):
            share = self._real_share(prefix)
            if share is None or not path.startswith(share.rstrip(os.sep) + os.sep):
                continue
            name = path[len(share.rstrip(os.sep)) + 1:].split(os.sep, 1)[0]
            found = self._ament_share(prefix, name)
            if found is not None:
                return str(found)
        if "ROS_PACKAGE_PATH" in self.env_paths:
            folders = self._ros_packages()[1]
            d = path
            while True:
                if d in folders:
                    return d
                parent = os.path.dirname(d)
                if parent == d:
                    return None
                d = parent
        return None

    def readable(self, path: str | os.PathLike[str], cap: int | None = None) -> bool:
        """May urdf-lint read this file? Inside the roots after symlinks, a regular file (not
        a device, FIFO or folder) and, with ``cap``, at most that many bytes."""
        return self.is_inside(path) and regular_file(path, cap)

    def to_dict(self) -> dict[str, Any]:
        return {"explicit": {k: str(v) for k, v in self.explicit.items()},
                "scanned": {k: str(v) for k, v in self.scanned.items()},
                "roots": [str(r) for r in self.roots],
                "scanned_dirs": list(self.scanned_dirs),
                "use_environment": self.use_environment,
                "env_paths": {k: list(v) for k, v in self.env_paths.items()}}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> "PackageResolver":
        return cls(explicit={k: Path(v) for k, v in d["explicit"].items()},
                   scanned={k: Path(v) for k, v in d["scanned"].items()},
                   roots=tuple(Path(r) for r in d["roots"]), scanned_dirs=tuple(d["scanned_dirs"]),
                   use_environment=d["use_environment"],
                   env_paths={k: tuple(v) for k, v in d.get("env_paths", {}).items()})

    def read_paths(self) -> list[str]:
        """Every folder a worker may read below: the roots and the environment's package
        search path (its packages are roots too)."""
        out = [str(r) for r in self.roots] + [str(p) for p in self.explicit.values()] + \
            [str(p) for p in self.scanned.values()]
        out += [os.path.join(p, "share") for p in self.env_paths.get("AMENT_PREFIX_PATH", ())]
        out += list(self.env_paths.get("ROS_PACKAGE_PATH", ()))
        return out


_LAST: list[Any] = [None, None]   # (a settings' resolver dict, the resolver made from it)


def from_settings(d: dict[str, Any]) -> PackageResolver:
    """The resolver of a run's settings (``LintSettings.resolver``), made once for the same
    dict: a worker lints its jobs with one snapshot, and so shares its lookups (it is
    immutable, so sharing it cannot widen a job's roots)."""
    if _LAST[0] is not d:
        _LAST[:] = [d, PackageResolver.from_dict(d)]
    made: PackageResolver = _LAST[1]
    return made


# ROS_PACKAGE_PATH (folders and their mtimes) -> its package index
_ROS_INDEX: dict[Any, tuple[dict[str, Path], frozenset[str]]] = {}


def ros_package_index(dirs: Iterable[str]) -> tuple[dict[str, Path], frozenset[str]]:
    """(name -> folder, the set of folders) of the packages under ``dirs`` (``package.xml``
    files, the first of a name wins, in the order a lookup walked them before). Built once per
    search path and process: forked workers inherit the parent's."""
    def stamp(d: str) -> int | None:
        try:
            return os.stat(d).st_mtime_ns
        except OSError:
            return None
    key = tuple((d, stamp(d)) for d in dirs)
    hit = _ROS_INDEX.get(key)
    if hit is None:
        names: dict[str, Path] = {}
        for d in dirs:
            for pxml in iter_files(Path(d), names={"package.xml"}):
                name = package_name(pxml)
                if name and valid_package_name(name) and name not in names:
                    names[name] = pxml.parent.resolve()
        hit = _ROS_INDEX[key] = (names, frozenset(str(p) for p in names.values()))
    return hit


MAX_SOURCE_BYTES = 256 << 20   # an XML source file urdf-lint reads in the parent


def regular_file(path: str | os.PathLike[str], cap: int | None = None) -> bool:
    """A regular file after symlinks (no device, FIFO, socket or folder), not above ``cap``."""
    import stat
    try:
        st = os.stat(path)
    except (OSError, ValueError):
        return False
    return stat.S_ISREG(st.st_mode) and (cap is None or st.st_size <= cap)


def environment_paths() -> dict[str, list[str]]:
    """The existing absolute folders of AMENT_PREFIX_PATH and ROS_PACKAGE_PATH."""
    out = {}
    for var in ("AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH"):
        dirs = [os.path.abspath(d) for d in os.environ.get(var, "").split(os.pathsep) if d]
        dirs = [d for d in dict.fromkeys(dirs) if os.path.isdir(d)]
        if dirs:
            out[var] = dirs
    return out


def colcon_workspace(start: str) -> str | None:
    """The colcon workspace holding ``start``: the nearest folder above it with a ``src``
    folder and a colcon marker (``build``/``install``/``log`` or colcon's config files)."""
    d = Path(start).resolve()
    for parent in [d, *d.parents]:
        if parent == Path(parent.anchor):
            break
        if (parent / "src").is_dir() and inside(str(d), str(parent / "src")) and (
                any((parent / m).is_dir() for m in ("build", "install", "log"))
                or any((parent / m).is_file() for m in ("colcon.meta", "colcon_defaults.yaml"))):
            return str(parent)
    return None


def discover_roots(paths: Iterable[str], git_top: str | None) -> tuple[list[str], list[str]]:
    """(folders to scan for package.xml, extra roots) for the linted ``paths``.

    Roots are exactly: the packages holding the linted paths, the git repository holding them
    (``git_top``), the colcon workspace holding them, and the linted paths themselves. The
    working directory is never a root by itself, and without git (not a repository, or git
    not installed) nothing above the linted paths is: the tool fails closed.
    """
    scan = [os.path.abspath(p) for p in paths]
    if git_top:
        scan.append(git_top)
    # (each folder once: a run may name hundreds of files from a few folders)
    folders = list(dict.fromkeys(p if os.path.isdir(p) else os.path.dirname(p) for p in scan))
    for folder in folders:
        d = Path(folder).resolve()
        for parent in [d, *d.parents]:
            if (parent / "package.xml").is_file():  # the package a path belongs to
                scan.append(str(parent))
                break
            if (git_top is not None and str(parent) == git_top) or parent == Path(parent.anchor):
                break
    for folder in dict.fromkeys(os.path.dirname(p) if not os.path.isdir(p) else p
                                for p in map(os.path.abspath, paths)):
        ws = colcon_workspace(folder)
        if ws and (git_top is None or inside(ws, git_top) or inside(git_top, ws)):
            scan.append(os.path.join(ws, "src"))
    scan = list(dict.fromkeys(scan))
    extra = [p if os.path.isdir(p) else os.path.dirname(p) for p in scan]
    return scan, list(dict.fromkeys(extra))
