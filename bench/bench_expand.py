"""In-process costs on the corpus entry models, split by stage:

    .venv/bin/python bench/bench_expand.py [--corpus DIR] [--repeat N]

* stock:  stock xacro ``process_file`` + ``toprettyxml`` (no hooks, Python ``eval``), in a child
          process that never imports urdf-lint;
* safe:   urdf-lint's expansion (location tracking, confinement, allow-list evaluator);
* rules:  the full rule catalogue on the expanded models, meshes included, mesh cache warm.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests" / "support"))

STOCK = r'''
import json, os, sys, time
sys.path.insert(0, os.environ["SHIM"])
import xacro
entries = json.loads(sys.argv[1]); repeat = int(sys.argv[2])
best = None
for _ in range(repeat):
    t0 = time.perf_counter()
    for f, args in entries:
        if not f.endswith(".xacro"):
            continue
        try:
            xacro.process_file(f, mappings=dict(args)).toprettyxml(indent="  ")
        except Exception:
            pass
    dt = time.perf_counter() - t0
    best = dt if best is None else min(best, dt)
print(best)
'''


def main():
    from bench import corpus_parser, entries
    a = corpus_parser(repeat=3).parse_args()
    corpus = Path(a.corpus).resolve()
    xacro_entries = [(str(f), args) for f, args in entries(corpus) if f.suffix == ".xacro"]

    from stock_xacro import _shim_dir
    from urdf_lint.discovery.packages import PackageResolver
    res = PackageResolver.build([corpus], extra_roots=[corpus])
    env = dict(os.environ, SHIM=_shim_dir(), STOCK_XACRO_PACKAGE_MAP=json.dumps(
        {k: str(v) for k, v in res.scanned.items()}))
    stock = float(subprocess.run([sys.executable, "-c", STOCK, json.dumps(xacro_entries), str(a.repeat)],
                                 env=env, capture_output=True, text=True, check=True).stdout)

    from urdf_lint.expansion import expand_file
    from urdf_lint.run.pipeline import settings_for
    from urdf_lint.config.schema import load_config
    from urdf_lint.engine.lint import Context
    from urdf_lint.engine.model import model_from_xml
    from urdf_lint.engine.registry import load_rules
    safe, models = None, []
    for _ in range(a.repeat):
        t0 = time.perf_counter()
        models = []
        for f, args in xacro_entries:
            e = expand_file(f, args, res)
            if e.error is None:
                models.append((f, args, e))
        dt = time.perf_counter() - t0
        safe = dt if safe is None else min(safe, dt)

    rules = load_rules()
    cfg = load_config(None)
    settings = settings_for(cfg, res, tempfile.mkdtemp())
    built = [model_from_xml(f, args, e.xml, e.origins, e.deps, res) for f, args, e in models]

    def run_rules():
        n = 0
        for m in built:
            ctx = Context({}, settings.mesh_cache_dir)
            for code in settings.selected:
                r = rules[code]
                if r.check is not None and r.scope == "model":
                    ctx.options = dict(r.options)
                    n += sum(1 for _ in r.check(m, ctx))
        return n
    run_rules()  # warm the mesh cache
    best = None
    for _ in range(a.repeat):
        t0 = time.perf_counter()
        n = run_rules()
        dt = time.perf_counter() - t0
        best = dt if best is None else min(best, dt)
    print(f"{len(xacro_entries)} xacro entry models, best of {a.repeat}:")
    print(f"  stock xacro process_file (Python eval, no hooks): {stock:6.2f} s")
    print(f"  urdf-lint safe expansion (locations + sandbox):   {safe:6.2f} s  (x{safe / stock:.2f})")
    print(f"  full rule catalogue, mesh cache warm ({n} findings): {best:6.2f} s  "
          f"({best / safe:.0%} of expansion)")


if __name__ == "__main__":
    main()
