"""What a process tree opens, as the kernel sees it: a command run under
``strace -f -ff -yy -e trace=open,openat,openat2`` (one log per thread: ``-ff``), and, for each
open call, the path asked for (made absolute against the caller's directory, which ``-yy``
shows) and, when it succeeded, the file the kernel opened (symlinks followed). The one parser
of strace's output for the tests that observe what urdf-lint opens: the formatter's
(:func:`opened`), the MCP server's (:func:`command`, :func:`opens`) and the language server's
(``strace_lsp``). Tests skip when strace is missing or cannot trace (:func:`available`)."""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import sysconfig
import tempfile
from dataclasses import dataclass
from pathlib import Path

_OPEN = re.compile(
    r'^(?:open|openat|openat2)\((?:(?:AT_FDCWD|-?\d+)(?:<(?P<dir>(?:[^>\\]|\\.)*)>)?, )?'
    r'"(?P<path>(?:[^"\\]|\\.)*)"[^\n]*\) = (?P<ret>-?\d+)(?:<(?P<real>(?:[^>\\]|\\.)*)>)?')


@dataclass(frozen=True)
class Open:
    pid: int
    asked: str          # the path passed, absolute
    opened: str | None  # the file the kernel opened (None: the call failed)


def available() -> str | None:
    """Why strace cannot be used here, or None."""
    exe = shutil.which("strace")
    if exe is None:
        return "strace is not installed (apt-get install -y strace)"
    p = subprocess.run([exe, "-f", "-o", os.devnull, "true"], capture_output=True, text=True)
    return None if p.returncode == 0 else f"strace cannot trace here: {p.stderr.strip()[:200]}"


def command(log_dir: Path, argv: list[str]) -> list[str]:
    """``argv`` under strace, following every child, one log per process in ``log_dir``."""
    log_dir.mkdir(parents=True, exist_ok=True)
    return [shutil.which("strace") or "strace", "-f", "-ff", "-yy", "-qq", "-s", "4096",
            "-e", "trace=open,openat,openat2", "-o", str(log_dir / "trace"), "--", *argv]


def _unescape(s: str) -> str:
    return s.encode("latin-1", "backslashreplace").decode("unicode_escape")


def opens(log_dir: Path) -> list[Open]:
    out = []
    for log in sorted(log_dir.glob("trace.*")):
        pid = int(log.suffix[1:])
        for line in log.read_text(errors="replace").splitlines():
            m = _OPEN.match(line)
            if not m:
                continue
            asked = _unescape(m["path"])
            if not asked.startswith("/") and m["dir"]:
                asked = os.path.join(_unescape(m["dir"]), asked)
            real = _unescape(m["real"]) if m["real"] and int(m["ret"]) >= 0 else None
            out.append(Open(pid, os.path.normpath(asked), real))
    return out


def outside(found: list[Open], allowed: list[str]) -> list[Open]:
    """The opens whose file (the one opened, else the one asked for) is under none of the
    ``allowed`` folders (as given or resolved: ``/lib`` is ``/usr/lib`` on a merged-usr
    system)."""
    roots = {p.rstrip(os.sep) for a in allowed for p in (a, os.path.realpath(a))}

    def ok(p: str) -> bool:
        return any(p == r or p.startswith(r + os.sep) for r in roots)
    return [o for o in found if not ok(o.opened or o.asked)]


# -- a urdf-lint command, and the places it may read ------------------------------------------
# the runtime's own files, and the system's: never the user's data
SYSTEM = ("/proc/", "/dev/", "/sys/", "/etc/", "/usr/lib/", "/usr/lib64/", "/lib/", "/lib64/",
          "/usr/share/locale/", "/usr/share/zoneinfo/", "/usr/local/lib/", "/usr/share/")


def opened(args, cwd, env: dict | None = None, timeout: int = 300) -> tuple[set, object]:
    """(every real path ``urdf-lint ARGS`` and its children opened, the completed process)."""
    e = dict(os.environ)
    e.pop("GITHUB_ACTIONS", None)
    e.update(env or {})
    with tempfile.TemporaryDirectory(dir=Path(cwd).parent, prefix=".strace-") as logs:
        p = subprocess.run(command(Path(logs), [sys.executable, "-m", "urdf_lint",
                                                *map(str, args)]),
                           cwd=cwd, env=e, capture_output=True, text=True, timeout=timeout)
        return {o.opened for o in opens(Path(logs)) if o.opened}, p


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
