"""``urdf-lint clean``: remove the result cache."""
from __future__ import annotations

from urdf_lint.core.emit import tell


NAME = "clean"


def add_parser(sub, raw):
    cl = sub.add_parser("clean", help="remove the cache", description="Remove the result cache.")
    cl.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                    help="find the cache from here (default: .)")


def run(args) -> int:
    from urdf_lint.run.cache import Cache
    from urdf_lint.config.schema import load_config
    removed = Cache.for_paths(args.paths, load_config(None)).clear()
    tell(f"removed {removed}" if removed else "no cache to remove")
    return 0
