"""``urdf-lint clean``: remove the result cache and empty the user's mesh facts store."""
from __future__ import annotations

from urdf_lint.core.emit import tell


NAME = "clean"


def add_parser(sub, raw) -> None:
    cl = sub.add_parser("clean", help="remove the cache",
                        description="Remove the result cache and empty the mesh facts store "
                        "(in the user's cache folder, shared by every repository).")
    cl.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                    help="find the cache from here (default: .)")


def run(args) -> int:
    from urdf_lint.run.cache import Cache
    from urdf_lint.config.schema import load_config
    from urdf_lint.meshes.store import FactsStore, facts_dir
    removed = Cache.for_paths(args.paths, load_config(None)).clear()
    tell(f"removed {removed}" if removed else "no cache to remove")
    facts = FactsStore(facts_dir(), b"").clear()   # (no key needed to empty it)
    if facts:
        tell(f"removed {facts}")
    return 0
