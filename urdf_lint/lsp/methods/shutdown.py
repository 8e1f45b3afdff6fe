"""``shutdown``: no further job is handed out; the workers are stopped."""
from __future__ import annotations

import asyncio

from urdf_lint.lsp.core import UrdfLintServer


async def handle(ls: UrdfLintServer, params: None) -> None:
    from urdf_lint.lsp.methods import preview
    preview.stop_all()   # (the previews' servers: their pages stop following)
    if ls.ws is not None:
        ls.ws.stop_soon()   # the lint under way ends with the jobs it has started
        await asyncio.get_running_loop().run_in_executor(ls.executor, ls.ws.close)
