"""Review snapshots: a rerun recording (.rrd) and a PNG per model, and the ``summary.md`` of a run.

A consumer of the linted model (see ARCHITECTURE.md): :mod:`.scene` builds what is drawn,
:mod:`.raster` draws the PNG, :mod:`.recording` logs the recording. Geometry comes from the same
resolved, confined mesh paths as the lint rules; nothing the package resolver did not vet is ever
read or handed to rerun.
"""
from __future__ import annotations

import hashlib
import os
import sys
import threading
import zlib
from typing import TYPE_CHECKING, Any, Iterable, Sequence

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.core.findings import Problem
    from urdf_lint.core.jobs import ModelReport
    from urdf_lint.engine.lint import Context
    from urdf_lint.engine.model import Model
    from urdf_lint.run.pipeline import CheckResult

from urdf_lint.render.raster import caption, model_caption, render_image, save_png
from urdf_lint.render.recording import _import_rerun, entity_paths, record_findings, record_rrd
from urdf_lint.render.scene import build_scene
# what the worker (diff --render) and review.py use through this module
from urdf_lint.render.raster import Geometry, frame_for, scene_geometry  # noqa: F401,E402
from urdf_lint.render.raster import render_pair as render_pair  # noqa: E402 - (re-exported)


# -- orchestration -----------------------------------------------------------------------------
def render_model(model: "Model", ctx: "Context", findings: Sequence["Problem"], out_dir: str,
                 base: str | None, rrd: bool = True, views: str = "single", forward: str = "+x",
                 refused: Iterable[str] = ()) -> dict[str, Any]:
    """Draw the picture of ``model`` and write its recording (without findings); return a
    summary dict. Runs in the worker, the only process that reads meshes and textures. The
    parent captions the picture and adds the findings to the recording once the run's
    findings are final (:func:`finish_snapshots`): suppressions, per-file ignores, severities,
    run-scope rules and the baseline are applied there. ``findings`` is not used (kept for
    callers that render one model in process). Never raises for model problems. A name in
    ``refused`` (the parent found another model of the run with the same one) is not
    written."""
    from urdf_lint.core.locations import snapshot_name
    name = snapshot_name(model.entry, model.args, base)
    if name in refused:
        return {"name": name, "png": None, "rrd": None, "image": None, "problems": [
            f"another model of this run has the picture name {name}: neither is drawn"]}
    from urdf_lint.core import fsbound
    fsbound.make_own_dirs(out_dir)   # the snapshot folder the CLI checked
    importer = None
    if rrd and "rerun" not in sys.modules:
        # rerun's import (~0.5 s) overlaps with the PNG rasterization
        importer = threading.Thread(target=_import_rerun, daemon=True)
        importer.start()
    scene = build_scene(model, ctx)
    info: dict[str, Any] = {
        "name": name, "png": os.path.join(out_dir, name + ".png"), "rrd": None, "problems": [],
        "image": None, "title": scene.name, "entities": entity_paths(scene)}
    try:
        img, facts = render_image(scene, ctx, views, forward)
        # raw pixels, deflated (a run may hold a hundred of them until its findings are final)
        info["image"] = (img.height, img.width, zlib.compress(img.tobytes(), 1))
        info.update(facts)
    except Exception as e:  # noqa: BLE001
        info["problems"].append(f"png: {type(e).__name__}: {e}")
        info["png"] = None
    if rrd:
        if importer is not None:
            importer.join()
        try:
            import rerun  # noqa: F401
        except ImportError:
            from urdf_lint.render.recording import NO_RERUN
            info["problems"].append(f"rrd: {NO_RERUN}")
        else:
            path = os.path.join(out_dir, name + ".rrd")
            try:
                # no findings yet: the parent adds the final ones (finish_snapshots)
                info.update(record_rrd(scene, ctx, path, recording_id=f"urdf-lint/{name}",
                                       model=model, base=base))
                info["rrd"] = path
            except Exception as e:  # noqa: BLE001
                info["problems"].append(f"rrd: {type(e).__name__}: {e}")
    return info


