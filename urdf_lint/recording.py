"""The rerun recording (.rrd) of a snapshot: the entity tree follows the kinematic tree, visual
and collision geometry on their own subtrees, findings on the link or joint they concern. Static
data only, a fixed recording id: deterministic.
"""
from __future__ import annotations

import os
import re

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


def record_rrd(scene, ctx, findings, path, recording_id, prefix="", model=None, base=None,
               blueprint=True):
    """Log ``scene`` to ``path``; ``prefix`` (e.g. ``"head/"``) puts every entity under one
    root, so that two revisions can share a recording. With ``model`` the recording gets the
    ``joint_sweep`` timeline; ``base`` is what file names in labels are relative to;
    ``blueprint`` sends the viewer layout: True for this recording's own root, or the prefixes
    of every revision a merged recording will hold (``("base/", "head/")``)."""
    from .atomic import atomic_path
    with atomic_path(path) as tmp:
        return _record_rrd(scene, ctx, findings, tmp, recording_id, prefix, model, base,
                           blueprint)


def robot_size(scene, meshes) -> float:
    """The robot's extent (largest side of the box around link origins and geometry, m)."""
    pts = [T[:3, 3] for T in scene.links.values()]
    for part, got in meshes:
        if got is not None:
            v = got[0]
            lo, hi = v.min(axis=0), v.max(axis=0)
            corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])
                                for z in (lo[2], hi[2])])
            pts.extend(corners @ part.T[:3, :3].T + part.T[:3, 3])
    if not pts:
        return 1.0
    arr = np.asarray(pts, dtype=float)
    arr = arr[np.isfinite(arr).all(axis=1)]
    size = float(np.ptp(arr, axis=0).max()) if len(arr) else 0.0
    return min(max(size, 0.05), 100.0) if size > 0 else 0.5


def blueprint_for(prefixes=("",)):
    """Opens on a 3D view of the visuals per revision (collision in the tree, hidden: one
    click away), the findings and sweep log beside it."""
    import rerun.blueprint as rrb
    views = []
    for p in prefixes:
        name = {"": "robot", "base/": "before (base)", "head/": "after (head)"}.get(p, p)
        views.append(rrb.Spatial3DView(
            name=name, origin="/",
            contents=[f"+ /{p}robot/**", f"+ /{p}collision/**"],
            overrides={f"/{p}collision": rrb.EntityBehavior(visible=False)}))
    log = rrb.TextLogView(name="findings", origin="/", contents=["+ /**"])
    return rrb.Blueprint(rrb.Horizontal(*views, log, column_shares=[3] * len(views) + [2]),
                         collapse_panels=False)


_ABS = re.compile(r"(?<![\w.:/~$)}\]])/(?:[^\s:'\"()]+/)*[^\s:'\"()]+")


def relative_text(text: str, base: str | None) -> str:
    """``text`` with every absolute path in it relative to ``base`` (else its file name): no
    path of the machine that made the recording ends up in it."""
    from .locations import display_path

    def sub(m):
        p = m.group(0)
        rel = display_path(p, base) if base else p
        return (os.path.basename(p.rstrip("/")) or p) if os.path.isabs(rel) else rel
    return _ABS.sub(sub, text or "")


def label_base(entry: str) -> str:
    """What file names in a recording's labels are relative to: the folder holding the
    entry's package (so labels read ``ur_description/urdf/ur5e.xacro``), else the entry's
    folder; never a path of the machine that made it."""
    d = os.path.dirname(os.path.abspath(entry))
    probe = d
    while True:
        if os.path.isfile(os.path.join(probe, "package.xml")):
            return os.path.dirname(probe)
        up = os.path.dirname(probe)
        if up == probe:
            return d
        probe = up


def relative_label(path: str) -> str:
    """``path`` relative to :func:`label_base` of itself (for summary.md and labels)."""
    return os.path.relpath(path, label_base(path))


