"""Snapshot cost per model, in process (rerun already imported), on corpus robots:

    .venv/bin/python bench/bench_render.py [--corpus DIR]

For each robot: lint cold (meshes parsed), lint again (meshes in memory), lint + .png + .rrd;
the difference of the last two is what snapshots add on top of linting.
"""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
ROBOTS = [("ur_description/urdf/ur5e.xacro", {}),
          ("franka_description/robots/panda/panda.urdf.xacro", {"hand": "true"}),
          ("turtlebot3_description/urdf/turtlebot3_waffle_pi.urdf.xacro", {}),
          ("franka_description/robots/dual_panda/dual_panda_example.urdf.xacro", {})]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--corpus", default=str(REPO.parent / "shared" / "corpus"))
    a = ap.parse_args()
    os.chdir(a.corpus)
    import rerun  # noqa: F401 - measured separately: imported once per worker process
    import dataclasses
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.core.jobs import LintJob
    from urdf_lint.engine.lint import run_job
    from urdf_lint.run.pipeline import settings_for
    from urdf_lint.run.worker import process_job
    cfg = load_config(None)
    for path, args in ROBOTS:
        entry = os.path.abspath(path)
        settings = settings_for(cfg, build_resolver([entry], cfg), None)
        job = LintJob(entry, args, "xacro", explicit=True)
        t0 = time.perf_counter()
        r = run_job(job, settings)
        cold = time.perf_counter() - t0
        t0 = time.perf_counter()
        run_job(job, settings)
        warm = time.perf_counter() - t0
        rs = dataclasses.replace(settings, render_dir=tempfile.mkdtemp(), render_base=a.corpus)
        t0 = time.perf_counter()
        r2 = process_job(job, rs)
        both = time.perf_counter() - t0
        snap = r2.snapshot
        print(f"{path} {args or ''}: {r.links} links, {r.meshes} meshes, "
              f"{snap.get('triangles')} triangles; lint cold {cold:.2f} s, lint {warm:.2f} s, "
              f"lint + snapshots {both:.2f} s -> snapshots add {both - warm:.2f} s")
    t0 = time.perf_counter()
    import subprocess
    subprocess.run([sys.executable, "-c", "import rerun"], check=True)
    print(f"importing rerun in a fresh process: {time.perf_counter() - t0:.2f} s (once per worker)")


if __name__ == "__main__":
    main()
