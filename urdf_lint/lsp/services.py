"""What every method handler of the language server reads: :class:`Services`, the one object
a handler is given (``handle(services, params)``, :mod:`.methods`).

* the workspace (:class:`~urdf_lint.lsp.state.Workspace`): buffers, the models' reports and
  the findings, what the server may read and write;
* the documents (:meth:`Services.doc`): the text the editor has, else the file through the
  boundary;
* the declarations index (:class:`Index`, from the text: :mod:`.index`);
* the expanded models (:class:`ModelView`, from the workers' reports through their source
  maps).
"""
from __future__ import annotations

import os
from typing import Any

from lsprotocol import types

from urdf_lint.core.jobs import ModelReport
from urdf_lint.lsp.index import Decl, FileIndex, index_text
from urdf_lint.lsp.state import Workspace
from urdf_lint.lsp.text import Doc
from urdf_lint.lsp.uris import path_uri


class Services:
    """The language server's shared state, without the protocol (a test makes one from a
    workspace folder: ``Services(Workspace(root, in_process=True))``)."""

    def __init__(self, ws: Workspace | None = None):
        self.ws = ws
        self.index = Index(self)
        self._views: dict[int, tuple[ModelReport, ModelView]] = {}

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

    def loc(self, file: str, line: int, col: int) -> types.Location:
        """The location of the start tag at (line, col) of ``file``."""
        return types.Location(uri=path_uri(file), range=self.doc(file).element_range(line, col))

    def views(self) -> list[ModelView]:
        """The expanded robot of every model linted, with its source map."""
        ws = self.ws
        out = []
        for r in list(ws.models()) if ws else []:
            v = self.view_of(r)
            if v is not None:
                out.append(v)
        return out

    def view_of(self, r: ModelReport) -> ModelView | None:
        """The view of one model's report (kept while the report is), None without a robot
        (the last report that expanded, :attr:`Workspace.last_good`, included)."""
        if r.kept_model is None or r.kept_model.xml is None:
            return None
        v = self._views.get(id(r))
        if v is None or v[0] is not r:
            try:
                v = self._views[id(r)] = (r, ModelView(r))
            except Exception:  # noqa: BLE001 - a model lxml cannot hold: no navigation in it
                return None
        return v[1]


class Index:
    """Every xacro file's declarations, re-read when its text changes."""

    def __init__(self, services: Services):
        self.services = services
        self.files: dict[str, tuple[bytes, FileIndex]] = {}

    def of(self, path: str) -> FileIndex:
        doc = self.services.doc(path)
        hit = self.files.get(path)
        if hit is None or hit[0] is not doc.data and hit[0] != doc.data:
            hit = self.files[path] = (doc.data, index_text(path, doc.data))
        return hit[1]

    def all_files(self) -> list[str]:
        """The workspace's xacro files: open or in the include graph, inside the run's roots
        (an include a symlink or ``$(find)`` leads out of them is not indexed)."""
        ws = self.services.ws
        if ws is None:
            return []
        files = set(ws.buffers)
        for f, inc in ws.graph.includes.items():
            files.add(f)
            files.update(inc)
        return sorted(f for f in files if f.endswith(".xacro") and ws.readable(f))

    def reachable(self, path: str) -> list[str]:
        """``path``, the files it includes (transitively), then every other xacro file."""
        ws = self.services.ws
        out: list[str] = []
        todo = [path]
        while todo:
            f = todo.pop(0)
            if f in out:
                continue
            out.append(f)
            if ws is not None:
                todo.extend(i for i in ws.graph.includes.get(f, ()) if ws.readable(i))
        return out + [f for f in self.all_files() if f not in out]

    def decls(self, path: str, kind: str, name: str | None = None) -> list[Decl]:
        return [d for f in self.reachable(path) for d in self.of(f).decls
                if d.kind == kind and (name is None or d.name == name)]


class ModelView:
    """One model's expanded robot with its source map: elements by source origin and by name."""

    def __init__(self, report: ModelReport):
        from lxml import etree
        kept = report.kept_model
        assert kept is not None and kept.xml is not None and kept.origins is not None
        self.label = report.label
        self.name = os.path.splitext(os.path.basename(report.entry))[0]
        self.root: Any = etree.fromstring(kept.xml.encode("utf-8"))
        self.at: dict[tuple[str, int, int], list[Any]] = {}
        self.origin: dict[Any, Any] = {}
        for el, o in kept.origins.align(self.root.iter(tag=etree.Element)).items():
            self.at.setdefault((o.file, o.line, o.col), []).append(el)
            self.origin[el] = o
        self.named = {(el.tag, el.get("name")): el for el in self.root
                      if el.tag in ("link", "joint")}
        self.files = {k[0] for k in self.at}   # the source files that write it
