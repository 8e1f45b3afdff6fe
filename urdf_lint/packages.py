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
        super().__init__(f"unknown package '{name}' (searched: {where}){hint}")


class OutsideRoots(Exception):
    def __init__(self, path: str, what: str = "file"):
        self.path = path
        super().__init__(f"{what} '{path}' resolves outside the package roots and the linted "
                         f"repository; it was not read")


def package_name(package_xml: Path) -> str | None:
    try:
        data = package_xml.read_bytes()[:65536]
    except OSError:
        return None
    m = _NAME_RE.search(data)
    return m.group(1).decode("utf-8", "replace") if m else None


def iter_files(top: Path, suffixes: tuple[str, ...] | None = None, names: set[str] | None = None):
    """Walk ``top`` (skipping build/VCS/venv folders), yielding files that match."""
    top = Path(top)
    if top.is_file():
        yield top
        return
    for dirpath, dirnames, filenames in os.walk(top):
        dirnames[:] = sorted(d for d in dirnames if d not in SKIP_DIRS and not d.startswith("."))
        for fn in sorted(filenames):
            if (names and fn in names) or (suffixes and fn.endswith(suffixes)):
                yield Path(dirpath, fn)


def _colcon_ignored(folder: Path, top: Path) -> bool:
    from .folders import ignored
    return ignored(folder, top)


@dataclass
class PackageResolver:
    explicit: dict[str, Path] = field(default_factory=dict)
    scanned: dict[str, Path] = field(default_factory=dict)
    roots: list[Path] = field(default_factory=list)
    scanned_dirs: list[str] = field(default_factory=list)
    use_environment: bool = True

    @classmethod
    def build(cls, scan_dirs, explicit: dict[str, str] | None = None, extra_roots=(),
              use_environment: bool = True, packages: dict | None = None) -> "PackageResolver":
        """``packages``: name -> folder found elsewhere (a workspace index), after the scan."""
        res = cls(use_environment=use_environment)
        for name, d in (explicit or {}).items():
            res.explicit[name] = Path(d).resolve()
        seen = set()
        for d in scan_dirs:
            d = Path(d).resolve()
            if d in seen or not d.exists():
                continue
            seen.add(d)
            res.scanned_dirs.append(str(d))
            for pxml in iter_files(d, names={"package.xml"}):
                if _colcon_ignored(pxml.parent, d):
                    continue
                name = package_name(pxml)
                if name and name not in res.scanned:
                    res.scanned[name] = pxml.parent.resolve()
        for name, d in (packages or {}).items():
            res.scanned.setdefault(name, Path(d).resolve())
        roots = list(res.explicit.values()) + list(res.scanned.values())
        roots += [Path(r).resolve() for r in extra_roots]
        res.roots = sorted(set(roots), key=str)
        return res

    # -- lookup ------------------------------------------------------------------------------
    def _from_environment(self, name: str) -> Path | None:
        if not self.use_environment:
            return None
        for prefix in filter(None, os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep)):
            marker = Path(prefix, "share", "ament_index", "resource_index", "packages", name)
            if marker.exists():
                share = Path(prefix, "share", name)
                if share.is_dir():
                    return share.resolve()
        for d in filter(None, os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep)):
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
        raise PackageNotFound(name, self.searched(),
                              folder_named(name, [str(r) for r in self.roots], SKIP_DIRS))

    def searched(self) -> list[str]:
        out = [f"--package-path/package-paths ({', '.join(sorted(self.explicit)) or 'none'})"]
        out += [f"package.xml under {d}" for d in self.scanned_dirs]
        if self.use_environment:
            out.append("AMENT_PREFIX_PATH=" + (os.environ.get("AMENT_PREFIX_PATH") or "(unset)"))
            out.append("ROS_PACKAGE_PATH=" + (os.environ.get("ROS_PACKAGE_PATH") or "(unset)"))
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
        real = Path(os.path.realpath(path))
        for root in self.roots:
            try:
                real.relative_to(root)
                return True
            except ValueError:
                continue
        return False

    def confine(self, path: str | os.PathLike, what: str = "file") -> Path:
        if not self.is_inside(path):
            raise OutsideRoots(str(path), what)
        return Path(path)

    def to_dict(self) -> dict:
        return {"explicit": {k: str(v) for k, v in self.explicit.items()},
                "scanned": {k: str(v) for k, v in self.scanned.items()},
                "roots": [str(r) for r in self.roots],
                "scanned_dirs": self.scanned_dirs,
                "use_environment": self.use_environment}

    @classmethod
    def from_dict(cls, d: dict) -> "PackageResolver":
        return cls(explicit={k: Path(v) for k, v in d["explicit"].items()},
                   scanned={k: Path(v) for k, v in d["scanned"].items()},
                   roots=[Path(r) for r in d["roots"]], scanned_dirs=list(d["scanned_dirs"]),
                   use_environment=d["use_environment"])
