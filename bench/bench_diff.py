"""``urdf-lint diff`` on a one-file change in the corpus, as a reviewer's CI would run it:

    .venv/bin/python bench/bench_diff.py [--corpus DIR] [--runs N] [--profile OUT.prof]

Copies the corpus into a temporary git repository, commits it, changes one joint limit in a
macro file that exactly one model includes (``m10ia7l_macro.xacro``), and times
``urdf-lint diff HEAD`` (the working tree against the commit):

* cold: empty cache; warm: the cache of the previous run is there (the usual pre-commit / CI
  with a restored cache);
* without rendering, then with ``--render DIR`` (before/after/difference PNGs + one .rrd with both revisions).

Target (issue 13): under 2 s without rendering, under 2 s per changed model with rendering.
``--profile`` writes a cProfile of one warm run without rendering, in process.

``--compare TREE [TREE ...] --runs N`` times cold runs only (no render, then render; with
``--warm``, warm runs, each after an untimed one), the trees interleaved N times (``.`` is this
tree; another is a source tree as for ``--src``), and prints the min and median of each: on a
shared machine only runs taken side by side compare.
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
CHANGED = "fanuc/fanuc_m10ia_support/urdf/m10ia7l_macro.xacro"
OLD, NEW = 'lower="-1.57" upper="2.79"', 'lower="-1.57" upper="2.5"'


def build_repo(corpus: str, dest: str) -> str:
    top = os.path.join(dest, "corpus")
    shutil.copytree(corpus, top, symlinks=True)
    env = dict(os.environ, GIT_AUTHOR_NAME="b", GIT_AUTHOR_EMAIL="b@example.com",
               GIT_COMMITTER_NAME="b", GIT_COMMITTER_EMAIL="b@example.com")
    for cmd in (["git", "init", "-q"], ["git", "add", "-A"],
                ["git", "commit", "-q", "-m", "corpus"]):
        subprocess.run(cmd, cwd=top, check=True, env=env)
    path = os.path.join(top, CHANGED)
    text = Path(path).read_text()
    assert OLD in text, f"{CHANGED} changed upstream: update the bench"
    Path(path).write_text(text.replace(OLD, NEW, 1))
    return top


SRC = None   # --src: run urdf-lint from this source tree (another revision) instead


def urdf_lint(top, *args):
    exe = str(REPO / ".venv" / "bin" / "urdf-lint")
    if not os.path.exists(exe):
        exe = shutil.which("urdf-lint") or "urdf-lint"
    env = dict(os.environ, RERUN_ANALYTICS="off")
    cmd = [exe]
    if SRC:
        cmd = [sys.executable, "-P", "-m", "urdf_lint"]   # (-P: not the cwd's urdf_lint)
        env["PYTHONPATH"] = SRC
    import resource
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    p = subprocess.run([*cmd, *args], cwd=top, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    CPU.append(r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime)
    return wall, p


CPU: list = []   # CPU seconds (user + sys, the process and its workers) of each run


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--corpus", default=str(REPO.parent / "shared" / "corpus"))
    ap.add_argument("--runs", type=int, default=3, help="warm runs to take the median of")
    ap.add_argument("--profile", metavar="OUT", help="cProfile one warm run to OUT")
    ap.add_argument("--src", help="source tree of another revision to run instead (e.g. "
                    "'git archive main | tar -x -C DIR' and a urdf_lint/rules -> ../rules link)")
    ap.add_argument("--compare", nargs="+", metavar="TREE",
                    help="cold runs only, these source trees interleaved (see above)")
    ap.add_argument("--warm", action="store_true", help="with --compare: warm runs instead")
    a = ap.parse_args()
    global SRC
    SRC = a.src
    if a.compare:
        return compare(a)
    with tempfile.TemporaryDirectory(prefix="bench-diff-") as tmp:
        t0 = time.perf_counter()
        top = build_repo(a.corpus, tmp)
        print(f"repository built in {time.perf_counter() - t0:.1f} s: {top}")
        cache = os.path.join(top, ".urdf_lint_cache")
        out = os.path.join(tmp, "snaps")
        rows = []
        for label, extra in (("no render", []), ("render", ["--render", out])):
            shutil.rmtree(cache, ignore_errors=True)
            cold, p = urdf_lint(top, "diff", "HEAD", "--format", "json", *extra)
            cold_cpu = CPU[-1]
            if p.returncode not in (0, 1):
                sys.exit(f"diff failed ({p.returncode}): {p.stderr[-2000:]}")
            doc = json.loads(p.stdout)
            changed = [m for m in doc["models"] if m["status"] != "unchanged"]
            del CPU[:]
            warm = [urdf_lint(top, "diff", "HEAD", "--format", "json", *extra)[0]
                    for _ in range(a.runs)]
            rows.append((label, cold, statistics.median(warm), cold_cpu, statistics.median(CPU),
                         len(doc["models"]), len(changed), doc.get("base_expanded")))
        print(f"load average (1 min) {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
        for label, cold, warm, ccpu, wcpu, n, changed, base_n in rows:
            print(f"diff HEAD, {label:9}: cold {cold:.2f} s ({ccpu:.2f} s CPU), warm {warm:.2f} s "
                  f"({wcpu:.2f} s CPU) (median of {a.runs}); {n} affected model(s), {changed} "
                  f"changed, {base_n} expanded at base")
        if a.profile:
            import cProfile
            os.chdir(top)
            sys.argv = ["urdf-lint", "diff", "HEAD", "--format", "json"]
            from urdf_lint.cli.main import main as cli_main
            cProfile.runctx("cli_main(sys.argv[1:])", globals(), {"cli_main": cli_main,
                                                                    "sys": sys}, a.profile)
            print(f"profile written to {a.profile}")


def compare(a):
    global SRC
    # every tree, this one too, runs the same way (python -m with PYTHONPATH): the console
    # script's start-up differs, and start-up is part of what is compared
    trees = [str(REPO) if t == "." else os.path.abspath(t) for t in a.compare]
    times: dict = {}
    with tempfile.TemporaryDirectory(prefix="bench-diff-") as tmp:
        top = build_repo(a.corpus, tmp)
        cache = os.path.join(top, ".urdf_lint_cache")
        out = os.path.join(tmp, "snaps")
        for _ in range(a.runs):
            for name, tree in zip(a.compare, trees, strict=True):
                SRC = tree
                for label, extra in (("no render", []), ("render", ["--render", out])):
                    if a.warm:   # the cache of a run just before (not timed)
                        urdf_lint(top, "diff", "HEAD", "--format", "json", *extra)
                    else:
                        shutil.rmtree(cache, ignore_errors=True)
                    wall, p = urdf_lint(top, "diff", "HEAD", "--format", "json", *extra)
                    if p.returncode not in (0, 1):
                        sys.exit(f"{name}: diff failed ({p.returncode}): {p.stderr[-2000:]}")
                    times.setdefault((name, label), []).append(wall)
    print(f"load average (1 min) {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores; "
          f"{'warm' if a.warm else 'cold'} runs, {a.runs} per tree, interleaved")
    for (name, label), ts in times.items():
        print(f"{name:30} {label:9}: min {min(ts):.2f} s, median {statistics.median(ts):.2f} s "
              f"({' '.join(f'{t:.2f}' for t in ts)})")


if __name__ == "__main__":
    main()
