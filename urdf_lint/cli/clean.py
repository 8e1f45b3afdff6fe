"""``urdf-lint clean``: remove the result cache and empty the user's mesh facts store."""
from __future__ import annotations

from typing import TYPE_CHECKING

from urdf_lint.core.emit import tell

if TYPE_CHECKING:  # pragma: no cover
    from argparse import Namespace

    from urdf_lint.cli.parser import Formatter, SubParsers


NAME = "clean"


def add_parser(sub: SubParsers, raw: Formatter) -> None:
    cl = sub.add_parser("clean", help="remove the cache",
                        description="Remove the result cache and empty the mesh facts store "
                        "(in the user's cache folder, shared by every repository).")
    cl.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                    help="find the cache from here (default: .)")


def run(args: Namespace) -> int:
    from urdf_lint.run.cache import Cache
    from urdf_lint.config.schema import load_config
    from urdf_lint.meshes.store import FactsStore, facts_dir
    removed = Cache.for_paths(args.paths, load_config(None)).clear()
    tell(f"removed {removed}" if removed else "no cache to remove")
    facts = FactsStore(facts_dir(), b"").clear()   # (no key needed to empty it)
    if facts:
        tell(f"removed {facts}")
    return 0
