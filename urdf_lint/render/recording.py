"""The rerun recording (.rrd) of a snapshot: the entity tree follows the kinematic tree, visual
and collision geometry on their own subtrees, findings on the link or joint they concern. Static
data only, a fixed recording id: deterministic.
"""
from __future__ import annotations

import os
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Iterable, Sequence

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.core.findings import Problem
    from urdf_lint.engine.lint import Context
    from urdf_lint.engine.model import Model
    from urdf_lint.render.scene import MeshArrays, Part, Scene
    from urdf_lint.render.sweep import Sweep

import numpy as np

from urdf_lint.core.jobs import DEFAULT_MEMORY_MB
# (re-exported: where they are used from)
from urdf_lint.core.locations import label_base as label_base, relative_label as relative_label
from urdf_lint.engine.api import numbers
from urdf_lint.render.scene import origin_matrix, part_mesh


# -- rerun recording -------------------------------------------------------------------------
def entity_paths(scene: "Scene") -> tuple[dict[str, str], dict[str, str]]:
    """link -> entity path following the kinematic tree: /robot/<root>/<joint>/<child>/..."""
    paths = {r: f"robot/{_safe(r)}" for r in scene.roots}
    joints: dict[str, str] = {}
    for parent, j, child in scene.tree:
        jp = f"{paths[parent]}/{_safe(j.get('name') or 'joint')}"
        joints[j.get("name")] = jp
        paths[child] = f"{jp}/{_safe(child)}"
    return paths, joints


def _safe(s: object) -> str:
    return "".join(ch if ch.isalnum() or ch in "_-." else "_" for ch in str(s)) or "_"


def record_rrd(scene: "Scene", ctx: "Context", path: str, recording_id: str, prefix: str = "",
               model: "Model | None" = None, base: str | None = None) -> dict[str, Any]:
    """Log ``scene`` to ``path`` (its findings are added by the parent later,
    :func:`record_findings`); ``prefix`` (e.g. ``"head/"``) puts every entity under one root.
    With ``model`` the recording gets the ``joint_sweep`` timeline; ``base`` is what file
    names in labels are relative to."""
    from urdf_lint.core import fsbound  # the snapshot folder, checked by the CLI (and Landlock here)
    if model is not None:
        base = label_base(model.entry)
    plan = plan_rrd(scene, ctx, model, base)
    with fsbound.temp_path(path, os.path.dirname(os.path.abspath(path))) as tmp:
        write_rrd(tmp, recording_id, [(prefix, plan)])
    return plan_facts(plan)


def robot_size(scene: "Scene", meshes: Sequence[tuple["Part", "MeshArrays | None"]]) -> float:
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


def blueprint_for(prefixes: Sequence[str] = ("",)) -> Any:   # a rerun Blueprint
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
    from urdf_lint.core.locations import display_path

    def sub(m: "re.Match[str]") -> str:
        p = m.group(0)
        rel = display_path(p, base) if base else p
        return (os.path.basename(p.rstrip("/")) or p) if os.path.isabs(rel) else rel
    return _ABS.sub(sub, text or "")


@dataclass
class Plan:
    """What a recording logs for one robot, as plain data (entity paths, numpy arrays,
    strings), in logging order: made where the meshes may be read (a worker), written where
    rerun is imported (:func:`write_rrd`, possibly another process, with other revisions)."""
    ops: list[tuple[Any, ...]]
    paths: dict[str, str]      # link -> entity path
    joint_paths: dict[str, str]   # joint -> entity path
    size: float                # the robot's extent (m): axes and markers scale with it
    meshes: int                # meshes logged
    sweep_segments: int | None = None


def plan_facts(plan: Plan) -> dict[str, Any]:
    out: dict[str, Any] = {"meshes": plan.meshes, "robot_size": plan.size}
    if plan.sweep_segments is not None:
        out["sweep_segments"] = plan.sweep_segments
    return out


