"""Benchmark urdf-lint on the real robots of ../shared/corpus.

    .venv/bin/python bench/bench.py [--corpus DIR] [--repeat N] [--profile]

Measures, on every corpus entry model with its args (entries.json):
  * stock: the stock ``xacro`` CLI run once per entry model (the reference: bare expansion);
  * cold:  ``urdf-lint check`` with an empty cache (all rules, meshes loaded);
  * warm:  the same again, nothing changed;
  * one changed macro file: which models re-expand, and the wall time;
  * hook:  ``urdf-lint hook <changed file>`` in a one-robot git repository (pre-commit's view);
and, with --profile, where the cold run's time goes (cProfile of the in-process pipeline).
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests" / "support"))


def entries(corpus: Path):
    out = []
    for e in json.loads((corpus / "entries.json").read_text()):
        f = corpus / e["file"]
        if f.suffix not in (".urdf", ".xacro"):
            continue  # extension-less expected-output files are not models
        out.append((f, {k: v.replace("{CORPUS}", str(corpus)) for k, v in e["args"].items()}))
    return out


def corpus_parser(repeat: int) -> argparse.ArgumentParser:
    """The options every benchmark has: the corpus folder and how many runs."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--corpus", default=str(REPO.parent / "shared" / "corpus"))
    ap.add_argument("--repeat", type=int, default=repeat)
    return ap


def write_config(path: Path, ents) -> Path:
    by_file: dict = {}
    for f, args in ents:
        by_file.setdefault(str(f), []).append(args)
    lines = []
    for f, arg_sets in by_file.items():
        lines.append("[[models]]")
        lines.append(f"path = {json.dumps(f)}")
        sets = ", ".join("{" + ", ".join(f"{k} = {json.dumps(v)}" for k, v in a.items()) + "}"
                         for a in arg_sets)
        lines.append(f"args = [{sets}]")
    path.write_text("\n".join(lines) + "\n")
    return path


def run(cmd, env=None, cwd=None):
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=cwd)
    return time.perf_counter() - t0, p


def lint_cmd(files, config):
    return [str(REPO / ".venv/bin/urdf-lint"), "check", *map(str, files), "--config", str(config),
            "--format", "json", "--fail-on", "never"]


