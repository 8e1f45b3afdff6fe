"""What a run of urdf-lint opens, as the kernel sees it: ``strace -f -y`` of the command, every
``open``/``openat``/``openat2`` that succeeded, by the real path of the descriptor it returned
(``-y`` names it: symlinks and ``dir_fd``-relative names already resolved).

Tests call :func:`opened` and compare the paths with the places a run may read
(:func:`outside_allowed`): the repository, the cache, the Python runtime and the system's own
files. Skip when strace is missing or cannot trace (no ptrace in the container)."""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

_OPENED = re.compile(r"\bopen(?:at2?)?(?:\(| resumed>).*= \d+<(?P<path>[^>]*)>\s*$")
# the runtime's own files, and the system's: never the user's data
SYSTEM = ("/proc/", "/dev/", "/sys/", "/etc/", "/usr/lib/", "/usr/lib64/", "/lib/", "/lib64/",
          "/usr/share/locale/", "/usr/share/zoneinfo/", "/usr/local/lib/", "/usr/share/")


def available() -> str | None:
    """Why strace cannot be used here, or None."""
    exe = shutil.which("strace")
    if exe is None:
        return "strace is not installed"
    p = subprocess.run([exe, "-f", "-o", os.devnull, "true"], capture_output=True, text=True)
    return None if p.returncode == 0 else f"strace cannot trace here: {p.stderr.strip()[:200]}"


def opened(args, cwd, env: dict | None = None, timeout: int = 300) -> tuple[set, object]:
    """(every real path ``urdf-lint ARGS`` opened, the completed process)."""
    log = Path(cwd).parent / f".strace-{os.getpid()}.log"
    e = dict(os.environ)
    e.pop("GITHUB_ACTIONS", None)
    e.update(env or {})
    p = subprocess.run(["strace", "-f", "-y", "-e", "trace=open,openat,openat2", "-o", str(log),
                        sys.executable, "-m", "urdf_lint", *map(str, args)], cwd=cwd, env=e,
                       capture_output=True, text=True, timeout=timeout)
    try:
        lines = log.read_text(errors="replace").splitlines()
    finally:
        log.unlink(missing_ok=True)
    paths = {m.group("path") for m in map(_OPENED.search, lines) if m}
    return paths, p


def runtime_prefixes() -> tuple[str, ...]:
    """Where the Python running urdf-lint keeps itself and its packages (real paths)."""
    import site
    places = {sys.prefix, sys.base_prefix, sys.exec_prefix, *site.getsitepackages(),
              site.getusersitepackages(), *sysconfig.get_paths().values(),
              str(Path(__file__).resolve().parents[2])}     # the package, installed editable
    return tuple(sorted({os.path.realpath(p) for p in places if p}))


def outside_allowed(paths, *allowed) -> list[str]:
    """The paths that are none of ``allowed`` (folders: their contents too), the runtime or
    the system's files; sorted."""
    roots = tuple(os.path.realpath(a) for a in allowed) + runtime_prefixes()

    def ok(p: str) -> bool:
        return p.startswith(SYSTEM) or p in ("/", "/tmp", "/usr", "/usr/local") or \
            p in (s.rstrip("/") for s in SYSTEM) or \
            any(p == r or p.startswith(r.rstrip("/") + "/") for r in roots)
    return sorted(p for p in paths if not ok(p))
