"""``urdf-lint doctor``: which protections the worker sandbox has on this machine."""
from __future__ import annotations

import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # pragma: no cover
    from argparse import Namespace

    from urdf_lint.cli.parser import Formatter, SubParsers


NAME = "doctor"


def add_parser(sub: SubParsers, raw: Formatter) -> None:
    sub.add_parser("doctor", help="show which protections the worker sandbox has here",
                   description="Show which OS protections the workers get on this machine "
                               "(Landlock, seccomp, parent-death signal) and which are missing.")


def run(args: Namespace) -> int:
    from urdf_lint import __version__
    from urdf_lint.runner.sandbox import protections
    print(f"urdf-lint {__version__} on {sys.platform}, Python {sys.version.split()[0]}")
    for name, (ok, why) in protections().items():
        print(f"  {'on ' if ok else 'OFF'}  {name:<12} {why}")
    return 0