def main():
    ap = corpus_parser(repeat=3)
    ap.add_argument("--profile", action="store_true")
    a = ap.parse_args()
    corpus = Path(a.corpus).resolve()
    ents = entries(corpus)
    files = sorted({str(f) for f, _ in ents})
    tmp = Path(tempfile.mkdtemp(prefix="urdf-lint-bench-"))
    config = tmp / "urdf-lint.toml"
    write_config(config, ents)
    print(f"corpus: {corpus} ({len(ents)} entry models, {len(files)} files), {os.cpu_count()} cores")

    # -- stock xacro, once per entry model ------------------------------------------------
    from stock_xacro import stock_xacro
    from urdf_lint.discovery.packages import PackageResolver
    pmap = PackageResolver.build([corpus], extra_roots=[corpus]).scanned
    t0 = time.perf_counter()
    for f, args in ents:
        stock_xacro(str(f), args, pmap)
    stock = time.perf_counter() - t0
    print(f"stock xacro CLI, {len(ents)} runs:            {stock:7.2f} s")

    # -- cold / warm -----------------------------------------------------------------------
    colds, warms = [], []
    for i in range(a.repeat):
        cache = tmp / f"cache{i}"
        env = dict(os.environ, URDF_LINT_CACHE_DIR=str(cache))
        dt, p = run(lint_cmd(files, config), env)
        doc = json.loads(p.stdout)
        colds.append(dt)
        dt, p = run(lint_cmd(files, config), env)
        warm_doc = json.loads(p.stdout)
        warms.append(dt)
        assert all(m["cached"] for m in warm_doc["models"]), "warm run re-linted something"
        assert warm_doc["findings"] == doc["findings"], "warm and cold disagree"
    n_models = len(doc["models"])
    cold, warm = statistics.median(colds), statistics.median(warms)
    print(f"urdf-lint check, cold (all rules, meshes):  {cold:7.2f} s  "
          f"({n_models} models, {len(doc['findings'])} findings)  ratio to stock: {cold / stock:.2f}")
    print(f"urdf-lint check, warm (nothing changed):    {warm:7.2f} s")

    # -- one changed macro file -------------------------------------------------------------
    work = tmp / "changed"
    shutil.copytree(corpus / "ur_description", work / "ur_description")
    shutil.copytree(corpus / "fanuc", work / "fanuc")
    env = dict(os.environ, URDF_LINT_CACHE_DIR=str(tmp / "cache-changed"))
    base = [str(REPO / ".venv/bin/urdf-lint"), "check", str(work), "--format", "json",
            "--fail-on", "never"]
    run(base, env)
    macro = work / "ur_description/urdf/inc/ur_macro.xacro"
    macro.write_text(macro.read_text().replace("<!--", "<!-- bench edit -->\n  <!--", 1))
    dt, p = run(base, env)
    doc = json.loads(p.stdout)
    redone = sorted(m["entry"].split("/urdf/")[-1] for m in doc["models"] if not m["cached"])
    print(f"one changed macro (ur_macro.xacro):         {dt:7.2f} s  re-expanded "
          f"{len(redone)}/{len(doc['models'])}: {', '.join(redone)}")

    # -- the pre-commit hook on one robot -----------------------------------------------------
    one = tmp / "one"
    shutil.copytree(corpus / "urdf_tutorial", one / "urdf_tutorial")
    subprocess.run(["git", "init", "-q"], cwd=one, check=True)
    env = dict(os.environ, URDF_LINT_CACHE_DIR=str(tmp / "cache-hook"))
    hook = [str(REPO / ".venv/bin/urdf-lint"), "hook", "urdf_tutorial/urdf/08-macroed.urdf.xacro"]
    run(hook, env, cwd=one)
    warm_hooks = [run(hook, env, cwd=one)[0] for _ in range(a.repeat)]
    f = one / "urdf_tutorial/urdf/08-macroed.urdf.xacro"
    f.write_text(f.read_text().replace("<robot", "<!-- edit -->\n<robot", 1))
    dt, _ = run(hook, env, cwd=one)
    print(f"hook, one robot, file changed:              {dt:7.2f} s  (unchanged: "
          f"{statistics.median(warm_hooks):.2f} s)")

    # -- snapshots: a 22-link robot with 20 meshes (Panda + hand), lint vs lint + render --------
    panda = corpus / "franka_description/robots/panda/panda.urdf.xacro"
    pconf = tmp / "panda.toml"
    pconf.write_text(f'[[models]]\npath = {json.dumps(str(panda))}\nargs = [{{hand = "true"}}]\n')
    lint_only, with_render = [], []
    for i in range(a.repeat):
        dt, _ = run([str(REPO / ".venv/bin/urdf-lint"), "check", str(panda), "--config", str(pconf),
                     "--no-cache", "-j", "1", "-q", "--fail-on", "never"])
        lint_only.append(dt)
        dt, p = run([str(REPO / ".venv/bin/urdf-lint"), "check", str(panda), "--config", str(pconf),
                     "--no-cache", "-j", "1", "-q", "--fail-on", "never", "--render", str(tmp / f"snap{i}")])
        with_render.append(dt)
    lo, wr = statistics.median(lint_only), statistics.median(with_render)
    print(f"Panda+hand (22 links, 20 meshes): lint {lo:.2f} s, lint + .rrd + .png {wr:.2f} s "
          f"-> snapshots add {wr - lo:.2f} s")

    # -- start-up: a warm run must not import the heavy modules ------------------------------
    env = dict(os.environ, URDF_LINT_CACHE_DIR=str(tmp / "cache0"))
    code = ("import sys; from urdf_lint.cli.main import main; "
            f"main({['check', *files, '--config', str(config), '--format', 'json', '-q']!r}); "
            "print(sorted(m for m in ('xacro', 'trimesh', 'yourdfpy', 'rerun', 'collada') "
            "if m in sys.modules), file=sys.stderr)")
    _, p = run([sys.executable, "-c", code], env)
    print(f"heavy modules imported by a warm run:       {p.stderr.strip().splitlines()[-1]}")

    if a.profile:
        import cProfile
        import pstats
        from urdf_lint.config.schema import load_config
        from urdf_lint.discovery.discover import build_resolver
        cfg = load_config(config)
        res = build_resolver(files, cfg)
        from urdf_lint.engine.lint import run_job
        from urdf_lint.discovery.discover import discover
        from urdf_lint.run.pipeline import settings_for
        jobs = discover(files, cfg)
        settings = settings_for(cfg, res, None)
        prof = cProfile.Profile()
        prof.enable()
        for job in jobs:
            run_job(job, settings)
        prof.disable()
        st = pstats.Stats(prof)
        st.sort_stats("cumulative").print_stats(25)
    shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
