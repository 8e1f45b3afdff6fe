"""Latency of the commands a user runs on every commit, on this machine:

    .venv/bin/python bench/bench_startup.py [--corpus DIR] [--repeat N]

* ``urdf-lint expand`` of the seed R2D2 in a sandboxed worker (target: < 0.15 s);
* a warm ``urdf-lint check`` of the whole corpus, nothing changed (target: <= 0.15 s), as a
  folder (``check corpus/``) and as the entry models with their args (bench.py's config);
* one changed macro file (``ur_macro.xacro``): only its dependents re-lint (target: <= 0.6 s);
* the floor: ``python -c pass`` and ``python -c "import urdf_lint.cli.main"``.

Each is run ``--repeat`` times, interleaved; the table shows the minimum (what the code costs,
least disturbed by other processes) and the median. Bytecode is written and used, as after
``pip install``: PYTHONDONTWRITEBYTECODE is removed from the environment.
"""
from __future__ import annotations

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
sys.path.insert(0, str(REPO / "bench"))
LINT = str(REPO / ".venv" / "bin" / "urdf-lint")
PY = str(REPO / ".venv" / "bin" / "python")


def timed(cmd, env, cwd=None):
    t0 = time.perf_counter()
    p = subprocess.run(cmd, env=env, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    return time.perf_counter() - t0, p


def main():
    from bench import corpus_parser, entries, write_config
    a = corpus_parser(repeat=10).parse_args()
    corpus = Path(a.corpus).resolve()
    tmp = Path(tempfile.mkdtemp(prefix="urdf-lint-startup-"))
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env.pop("URDF_LINT_CACHE_DIR", None)

    ents = entries(corpus)
    files = sorted({str(f) for f, _ in ents})
    config = tmp / "urdf-lint.toml"
    write_config(config, ents)
    env_dir = dict(env, URDF_LINT_CACHE_DIR=str(tmp / "cache-dir"))
    env_ent = dict(env, URDF_LINT_CACHE_DIR=str(tmp / "cache-entries"))
    r2d2 = REPO / "descriptions" / "r2d2_description" / "urdf" / "r2d2.urdf.xacro"
    cases = {
        "python -c pass": ([PY, "-c", "pass"], env),
        "import urdf_lint.cli.main": ([PY, "-c", "import urdf_lint.cli.main"], env),
        "expand r2d2 (worker, sandbox)": ([LINT, "expand", str(r2d2)], env),
        "warm check corpus/": ([LINT, "check", str(corpus), "-q", "--fail-on", "never"], env_dir),
        "warm check entry models + args": ([LINT, "check", *files, "--config", str(config), "-q",
                                            "--fail-on", "never"], env_ent),
    }
    # prime: bytecode, and the caches of the warm runs (the folder's first run is the cold one)
    cold = None
    for name, (cmd, e) in cases.items():
        dt, _ = timed(cmd, e)
        if name == "warm check corpus/":
            cold = dt
    for cmd, e in cases.values():   # a second time: the include graph and mesh facts settle
        subprocess.run(cmd, env=e, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    times: dict = {k: [] for k in cases}
    for _ in range(a.repeat):
        for name, (cmd, e) in cases.items():
            dt, p = timed(cmd, e)
            if name.startswith("warm") and b"cached" not in p.stdout and p.returncode not in (0, 1):
                raise SystemExit(f"{name} failed: {p.stderr.decode()[-500:]}")
            times[name].append(dt)

    # one changed macro file: the UR models re-lint, nothing else
    work = tmp / "changed"
    shutil.copytree(corpus / "ur_description", work / "ur_description")
    shutil.copytree(corpus / "fanuc", work / "fanuc")
    env_chg = dict(env, URDF_LINT_CACHE_DIR=str(tmp / "cache-changed"))
    base = [LINT, "check", str(work), "--format", "json", "--fail-on", "never"]
    subprocess.run(base, env=env_chg, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    macro = work / "ur_description/urdf/inc/ur_macro.xacro"
    text = macro.read_text()
    changed, redone = [], []
    for i in range(max(3, a.repeat // 3)):
        macro.write_text(text.replace("<!--", f"<!-- bench edit {i} -->\n  <!--", 1))
        dt, p = timed(base, env_chg)
        doc = json.loads(p.stdout)
        redone = [m for m in doc["models"] if not m["cached"]]
        changed.append(dt)
    times[f"one changed macro ({len(redone)}/{len(doc['models'])} models re-lint)"] = changed

    # issue 10: discovery by include graph costs at most 10% of a cold run
    from urdf_lint.config.schema import load_config
    from urdf_lint.discovery.discover import build_resolver, discover_models
    cfg = load_config(None)
    t0 = time.perf_counter()
    found = discover_models([str(corpus)], cfg, build_resolver([str(corpus)], cfg), cache_dir=None)
    discovery = time.perf_counter() - t0

    targets = {"expand r2d2 (worker, sandbox)": 0.15, "warm check corpus/": 0.15,
               "warm check entry models + args": 0.15}
    print(f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f}, "
          f"{a.repeat} runs each (interleaved)")
    print(f"{'command':<48} {'min':>7} {'median':>7}  target")
    for name, ts in times.items():
        tgt = targets.get(name, 0.6 if name.startswith("one changed") else None)
        mark = "" if tgt is None else f"<= {tgt:.2f} s  {'ok' if min(ts) <= tgt else 'MISSED'}"
        print(f"{name:<48} {min(ts):7.3f} {statistics.median(ts):7.3f}  {mark}")
    assert cold is not None
    print(f"{'discovery (include graph, uncached) / cold check':<48} {discovery:7.3f} / {cold:.2f} s"
          f" = {discovery / cold:.1%} ({len(found.jobs)} candidates)  <= 10%  "
          f"{'ok' if discovery <= 0.1 * cold else 'MISSED'}")
    shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
