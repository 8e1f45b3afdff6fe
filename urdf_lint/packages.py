"""ROS package resolution without ROS.

One resolver serves expansion (``$(find)``, ``package://`` includes, ``load_yaml``), mesh
checks and rendering. It looks, in this order, at:

1. explicit ``package-paths`` (config or ``--package-path name=dir``);
2. ``package.xml`` files under the linted paths and the repository root (name from ``<name>``);
3. ``AMENT_PREFIX_PATH`` (the ament resource index);
4. ``ROS_PACKAGE_PATH``.

It also knows the *roots* that files may be read from: every package directory it found plus
the linted repository. Anything resolving (after symlinks) outside the roots is refused.
"""
from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from pathlib import Path

SKIP_DIRS = {".git", ".hg", ".svn", "node_modules", ".venv", "venv", "__pycache__", "build",
             "install", "log", ".urdf_lint_cache", ".tox", ".mypy_cache", ".pytest_cache"}

_NAME_RE = re.compile(rb"<name>\s*([^<\s]+)\s*</name>")


class PackageNotFound(Exception):
    def __init__(self, name: str, searched: list[str], folder: str | None = None):
        self.name = name
        self.searched = searched
        where = "; ".join(searched) if searched else "nowhere (no package.xml found)"
        hint = (f"; a folder named '{name}' exists: pass --package-path {name}={folder}"
                if folder else "")
        if not name:   # package:///x or $(find ): a slash too many, or an empty name
            super().__init__("the package URI names no package ('package:///...' has one slash "
                             "too many: write package://NAME/path)")
            return
        super().__init__(f"unknown package '{name}' (searched: {where}){hint}")


class OutsideRoots(Exception):
    def __init__(self, path: str, what: str = "file"):
        self.path = path
        super().__init__(f"{what} '{path}' resolves outside the package roots and the linted "
                         f"repository; it was not read")


def package_name(package_xml: Path) -> str | None:
    from . import fsbound
    try:   # a regular file (never a FIFO or device), its first 64 KiB
        data = fsbound.read_head(package_xml, 65536)
    except OSError:
        return None
    m = _NAME_RE.search(data)
    return m.group(1).decode("utf-8", "replace") if m else None


def iter_files(top: Path, suffixes: tuple[str, ...] | None = None, names: set[str] | None = None,
               folders: list | None = None):
    """Walk ``top`` (skipping build/VCS/venv folders), yielding files that match; each folder
    looked into is added to ``folders`` when given."""
    from . import fsbound
    for f in fsbound.walk_files(top, suffixes, names, folders=folders,
                                skip=lambda d: d in SKIP_DIRS or d.startswith(".")):
        yield Path(f)


def _colcon_ignored(folder: Path, top: Path) -> bool:
    from .folders import ignored
    return ignored(folder, top)


