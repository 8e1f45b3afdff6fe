"""``urdf-lint server`` under strace, driven by a real LSP client (pygls's), and the paths it
opened: for tests that a process opens nothing outside the folders it may read.

    async with TracedServer(trace_dir, cwd=repo, env={...}) as c:
        await c.initialize(root)
        uri = c.open(path)
        await c.diagnostics(uri)
        await c.request("hover", uri, line, char)
    bad = opened_outside(trace_dir, [repo, cache])

``strace -ff -y`` writes one file per thread (no call split across lines) and decorates each
returned descriptor with the path the kernel opened (symlinks resolved), so a symlink that
leads out shows where it leads. Only opens that succeeded count: a refused one (a worker's
Landlock says EACCES) or a lookup of a missing file read nothing.
"""
from __future__ import annotations

import os
import re
import site
import sys
from pathlib import Path

from lsprotocol import types

import strace

TRACED = "open,openat,openat2"
FORKS = "clone,clone3,fork,vfork"   # traced too: which thread belongs to which process
# what every Python process and git open: the kernel's and the system's files, never the user's
SYSTEM = ("/proc", "/sys", "/dev", "/etc", "/usr", "/lib", "/lib32", "/lib64", "/bin",
          "/sbin", "/run")
_FORK = re.compile(r"^(?P<call>clone3?|v?fork)\((?P<args>.*)\)\s+=\s+(?P<ret>\d+)")


def trace_works(tmp: Path) -> bool:
    """Can strace trace a child here (ptrace may be forbidden in a container)?"""
    return strace.available() is None


def runtime_folders() -> list[str]:
    """The Python runtime the server runs on: prefixes, site-packages, urdf-lint's sources."""
    import urdf_lint
    import urdf_lint.rules
    out = {sys.prefix, sys.base_prefix, sys.exec_prefix, *site.getsitepackages(),
           os.path.dirname(urdf_lint.__file__), os.path.dirname(urdf_lint.rules.__file__)}
    return sorted({os.path.realpath(p) for p in out})


def _threads(trace_dir: Path) -> tuple[dict, int | None]:
    """({thread id: the id of its process}, the first traced process), from the clone, fork
    and vfork calls of each thread's trace."""
    made: dict = {}   # child -> (parent thread, a thread of the parent's process?)
    for f in trace_dir.iterdir():
        tid = int(f.name.rsplit(".", 1)[1])
        for line in f.read_text(errors="replace").splitlines():
            m = _FORK.match(line)
            if m:
                made[int(m.group("ret"))] = (tid, "CLONE_THREAD" in m.group("args"))
    tids = [int(f.name.rsplit(".", 1)[1]) for f in trace_dir.iterdir()]
    roots = [t for t in tids if t not in made]

    def process(t: int) -> int:
        while t in made and made[t][1]:
            t = made[t][0]
        return t
    return {t: process(t) for t in tids}, (min(roots) if roots else None)


def opened(trace_dir: Path, server_only: bool = False) -> list[tuple[str, str]]:
    """(the real path the kernel opened, what to show of the call) of every successful traced
    call of every thread (a refused or failed call read nothing; strace.opens parses the
    logs); ``server_only``: of the threads of the first process only (not a worker it
    forked, not git)."""
    process, first = _threads(trace_dir)
    return [(o.opened, f"{o.pid}: {o.asked} -> {o.opened}") for o in strace.opens(trace_dir)
            if o.opened and not (server_only and process.get(o.pid) != first)]


def _below(path: str, folders) -> bool:
    return any(path == d or path.startswith(d.rstrip("/") + "/") for d in folders)


def opened_outside(trace_dir: Path, allowed, server_only: bool = False) -> list[str]:
    """The trace lines of every file or folder opened outside ``allowed`` (their real paths),
    the Python runtime and the system folders (``server_only``: as for :func:`opened`)."""
    folders = [os.path.realpath(a) for a in allowed]
    folders += runtime_folders() + list(SYSTEM)
    return [line for path, line in opened(trace_dir, server_only)
            if not _below(path, folders)]


