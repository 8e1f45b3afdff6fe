"""The review page of ``urdf-lint diff --html DIR``: one page for the whole pull request, every
changed model in it (the variant picker), the head robot drawn over the base one (the base in
translucent grey), the changed links highlighted, joint sliders that move both, the table of
changes and the new and fixed findings.

It opens from ``file://`` after the artifact is unzipped: classic scripts beside it (no ES
modules, which Chromium refuses from file://), and the robots with their meshes inlined as
base64 in ``review-data.js`` (no fetch: file:// has none). Meshes are collected while the diff
still has both revisions on disk (``collect``, called by ``review.run.run_diff``)."""
from __future__ import annotations

import base64
import hashlib
import json
import os
from typing import Any

from urdf_lint.core import fsbound
from urdf_lint.core.locations import display_path
from urdf_lint.preview.scene import DEFAULT_MAX_MESH_MB, FileTable, Scene, fill_scene
from urdf_lint.preview.server import REVIEW_CSP, STATIC, page_html

# all the meshes of one page together: a pull request of many large, distinct meshes (cheap in
# git as deltas of each other) would otherwise fill the diff's memory and the artifact
MAX_TOTAL_MB = 256
PAGE = "index.html"
DATA = "review-data.js"
ASSETS = {"vendor.js": "vendor/vendor.js", "viewer.js": "viewer.js", "viewer.css": "viewer.css",
          "LICENSE.three.txt": "vendor/LICENSE.three.txt",
          "LICENSE.urdf-loader.txt": "vendor/LICENSE.urdf-loader.txt"}


def changed_links(md: Any) -> list[str]:
    """The links a model diff names as changed: a change of the link itself, or a link that
    moved (its joint's origin, a parent's); what ``diff --format json`` says, as links."""
    out = {c.name for c in md.changes if c.kind == "link"}
    out |= {link for link, _, _ in md.moved}
    return sorted(out)


def _change_text(c: Any) -> str:
    what: str = c.change + (f" {c.field}" if c.field else "")
    if c.change == "changed":
        what += f": {_short(c.before)} -> {_short(c.after)}"
    return what


def _short(v: Any) -> str:
    s = json.dumps(v) if not isinstance(v, str) else v
    return s if len(s) <= 80 else s[:77] + "..."


def _finding(fk: Any, severity: str) -> dict[str, Any]:
    code, file, message = fk[0], fk[1], fk[2]
    return {"code": code, "name": "", "severity": severity, "message": message,
            "file": file, "line": "", "target": None}


class ReviewPage:
    """The models of one diff, their robots and meshes, as the page will hold them."""

    def __init__(self, max_mesh_mb: int = DEFAULT_MAX_MESH_MB,
                 max_total_mb: int = MAX_TOTAL_MB) -> None:
        self.table = FileTable(max_bytes=max_mesh_mb << 20)
        self.max_total = max_total_mb << 20
        self.total = 0                          # the bytes inlined so far
        self.models: list[dict[str, Any]] = []
        self.files: dict[str, dict[str, str]] = {}
        self._by_digest: dict[str, str] = {}   # the same bytes at base and head: sent once

    def collect(self, md: Any, head_model: Any, base_model: Any) -> None:
        """One model diff with its two robots (either may be None: added, removed, failed).
        The robots' trees are changed (mesh references renamed): call it last."""
        head = Scene(md.model, "", {})
        base = Scene(md.model, "", {})
        for model, scene in ((head_model, head), (base_model, base)):
            if model is not None:
                fill_scene(scene, model, model.resolver, self.table)
        roots = [r for m in (head_model, base_model) if m is not None and m.resolver is not None
                 for r in m.resolver.read_paths()]
        full = self._inline(self.table, roots or None)
        self.models.append({
            "label": f"{md.model} ({md.status})", "status": md.status,
            "urdf": head.urdf or base.urdf, "base_urdf": base.urdf if head.urdf else "",
            "error": md.error, "links": head.links or base.links,
            "joints": head.joints or base.joints, "notes": head.notes + base.notes + full,
            "findings": [], "changed_links": changed_links(md),
            "changes": [{"element": f"{c.kind} {c.name}", "text": _change_text(c)}
                        for c in md.changes] +
                       [{"element": f"link {link}",
                         "text": f"moved {d * 1000:.1f} mm, {a * 57.29578:.2f} deg"}
                        for link, d, a in md.moved],
            "new_findings": [_finding(fk, s) for fk, s in md.findings_introduced],
            "fixed_findings": [_finding(fk, s) for fk, s in md.findings_fixed]})

    def _inline(self, table: FileTable, roots: list[str] | None) -> list[str]:
        """Each file of the table not yet inlined, read now through the boundary (the base
        revision's files are gone once the diff returns); the notes of those left out because
        the page's total is used up."""
        notes = []
        for i, served in enumerate(table.files):
            name = f"m/{i}/{served.name}"
            if name in self.files:
                continue
            if served.refused:
                self.files[name] = {"refused": served.refused}
                continue
            left = self.max_total - self.total
            if served.size > left:
                why = f"not inlined: the page's {self.max_total >> 20} MB of meshes are used up"
                self.files[name] = {"refused": why}
                notes.append(f"{display_path(served.path)}: {why}")
                continue
            try:
                data = fsbound.read_bytes(served.path, roots,
                                          max_bytes=min(table.max_bytes, left))
            except OSError as e:
                self.files[name] = {"refused": f"cannot read: {e.strerror or e}"}
                continue
            digest = hashlib.sha256(data).hexdigest()
            if digest in self._by_digest:
                self.files[name] = {"same": self._by_digest[digest]}
                continue
            self.total += len(data)
            self._by_digest[digest] = name
            self.files[name] = {"data": base64.b64encode(data).decode("ascii")}
        return notes

    def write(self, out_dir: str, base: str, title: str) -> list[str]:
        """index.html, review-data.js and the page's scripts into ``out_dir``; the paths."""
        written = []
        for name, rel in ASSETS.items():
            data = fsbound.read_bytes(os.path.join(STATIC, rel), [STATIC], max_bytes=8 << 20)
            fsbound.write_bytes(os.path.join(out_dir, name), data, base, make_dirs=True)
            written.append(os.path.join(out_dir, name))
        doc = {"models": self.models, "files": self.files}
        # a JSON document is a JS expression; "</" is escaped so no </script> can end it
        js = "window.URDF_LINT_REVIEW = " + \
            json.dumps(doc).replace("</", "<\\/") + ";\n"
        fsbound.write_text(os.path.join(out_dir, DATA), js, base, make_dirs=True)
        html = page_html(title, scripts=(DATA, "vendor.js", "viewer.js"), css="viewer.css",
                         csp=REVIEW_CSP)
        fsbound.write_text(os.path.join(out_dir, PAGE), html, base, make_dirs=True)
        return written + [os.path.join(out_dir, DATA), os.path.join(out_dir, PAGE)]