@dataclass
class PackageResolver:
    """Where each ROS package lives (named with ``--package-path``, or found by ``package.xml``)
    and which folders a run may read."""
    explicit: dict[str, Path] = field(default_factory=dict)
    scanned: dict[str, Path] = field(default_factory=dict)
    roots: list[Path] = field(default_factory=list)
    scanned_dirs: list[str] = field(default_factory=list)
    use_environment: bool = True
    # AMENT_PREFIX_PATH / ROS_PACKAGE_PATH as the parent saw them: workers run with a scrubbed
    # environment, so the search path travels with the resolver
    env_paths: dict = field(default_factory=dict)

    @classmethod
    def build(cls, scan_dirs, explicit: dict[str, str] | None = None, extra_roots=(),
              use_environment: bool = True, packages: dict | None = None) -> "PackageResolver":
        """``packages``: name -> folder found elsewhere (a workspace index), after the scan."""
        res = cls(use_environment=use_environment)
        if use_environment:
            res.env_paths = environment_paths()
        for name, where in (explicit or {}).items():
            res.explicit[name] = Path(where).resolve()
        seen = set()
        for d0 in scan_dirs:
            d = Path(d0).resolve()
            if d in seen or not d.exists():
                continue
            seen.add(d)
            if d.is_dir():   # (a linted file holds no package.xml: not a place to name)
                res.scanned_dirs.append(str(d))
            for pxml in iter_files(d, names={"package.xml"}):
                if _colcon_ignored(pxml.parent, d):
                    continue
                found = package_name(pxml)
                if found and found not in res.scanned:
                    res.scanned[found] = pxml.parent.resolve()
        for pkg, where in (packages or {}).items():
            res.scanned.setdefault(pkg, Path(where).resolve())
        roots = list(res.explicit.values()) + list(res.scanned.values())
        roots += [Path(r).resolve() for r in extra_roots]
        res.roots = sorted(set(roots), key=str)
        return res

    # -- lookup ------------------------------------------------------------------------------
    def _from_environment(self, name: str) -> Path | None:
        if not self.use_environment:
            return None
        for prefix in self.env_paths.get("AMENT_PREFIX_PATH", ()):
            marker = Path(prefix, "share", "ament_index", "resource_index", "packages", name)
            if marker.exists():
                share = Path(prefix, "share", name)
                if share.is_dir():
                    return share.resolve()
        for d in self.env_paths.get("ROS_PACKAGE_PATH", ()):
            for pxml in iter_files(Path(d), names={"package.xml"}):
                if package_name(pxml) == name:
                    return pxml.parent.resolve()
        return None

    def find(self, name: str) -> Path:
        if name in self.explicit:
            return self.explicit[name]
        if name in self.scanned:
            return self.scanned[name]
        found = self._from_environment(name)
        if found is not None:
            if found not in self.roots:
                self.roots.append(found)
            return found
        from .folders import folder_named
        if not name:
            raise PackageNotFound("", [])
        raise PackageNotFound(name, self.searched(),
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
    def resolve_uri(self, uri: str, base_dir: str | os.PathLike | None) -> Path:
        """Turn a mesh/include URI (``package://``, ``file://``, absolute, relative) into a path.

        Raises PackageNotFound for unknown packages. Does not check confinement or existence.
        """
        if uri.startswith("package://"):
            rest = uri[len("package://"):]
            name, _, rel = rest.partition("/")
            return self.find(name) / rel
        if uri.startswith("file://"):
            return Path(uri[len("file://"):])
        p = Path(uri)
        if not p.is_absolute() and base_dir is not None:
            p = Path(base_dir) / p
        return p

    def is_inside(self, path: str | os.PathLike) -> bool:
        real = os.path.realpath(path)
        # string prefixes of the normalised roots (what Path.relative_to tests, 20x cheaper)
        return any(inside(real, r) for r in map(str, self.roots))

    def readable(self, path: str | os.PathLike, cap: int | None = None) -> bool:
        """May urdf-lint read this file? Inside the roots after symlinks, a regular file (not
        a device, FIFO or folder) and, with ``cap``, at most that many bytes."""
        return self.is_inside(path) and regular_file(path, cap)

    def confine(self, path: str | os.PathLike, what: str = "file") -> Path:
        if not self.is_inside(path):
            raise OutsideRoots(str(path), what)
        return Path(path)

    def to_dict(self) -> dict:
        return {"explicit": {k: str(v) for k, v in self.explicit.items()},
                "scanned": {k: str(v) for k, v in self.scanned.items()},
                "roots": [str(r) for r in self.roots],
                "scanned_dirs": self.scanned_dirs,
                "use_environment": self.use_environment,
                "env_paths": {k: list(v) for k, v in self.env_paths.items()}}

    @classmethod
    def from_dict(cls, d: dict) -> "PackageResolver":
        return cls(explicit={k: Path(v) for k, v in d["explicit"].items()},
                   scanned={k: Path(v) for k, v in d["scanned"].items()},
                   roots=[Path(r) for r in d["roots"]], scanned_dirs=list(d["scanned_dirs"]),
                   use_environment=d["use_environment"],
                   env_paths={k: list(v) for k, v in d.get("env_paths", {}).items()})

    def read_paths(self) -> list[str]:
        """Every folder a worker may read below: the roots and the environment's package
        search path (packages found there become roots when a description uses them)."""
        out = [str(r) for r in self.roots] + [str(p) for p in self.explicit.values()] + \
            [str(p) for p in self.scanned.values()]
        out += [os.path.join(p, "share") for p in self.env_paths.get("AMENT_PREFIX_PATH", ())]
        out += list(self.env_paths.get("ROS_PACKAGE_PATH", ()))
        return out


MAX_SOURCE_BYTES = 256 << 20   # an XML source file urdf-lint reads in the parent


def regular_file(path, cap: int | None = None) -> bool:
    """A regular file after symlinks (no device, FIFO, socket or folder), not above ``cap``."""
    import stat
    try:
        st = os.stat(path)
    except (OSError, ValueError):
        return False
    return stat.S_ISREG(st.st_mode) and (cap is None or st.st_size <= cap)


def environment_paths() -> dict:
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


def inside(f: str, p: str) -> bool:
    """Is path ``f`` the folder ``p`` or below it? (strings, as written: resolve first)"""
    return f == p or f.startswith(p.rstrip(os.sep) + os.sep)


def discover_roots(paths, git_top: str | None) -> tuple[list[str], list[str]]:
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
