"""Run the *stock* xacro CLI with a package map, as a reference for byte-identity tests.

Stock xacro resolves ``$(find pkg)`` through ``ament_index_python``, which is not on PyPI. We put
a tiny shim of that module on PYTHONPATH that answers from a JSON package map; nothing of
urdf-lint is imported in the child process.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

_SHIM = '''
import json, os
_MAP = json.loads(os.environ["STOCK_XACRO_PACKAGE_MAP"])
class PackageNotFoundError(KeyError):
    pass
def get_package_share_directory(name):
    try:
        return _MAP[name]
    except KeyError:
        raise PackageNotFoundError(name)
'''


def _shim_dir() -> str:
    d = Path(tempfile.gettempdir(), "urdf_lint_stock_shim")
    pkg = d / "ament_index_python"
    pkg.mkdir(parents=True, exist_ok=True)
    # shared by every test run on the machine: never truncate a file another run may be
    # importing (write beside it, then rename), and leave it alone when it is already right
    for name, text in (("__init__.py", ""), ("packages.py", _SHIM)):
        f = pkg / name
        try:
            if f.read_text() == text:
                continue
        except OSError:
            pass
        tmp = pkg / f".{name}.{os.getpid()}.tmp"
        tmp.write_text(text)
        os.replace(tmp, f)
    return str(d)


def stock_xacro(path: str, args: dict, package_map: dict, cwd: str | None = None):
    """Return (returncode, stdout, stderr) of ``xacro path name:=value ...``."""
    env = dict(os.environ)
    env["PYTHONPATH"] = _shim_dir()
    env["STOCK_XACRO_PACKAGE_MAP"] = json.dumps({k: str(v) for k, v in package_map.items()})
    cmd = [sys.executable, "-c", "import sys, xacro; sys.argv[0]='xacro'; xacro.main()", path]
    cmd += [f"{k}:={v}" for k, v in args.items()]
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=cwd, timeout=120)
    return p.returncode, p.stdout, p.stderr
