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

from .raster import (PNG_SIZE, Frame, Geometry, _mask, difference_image, draw,  # noqa: F401
                     frame_for, rasterize, render_pair, render_png, scene_geometry)
from .recording import _import_rerun, entity_paths, record_rrd  # noqa: F401
from .scene import Part, Scene, build_scene, kinematic_tree, part_mesh  # noqa: F401


# -- orchestration -----------------------------------------------------------------------------
def snapshot_name(entry, args, base):
    from .locations import display_path
    rel = display_path(entry, base)
    if os.path.isabs(rel):  # outside the base: no path of this machine in the name
        from .recording import relative_label
        rel = relative_label(entry)
    stem = rel.replace(os.sep, "__")
    for ext in (".urdf.xacro", ".xacro", ".urdf"):
        if stem.endswith(ext):
            stem = stem[: -len(ext)]
    if args:
        stem += "__" + "_".join(f"{k}-{v}" for k, v in sorted(args.items()))
        digest = hashlib.blake2b(repr(sorted(args.items())).encode(), digest_size=4).hexdigest()
        stem = stem[:150] + "_" + digest
    return "".join(ch if ch.isalnum() or ch in "_-.@" else "_" for ch in stem)


def render_model(model, ctx, findings, out_dir, base, rrd=True):
    """Write <name>.png (and <name>.rrd); return a summary dict. Never raises for model problems."""
    os.makedirs(out_dir, exist_ok=True)
    importer = None
    if rrd and "rerun" not in sys.modules:
        # rerun's import (~0.5 s) overlaps with the PNG rasterization
        importer = threading.Thread(target=_import_rerun, daemon=True)
        importer.start()
    name = snapshot_name(model.entry, model.args, base)
    scene = build_scene(model, ctx)
    info = {"name": name, "png": os.path.join(out_dir, name + ".png"), "rrd": None, "problems": []}
    try:
        info.update(render_png(scene, ctx, info["png"], findings_count=len(findings)))
    except Exception as e:  # noqa: BLE001
        info["problems"].append(f"png: {type(e).__name__}: {e}")
        info["png"] = None
    if rrd:
        if importer is not None:
            importer.join()
        try:
            import rerun  # noqa: F401
        except ImportError:
            info["problems"].append("rrd: rerun-sdk is not installed (pip install 'urdf-lint[render]')")
        else:
            path = os.path.join(out_dir, name + ".rrd")
            try:
                info.update(record_rrd(scene, ctx, findings, path, recording_id=f"urdf-lint/{name}",
                                       model=model, base=base))
                info["rrd"] = path
            except Exception as e:  # noqa: BLE001
                info["problems"].append(f"rrd: {type(e).__name__}: {e}")
    return info


def write_summary(result, out_dir):
    from collections import Counter
    from .locations import display_path
    from .recording import relative_label
    from .report.escape import escape_markdown, escape_markdown_code
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
    from .atomic import atomic_write
    atomic_write(path, text)
    return path