def plan_rrd(scene: "Scene", ctx: "Context", model: "Model | None" = None,
             base: str | None = None) -> Plan:
    """The :class:`Plan` of ``scene``: the kinematic tree twice, /robot (frames, axes,
    visuals) and /collision (collision geometry only, so that it toggles as one subtree);
    with ``model``, the ``joint_sweep`` timeline; ``base`` is what file names in labels are
    relative to."""
    paths, joint_paths = entity_paths(scene)
    meshes = [(part, part_mesh(part, ctx) if part.shape != "missing" else None)
              for part in scene.parts]
    size = robot_size(scene, meshes)
    sweep = _sweep(model) if model is not None else None
    moving = sweep.joints if sweep is not None else set()
    ops: list[tuple[Any, ...]] = []
    # joints the sweep moves get their transform on the joint_sweep timeline instead (static
    # data would hide it)
    for root in ("robot", "collision"):
        for _parent, j, _child in scene.tree:
            if j.get("name") in moving:
                continue
            T = origin_matrix(j)
            ops.append(("transform", root + joint_paths[j.get("name")][len("robot"):],
                        T[:3, 3].copy(), T[:3, :3].copy()))
    if sweep is not None:
        ops.extend(_sweep_ops(sweep, joint_paths))
    for _parent, j, child in scene.tree:
        if j.get("type") not in ("fixed", None):
            ax = j.find("axis")
            axis = numbers(ax.get("xyz") if ax is not None else "1 0 0", 3) or [1, 0, 0]
            ops.append(("axis", f"{paths[child]}/joint_axis", np.asarray(axis) * 0.15 * size,
                        j.get("name") or ""))
    for _link, p in paths.items():
        ops.append(("axes", p, 0.06 * size))
    logged = 0
    for part, got in meshes:
        root = "robot" if part.kind == "visual" else "collision"
        base_ent = f"{root}{paths[part.link][len('robot'):]}/{part.kind}/{part.index}"
        ops.append(("transform", base_ent, part.local[:3, 3].copy(), part.local[:3, :3].copy()))
        if got is None:
            ops.append(("missing", f"{base_ent}/missing", 0.02 * size,
                        relative_text(part.problem, base) or "missing geometry"))
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
        ops.append(("mesh", f"{base_ent}/mesh", kwargs))
        logged += 1
    return Plan(ops, paths, joint_paths, size, logged,
                len(sweep.segments) if sweep is not None else None)


