"""The joint sweep of a recording: each movable joint moves through its range in turn, its
mimic joints following, with the configuration-dependent kinematics done by yourdfpy.

yourdfpy is given the already expanded ``<robot>`` element and never a file: meshes are not
loaded (``load_meshes=False``) and its ``filename_handler`` refuses, so every file read stays
with the confined package resolver (SECURITY.md). Imported only when a recording is made.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, NoReturn

import numpy as np

MOVABLE = ("revolute", "continuous", "prismatic")
STEPS = 24          # samples of one segment: lower -> upper -> lower (then back to rest)
TIMELINE = "joint_sweep"

# a yourdfpy URDF, its joints, an lxml element (neither library ships type information here)
URDF = Any
Element = Any


def _refuse(fname: str | None = None, **_: Any) -> NoReturn:
    raise PermissionError("urdf-lint: yourdfpy may not resolve files; meshes come from the "
                          "confined package resolver")


def build_urdf(root: Element) -> URDF | None:
    """A yourdfpy URDF of the expanded ``<robot>`` element (a scene graph, no geometry read),
    or None when yourdfpy cannot take the model (a malformed joint, for example)."""
    import yourdfpy

    from urdf_lint.meshes.resolve import quiet_libraries
    quiet_libraries()   # "link not connected", a mimic of itself: the lint rules say that
    try:
        robot = yourdfpy.URDF._parse_robot(xml_element=root)
        return yourdfpy.URDF(robot=robot, build_scene_graph=True,
                             build_collision_scene_graph=False, load_meshes=False,
                             load_collision_meshes=False, filename_handler=_refuse)
    except PermissionError:
        raise
    except Exception:  # noqa: BLE001 - no sweep for a model yourdfpy cannot read
        return None


def link_poses(urdf: URDF) -> dict[str, np.ndarray]:
    """link -> world (base frame) transform at the current configuration."""
    return {lk.name: np.asarray(urdf.get_transform(lk.name), dtype=float)
            for lk in urdf.robot.links if lk.name in urdf.scene.graph.nodes}


@dataclass
class Segment:
    """One joint moving through its range on the joint_sweep timeline, with its mimic followers."""
    joint: str
    followers: list[str]       # the mimic joints that move with it
    start: int                 # first step on the timeline
    end: int                   # last step (the joint is back at rest there)
    values: list[float]        # the joint's value per step, start..end


@dataclass
class Sweep:
    """The joint_sweep timeline: segments, and the joint transforms at each step."""
    segments: list[Segment] = field(default_factory=list)
    # step -> {joint name: 4x4 transform parent link -> child link}; step 0 holds every
    # movable and mimic joint at rest, later steps only the joints whose transform changed
    frames: dict[int, dict[str, np.ndarray]] = field(default_factory=dict)

    @property
    def joints(self) -> set[str]:
        return {j for f in self.frames.values() for j in f}


def _range(joint: Any) -> tuple[float, float] | None:
    if joint.type == "continuous":
        return -math.pi, math.pi
    lim = joint.limit
    lo = getattr(lim, "lower", None) if lim is not None else None
    hi = getattr(lim, "upper", None) if lim is not None else None
    if lo is None or hi is None or not (math.isfinite(lo) and math.isfinite(hi)):
        return None
    if hi <= lo:
        return None   # no range to show
    return float(lo), float(hi)


def plan(urdf: URDF, steps: int = STEPS) -> Sweep:
    """Sweep every actuated revolute/prismatic/continuous joint (document order) in turn."""
    sweep = Sweep()
    joints = {j.name: j for j in urdf.robot.joints}
    moving = [j for j in urdf.robot.joints if j.type in MOVABLE and j.mimic is None
              and j.name in urdf.actuated_joint_names]
    mimics = [j for j in urdf.robot.joints if j.mimic is not None and j.type in MOVABLE]
    ranges = {j.name: _range(j) for j in moving}
    rest = {j.name: (min(max(0.0, r[0]), r[1]) if r else 0.0) for j, r in
            ((j, ranges[j.name]) for j in moving)}
    urdf.update_cfg(dict(rest)) if rest else None
    tracked = [j.name for j in moving] + [j.name for j in mimics]

    def local(name: str) -> np.ndarray:
        j = joints[name]
        return np.asarray(urdf.scene.graph.get(frame_to=j.child, frame_from=j.parent)[0],
                          dtype=float)
    current = {n: local(n) for n in tracked}
    sweep.frames[0] = dict(current)
    step = 1
    half = max(2, steps // 2)
    for j in moving:
        r = ranges[j.name]
        if r is None:
            continue
        lo, hi = r
        up = np.linspace(lo, hi, half + 1)
        values = list(up) + list(up[::-1][1:]) + [rest[j.name]]
        start = step
        for q in values:
            urdf.update_cfg({j.name: float(q)})
            changed: dict[str, np.ndarray] = {}
            for n in tracked:
                T = local(n)
                if not np.allclose(T, current[n], rtol=0, atol=1e-12):
                    changed[n] = T
                    current[n] = T
            sweep.frames[step] = changed
            step += 1
        followers = sorted({n for s in range(start, step) for n in sweep.frames[s]} - {j.name})
        sweep.segments.append(Segment(j.name, followers, start, step - 1,
                                      [float(v) for v in values]))
    return sweep
