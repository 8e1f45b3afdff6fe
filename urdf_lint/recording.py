"""The rerun recording (.rrd) of a snapshot: the entity tree follows the kinematic tree, visual
and collision geometry on their own subtrees, findings on the link or joint they concern. Static
data only, a fixed recording id: deterministic.
"""
from __future__ import annotations

import os

import numpy as np

from .ruleutil import numbers
from .scene import origin_matrix, part_mesh


# -- rerun recording -------------------------------------------------------------------------
def entity_paths(scene):
    """link -> entity path following the kinematic tree: /robot/<root>/<joint>/<child>/..."""
    paths = {r: f"robot/{_safe(r)}" for r in scene.roots}
    joints = {}
    for parent, j, child in scene.tree:
        jp = f"{paths[parent]}/{_safe(j.get('name') or 'joint')}"
        joints[j.get("name")] = jp
        paths[child] = f"{jp}/{_safe(child)}"
    return paths, joints


def _safe(s):
    return "".join(ch if ch.isalnum() or ch in "_-." else "_" for ch in str(s)) or "_"


def record_rrd(scene, ctx, findings, path, recording_id, prefix=""):
    """Log ``scene`` to ``path``; ``prefix`` (e.g. ``"head/"``) puts every entity under one
    root, so that two revisions can share a recording."""
    from .atomic import atomic_path
    with atomic_path(path) as tmp:
        return _record_rrd(scene, ctx, findings, tmp, recording_id, prefix)


def _record_rrd(scene, ctx, findings, tmp, recording_id, prefix):
    import rerun as rr
    rec = rr.RecordingStream("urdf-lint", recording_id=recording_id, send_properties=False)
    rec.save(tmp)

    def log(entity, *a, **kw):
        rec.log(prefix + entity, *a, **kw)
    log("robot", rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
    paths, joint_paths = entity_paths(scene)
    # the kinematic tree twice: /robot (frames, axes, visuals, findings) and /collision
    # (collision geometry only, so that it toggles as one subtree)
    for root in ("robot", "collision"):
        for _parent, j, _child in scene.tree:
            T = origin_matrix(j)
            jp = root + joint_paths[j.get("name")][len("robot"):]
            log(jp, rr.Transform3D(translation=T[:3, 3], mat3x3=T[:3, :3]), static=True)
    for _parent, j, child in scene.tree:
        if j.get("type") not in ("fixed", None):
            ax = j.find("axis")
            axis = numbers(ax.get("xyz") if ax is not None else "1 0 0", 3) or [1, 0, 0]
            log(f"{paths[child]}/joint_axis",
                    rr.Arrows3D(origins=[[0, 0, 0]], vectors=[np.asarray(axis) * 0.1],
                                colors=[[250, 200, 0]], labels=[j.get("name") or ""]), static=True)
    for _link, p in paths.items():
        log(p, rr.TransformAxes3D(0.05), static=True)
    logged = 0
    for part in scene.parts:
        root = "robot" if part.kind == "visual" else "collision"
        base = f"{root}{paths[part.link][len('robot'):]}/{part.kind}/{part.index}"
        log(base, rr.Transform3D(translation=part.local[:3, 3], mat3x3=part.local[:3, :3]), static=True)
        got = part_mesh(part, ctx) if part.shape != "missing" else None
        if got is None:
            log(f"{base}/missing", rr.Boxes3D(half_sizes=[[0.03, 0.03, 0.03]], colors=[[230, 30, 30]],
                                                 labels=[part.problem or "missing geometry"]), static=True)
            continue
        v, f, fc = got
        rgba = [int(255 * x) for x in part.rgba]
        if part.kind == "collision":
            rgba = [80, 160, 255, 110]
        kwargs = {"vertex_positions": v.astype(np.float32), "triangle_indices": f.astype(np.uint32),
                  "albedo_factor": rgba}
        tex = part.params.get("texture") if part.kind == "visual" else None
        if tex is not None and len(tex[0]) == len(v):
            kwargs["vertex_texcoords"] = tex[0].astype(np.float32)
            kwargs["albedo_texture"] = tex[1]
            kwargs["albedo_factor"] = [255, 255, 255, 255]
        elif fc is not None and len(fc) == len(f) and part.kind == "visual":
            vc = np.zeros((len(v), 3))
            vc[f.reshape(-1)] = np.repeat(fc, 3, axis=0)
            kwargs["vertex_colors"] = (vc * 255).astype(np.uint8)
        log(f"{base}/mesh", rr.Mesh3D(**kwargs), static=True)
        logged += 1
    log_findings(log, findings, paths, joint_paths)
    rec.flush()
    rec.disconnect()
    return {"meshes": logged}


def log_findings(log, findings, paths, joint_paths):
    """Each finding on the entity of the link or joint it concerns (``paths``/``joint_paths``
    from :func:`entity_paths`)."""
    import rerun as rr
    levels = {"error": "ERROR", "warning": "WARN", "info": "INFO"}
    for n, fd in enumerate(findings):
        target = fd.target
        ent = "robot"
        if target and target[0] == "link" and target[1] in paths:
            ent = paths[target[1]]
        elif target and target[0] == "joint" and target[1] in joint_paths:
            ent = joint_paths[target[1]]
        text = f"{fd.code} {fd.message} ({os.path.basename(fd.file)}:{fd.line})"
        log(f"{ent}/findings/{n}", rr.TextLog(text, level=levels.get(fd.severity, "WARN")),
            static=True)
        log(f"{ent}/findings/{n}", rr.Points3D([[0, 0, 0]], radii=[0.01], colors=[[230, 30, 30]],
                                              labels=[fd.code]), static=True)


def record_findings(findings, paths, joint_paths, path, recording_id, prefix=""):
    """A recording of ``findings`` alone, with the same entity paths and recording id as the
    model's (written by the parent once the run's findings are final; merged into the
    model's recording)."""
    import rerun as rr
    from .atomic import atomic_path
    with atomic_path(path) as tmp:
        rec = rr.RecordingStream("urdf-lint", recording_id=recording_id, send_properties=False)
        rec.save(tmp)
        log_findings(lambda entity, *a, **kw: rec.log(prefix + entity, *a, **kw), findings,
                     paths, joint_paths)
        rec.flush()
        rec.disconnect()


def _import_rerun():
    try:
        import rerun  # noqa: F401
    except Exception:  # noqa: BLE001 - reported by render_model when it imports again
        pass
