"""What the consumer-target mesh rules share (UL409, UL410): which meshes MuJoCo and Drake
load, and what MuJoCo's decoders reject."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, Iterator

from urdf_lint.engine.api import binary_stl_triangles, read_head
from urdf_lint.rules._meshes import resolved_meshes

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.engine.api import Context, Model

MUJOCO_FORMATS = (".stl", ".obj", ".msh")
MUJOCO_STL_FACES = 200000            # MuJoCo 4.0.0's stl_decoder: 1 to 200000 triangles
DRAKE_FORMATS = (".obj", ".vtk", ".gltf")      # Drake 1.51.1 rejects .glb collision meshes


def mujoco_keeps_visuals(model: Model) -> bool:
    """Whether the description's own ``<mujoco><compiler discardvisual="false"/>`` makes MuJoCo
    load its visuals (MuJoCo discards a URDF's visuals by default)."""
    return any(c.get("discardvisual", "").strip().lower() == "false"
               for c in model.root.iterfind("mujoco/compiler"))


def mujoco_problem(path: str, ext: str) -> str | None:
    if ext not in MUJOCO_FORMATS:
        return f"MuJoCo has no decoder for {ext or 'a file without extension'}"
    if ext != ".stl":
        return None
    n = binary_stl_triangles(path)
    if n is not None:
        return (None if 1 <= n <= MUJOCO_STL_FACES else
                f"MuJoCo reads at most {MUJOCO_STL_FACES} triangles from an STL, it has {n}")
    head = read_head(path, 5)            # (None: UL401/UL404 say why)
    return "MuJoCo reads binary STL only, this one is ASCII" if head == b"solid" else None


def geometry_meshes(model: Model, ctx: Context) -> Iterator[tuple[Any, str, str, str]]:
    """(mesh element, uri, path, "collision" or "visual") for every resolved mesh of a link."""
    for m, uri, path in resolved_meshes(model, ctx):
        geom = m.getparent().getparent() if m.getparent() is not None else None
        if geom is not None and geom.tag in ("collision", "visual"):
            yield m, uri, path, geom.tag


def wanted(model: Model, ctx: Context, targets: tuple[str, ...]) -> bool:
    """Whether a finding of a rule that only ``targets`` make more than off (and the model's own
    ``<mujoco>`` block makes info) can be kept in this run: else the rule has nothing to do."""
    return any(t in ctx.targets for t in targets) or model.root.find("mujoco") is not None


def mujoco_loads(model: Model) -> tuple[set[str], str]:
    """(the kinds of geometry MuJoCo decodes the meshes of, the severity of its findings for
    the other targets: ``info`` when the description's own ``<mujoco>`` block says MuJoCo
    loads it, else ``off``)."""
    kinds = {"collision", "visual"} if mujoco_keeps_visuals(model) else {"collision"}
    return kinds, "info" if model.root.find("mujoco") is not None else "off"