def _record_rrd(scene, ctx, findings, tmp, recording_id, prefix, model=None, base=None,
                blueprint=True):
    import rerun as rr
    if model is not None:
        base = label_base(model.entry)
    rec = rr.RecordingStream("urdf-lint", recording_id=recording_id, send_properties=False)
    rec.save(tmp)
    if blueprint:
        prefixes = (prefix,) if blueprint is True else tuple(blueprint)
        rec.send_blueprint(blueprint_for(prefixes), make_active=True, make_default=True)

    def log(entity, *a, **kw):
        rec.log(prefix + entity, *a, **kw)
    rec.log("/", rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
    paths, joint_paths = entity_paths(scene)
    meshes = [(part, part_mesh(part, ctx) if part.shape != "missing" else None)
              for part in scene.parts]
    size = robot_size(scene, meshes)
    sweep = _sweep(model) if model is not None else None
    moving = sweep.joints if sweep is not None else set()
    # the kinematic tree twice: /robot (frames, axes, visuals, findings) and /collision
    # (collision geometry only, so that it toggles as one subtree). Joints the sweep moves get
    # their transform on the joint_sweep timeline instead (static data would hide it).
    for root in ("robot", "collision"):
        for _parent, j, _child in scene.tree:
            if j.get("name") in moving:
                continue
            T = origin_matrix(j)
            jp = root + joint_paths[j.get("name")][len("robot"):]
            log(jp, rr.Transform3D(translation=T[:3, 3], mat3x3=T[:3, :3]), static=True)
    if sweep is not None:
        _log_sweep(rec, rr, prefix, sweep, joint_paths)
    for _parent, j, child in scene.tree:
        if j.get("type") not in ("fixed", None):
            ax = j.find("axis")
            axis = numbers(ax.get("xyz") if ax is not None else "1 0 0", 3) or [1, 0, 0]
            log(f"{paths[child]}/joint_axis",
                rr.Arrows3D(origins=[[0, 0, 0]], vectors=[np.asarray(axis) * 0.15 * size],
                            colors=[[250, 200, 0]], labels=[j.get("name") or ""]), static=True)
    for _link, p in paths.items():
        log(p, rr.TransformAxes3D(0.06 * size), static=True)
    logged = 0
    for part, got in meshes:
        root = "robot" if part.kind == "visual" else "collision"
        base_ent = f"{root}{paths[part.link][len('robot'):]}/{part.kind}/{part.index}"
        log(base_ent, rr.Transform3D(translation=part.local[:3, 3], mat3x3=part.local[:3, :3]),
            static=True)
        if got is None:
            h = 0.02 * size
            log(f"{base_ent}/missing",
                rr.Boxes3D(half_sizes=[[h, h, h]], colors=[[230, 30, 30]],
                           labels=[relative_text(part.problem, base) or "missing geometry"]),
                static=True)
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
        log(f"{base_ent}/mesh", rr.Mesh3D(**kwargs), static=True)
        logged += 1
    log_findings(log, findings, paths, joint_paths, base, size)
    rec.flush()
    rec.disconnect()
    out = {"meshes": logged, "robot_size": size}
    if sweep is not None:
        out["sweep_segments"] = len(sweep.segments)
    return out


def log_findings(log, findings, paths, joint_paths, base=None, size=1.0):
    """Each finding on the entity of the link or joint it concerns (``paths``/``joint_paths``
    from :func:`entity_paths`), file names relative to ``base``, markers scaled to ``size``."""
    import rerun as rr
    levels = {"error": "ERROR", "warning": "WARN", "info": "INFO"}
    for n, fd in enumerate(findings):
        target = fd.target
        ent = "robot"
        if target and target[0] == "link" and target[1] in paths:
            ent = paths[target[1]]
        elif target and target[0] == "joint" and target[1] in joint_paths:
            ent = joint_paths[target[1]]
        where = relative_text(fd.file, base) if fd.file else "<unknown>"
        text = f"{fd.code} {relative_text(fd.message, base)} ({where}:{fd.line})"
        log(f"{ent}/findings/{n}", rr.TextLog(text, level=levels.get(fd.severity, "WARN")),
            static=True)
        log(f"{ent}/findings/{n}", rr.Points3D([[0, 0, 0]], radii=[0.01 * size],
                                               colors=[[230, 30, 30]], labels=[fd.code]),
            static=True)


def record_findings(findings, paths, joint_paths, path, recording_id, prefix="", base=None,
                    size=1.0):
    """A recording of ``findings`` alone, with the same entity paths and recording id as the
    model's (written by the parent once the run's findings are final; merged into the
    model's recording)."""
    import rerun as rr
    from .atomic import atomic_path
    with atomic_path(path) as tmp:
        rec = rr.RecordingStream("urdf-lint", recording_id=recording_id, send_properties=False)
        rec.save(tmp)
        log_findings(lambda entity, *a, **kw: rec.log(prefix + entity, *a, **kw), findings,
                     paths, joint_paths, base, size)
        rec.flush()
        rec.disconnect()


def _sweep(model):
    """The joint sweep of ``model`` (yourdfpy kinematics), or None without yourdfpy."""
    try:
        from .sweep import build_urdf, plan
    except ImportError:
        return None
    try:
        import yourdfpy  # noqa: F401
    except ImportError:
        return None
    urdf = build_urdf(model.root)
    return plan(urdf) if urdf is not None else None


def _log_sweep(rec, rr, prefix, sweep, joint_paths):
    """Per moving joint, its transform at every step it changes, as columns on the
    ``joint_sweep`` timeline (in both the /robot and the /collision tree); the joint each
    segment moves as a text log on /sweep."""
    from .sweep import TIMELINE
    per_joint: dict = {}
    for step in sorted(sweep.frames):
        for name, T in sweep.frames[step].items():
            per_joint.setdefault(name, []).append((step, T))
    for name, rows in per_joint.items():
        if name not in joint_paths:
            continue
        steps = [s for s, _ in rows]
        Ts = np.asarray([T for _, T in rows], dtype=float)
        for root in ("robot", "collision"):
            jp = root + joint_paths[name][len("robot"):]
            rec.send_columns(prefix + jp, indexes=[rr.TimeColumn(TIMELINE, sequence=steps)],
                             columns=rr.Transform3D.columns(translation=Ts[:, :3, 3],
                                                            mat3x3=Ts[:, :3, :3]))
    if sweep.segments:
        seg = sweep.segments
        rec.send_columns(prefix + "sweep",
                         indexes=[rr.TimeColumn(TIMELINE, sequence=[s.start for s in seg])],
                         columns=rr.TextLog.columns(
                             text=[f"sweep {s.joint}" + (f" (+ {', '.join(s.followers)})"
                                                         if s.followers else "") for s in seg],
                             level=["INFO"] * len(seg)))


def _import_rerun():
    try:
        import rerun  # noqa: F401
    except Exception:  # noqa: BLE001 - reported by render_model when it imports again
        pass
