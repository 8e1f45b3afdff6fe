"""One consumer, loading the robot descriptions named on standard input, one verdict a line.

``python worker.py CONSUMER`` reads paths (one a line) and writes, for each, one JSON line
``{"v": ".", "msg": ""}`` (loads) or ``{"v": "R", "msg": "..."}`` (rejects: the consumer raised
or returned failure) on the file descriptor it was given as ``--out FD`` (default: a copy of
standard output taken before the consumer is imported, standard output itself being sent to
standard error, because consumers print there). A crash (a segfault) ends the process: the
harness (``harness.py``) records it as ``C`` and starts a new worker for the next file.

Nothing here is imported by urdf-lint: it is run by the harness only.
"""
from __future__ import annotations

import json
import os
import sys


def _mujoco():
    import mujoco

    def load(path):
        m = mujoco.MjModel.from_xml_path(path)
        d = mujoco.MjData(m)
        mujoco.mj_step(m, d)
    return load, mujoco.__version__


def _pinocchio():
    import numpy as np
    import pinocchio as pin

    def load(path):
        model = pin.buildModelFromUrdf(path)
        for kind in (pin.GeometryType.COLLISION, pin.GeometryType.VISUAL):
            pin.buildGeomFromUrdf(model, path, kind, package_dirs=[os.path.dirname(path)])
        data = model.createData()
        q = pin.neutral(model)
        pin.computeAllTerms(model, data, q, np.zeros(model.nv))
        pin.aba(model, data, q, np.zeros(model.nv), np.zeros(model.nv))
    return load, pin.__version__


def _pybullet():
    import pybullet as p
    p.connect(p.DIRECT)

    def load(path):
        p.resetSimulation()
        p.loadURDF(path)
        for _ in range(240):
            p.stepSimulation()
    from importlib.metadata import version
    return load, version("pybullet")


def _drake():
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.systems.framework import DiagramBuilder

    def load(path):
        builder = DiagramBuilder()
        plant, scene_graph = AddMultibodyPlantSceneGraph(builder, 0.0)
        Parser(plant).AddModels(path)
        plant.Finalize()
        diagram = builder.Build()
        context = diagram.CreateDefaultContext()
        query = scene_graph.get_query_output_port().Eval(
            scene_graph.GetMyContextFromRoot(context))
        query.ComputePointPairPenetration()
        plant.CalcMassMatrix(plant.GetMyContextFromRoot(context))
    from importlib.metadata import version
    return load, version("drake")


def _yourdfpy():
    import yourdfpy

    def load(path):
        yourdfpy.URDF.load(path, build_scene_graph=True, load_meshes=True,
                           load_collision_meshes=True)
    from importlib.metadata import version
    return load, version("yourdfpy")


def _urdf_parser_py(dist="urdfdom-py"):
    import urdf_parser_py
    from urdf_parser_py.urdf import URDF

    def load(path):
        with open(path, "rb") as f:          # as from_xml_file does: bytes, not str
            URDF.from_xml_string(f.read())
    from importlib.metadata import PathDistribution
    from pathlib import Path
    # the distribution beside the module that was imported (0.0.4 shadows urdfdom-py)
    site = Path(urdf_parser_py.__file__).parents[1]
    info = [d for d in site.glob("*.dist-info") if d.name.lower().replace("-", "_").startswith(
        dist.replace("-", "_"))]
    if not info:
        raise ImportError(f"{dist} is not what imports as urdf_parser_py ({site})")
    return load, PathDistribution(info[0]).version


def _urchin():
    import urchin

    def load(path):
        urchin.URDF.load(path)
    from importlib.metadata import version
    return load, version("urchin")


def _idyntree():
    import idyntree.bindings as idt

    def load(path):
        loader = idt.ModelLoader()
        if not loader.loadModelFromFile(path):
            raise RuntimeError("ModelLoader.loadModelFromFile returned false")
    from importlib.metadata import version
    return load, version("idyntree")


def _isaac():
    """Isaac Sim 6's URDF importer as a package: urdf-usd-converter with its default settings
    (layer structure and a physics scene), into a scratch folder that is emptied each time."""
    import shutil
    import tempfile

    from urdf_usd_converter import Converter
    out = tempfile.mkdtemp(prefix="ul-isaac-")

    def load(path):
        shutil.rmtree(out, ignore_errors=True)
        Converter().convert(path, out)
    from importlib.metadata import version
    return load, version("urdf-usd-converter")


def _isaac_isolated():
    """Isaac Sim 6's URDF importer itself, from the package index (``isaacsim-asset-isolated``:
    ``URDFImporter`` with its default ``URDFImporterConfig``, which runs urdf-usd-converter and
    then Isaac Sim's own passes: fixed-joint merging, drives, the MuJoCo-PhysX conversion),
    into a scratch folder that is emptied each time."""
    import shutil
    import tempfile

    from isaacsim.asset.importer.urdf import URDFImporter, URDFImporterConfig
    out = tempfile.mkdtemp(prefix="ul-isaac-isolated-")

    def load(path):
        shutil.rmtree(out, ignore_errors=True)
        os.makedirs(out)
        URDFImporter(URDFImporterConfig(urdf_path=path, usd_path=out)).import_urdf()
    from importlib.metadata import version
    return load, version("isaacsim-asset-isolated")


def _check_urdf():
    """urdfdom's check_urdf (Debian's liburdfdom-tools), one process per file."""
    import shutil
    import subprocess
    exe = shutil.which("check_urdf")
    if exe is None:
        raise ImportError("check_urdf is not installed (apt-get install liburdfdom-tools)")

    def load(path):
        p = subprocess.run([exe, path], capture_output=True, text=True, timeout=50)
        if p.returncode < 0:
            return {"v": "C", "msg": f"check_urdf died (signal {-p.returncode})"}
        if p.returncode != 0:
            raise RuntimeError((p.stderr or p.stdout).strip()[-300:])
        return None
    ver = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "liburdfdom-tools"],
                         capture_output=True, text=True).stdout.strip() or "unknown"
    return load, ver


LOADERS = {"mujoco": _mujoco, "pinocchio": _pinocchio, "pybullet": _pybullet, "drake": _drake,
           "yourdfpy": _yourdfpy, "urdf_parser_py": _urdf_parser_py,
           "urdf_parser_py_0.0.4": lambda: _urdf_parser_py("urdf_parser_py"),
           "urchin": _urchin, "idyntree": _idyntree, "isaac": _isaac,
           "isaac_isolated": _isaac_isolated, "check_urdf": _check_urdf}


def main() -> int:
    which = sys.argv[1]
    out = os.fdopen(os.dup(1), "w", buffering=1)
    os.dup2(2, 1)          # the consumers' own prints go to standard error
    try:
        load, ver = LOADERS[which]()
    except Exception as e:  # not installed, or does not import here
        out.write(json.dumps({"unavailable": f"{type(e).__name__}: {e}"}) + "\n")
        return 0
    out.write(json.dumps({"version": ver}) + "\n")
    for line in sys.stdin:
        path = line.strip()
        if not path:
            continue
        os.chdir(os.path.dirname(path))    # MuJoCo writes MUJOCO_LOG.TXT into the cwd
        try:
            res = load(path) or {"v": ".", "msg": ""}
        except BaseException as e:          # noqa: BLE001  (a consumer's refusal, any type)
            res = {"v": "R", "msg": f"{type(e).__name__}: {str(e)[:300]}"}
        out.write(json.dumps(res) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