def finish_snapshots(models: Iterable["ModelReport"], findings: Iterable["Problem"],
                     out_dir: str) -> None:
    """In the parent, after the run's policy and the baseline: caption each model's picture
    with its findings and write it, and merge those findings into its recording. Reads only
    what the workers handed back, never a model file. Models are finished in parallel
    threads (PNG encoding and ``rerun rrd merge`` subprocesses do not hold the GIL)."""
    from concurrent.futures import ThreadPoolExecutor
    todo = [m for m in models if m.snapshot]
    by_model: dict[str, list["Problem"]] = {m.label: [] for m in todo}
    for f in findings:
        for label in f.models:
            if label in by_model:
                by_model[label].append(f)
    if any((m.snapshot or {}).get("rrd") and by_model[m.label] for m in todo):
        import rerun  # noqa: F401 - once, before the threads
    with ThreadPoolExecutor(max_workers=max(1, min(len(todo), os.cpu_count() or 1))) as pool:
        list(pool.map(lambda m: _finish_one(m, by_model[m.label], out_dir), todo))


def _in_folder(path: object, out_dir: str) -> bool:
    """Is ``path`` (sent back by a worker) a file directly in the output folder?"""
    return isinstance(path, str) and os.path.basename(path) not in ("", ".", "..") and \
        os.path.dirname(os.path.abspath(path)) == os.path.realpath(out_dir)


def _finish_one(m: "ModelReport", mine: list["Problem"], out_dir: str) -> None:
    snap = m.snapshot
    assert snap is not None   # (models with a snapshot only: finish_snapshots)
    # a worker's reply is data: the parent writes only files directly in the output folder
    name = snap.get("name")
    for k in ("png", "rrd"):
        if snap.get(k) is not None and not _in_folder(snap[k], out_dir):
            snap.setdefault("problems", []).append(f"{k}: not in the output folder; not written")
            snap[k] = None
    if not isinstance(name, str) or not _in_folder(os.path.join(out_dir, name), out_dir):
        snap["rrd"] = None
    snap["findings"] = len(mine)
    _finish_png(snap, snap.pop("image", None), m, len(mine))
    if snap.get("rrd") and mine:
        paths, joints = snap.get("entities") or ({}, {})
        part = os.path.join(out_dir, snap["name"] + ".findings.rrd")
        try:
            from urdf_lint.core.locations import label_base
            record_findings(mine, paths, joints, part, recording_id=f"urdf-lint/{snap['name']}",
                            base=label_base(m.entry), size=snap.get("robot_size", 1.0))
            merge_rrd([snap["rrd"], part], snap["rrd"])
        except Exception as e:  # noqa: BLE001
            snap["problems"].append(f"rrd: findings not recorded: {type(e).__name__}: {e}")
            _remove(part)
            _remove(snap["rrd"])
            snap["rrd"] = None


def _finish_png(snap: dict[str, Any], image: tuple[int, int, bytes], m: "ModelReport",
                findings: int) -> None:
    if not snap.get("png") or image is None:
        snap["png"] = None
        return
    from PIL import Image
    h, w, data = image
    raw = zlib.decompressobj().decompress(data, 3 * h * w + 1) if 0 < h * w <= 4096 * 4096 else b""
    if len(raw) != h * w * 3:
        snap["problems"].append("png: the worker's picture has the wrong size")
        snap["png"] = None
        return
    img = Image.frombytes("RGB", (w, h), raw)
    caption(img, model_caption(snap.get("title"), snap.get("links", m.links),
                               snap.get("placeholders", 0), findings))
    try:
        save_png(img, snap["png"])
    except OSError as e:
        snap["problems"].append(f"png: cannot write: {e.strerror or e}")
        snap["png"] = None


def merge_rrd(parts: list[str], out: str) -> str:
    """Merge recordings (``rerun rrd merge``) into ``out`` (which may be one of ``parts``),
    then remove the other parts."""
    import shutil
    import subprocess
    from urdf_lint.core import fsbound
    # the rerun of this environment (the one whose rerun-sdk recorded the parts) before any on
    # PATH: a pyenv shim on PATH may name an interpreter without rerun-sdk
    here = os.path.join(os.path.dirname(sys.executable), "rerun")
    exe = here if os.access(here, os.X_OK) else (shutil.which("rerun") or here)
    with fsbound.temp_path(out, os.path.dirname(os.path.abspath(out)), ".rrd") as tmp:
        p = subprocess.run([exe, "rrd", "merge", *parts, "-o", tmp], capture_output=True,
                           timeout=120, env=dict(os.environ, RERUN_ANALYTICS="off"))
        if p.returncode != 0:
            raise RuntimeError("rerun rrd merge failed: "
                               + p.stderr.decode(errors="replace")[-300:])
    for h in parts:
        if os.path.abspath(h) != os.path.abspath(out):
            _remove(h)
    return out


