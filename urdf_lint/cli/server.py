"""``urdf-lint server``: the language server (LSP over stdio)."""
from __future__ import annotations

from typing import TYPE_CHECKING

from urdf_lint.core.errors import UsageError

if TYPE_CHECKING:  # pragma: no cover
    from argparse import Namespace

    from urdf_lint.cli.parser import Formatter, SubParsers


NAME = "server"


def add_parser(sub: SubParsers, raw: Formatter) -> None:
    sub.add_parser("server", help="a language server for editors (LSP over stdio; needs the "
                   "'server' extra)",
                   description="Run the urdf-lint language server on stdin/stdout: diagnostics "
                               "from the real expansion, fixes, navigation, hover, completion. "
                               "Editors start it; see docs/editors.md for the set-up.")


def run(args: Namespace) -> int:
    try:
        from urdf_lint.lsp.server import main as serve
    except ImportError as e:
        raise UsageError(f"the language server needs the 'server' extra ({e.name} is not "
                         "installed): pip install 'urdf-lint[server]'") from None
    return serve()
