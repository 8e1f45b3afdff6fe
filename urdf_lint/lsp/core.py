"""The language server's core: its documents, the debounced lint of what a change reaches,
and the diagnostics it publishes (the features register in :mod:`.server`).

``urdf-lint server`` is a language server (LSP over stdio, on pygls) that knows the real
expansion.

Diagnostics come from the same expansion, rules, policy and suppressions as ``check``, run
in the same sandboxed workers with the same limits, on the unsaved buffers (given to the
workers as their jobs' overlay, :mod:`urdf_lint.core.overlay`). A finding in an included file (a
macro library, a fragment, a YAML file) is shown there, with the macro chain as related
information at each call site. Code actions are the findings' fixes and suppression comments;
navigation, hover, completion and symbols are in :mod:`.features`.
"""
from __future__ import annotations

import asyncio
import os
from concurrent.futures import ThreadPoolExecutor
from urllib.parse import unquote, urlparse

from lsprotocol import types
from pygls.lsp.server import LanguageServer

from urdf_lint import __version__
from urdf_lint.lsp.state import Workspace
from urdf_lint.lsp.text import Doc

DEBOUNCE_S = 0.15        # after the last keystroke, before a change is linted
SOURCE = "urdf-lint"
SEVERITY = {"error": types.DiagnosticSeverity.Error, "warning": types.DiagnosticSeverity.Warning,
            "info": types.DiagnosticSeverity.Information}


def uri_path(uri: str) -> str:
    return os.path.realpath(unquote(urlparse(uri).path))


def path_uri(path: str) -> str:
    from pathlib import Path
    return Path(path).as_uri()