def write_rrd(path: str, recording_id: str, plans: Sequence[tuple[str, Plan]],
              blueprint: bool | Sequence[str] = True) -> None:
    """Write ``plans`` (``(prefix, Plan)`` pairs: one per revision, ``"base/"`` and
    ``"head/"``, or ``("", plan)``) to ``path`` as one recording. ``blueprint``: True for a
    view of each plan's root, or the prefixes to give a view each (``("base/", "head/")``:
    a model added or removed by the change still shows its empty side)."""
    import rerun as rr
    rec = rr.RecordingStream("urdf-lint", recording_id=recording_id, send_properties=False)
    rec.save(path)
    if blueprint:
        prefixes = tuple(p for p, _ in plans) if blueprint is True else tuple(blueprint)
        rec.send_blueprint(blueprint_for(prefixes), make_active=True, make_default=True)
    rec.log("/", rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
    for prefix, plan in plans:
        _log_plan(rec, rr, prefix, plan)
    rec.flush()
    rec.disconnect()


def _log_plan(rec: Any, rr: Any, prefix: str, plan: Plan) -> None:   # rerun's objects
    for op in plan.ops:
        kind, entity = op[0], prefix + op[1]
        if kind == "transform":
            rec.log(entity, rr.Transform3D(translation=op[2], mat3x3=op[3]), static=True)
        elif kind == "columns":
            rec.send_columns(entity, indexes=[rr.TimeColumn(op[2], sequence=op[3])],
                             columns=rr.Transform3D.columns(translation=op[4], mat3x3=op[5]))
        elif kind == "textlog_columns":
            rec.send_columns(entity, indexes=[rr.TimeColumn(op[2], sequence=op[3])],
                             columns=rr.TextLog.columns(text=op[4], level=op[5]))
        elif kind == "axis":
            rec.log(entity, rr.Arrows3D(origins=[[0, 0, 0]], vectors=[op[2]],
                                        colors=[[250, 200, 0]], labels=[op[3]]), static=True)
        elif kind == "axes":
            rec.log(entity, rr.TransformAxes3D(op[2]), static=True)
        elif kind == "missing":
            h = op[2]
            rec.log(entity, rr.Boxes3D(half_sizes=[[h, h, h]], colors=[[230, 30, 30]],
                                       labels=[op[3]]), static=True)
        elif kind == "mesh":
            rec.log(entity, rr.Mesh3D(**op[2]), static=True)
        else:  # pragma: no cover - a plan only holds the kinds above
            raise ValueError(f"unknown recording op {kind!r}")


def log_findings(log: Any, findings: Iterable["Problem"], paths: dict[str, str],
                 joint_paths: dict[str, str], base: str | None = None, size: float = 1.0) -> None:
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


def record_findings(findings: Iterable["Problem"], paths: dict[str, str],
                    joint_paths: dict[str, str], path: str, recording_id: str, prefix: str = "",
                    base: str | None = None,
                    size: float = 1.0) -> None:
    """A recording of ``findings`` alone, with the same entity paths and recording id as the
    model's (written by the parent once the run's findings are final; merged into the
    model's recording)."""
    import rerun as rr
    from urdf_lint.core import fsbound
    with fsbound.temp_path(path, os.path.dirname(os.path.abspath(path))) as tmp:
        rec = rr.RecordingStream("urdf-lint", recording_id=recording_id, send_properties=False)
        rec.save(tmp)
        log_findings(lambda entity, *a, **kw: rec.log(prefix + entity, *a, **kw), findings,
                     paths, joint_paths, base, size)
        rec.flush()
        rec.disconnect()


def _sweep(model: "Model") -> "Sweep | None":
    """The joint sweep of ``model`` (yourdfpy kinematics), or None without yourdfpy."""
    try:
        from urdf_lint.render.sweep import build_urdf, plan
    except ImportError:
        return None
    try:
        import yourdfpy  # noqa: F401
    except ImportError:
        return None
    urdf = build_urdf(model.root)
    return plan(urdf) if urdf is not None else None


def _sweep_ops(sweep: "Sweep", joint_paths: dict[str, str]) -> list[tuple[Any, ...]]:
    """Per moving joint, its transform at every step it changes, as columns on the
    ``joint_sweep`` timeline (in both the /robot and the /collision tree); the joint each
    segment moves as a text log on /sweep."""
    from urdf_lint.render.sweep import TIMELINE
    ops: list[tuple[Any, ...]] = []
    per_joint: dict[str, list[tuple[int, np.ndarray]]] = {}
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
            ops.append(("columns", jp, TIMELINE, steps, Ts[:, :3, 3], Ts[:, :3, :3]))
    if sweep.segments:
        seg = sweep.segments
        ops.append(("textlog_columns", "sweep", TIMELINE, [s.start for s in seg],
                    [f"sweep {s.joint}" + (f" (+ {', '.join(s.followers)})" if s.followers else "")
                     for s in seg], ["INFO"] * len(seg)))
    return ops


def _import_rerun() -> None:
    try:
        import rerun  # noqa: F401
    except Exception:  # noqa: BLE001 - reported by render_model when it imports again
        pass


# -- a process that writes recordings ----------------------------------------------------------
class Recorder:
    """A child process that imports rerun at once (~0.4 s, while the run discovers and lints)
    and then writes recordings from :class:`Plan` s: ``urdf-lint diff --render`` writes both
    revisions of a model into one .rrd there, so no worker imports rerun and no half
    recording is merged. It reads no file: it gets plain data and writes where it is told
    (the snapshot folder), like the parent it was forked from. Forked before any worker or
    thread of the run, so no import or lock is half-held in it."""

    def __init__(self, out_dir: str, memory_mb: int = DEFAULT_MEMORY_MB) -> None:
        from urdf_lint.runner import forked
        self.out_dir = os.path.realpath(out_dir)
        # (its answers are plain data: ``allowed=frozenset()``)
        self.conn, self.proc = forked.start(_recorder_main, (os.getpid(), self.out_dir, memory_mb),
                                            allowed=frozenset())
        self.pending: list[str] = []
        self.failed: list[str] = []      # recordings that could not be sent (the recorder is gone)
        self._queue: Any = None
        self._sender: Any = None

    def write(self, path: str, recording_id: str, plans: Sequence[tuple[str, Plan]],
              blueprint: bool | Sequence[str] = True) -> None:
        """Queue a recording (:func:`write_rrd`) to ``path``; :meth:`results` says how it went.
        Returns at once: one thread sends the plans in order (a plan is larger than the pipe,
        and the recorder may still be importing rerun or writing the previous one)."""
        if self._sender is None:
            import queue
            import threading
            self._queue = queue.SimpleQueue()
            self._sender = threading.Thread(target=self._send_all, name="urdf-lint-recorder",
                                            daemon=True)
            self._sender.start()
        self.pending.append(path)
        self._queue.put((path, recording_id, plans, blueprint))

    def _send_all(self) -> None:
        while (msg := self._queue.get()) is not None:
            try:
                self.conn.send(msg)
            except OSError:
                self.failed.append(msg[0])

    def _gone(self) -> str:
        self.proc.join(0.5)
        return f"the recorder died (exit code {self.proc.exitcode})"

    def results(self, timeout: float = 120.0) -> dict[str, str | None]:
        """path -> None (written) or why not ("rerun-sdk is not installed", an error), for
        every queued recording."""
        from urdf_lint.runner import forked
        if self._sender is not None:
            self._queue.put(None)          # every plan queued so far, then the thread ends
            self._sender.join(timeout)
            if self._sender.is_alive():    # stuck sending: the recorder reads nothing
                out: dict[str, str | None] = {
                    p: f"the recorder did not answer within {timeout:g} s" for p in self.pending}
                self.pending = []
                return out
            self._sender = None
        out = {path: self._gone() for path in self.failed}
        self.pending = [p for p in self.pending if p not in out]
        self.failed = []
        while self.pending:
            if not forked.wait([self.conn], timeout):
                why = f"the recorder did not answer within {timeout:g} s"
                break
            try:
                path, why = self.conn.recv()
            except (EOFError, OSError):
                why = self._gone()
                break
            out[path] = why
            self.pending.remove(path)
        else:
            return out
        out.update((p, why) for p in self.pending)   # the recorder is stuck or gone
        self.pending = []
        return out

    def close(self) -> None:
        from urdf_lint.runner import forked
        if self._sender is not None and self._sender.is_alive():
            self.proc.kill()   # stuck reading a plan: no end message through a half-sent one
            self.proc.join(1)
            self.conn.close()
        else:
            forked.stop(self.conn, self.proc, 2)


NO_RERUN = "rerun-sdk is not installed (pip install 'urdf-lint[render]')"


def write_recording(path: str, recording_id: str, plans: Sequence[tuple[str, Plan]],
                    blueprint: bool | Sequence[str] = True) -> str | None:
    """:func:`write_rrd` to ``path`` (atomically): None when written, else why not
    (:data:`NO_RERUN`, or the error)."""
    try:
        import rerun  # noqa: F401
    except ImportError:
        return NO_RERUN
    from urdf_lint.core import fsbound
    try:
        with fsbound.temp_path(path, os.path.dirname(os.path.abspath(path)), ".rrd") as tmp:
            write_rrd(tmp, recording_id, plans, blueprint)
    except Exception as e:  # noqa: BLE001 - said in the snapshot's problems
        return f"{type(e).__name__}: {e}"
    return None


def _recorder_main(conn: Any, parent_pid: int, out_dir: str, memory_mb: int) -> None:
    """The recorder: hardened like a worker (memory limit, scrubbed environment, then
    Landlock, seccomp and the audit hook: it reads no file of the repository and writes only
    into ``out_dir``, the folder the user named)."""
    import signal
    signal.signal(signal.SIGINT, signal.SIG_IGN)    # the parent stops it
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    try:
        from urdf_lint.runner.sandbox import set_parent_death_signal
        set_parent_death_signal(parent_pid)
    except Exception:  # noqa: BLE001 - it also ends when the parent's end of the pipe closes
        pass
    from urdf_lint.runner.hardening import (confine_writer, inherited_data_bytes, limit_memory,
                                            scrub_environment)
    from urdf_lint.runner.sandbox import close_inherited_fds, warm
    close_inherited_fds(getattr(conn, "fds", None) or (conn.fileno(),))
    limit_memory(memory_mb, inherited_data_bytes(), rerun=True)
    warm()   # (the sandbox's own imports, before the environment is scrubbed)
    scrub_environment(set())
    try:
        import rerun  # noqa: F401 - while the first plan is made
    except ImportError:
        pass
    from urdf_lint.runner import forked
    confined = False
    for path, recording_id, plans, blueprint in forked.messages(conn):
        if os.path.dirname(os.path.realpath(path)) != out_dir:
            conn.send((path, "not in the output folder; not written"))
            continue
        if not confined:   # (the folder exists once the run has cleared it for its pictures)
            confine_writer(out_dir)
            confined = True
        conn.send((path, write_recording(path, recording_id, plans, blueprint)))