def _remove(path: str) -> None:
    """Remove a file this run wrote in its output folder (a regular file, not a link)."""
    from urdf_lint.core import fsbound
    fsbound.remove(path, os.path.dirname(os.path.abspath(path)))


# -- files this tool wrote in an output folder -------------------------------------------------
MANIFEST = ".urdf-lint-snapshots.json"
_OUTPUT_SUFFIXES = (".png", ".rrd", ".md")


def _digest(path: str) -> str | None:
    from urdf_lint.core import fsbound
    try:   # a snapshot: a regular file, not a link, bounded
        data = fsbound.read_bytes(path, max_bytes=fsbound.MAX_DATA_BYTES * 4, nofollow=True)
    except OSError:
        return None
    return hashlib.blake2b(data, digest_size=16).hexdigest()


def clear_stale(out_dir: str, base: str | None = None) -> None:
    """Remove what an earlier run wrote in ``out_dir`` (listed in its manifest), so no stale
    picture survives. A file is removed only when it is a regular file directly in ``out_dir``
    with an output suffix and the very bytes that run wrote (the manifest keeps a digest), so
    a planted or edited manifest cannot make urdf-lint delete anyone's file. With ``base``
    (the repository, when ``out_dir`` is in it), a symlinked folder anywhere from ``base``
    down to ``out_dir`` is refused (:class:`urdf_lint.core.fsbound.BoundaryError`)."""
    import json
    from urdf_lint.core import fsbound
    if base is not None:
        fsbound.check_no_symlink(out_dir, base)
    path = os.path.join(out_dir, MANIFEST)
    try:
        files = json.loads(fsbound.read_bytes(path, max_bytes=fsbound.MAX_CONFIG_BYTES,
                                              nofollow=True)).get("files", {})
    except (OSError, ValueError, AttributeError, RecursionError):   # a planted manifest
        return
    for name, digest in files.items() if isinstance(files, dict) else ():
        if not isinstance(name, str) or os.path.basename(name) != name \
                or not name.endswith(_OUTPUT_SUFFIXES):
            continue
        p = os.path.join(out_dir, name)
        if os.path.isfile(p) and not os.path.islink(p) and _digest(p) == digest:
            _remove(p)
    _remove(path)


def write_manifest(out_dir: str, files: Iterable[str]) -> None:
    """Record the files this run wrote in ``out_dir`` with their digests (the next run
    removes them first, if they are unchanged)."""
    import json
    from urdf_lint.core import fsbound
    out = {}
    for f in files:
        if f and os.path.dirname(os.path.abspath(f)) == os.path.abspath(out_dir):
            d = _digest(f)
            if d is not None:
                out[os.path.basename(f)] = d
    fsbound.write_text(os.path.join(out_dir, MANIFEST),
                       json.dumps({"files": dict(sorted(out.items()))}, indent=1) + "\n", out_dir)


def write_summary(result: "CheckResult", out_dir: str) -> str:
    from collections import Counter
    from urdf_lint.core.locations import display_path
    from urdf_lint.core.locations import relative_label
    from urdf_lint.core.escape import escape_markdown, escape_markdown_code
    lines = ["# urdf-lint snapshots", "",
             "| model | links | joints | meshes | errors | warnings | info |",
             "|---|---:|---:|---:|---:|---:|---:|"]
    images = []
    for m in result.models:
        c = Counter(f.severity for f in result.findings if m.label in f.models)
        shown = m.label
        if os.path.isabs(display_path(m.entry)):  # outside the working directory
            shown = relative_label(m.entry) + m.label[len(display_path(m.entry)):]
        label = escape_markdown(shown)  # names are the description's: no HTML, no links
        lines.append(f"| `{escape_markdown_code(shown)}` | {m.stats.get('links', '-')} | "
                     f"{m.stats.get('joints', '-')} | "
                     f"{m.stats.get('meshes', '-')} | {c['error']} | {c['warning']} | {c['info']} |")
        snap = m.snapshot or {}
        if snap.get("png"):
            images.append(f"### {label}\n\n![{label}]({os.path.relpath(snap['png'], out_dir)})\n")
            if snap.get("rrd"):
                rel = os.path.relpath(snap['rrd'], out_dir)  # never a path of this machine
                images.append(f"Recording: `{rel}` (open with `rerun {rel}` in this folder)\n")
    text = "\n".join(lines) + "\n\n" + "\n".join(images)
    path = os.path.join(out_dir, "summary.md")
    from urdf_lint.core import fsbound
    fsbound.write_text(path, text, out_dir)
    return path
