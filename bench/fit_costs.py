"""Fit the scheduler's first-time cost estimates (``urdf_lint.runner.pool``: ``JOB_COST_S``,
``XACRO_ELEMENT_COST_S``, ``STL_COST_S_PER_MB``, ``MESH_COST_S_PER_MB``) to measured times.

    python bench/fit_costs.py [PATH ...]     (default: the corpus, as bench_heavy.py lints it,
                                              and a heavy repository from heavy_repo.py)

Each path is discovered as ``urdf-lint check`` discovers it, its models are linted one after
the other in this process (as one worker does: a package's meshes measured once, no result
cache, no mesh facts store), and each package block's time is set against its features: its
models, the xacro elements of their entry files, and the megabytes of binary STL and of other
meshes under the package. Prints the least-squares coefficients, and each package's time
beside both estimates. The workers are scheduled costliest block first (``pool.assign``): what
matters is that the estimates rank and weigh packages as their times do.
"""
from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "bench"))


def features(block) -> list[float]:
    stl = other = 0.0
    if block.key:
        for folder, _, files in os.walk(block.key):
            for f in files:
                low = f.lower()
                if low.endswith((".stl", ".dae", ".obj", ".ply", ".glb", ".gltf")):
                    mb = os.path.getsize(os.path.join(folder, f)) / 2**20
                    if low.endswith(".stl"):
                        stl += mb
                    else:
                        other += mb
    elements = sum(Path(j.entry).read_bytes().count(b"<xacro:") for j in block.jobs
                   if Path(j.entry).is_file())
    return [len(block.jobs), elements, stl, other]


def measure(paths: list[str], config: str | None) -> list[tuple[str, list[float], float, float]]:
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver, discover
    from urdf_lint.engine.lint import run_job
    from urdf_lint.meshes import resolve
    from urdf_lint.run.pipeline import settings_for
    from urdf_lint.runner import pool
    cfg = load_config(Path(config) if config else None)
    resolver = build_resolver(paths, cfg)
    jobs = discover(paths, cfg, resolver)
    settings = settings_for(cfg, resolver, None)
    rows = []
    for block in pool.package_blocks(jobs, settings):
        for memo in (resolve._memory, resolve._mass_memory, resolve._arrays_memo):
            memo.clear()
        t = time.process_time()
        for job in block.jobs:
            run_job(job, settings)
        rows.append((block.key, features(block), time.process_time() - t, block.cost))
    return rows


def main() -> None:
    from urdf_lint.runner import pool
    sets: list[tuple[list[str], str | None]] = []
    tmp = Path(tempfile.mkdtemp(prefix="urdf-lint-fit-"))
    if len(sys.argv) > 1:
        sets = [([p], None) for p in sys.argv[1:]]
    else:
        from bench import entries, write_config
        from heavy_repo import generate
        corpus = (REPO.parent / "shared" / "corpus").resolve()
        if (corpus / "entries.json").is_file():
            models = entries(corpus)
            config = tmp / "corpus.toml"
            write_config(config, models)
            sets.append((sorted({str(f) for f, _ in models}), str(config)))
        generate(tmp / "heavy", packages=6, stl_triangles=200_000)
        sets.append(([str(tmp / "heavy" / "src")], None))
    rows = [r for paths, config in sets for r in measure(paths, config)]
    x = np.array([r[1] for r in rows])
    y = np.array([r[2] for r in rows])
    coef, *_ = np.linalg.lstsq(x, y, rcond=None)
    now = [pool.JOB_COST_S, pool.XACRO_ELEMENT_COST_S, pool.STL_COST_S_PER_MB,
           pool.MESH_COST_S_PER_MB]
    names = ["JOB_COST_S", "XACRO_ELEMENT_COST_S", "STL_COST_S_PER_MB", "MESH_COST_S_PER_MB"]
    print(f"{len(rows)} package blocks, {y.sum():.2f} s measured")
    for name, c, n in zip(names, coef, now, strict=True):
        print(f"  {name:22s} fitted {c:.5f}   in use {n:.5f}")
    print(f"\n{'package':32s} {'measured':>9s} {'in use':>8s} {'fitted':>8s}")
    for key, feat, took, _ in sorted(rows, key=lambda r: -r[2])[:20]:
        print(f"{os.path.basename(key) or '(none)':32.32s} {took:9.3f} "
              f"{float(np.dot(feat, now)):8.3f} {float(np.dot(feat, coef)):8.3f}")


if __name__ == "__main__":
    main()