class TracedServer:
    """``urdf-lint server`` under ``strace -ff``, and a pygls client talking to it; every
    answer and diagnostic it received is kept as text in ``shown``."""

    def __init__(self, trace_dir: Path, cwd: Path, env: dict | None = None):
        from pygls.lsp.client import LanguageClient
        self.trace_dir, self.cwd = trace_dir, cwd
        self.env = dict(os.environ, **(env or {}))
        self.lsp = LanguageClient("strace-lsp", "1")
        self.got: dict = {}
        self.shown = ""
        self.versions: dict = {}

        @self.lsp.feature(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
        def _diagnostics(params: types.PublishDiagnosticsParams):
            self.got[params.uri] = params
            self.shown += repr(params)

    async def __aenter__(self):
        self.trace_dir.mkdir(parents=True, exist_ok=True)
        await self.lsp.start_io("strace", "-ff", "-y", "-qq", "-s", "4096", "-e",
                                f"trace={TRACED},{FORKS}", "-o", str(self.trace_dir / "trace"),
                                sys.executable, "-m", "urdf_lint", "server",
                                cwd=str(self.cwd), env=self.env)
        return self

    async def __aexit__(self, *exc):
        try:
            await self.lsp.shutdown_async(None)
            self.lsp.exit(None)
        finally:
            await self.lsp.stop()

    async def initialize(self, root: Path) -> None:
        await self.lsp.initialize_async(types.InitializeParams(
            capabilities=types.ClientCapabilities(), root_uri=root.as_uri()))
        self.lsp.initialized(types.InitializedParams())

    def open(self, path: Path, text: str | None = None) -> str:
        uri = path.as_uri()
        self.versions[uri] = 1
        self.lsp.text_document_did_open(types.DidOpenTextDocumentParams(types.TextDocumentItem(
            uri=uri, language_id="xml", version=1,
            text=path.read_text() if text is None else text)))
        return uri

    def change(self, uri: str, text: str, version: int) -> None:
        self.versions[uri] = version
        self.lsp.text_document_did_change(types.DidChangeTextDocumentParams(
            text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=version),
            content_changes=[types.TextDocumentContentChangeWholeDocument(text=text)]))

    async def diagnostics(self, uri: str, version: int = 1, timeout: float = 60.0) -> list:
        """The diagnostics of ``uri`` published for ``version`` (or a later one)."""
        import asyncio
        loop = asyncio.get_running_loop()
        end = loop.time() + timeout
        while True:
            got = self.got.get(uri)
            if got is not None and (got.version or 0) >= version:
                return got.diagnostics
            if loop.time() > end:
                raise TimeoutError(uri)
            await asyncio.sleep(0.01)

    async def request(self, kind: str, uri: str, line: int = 0, char: int = 0):
        doc = types.TextDocumentIdentifier(uri=uri)
        at = types.Position(line, char)
        if kind == "hover":
            got = await self.lsp.text_document_hover_async(types.HoverParams(doc, at))
        elif kind == "definition":
            got = await self.lsp.text_document_definition_async(types.DefinitionParams(doc, at))
        elif kind == "completion":
            got = await self.lsp.text_document_completion_async(types.CompletionParams(doc, at))
        elif kind == "document_symbol":
            got = await self.lsp.text_document_document_symbol_async(
                types.DocumentSymbolParams(doc))
        elif kind == "code_action":
            got = await self.lsp.text_document_code_action_async(types.CodeActionParams(
                doc, types.Range(at, types.Position(line + 999, 0)),
                types.CodeActionContext(diagnostics=[])))
        else:
            raise ValueError(kind)
        self.shown += repr(got)
        return got

    async def workspace_symbols(self, query: str):
        got = await self.lsp.workspace_symbol_async(types.WorkspaceSymbolParams(query=query))
        self.shown += repr(got)
        return got
