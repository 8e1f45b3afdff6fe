"""Latency and memory of ``urdf-lint server`` (issue 26's targets) on a copy of the corpus UR
description, through a real LSP client over stdio (pytest-lsp's).

* first diagnostics after opening a file, cold (a fresh server process each repeat);
* warm: diagnostics for the edited file after a change (time from the change notification,
  so the 150 ms debounce is included) to a macro used by one robot (``ur5e_macro.xacro``) and
  to the macro all nine robots use (``ur_macro.xacro``), interleaved in each repeat;
* hover, definition and completion round trips;
* the resident memory of the server process (and of its workers, separately).

    .venv/bin/python bench/bench_server.py [--repeats 15] [--cold 3]

Medians (p50) and the worst of the repeats are printed against the targets.
"""
from __future__ import annotations

import argparse
import asyncio
import os
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

from lsprotocol import types

CORPUS = Path(os.environ.get("URDF_LINT_CORPUS") or
              Path(__file__).resolve().parents[2] / "shared" / "corpus")
TARGETS = {"one robot": 0.300, "nine robots": 1.0, "hover": 0.050, "definition": 0.050,
           "completion": 0.100, "first diagnostics (cold)": 1.5}


class Client:
    """A pygls client that keeps the last diagnostics of each file with their version."""

    def __init__(self):
        from pygls.lsp.client import LanguageClient
        self.lsp = LanguageClient("bench-server", "1")
        self.got: dict = {}

        @self.lsp.feature(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
        def _diagnostics(params: types.PublishDiagnosticsParams):
            self.got[params.uri] = params

    async def start(self, root: Path):
        await self.lsp.start_io(sys.executable, "-m", "urdf_lint", "server")
        await self.lsp.initialize_async(types.InitializeParams(
            capabilities=types.ClientCapabilities(), root_uri=root.as_uri()))
        self.lsp.initialized(types.InitializedParams())
        return self

    @property
    def pid(self) -> int:
        return self.lsp._server.pid   # the server process pygls started

    async def stop(self):
        await self.lsp.shutdown_async(None)
        self.lsp.exit(None)
        await self.lsp.stop()


async def start(root: Path) -> Client:
    return await Client().start(root)


async def diagnostics(client: Client, uri: str, version: int, timeout=60.0):
    """The diagnostics of ``uri`` for ``version`` of it (or a later one)."""
    end = time.perf_counter() + timeout
    while True:
        got = client.got.get(uri)
        if got is not None and (got.version or 0) >= version:
            return got
        if time.perf_counter() > end:
            raise TimeoutError(uri)
        await asyncio.sleep(0.001)


def open_doc(client, path: Path, text: str | None = None) -> str:
    uri = path.as_uri()
    client.lsp.text_document_did_open(types.DidOpenTextDocumentParams(types.TextDocumentItem(
        uri=uri, language_id="xml", version=1, text=text if text is not None else path.read_text())))
    return uri


def rss_mb(pid: int) -> float:
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        pass
    return 0.0


def children(pid: int) -> list[int]:
    try:
        with open(f"/proc/{pid}/task/{pid}/children") as f:
            return [int(x) for x in f.read().split()]
    except OSError:
        return []


async def cold(root: Path) -> float:
    t0 = time.perf_counter()
    client = await start(root)
    uri = open_doc(client, root / "urdf" / "ur5e.xacro")
    await diagnostics(client, uri, 1)
    dt = time.perf_counter() - t0
    await client.stop()
    return dt


async def warm(root: Path, repeats: int) -> tuple[dict, dict]:
    client = await start(root)
    times: dict = {k: [] for k in ("one robot", "nine robots", "hover", "definition",
                                   "completion")}
    one = root / "urdf" / "inc" / "ur5e_macro.xacro"
    nine = root / "urdf" / "inc" / "ur_macro.xacro"
    texts = {p: p.read_text() for p in (one, nine)}
    uris = {p: open_doc(client, p) for p in (one, nine)}
    await diagnostics(client, uris[nine], 1)
    await asyncio.sleep(1.0)
    lines = texts[nine].split("\n")
    version = 1
    for i in range(repeats):
        for label, p in (("one robot", one), ("nine robots", nine)):
            version += 1
            text = texts[p] + ("\n" if i % 2 == 0 else "")   # a real edit, valid either way
            t0 = time.perf_counter()
            client.lsp.text_document_did_change(types.DidChangeTextDocumentParams(
                text_document=types.VersionedTextDocumentIdentifier(uri=uris[p],
                                                                    version=version),
                content_changes=[types.TextDocumentContentChangeWholeDocument(text=text)]))
            await diagnostics(client, uris[p], version)
            times[label].append(time.perf_counter() - t0)
        doc = types.TextDocumentIdentifier(uri=uris[nine])
        at = types.Position(121, lines[121].index("shoulder_offset") + 3)
        t0 = time.perf_counter()
        await client.lsp.text_document_hover_async(types.HoverParams(text_document=doc, position=at))
        times["hover"].append(time.perf_counter() - t0)
        at = types.Position(223, lines[223].index("base_link") + 1)
        t0 = time.perf_counter()
        await client.lsp.text_document_definition_async(types.DefinitionParams(
            text_document=doc, position=at))
        times["definition"].append(time.perf_counter() - t0)
        at = types.Position(121, lines[121].index("${") + 2)
        t0 = time.perf_counter()
        await client.lsp.text_document_completion_async(types.CompletionParams(
            text_document=doc, position=at))
        times["completion"].append(time.perf_counter() - t0)
    pid = client.pid
    mem = {"server": rss_mb(pid),
           "workers": sum(rss_mb(c) for c in children(pid))}
    await client.stop()
    return times, mem


async def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=15)
    ap.add_argument("--cold", type=int, default=3)
    a = ap.parse_args()
    src = CORPUS / "ur_description"
    if not src.is_dir():
        sys.exit(f"no corpus UR description at {src} (set URDF_LINT_CORPUS)")
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp) / "ur_description"
        shutil.copytree(src, root)
        colds = [await cold(root) for _ in range(a.cold)]
        times, mem = await warm(root, a.repeats)
    times["first diagnostics (cold)"] = colds
    print(f"urdf-lint server on a copy of {src} ({a.repeats} warm repeats, interleaved; "
          f"{a.cold} cold starts)")
    for k, v in times.items():
        med = statistics.median(v)
        ok = "ok" if med <= TARGETS[k] else "MISSED"
        print(f"  {k:26s} p50 {med * 1000:7.1f} ms  max {max(v) * 1000:7.1f} ms  "
              f"(target {TARGETS[k] * 1000:.0f} ms: {ok})")
    print(f"  memory: server {mem['server']:.0f} MB RSS (target 300 MB), "
          f"workers {mem['workers']:.0f} MB RSS together")


if __name__ == "__main__":
    asyncio.run(main())
