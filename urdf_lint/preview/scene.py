"""What the 3D page shows of one expanded model: its URDF with every mesh and texture
reference replaced by a served name (``m/<index>/<basename>``), the table of the files behind
those names (the only files the page may read), where each link and joint was written, and the
findings that concern it.

Built in the parent from a ``ModelReport`` that kept its robot (``LintSettings.keep_model``):
the expansion itself ran in a sandboxed worker. Mesh and texture references are resolved as
the rules resolve them (``meshes.resolve``: inside the package roots, or not at all)."""
from __future__ import annotations

import os
import posixpath
from dataclasses import dataclass, field
from typing import Any

from lxml import etree

from urdf_lint.core.locations import display_path

# meshes above this are not sent to the page (a placeholder box in their place, and a note);
# a browser tab holds a few hundred MB of vertex buffers before it gives up
DEFAULT_MAX_MESH_MB = 64
MESH_SUFFIXES = (".stl", ".dae", ".obj")


@dataclass
class Served:
    """One file the page may read: a mesh or a texture the robot references, and the
    textures that mesh references in turn (its only allowed relative names)."""
    path: str
    kind: str                              # "mesh" | "texture"
    size: int = 0
    refused: str = ""                      # why it is not served (too big)
    textures: dict[str, str] = field(default_factory=dict)   # served name -> absolute path
    name: str = ""                         # the name it is served by (below m/<index>/)


@dataclass
class FileTable:
    """Every file the page may read, shared by the variants of a session (one index per
    path)."""
    files: list[Served] = field(default_factory=list)
    index: dict[str, int] = field(default_factory=dict)
    max_bytes: int = DEFAULT_MAX_MESH_MB << 20

    def add(self, path: str, kind: str, resolver: Any) -> int:
        if path in self.index:
            return self.index[path]
        try:
            size = os.stat(path).st_size
        except OSError:
            size = 0
        s = Served(path, kind, size)
        if size > self.max_bytes:
            s.refused = (f"{display_path(path)} is {size / 1e6:.0f} MB, over the preview's "
                         f"{self.max_bytes >> 20} MB cap (--max-mesh-mb)")
        s.name = os.path.basename(path)
        if kind == "mesh" and not s.refused:
            s.name, s.textures = _textures_of(path, resolver)
        self.index[path] = len(self.files)
        self.files.append(s)
        return self.index[path]

    def lookup(self, i: int, name: str) -> Served | str | None:
        """The file behind ``m/<i>/<name>``: the mesh or texture itself (``name`` its base
        name), a texture the mesh references by ``name`` (an absolute path), else None."""
        if not 0 <= i < len(self.files):
            return None
        s = self.files[i]
        if name == s.name:
            return s
        return s.textures.get(name)


def _textures_of(path: str, resolver: Any) -> tuple[str, dict[str, str]]:
    """(the mesh's served name, {served name: path} of the images and MTL files it names),
    the references kept only when they resolve inside the package roots. A mesh whose
    references climb out of its folder (``../textures/a.png``) is served that many folders
    deep (``_/_/mesh.dae``), so that the browser's resolution of the relative name stays below
    ``m/<index>/``."""
    from urdf_lint.meshes.resolve import texture_refs
    from urdf_lint.meshes.store import MeshStore
    base = os.path.dirname(path)
    rels = {}
    # (confined: an MTL that the OBJ names outside the roots is not even read)
    store = MeshStore(inside=resolver.is_inside) if resolver is not None else None
    for ref in texture_refs(path, store):
        if resolver is not None and not resolver.is_inside(ref):
            continue
        rels[os.path.relpath(ref, base).replace(os.sep, "/")] = ref
    depth = max((r.split("/").count("..") for r in rels), default=0)
    pad = "_/" * depth
    out = {posixpath.normpath(pad + r): ref for r, ref in rels.items()}
    return pad + os.path.basename(path), out


@dataclass
class Scene:
    """One model (one variant) as the page receives it (``to_json``)."""
    label: str
    entry: str
    args: dict[str, str]
    urdf: str = ""
    error: str = ""
    links: dict[str, list[Any]] = field(default_factory=dict)    # name -> [file, line]
    joints: dict[str, list[Any]] = field(default_factory=dict)
    findings: list[dict[str, Any]] = field(default_factory=list)
    # the findings as ``check`` counts them (core.findings.group): a macro line wrong in two
    # links is one problem with two markers
    problems: int = 0
    notes: list[str] = field(default_factory=list)
    deps: list[str] = field(default_factory=list)
    # where each element and finding was written, the real path (kept here, never sent: the
    # page names an element, the server finds its line; ``Session.jump``)
    sources: dict[str, tuple[str, int, int]] = field(default_factory=dict)   # "link:NAME" ->
    finding_sources: list[tuple[str, int, int]] = field(default_factory=list)   # (file, line, col)

    def to_json(self) -> dict[str, Any]:
        return {"label": self.label, "entry": display_path(self.entry), "args": self.args,
                "urdf": self.urdf, "error": self.error, "links": self.links,
                "joints": self.joints, "findings": self.findings, "notes": self.notes}


