"""``urdf-lint preview``: the expanded robot in 3D in a local, read-only web page that follows
the files as they are saved (urdf_lint/preview; its security: SECURITY.md, "The preview")."""
from __future__ import annotations

import os
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from urdf_lint.cli.common import ConfigOptions, load_cfg, options_from, parse_package_paths
from urdf_lint.cli.parser import add_inputs
from urdf_lint.core.emit import say, tell
from urdf_lint.core.errors import UsageError

if TYPE_CHECKING:  # pragma: no cover
    from argparse import Namespace

    from urdf_lint.cli.parser import Formatter, SubParsers
    from urdf_lint.config.schema import Config
    from urdf_lint.preview.scene import Scene
    from urdf_lint.preview.server import PreviewServer
    from urdf_lint.preview.session import Session


NAME = "preview"


def add_parser(sub: SubParsers, raw: Formatter) -> None:
    p = sub.add_parser("preview", help="show the expanded robot in 3D in a local web page",
                       description="Serve a live 3D view of the expanded robot (joint sliders, "
                                   "findings as markers) on 127.0.0.1; it follows saved files.")
    p.add_argument("path", nargs="?", default=".", metavar="PATH",
                   help="a model file or a folder (default: .)")
    p.add_argument("mappings", nargs="*", metavar="name:=value",
                   help="xacro args: a variant of PATH shown first (the configured [[models]] "
                        "args are the others)")
    p.add_argument("--port", type=int, default=0, help="port (default: 0, a random free one)")
    p.add_argument("--open", action="store_true", help="open the page in the web browser")
    p.add_argument("--highlight", metavar="KIND:NAME", default="",
                   help="a link or joint to highlight, e.g. link:base_link (default: none)")
    p.add_argument("--max-mesh-mb", type=int, default=64, metavar="MB",
                   help="meshes larger than this are not sent to the page (default: 64)")
    add_inputs(p)


@dataclass
class PreviewOptions:
    """What `urdf-lint preview` was asked: the robot, its args, the port and the limits."""
    path: str = "."
    mappings: list[str] = field(default_factory=list)
    port: int = 0
    open: bool = False
    highlight: str = ""
    max_mesh_mb: int = 64
    package_path: list[str] | None = None
    config: ConfigOptions = field(default_factory=ConfigOptions)


def run(args: Namespace) -> int:
    return preview(options_from(PreviewOptions, args, config=ConfigOptions.from_args(args)))


def start(o: PreviewOptions) -> tuple[PreviewServer, Session]:
    """(server, session): the first expansion done and the server listening (not serving
    yet: ``server.start()``)."""
    from urdf_lint.cli.expand import parse_mappings
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.preview.server import PreviewServer
    from urdf_lint.preview.session import Session
    if not os.path.exists(o.path):
        raise UsageError(f"no such file or directory: {o.path}")
    mappings, rest = parse_mappings(o.mappings)
    if rest:
        raise UsageError(f"expected name:=value, got {' '.join(rest)}")
    cfg = load_cfg(o.config, [o.path])
    if mappings:
        if not os.path.isfile(o.path):
            raise UsageError("xacro args need a file, not a folder")
        _with_variant(cfg, os.path.abspath(o.path), mappings)
    resolver = build_resolver([o.path], cfg, parse_package_paths(o.package_path))
    session = Session([o.path], cfg, resolver, o.max_mesh_mb, jobs_n=cfg.jobs)
    session.load()
    return PreviewServer(session, port=o.port), session


def _with_variant(cfg: Config, entry: str, args: dict[str, str]) -> None:
    """The command line's args as the first variant of ``entry`` (before the configured ones)."""
    from urdf_lint.config.schema import ModelSpec
    specs = list(getattr(cfg, "models", None) or [])
    mine = next((s for s in specs if s.path == entry), None)
    if mine is None:
        specs.append(ModelSpec(path=entry, arg_sets=[args]))
    else:
        mine.arg_sets = [args] + [a for a in mine.arg_sets if a != args]
    cfg.models = specs


def page_url(server: PreviewServer, highlight: str = "") -> str:
    from urllib.parse import quote
    return server.url + (f"#highlight={quote(highlight)}" if highlight else "")


def scene_summary(s: Scene) -> str:
    """The line said for a scene: its problems counted as ``check`` counts them."""
    return (f"urdf-lint: {s.label}: {len(s.links)} links, {len(s.joints)} joints, "
            f"{s.problems} problem(s) ({len(s.findings)} marker(s))")


def preview(o: PreviewOptions) -> int:
    server, session = start(o)
    server.start()
    session.watch(on_error=lambda e: say(f"urdf-lint: preview: reload failed: {e}"))
    url = page_url(server, o.highlight)
    for s in session.scenes:
        say(scene_summary(s))
    tell(url)
    if o.open:
        import webbrowser
        webbrowser.open_new_tab(url)
    seen = session.version
    try:
        while True:
            v = session.wait_version(seen, 3600)
            if v != seen:
                seen = v
                say(f"urdf-lint: preview: reloaded ({time.strftime('%H:%M:%S')})")
    except KeyboardInterrupt:
        pass
    finally:
        session.stop()
        server.shutdown()
        server.server_close()
    return 0
