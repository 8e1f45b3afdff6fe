"""``urdf-lint server`` while typing (issue 34's editor targets), through a real LSP client
over stdio (pygls's), on a generated UR-like package of nine variants
(tests/support/ur_like.py: one macro every variant uses, one only the first uses, a binary
STL per link and variant).

* **typing**: bursts of keystrokes 250 ms apart into a macro one robot uses
  (``inc/ur3_tool.xacro``) and into the macro all nine use (``inc/arm_macro.xacro``); per
  burst, the time from the last keystroke to the final diagnostics of the last version (the
  last publication for it: the edited file's model comes first, the other variants after)
  and to the first diagnostics of the last version; p50 and p95 over the bursts;
* **stale publications**: diagnostics of a version older than one the server had already
  published diagnostics of (it had received the newer text: must be 0); and, apart, those
  older than the newest version sent but not older than any published (the server may have
  sent them before the keystroke reached it: in flight);
* **first diagnostics on opening a workspace root**: a fresh server process started on the
  package root, a model opened, until its first diagnostics; cold (an empty cache folder:
  no mesh facts store) and warm (the store the previous start filled).

    .venv/bin/python bench/bench_server.py [--bursts 10] [--keys 10] [--starts 3]
    .venv/bin/python bench/bench_server.py --small      # one short run: does it work?

Only the numbers it prints; run it on a quiet machine.
"""
from __future__ import annotations

import argparse
import asyncio
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

from lsprotocol import types

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "support"))
import ur_like  # noqa: E402

KEY_S = 0.25            # between keystrokes
QUIET_S = 3.0           # no publication for this long after the last version's: final
TARGETS = {"one robot": 0.300, "all variants": 1.0, "open root (warm)": 2.0,
           "open root (cold)": 5.0}


class Client:
    """A pygls client that records every publication: (time, uri, version, newest sent)."""

    def __init__(self) -> None:
        from pygls.lsp.client import LanguageClient
        self.lsp = LanguageClient("bench-server", "1")
        self.sent: dict[str, int] = {}
        self.log: list[tuple[float, str, int | None, int]] = []

        @self.lsp.feature(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
        def _diagnostics(params: types.PublishDiagnosticsParams) -> None:
            self.log.append((time.perf_counter(), params.uri, params.version,
                             self.sent.get(params.uri, 0)))

    async def start(self, root: Path, cache: Path) -> "Client":
        env = dict(os.environ, XDG_CACHE_HOME=str(cache))
        env.pop("URDF_LINT_CACHE_DIR", None)
        await self.lsp.start_io(sys.executable, "-m", "urdf_lint", "server", env=env)
        await self.lsp.initialize_async(types.InitializeParams(
            capabilities=types.ClientCapabilities(), root_uri=root.as_uri()))
        self.lsp.initialized(types.InitializedParams())
        return self

    def open(self, path: Path) -> str:
        uri = path.resolve().as_uri()
        self.sent[uri] = 1
        self.lsp.text_document_did_open(types.DidOpenTextDocumentParams(types.TextDocumentItem(
            uri=uri, language_id="xml", version=1, text=path.read_text())))
        return uri

    def change(self, uri: str, text: str) -> None:
        self.sent[uri] += 1
        self.lsp.text_document_did_change(types.DidChangeTextDocumentParams(
            text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=self.sent[uri]),
            content_changes=[types.TextDocumentContentChangeWholeDocument(text=text)]))

    async def settled(self, uri: str, version: int, timeout: float = 120.0) -> None:
        """Until ``version``'s diagnostics came and nothing more for ``QUIET_S``."""
        end = time.perf_counter() + timeout
        while time.perf_counter() < end:
            mine = [e for e in self.log if e[1] == uri and (e[2] or 0) >= version]
            if mine and time.perf_counter() - self.log[-1][0] >= QUIET_S:
                return
            await asyncio.sleep(0.02)
        raise TimeoutError(f"no diagnostics of version {version} of {uri}")

    async def stop(self) -> None:
        await self.lsp.shutdown_async(None)
        self.lsp.exit(None)
        await self.lsp.stop()