def finding_json(p: Any) -> dict[str, Any]:
    o = p.origin
    target = list(p.target) if p.target else None
    return {"code": p.code, "name": p.name, "severity": p.severity, "message": p.message,
            "file": display_path(o.file), "line": o.line, "col": o.col, "target": target}


def model_of(report: Any, resolver: Any) -> tuple[Any, str]:
    """(Model, "") of a report that kept its robot, else (None, why)."""
    from urdf_lint.engine.model import Model, model_from_xml, parse_urdf_bytes
    kept = report.kept_model
    if kept is None:
        errors = [p.message for p in report.problems if p.severity in ("", "error")]
        return None, (errors[0] if errors else "the model could not be expanded")
    if kept.xml is not None:
        return model_from_xml(report.entry, report.args, kept.xml, kept.origins, report.deps,
                              resolver, kept.values), ""
    from urdf_lint.core import fsbound
    try:
        data = fsbound.read_bytes(report.entry, resolver.roots if resolver is not None else None)
    except OSError as e:
        return None, f"cannot read {display_path(report.entry)}: {e}"
    root, origins, _ = parse_urdf_bytes(report.entry, data)
    if root is None:
        return None, f"{display_path(report.entry)} is not well-formed XML"
    return Model(entry=report.entry, args={}, root=root, origins=origins, deps=[report.entry],
                 resolver=resolver), ""


def build_scene(report: Any, findings: list[Any], resolver: Any, table: FileTable,
                mesh_base: str | None = None) -> Scene:
    """The Scene of one linted model: ``findings`` are the run's (those of this model only
    are kept, by its label)."""
    label = report.label
    scene = Scene(label, report.entry, dict(report.args), deps=list(report.deps))
    from urdf_lint.core.findings import group
    own = [p for p in findings if not p.models or label in p.models]
    scene.findings = [finding_json(p) for p in own]
    scene.finding_sources = [(p.origin.file, p.origin.line, p.origin.col) for p in own]
    scene.problems = len(group(own))
    model, why = model_of(report, resolver)
    if model is None:
        scene.error = why
        return scene
    if mesh_base:
        model.mesh_base = mesh_base
    fill_scene(scene, model, resolver, table)
    return scene


def fill_scene(scene: Scene, model: Any, resolver: Any, table: FileTable) -> None:
    """The links and joints of ``model`` (where each was written), and its URDF with the
    mesh and texture references renamed to the served names (``model.root`` is changed)."""
    for kind, items in (("link", model.root.iter("link")), ("joint", model.root.iter("joint"))):
        out = scene.links if kind == "link" else scene.joints
        for el in items:
            if el.getparent() is model.root and el.get("name"):
                o = model.origin(el)
                out[el.get("name")] = [display_path(o.file), o.line]
                scene.sources[f"{kind}:{el.get('name')}"] = (o.file, o.line, o.col)
    _serve_files(model, resolver, table, scene)
    scene.urdf = etree.tostring(model.root, encoding="unicode")


def _serve_files(model: Any, resolver: Any, table: FileTable, scene: Scene) -> None:
    """Each mesh and texture reference becomes ``m/<index>/<basename>`` (resolved as the rules
    resolve it); one that does not resolve becomes ``missing/<n>`` and a note."""
    from urdf_lint.meshes.resolve import MeshStatus, resolve
    missing = 0
    for el in list(model.root.iter("mesh", "texture")):
        uri = el.get("filename")
        if not uri:
            continue
        ref = resolve(model, uri)
        kind = "mesh" if el.tag == "mesh" else "texture"
        if ref.status is not MeshStatus.OK or ref.path is None:
            scene.notes.append(ref.message or f"{kind} '{uri}' does not resolve")
            el.set("filename", f"missing/{missing}")
            missing += 1
            continue
        i = table.add(ref.path, kind, resolver)
        served = table.files[i]
        if served.refused:
            scene.notes.append(served.refused)
        el.set("filename", f"m/{i}/{served.name}")