class UrdfLintServer(LanguageServer):
    def __init__(self):
        super().__init__("urdf-lint", __version__)
        self.ws: Workspace | None = None
        self.pending: dict[str, asyncio.TimerHandle | asyncio.Task] = {}
        self.executor = ThreadPoolExecutor(max_workers=1)   # one lint at a time, in order
        self.published: set = set()
        self.generation = 0

    # -- documents -------------------------------------------------------------------------
    def doc(self, path: str) -> Doc:
        """The file as the editor has it, else as on disk through the boundary with the run's
        roots (b"" when unreadable or outside them: never a file ``check`` could not read)."""
        ws = self.ws
        if ws is None:
            return Doc(b"")
        if path in ws.buffers:
            return Doc(ws.buffers[path])
        try:
            return Doc(ws.read(path))
        except OSError:
            return Doc(b"")

    def set_buffer(self, uri: str) -> str:
        path = uri_path(uri)
        if self.ws is not None:
            text = self.workspace.get_text_document(uri).source
            self.ws.buffers[path] = text.encode("utf-8")
        return path

    # -- linting ------------------------------------------------------------------------------
    def schedule(self, path: str, delay: float) -> None:
        """Lint what a change to ``path`` reaches, ``delay`` seconds from now (a newer change
        to the same file restarts the wait)."""
        old = self.pending.pop(path, None)
        if old is not None:
            old.cancel()
        loop = asyncio.get_running_loop()
        self.pending[path] = loop.call_later(
            delay, lambda: loop.create_task(self._lint(path)))

    async def _lint(self, path: str) -> None:
        self.pending.pop(path, None)
        ws = self.ws
        if ws is None:
            return
        loop = asyncio.get_running_loop()
        if not ws.readable(path):   # not linted: it gets the diagnostic saying so
            self.publish({path}, self.versions())
        else:
            jobs = ws.affected(path)
            versions = self.versions()   # what the lint reads: its diagnostics carry these
            files = await loop.run_in_executor(self.executor, ws.lint, jobs)
            self.publish(files | {path} | set(ws.buffers), versions)
        rest = ws.unlinted()
        if rest:   # then the models this file does not reach, to have them warm
            versions = self.versions()
            files = await loop.run_in_executor(self.executor, ws.lint, rest)
            self.publish(files | set(ws.buffers), versions)

    def versions(self) -> dict:
        """path -> the version of each open document."""
        out = {}
        for uri, doc in list(self.workspace.text_documents.items()):
            out[uri_path(uri)] = doc.version
        return out

    def publish(self, files, versions: dict | None = None) -> None:
        ws = self.ws
        if ws is None:
            return
        versions = versions or {}
        for f in sorted(set(files) | self.published):
            diags = self.diagnostics(f)
            if not diags and f not in self.published and f not in ws.buffers:
                continue   # (an open file always gets its diagnostics, none included)
            self.text_document_publish_diagnostics(types.PublishDiagnosticsParams(
                uri=path_uri(f), diagnostics=diags, version=versions.get(f)))
            (self.published.add if diags else self.published.discard)(f)

    def diagnostics(self, path: str) -> list[types.Diagnostic]:
        ws = self.ws
        assert ws is not None
        if path in ws.buffers and not ws.readable(path):
            return [not_linted(ws, path)]
        out = []
        cp = ws.config_problem
        if cp is not None and cp.file == path:
            line = max(cp.line, 1)
            d = self.doc(path)
            text = d.line(line - 1)
            out.append(types.Diagnostic(
                range=types.Range(types.Position(line - 1, len(text) - len(text.lstrip())),
                                  types.Position(line - 1, len(text))),
                message=cp.message, severity=types.DiagnosticSeverity.Error, source=SOURCE,
                code="config"))
        findings = ws.findings_in(path)
        valued = ws.findings_valued_in(path)
        if not findings and not valued:
            return out
        doc = self.doc(path)
        out.extend(self._value_diagnostics(doc, valued))
        docs: dict = {}
        # one diagnostic per finding, as check counts them (core.findings.group): a macro line
        # that makes 24 links wrong in 10 models is one diagnostic listing them
        from urdf_lint.core.findings import group
        from urdf_lint.report.base import fold_instances
        for f in group(findings):
            related = []
            for (cf, cl, cc) in f.chain:
                cdoc = docs.get(cf) or docs.setdefault(cf, self.doc(cf))
                related.append(types.DiagnosticRelatedInformation(
                    location=types.Location(uri=path_uri(cf), range=cdoc.element_range(cl, cc)),
                    message="macro called here"))
            if f.related:   # a finding in an SRDF or a controller YAML: the robot's element
                rf, rl, rc = f.related
                rdoc = docs.get(rf) or docs.setdefault(rf, self.doc(rf))
                related.append(types.DiagnosticRelatedInformation(
                    location=types.Location(uri=path_uri(rf), range=rdoc.element_range(rl, rc)),
                    message="robot element here"))
            models = [m for m in f.models if m]
            msg = f.message
            folded = fold_instances(f)
            if folded:
                msg += f" ({folded})"
            if models and len(ws.models()) > 1:
                names = [_model_name(m) for m in models]
                msg += f" (in {', '.join(names[:4])}{' ...' if len(names) > 4 else ''})"
            out.append(types.Diagnostic(
                range=doc.element_range(f.line, f.col), message=msg,
                severity=SEVERITY.get(f.severity, types.DiagnosticSeverity.Error),
                code=f.code, source=SOURCE, related_information=related or None,
                data={"name": f.name}))
        return out


    def _value_diagnostics(self, doc, valued) -> list[types.Diagnostic]:
        """A finding whose value is written in this file (a YAML scalar): one diagnostic at
        that value, pointing at the element that uses it (once per value, code and message)."""
        out, seen = [], set()
        for f in valued:
            _, line, col = f.value_from
            key = (f.code, f.message, line, col)
            if key in seen:
                continue
            seen.add(key)
            text = doc.line(line - 1)
            start = max(col - 1, 0)
            use = self.doc(f.file)
            out.append(types.Diagnostic(
                range=types.Range(types.Position(line - 1, start),
                                  types.Position(line - 1, max(len(text.rstrip()), start))),
                message=f"{f.message} (the value is used at {os.path.basename(f.file)}:{f.line})",
                severity=SEVERITY.get(f.severity, types.DiagnosticSeverity.Error),
                code=f.code, source=SOURCE, data={"name": f.name},
                related_information=[types.DiagnosticRelatedInformation(
                    location=types.Location(uri=path_uri(f.file),
                                            range=use.element_range(f.line, f.col)),
                    message="the value is used here")]))
        return out


def not_linted(ws: Workspace, path: str) -> types.Diagnostic:
    """The one diagnostic of an open file outside the run's roots: it is not linted (no
    diagnostic would look clean), and why."""
    return types.Diagnostic(
        range=types.Range(types.Position(0, 0), types.Position(0, 0)),
        message=f"not linted: this file is outside the roots of the workspace {ws.root} "
        "(the packages, git repository and colcon workspace holding it); urdf-lint reads "
        "no file there", severity=types.DiagnosticSeverity.Information, source=SOURCE,
        code="not-linted")


def _model_name(label: str) -> str:
    """``ur10`` for the model ``urdf/ur10.xacro`` (its args kept: ``ur [robot_model:=ur5e]``)."""
    entry, _, args = label.partition(" [")
    name = os.path.splitext(os.path.basename(entry))[0]
    return f"{name} [{args}" if args else name