async def typing(root: Path, cache: Path, bursts: int,
                 keys: int) -> tuple[dict, tuple[int, int], int]:
    """Per file typed into: (final latencies, first latencies); stale count; publications."""
    files = {"one robot": root / "urdf" / "inc" / "ur3_tool.xacro",
             "all variants": root / "urdf" / "inc" / "arm_macro.xacro"}
    client = await Client().start(root, cache)
    out: dict = {k: ([], []) for k in files}
    try:
        uris = {k: client.open(p) for k, p in files.items()}
        for k in files:
            await client.settled(uris[k], 1)
        for b in range(bursts):
            for label in files:
                uri = uris[label]
                last = time.perf_counter()
                for i in range(keys):   # a link name typed one character at a time
                    marker = "k" + "x" * (i + 1) + str(b)
                    text = ur_like.tool_macro(marker) if label == "one robot" else \
                        ur_like.arm_macro(marker, meshes=True)
                    client.change(uri, text)
                    last = time.perf_counter()
                    if i < keys - 1:
                        await asyncio.sleep(KEY_S)
                version = client.sent[uri]
                await client.settled(uri, version)
                got = [t for t, u, v, _ in client.log if u == uri and v == version]
                out[label][0].append(got[-1] - last)
                out[label][1].append(got[0] - last)
    finally:
        await client.stop()
    stale = in_flight = 0
    newest: dict[str, int] = {}
    for _, u, v, sent in client.log:
        if v is None:
            continue
        if v < newest.get(u, 0):
            stale += 1
        elif v < sent:
            in_flight += 1
        newest[u] = max(newest.get(u, 0), v)
    return out, (stale, in_flight), len(client.log)


async def open_root(root: Path, cache: Path) -> float:
    t0 = time.perf_counter()
    client = await Client().start(root, cache)
    try:
        model = root / "urdf" / "ur5e.urdf.xacro"
        uri = client.open(model if model.exists() else next((root / "urdf").glob("*.urdf.xacro")))
        while time.perf_counter() - t0 < 300:
            first = next((t for t, u, _, _ in client.log if u == uri), None)
            if first is not None:
                return first - t0
            await asyncio.sleep(0.005)
        raise TimeoutError("no first diagnostics")
    finally:
        await client.stop()


def pct(values: list[float], p: float) -> float:
    s = sorted(values)
    return s[min(len(s) - 1, max(0, round(p / 100 * (len(s) - 1))))]


def line(label: str, values: list[float], target: float | None) -> str:
    p50, p95 = statistics.median(values), pct(values, 95)
    verdict = "" if target is None else \
        f"  (target p50 {target * 1000:.0f} ms: {'ok' if p50 <= target else 'MISSED'})"
    return f"  {label:34s} p50 {p50 * 1000:7.0f} ms  p95 {p95 * 1000:7.0f} ms  " \
           f"n={len(values)}{verdict}"


async def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--bursts", type=int, default=10, help="typing bursts per file")
    ap.add_argument("--keys", type=int, default=10, help="keystrokes per burst")
    ap.add_argument("--starts", type=int, default=3, help="server starts, cold and warm each")
    ap.add_argument("--variants", type=int, default=9)
    ap.add_argument("--triangles", type=int, default=20000, help="per mesh (binary STL)")
    ap.add_argument("--small", action="store_true", help="a short run on a small package")
    a = ap.parse_args()
    if a.small:
        a.bursts, a.keys, a.starts, a.variants, a.triangles = 1, 3, 1, 2, 50
    with tempfile.TemporaryDirectory() as tmp:
        root = ur_like.write(Path(tmp), variants=a.variants, mesh_triangles=a.triangles)
        cold, warm = [], []
        for i in range(a.starts):
            cache = Path(tmp) / f"cache{i}"
            cold.append(await open_root(root, cache))   # an empty store
            warm.append(await open_root(root, cache))   # the store it filled
        times, stale, n = await typing(root, Path(tmp) / "cache0", a.bursts, a.keys)
    print(f"urdf-lint server, UR-like package of {a.variants} variants "
          f"({a.triangles} triangles per mesh); {a.bursts} bursts of {a.keys} keystrokes "
          f"{KEY_S * 1000:.0f} ms apart per file; {a.starts} starts cold and warm")
    for label, (final, first) in times.items():   # (p95 of few bursts: their worst)
        print(line(f"{label}: last key -> final diagnostics", final, TARGETS[label]))
        print(line(f"{label}: last key -> first diagnostics", first, None))
    print(f"  stale publications (older than a version already published): {stale[0]} of {n}"
          f" (target 0); older than the newest sent, in flight: {stale[1]}")
    print(line("open root (cold): first diagnostics", cold, TARGETS["open root (cold)"]))
    print(line("open root (warm): first diagnostics", warm, TARGETS["open root (warm)"]))


if __name__ == "__main__":
    asyncio.run(main())
