"""Every file a process tree opens, as strace sees it: run a command under
``strace -f -yy -e trace=open,openat,openat2`` (one log per process: ``-ff``) and read back,
for each open call, the path asked for (made absolute against the caller's working directory,
which ``-yy`` shows) and, when it succeeded, the path the kernel actually opened (symlinks
followed). Tests skip when strace is not installed (``apt-get install -y strace``)."""
from __future__ import annotations

import os
import re
import shutil
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


def available() -> bool:
    return shutil.which("strace") is not None


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
