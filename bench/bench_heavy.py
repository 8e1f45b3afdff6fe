"""Issue 34's goals, measured side by side in one run: urdf-lint against the stock xacro CLI
run once per model, on a generated mesh-heavy repository, on the dev corpus (its entry models
and args) and on the corpus laid out as a colcon workspace (``check ws``: discovery finds the
robots; stock runs on the models it found).

    .venv/bin/python bench/bench_heavy.py [--packages 6] [--triangles 200000] [--repeat 3]
                                          [--corpus DIR | --no-corpus] [--no-workspace]
                                          [--no-heavy] [--huge]
                                          [--base OTHER/urdf-lint] [--findings DIR]

Each set is run as four sides, interleaved (in an order that rotates with each repeat):
stock; urdf-lint cold at the default ``-j`` and at ``-j1`` (``--no-cache``: no result cache,
no mesh facts store); urdf-lint warm (the result cache and the mesh facts store a run before
filled). The table gives the medians over the repeats of: cold wall / stock (goal <= 0.35),
cold CPU / stock (<= 0.5), warm wall / stock (<= 0.05), -j1 wall / -j wall (>= 1.7).
For each side the wall time and the CPU time of the child processes (user + system, from
``resource.getrusage(RUSAGE_CHILDREN)``, which counts the workers too) are measured; the peak
memory is the largest max RSS of any process of an ``urdf-lint check -j2`` run (measured in a
fresh helper process, since ``ru_maxrss`` of the children only ever grows). ``--huge`` also
lints one valid 5M-triangle binary STL (250 MB) and reports its time and peak memory.
Prints a table of targets vs measured; the exit code is 0 (a benchmark reports, it does not
gate).

``--base OTHER/.venv/bin/urdf-lint`` (e.g. ``/work/main/.venv/bin/urdf-lint``; repeatable)
measures changes on the three sets: stock, this tree and the other trees run interleaved (in
an order that rotates with each repeat), and the wall and CPU ratios to stock of each are
printed (min and median), with whether its findings are this tree's. A tree without a
virtualenv of its own is run by a wrapper script doing ``PYTHONPATH=TREE python -P -m
urdf_lint``: without ``-P``, ``python -m`` imports the ``urdf_lint`` of the working directory
(this one). Every tree measured, a wrapper's too, has its bytecode written first.
``--findings DIR`` keeps each side's findings there as JSON.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests" / "support"))
sys.path.insert(0, str(REPO / "bench"))
from bench import entries, write_config  # noqa: E402
LINT = str(REPO / ".venv" / "bin" / "urdf-lint")


def _cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed(fn):
    """(wall s, children CPU s, result) of fn()."""
    c0, t0 = _cpu(), time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, _cpu() - c0, out


def stock_all(models, pmap):
    from stock_xacro import stock_xacro

    def go():  # some corpus entries fail in stock xacro too (no ROS): they still count
        return sum(stock_xacro(str(f), args, pmap)[0] != 0 for f, args in models)
    return timed(go)


def lint(paths, extra=(), env=None, cwd=None, exe=None, cache_home=None):
    """One ``urdf-lint check`` of ``paths``: cold (``--no-cache``: no result cache, no mesh
    facts store), or with ``cache_home`` the result cache and the mesh facts store kept
    there (warm once a run has filled them)."""
    cold = () if cache_home else ("--no-cache",)
    if cache_home:
        env = dict(env or os.environ, XDG_CACHE_HOME=str(cache_home),
                   URDF_LINT_CACHE_DIR=str(Path(cache_home, "results")))
    cmd = [exe or LINT, "check", *map(str, paths), *cold, "--format", "json", "--fail-on",
           "never", *extra]

    def go():
        p = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=cwd)
        if p.returncode not in (0, 1):
            raise SystemExit(f"urdf-lint failed ({p.returncode}): {p.stderr[-2000:]}")
        return json.loads(p.stdout)
    return timed(go)


_PEAK = ("import resource, subprocess, sys; subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL,"
         " stderr=subprocess.DEVNULL); print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)")


def peak_mb(paths, extra=()) -> float:
    """The largest max RSS (MiB) of any process of one urdf-lint run."""
    cmd = [sys.executable, "-c", _PEAK, LINT, "check", *map(str, paths), "--no-cache",
           "--format", "json", "--fail-on", "never", *extra]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    return int(out.strip()) / 1024


def interleaved(sides: dict, repeat: int) -> dict:
    """Each side's (wall, cpu, result) per repeat, the sides run one after the other within a
    repeat (in an order that rotates), so a machine that gets busier or quieter during the
    benchmark weighs on all of them alike."""
    names = list(sides)
    out: dict = {n: [] for n in names}
    for i in range(repeat):
        k = i % len(names)
        for n in names[k:] + names[:k]:
            out[n].append(sides[n]())
    return out


def median_of(runs, what: int) -> float:
    return statistics.median(r[what] for r in runs)


def median_ratio(a, b, what: int, show: str = "") -> float:
    """The median over the repeats of a's wall (0) or CPU (1) over b's in the same repeat
    (with ``show``, each repeat's ratio is printed under that name)."""
    ratios = [x[what] / y[what] for x, y in zip(a, b, strict=True)]
    if show:
        print(f"  {show} per repeat: " + " ".join(f"{r:.2f}" for r in ratios))
    return statistics.median(ratios)


def ab(label, models, pmap, paths, extra, bases, repeat, findings_dir):
    """Stock, this tree and each of ``bases`` :func:`interleaved`: the min and median wall
    ratio to stock of each tree."""
    trees = {"this": LINT, **{_side_name(b): b for b in bases}}
    sides = {"stock": lambda: stock_all(models, pmap)}
    sides.update({name: (lambda exe=exe: lint(paths, extra, exe=exe)) for name, exe in trees.items()})
    runs = interleaved(sides, repeat)
    mine = runs["this"][-1][2]["findings"]
    for side in trees:
        r = [x[0] / y[0] for x, y in zip(runs[side], runs["stock"], strict=True)]
        c = [x[1] / y[1] for x, y in zip(runs[side], runs["stock"], strict=True)]
        found = runs[side][-1][2]["findings"]
        print(f"  {label} {side:>14s}: wall / stock min {min(r):.2f} median "
              f"{statistics.median(r):.2f}, CPU / stock min {min(c):.2f} median "
              f"{statistics.median(c):.2f}  ({len(found)} findings"
              f"{'' if found == mine else ', NOT the same as this tree'})")
        if findings_dir:
            Path(findings_dir).mkdir(parents=True, exist_ok=True)
            Path(findings_dir, f"{label}-{side}.json").write_text(json.dumps(found, indent=1))


def _side_name(exe: str) -> str:
    """A tree's name: the folder holding ``.venv/bin/urdf-lint`` (or the script)."""
    p = Path(exe).resolve()
    return (p.parents[2] if p.parent.name == "bin" else p.parent).name


def report_sides(runs: dict, n_models: int, doc) -> None:
    for name, label in (("stock", f"stock xacro CLI x{n_models}:"),
                        ("lint", "urdf-lint cold -j default: "), ("lint1", "urdf-lint cold -j1:        "),
                        ("warm", "urdf-lint warm:            ")):
        r = runs[name]
        extra = f"  ({len(doc['models'])} models, {len(doc['findings'])} findings)" \
            if name == "lint" else ""
        print(f"  {label} wall {median_of(r, 0):6.2f} s  cpu {median_of(r, 1):6.2f} s{extra}")


def measure(rows, label, models, pmap, paths, extra, repeat, tmp, defaults_only=False):
    """Issue 34's goals on one set of models, interleaved: stock, cold at the default -j and
    at -j1, and warm (result cache and mesh facts store filled by a run before); with
    ``defaults_only`` also cold with ``--explore false`` (stock's work: no variants)."""
    home = Path(tmp, f"cache-{label}")
    lint(paths, extra, cache_home=home)          # fills the caches for the warm side
    # (the run memo keeps no run whose folders changed within its last 2 s: the first run
    # just made the cache folder; the second is remembered, so every warm side is alike)
    time.sleep(2.5)
    lint(paths, extra, cache_home=home)
    sides = {"stock": lambda: stock_all(models, pmap),
             "lint": lambda: lint(paths, extra),
             "lint1": lambda: lint(paths, [*extra, "-j1"]),
             "warm": lambda: lint(paths, extra, cache_home=home)}
    if defaults_only:
        sides["defaults"] = lambda: lint(paths, [*extra, "--explore", "false"])
    runs = interleaved(sides, repeat)
    doc, doc1, docw = runs["lint"][-1][2], runs["lint1"][-1][2], runs["warm"][-1][2]
    assert doc1["findings"] == doc["findings"], "-j1 and -j disagree"
    assert docw["findings"] == doc["findings"], "warm and cold disagree"
    print(f"{label}: {len(models)} models")
    report_sides(runs, len(models), doc)
    wall = median_ratio(runs["lint"], runs["stock"], 0, "cold wall / stock")
    cpu = median_ratio(runs["lint"], runs["stock"], 1, "cold CPU / stock")
    warm = median_ratio(runs["warm"], runs["stock"], 0, "warm wall / stock")
    speed = 1 / median_ratio(runs["lint"], runs["lint1"], 0, "-j wall / -j1 wall")
    if defaults_only:
        dw = median_ratio(runs["defaults"], runs["stock"], 0, "--explore false: wall / stock")
        dc = median_ratio(runs["defaults"], runs["stock"], 1, "--explore false: CPU / stock")
        print(f"  (at the defaults only, stock's work: wall / stock {dw:.2f}, CPU / stock "
              f"{dc:.2f})")
    row(rows, f"{label}: cold wall / stock wall", "<= 0.35", f"{wall:.2f}", wall <= 0.35)
    row(rows, f"{label}: cold CPU / stock CPU", "<= 0.50", f"{cpu:.2f}", cpu <= 0.5)
    row(rows, f"{label}: warm wall / stock wall", "<= 0.05", f"{warm:.3f}", warm <= 0.05)
    row(rows, f"{label}: -j1 wall / -j default wall", ">= 1.7", f"{speed:.2f}", speed >= 1.7)
    return runs


def corpus_workspace(corpus: Path, ws: Path) -> Path:
    """The corpus laid out as a colcon workspace: every description folder (not the peer
    tests) copied under ``ws/src``, where ``check ws`` discovers the robots itself."""
    src = ws / "src"
    src.mkdir(parents=True)
    for d in sorted(corpus.iterdir()):
        if d.is_dir() and d.name != "peer-tests":
            shutil.copytree(d, src / d.name)
    return ws


def row(rows, what, target, measured, ok):
    rows.append((what, target, measured, "yes" if ok else "NO"))


def compile_bytecode(exes) -> None:
    """Write the bytecode of each measured tree's modules first, as ``pip install`` does: with
    ``PYTHONDONTWRITEBYTECODE`` set, a module edited since its last ``.pyc`` (or a fresh
    worktree with none) is compiled again on every run and in every measurement."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    for exe in exes:
        for tree in trees_of(exe):
            dirs = [str(tree / d) for d in ("urdf_lint", "rules") if (tree / d).is_dir()]
            if dirs:
                subprocess.run([sys.executable, "-m", "compileall", "-q", *dirs], env=env,
                               stdout=subprocess.DEVNULL, check=False)


def trees_of(exe) -> list[Path]:
    """The source trees an ``urdf-lint`` runs: its virtualenv's checkout, and the
    ``PYTHONPATH=TREE`` of a wrapper script (``--base``: ``PYTHONPATH=TREE python -P -m
    urdf_lint``), whose modules were otherwise compiled again on every run."""
    p = Path(exe).resolve()
    trees = [p.parents[2] if p.parent.name == "bin" else p.parent]
    try:
        head = p.read_bytes()[:4096]
    except OSError:
        return trees
    if head.startswith(b"#!"):
        trees += [Path(os.fsdecode(m)) for m in re.findall(rb"PYTHONPATH=([^\s:]+)", head)]
    return trees


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--packages", type=int, default=6)
    ap.add_argument("--triangles", type=int, default=200_000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--corpus", default=str(REPO.parent / "shared" / "corpus"))
    ap.add_argument("--no-corpus", action="store_true")
    ap.add_argument("--no-heavy", action="store_true")
    ap.add_argument("--no-workspace", action="store_true",
                    help="skip the corpus laid out as a colcon workspace (check discovers it)")
    ap.add_argument("--huge", action="store_true", help="also a 5M-triangle (250 MB) STL")
    ap.add_argument("--keep", action="store_true")
    ap.add_argument("--base", action="append", default=[],
                    help="another tree's urdf-lint (repeatable): an interleaved A/B of changes")
    ap.add_argument("--findings", help="keep the findings of each side here (JSON)")
    a = ap.parse_args()
    compile_bytecode([LINT, *a.base])
    from heavy_repo import generate
    from urdf_lint.discovery.packages import PackageResolver
    tmp = Path(tempfile.mkdtemp(prefix="urdf-lint-heavy-"))
    rows: list = []
    print(f"{os.cpu_count()} cores; {a.repeat} repeats, the sides interleaved in each; ratios are "
          "the median of the repeats' ratios; CPU = user + system of children")
    try:
        if not a.no_heavy:
            repo = tmp / "ws"
            models = generate(repo, packages=a.packages, stl_triangles=a.triangles)
            size = sum(f.stat().st_size for f in repo.rglob("*") if f.is_file()) / 2**20
            pmap = PackageResolver.build([repo / "src"]).scanned
            print(f"heavy repository: {len(models)} models, {a.packages + 1} packages, "
                  f"{size:.0f} MB")
        if not a.no_heavy and a.base:
            ab("heavy", models, pmap, [repo / "src"], [], a.base, a.repeat, a.findings)
        elif not a.no_heavy:
            measure(rows, "heavy", models, pmap, [repo / "src"], [], a.repeat, tmp)
            peak = peak_mb([repo / "src"], ["-j2"])
            print(f"  peak RSS at -j2:            {peak:6.0f} MiB")
            row(rows, "heavy: peak memory at -j2", "<= 500 MiB", f"{peak:.0f} MiB", peak <= 500)
        if not a.no_corpus and Path(a.corpus, "entries.json").is_file():
            corpus = Path(a.corpus).resolve()
            models = entries(corpus)
            files = sorted({str(f) for f, _ in models})
            config = write_config(tmp / "corpus.toml", models)
            pmap = PackageResolver.build([corpus], extra_roots=[corpus]).scanned
        if not a.no_corpus and a.base and Path(a.corpus, "entries.json").is_file():
            ab("corpus", models, pmap, files, ["--config", str(config)], a.base, a.repeat,
               a.findings)
        elif not a.no_corpus and Path(a.corpus, "entries.json").is_file():
            measure(rows, "corpus", models, pmap, files, ["--config", str(config)], a.repeat, tmp)
        if not a.no_corpus and not a.no_workspace and Path(a.corpus, "entries.json").is_file():
            ws = corpus_workspace(Path(a.corpus).resolve(), tmp / "corpus_ws")
            found = lint([ws])[2]
            models = [(Path(m["entry"]), m["args"]) for m in found["models"]
                      if m.get("status") == "model"]
            pmap = PackageResolver.build([ws / "src"]).scanned
            if a.base:
                ab("workspace", models, pmap, [ws], [], a.base, a.repeat, a.findings)
            else:
                measure(rows, "workspace", models, pmap, [ws], [], a.repeat, tmp,
                        defaults_only=True)
        if a.huge:
            from heavy_repo import package_xml, sphere, write_binary_stl
            pkg = tmp / "huge" / "huge_description"
            (pkg / "meshes").mkdir(parents=True)
            (pkg / "package.xml").write_text(package_xml("huge_description"))
            v, f = sphere(5_000_000, radius=0.2)
            write_binary_stl(pkg / "meshes" / "huge.stl", v, f)
            del v, f
            (pkg / "huge.urdf").write_text(
                '<robot name="huge"><link name="a"/><link name="b"><inertial><mass value="100"/>'
                '<inertia ixx="1.6" ixy="0" ixz="0" iyy="1.6" iyz="0" izz="1.6"/></inertial>'
                '<collision><geometry><mesh filename="package://huge_description/meshes/huge.stl"/>'
                '</geometry></collision></link><joint name="j" type="revolute"><parent link="a"/>'
                '<child link="b"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
                '</robot>\n')
            mb = (pkg / "meshes" / "huge.stl").stat().st_size / 2**20
            w, c, doc = lint([pkg], ["-j1"])
            peak = peak_mb([pkg], ["-j1"])
            bad = [x for x in doc["findings"] if x["code"] == "UL404"]
            print(f"huge STL ({mb:.0f} MB, 5M triangles): wall {w:.2f} s  cpu {c:.2f} s  "
                  f"peak {peak:.0f} MiB  UL404: {[x['message'] for x in bad]}")
            row(rows, "huge STL: facts, not UL404", "no UL404", f"{len(bad)} UL404", not bad)
    finally:
        if not a.keep:
            shutil.rmtree(tmp, ignore_errors=True)
        else:
            print(f"kept {tmp}")
    if rows:
        w = [max(len(r[i]) for r in rows + [("target", "target", "measured", "met")])
             for i in range(4)]
        print()
        print(" | ".join(h.ljust(w[i]) for i, h in enumerate(("what", "target", "measured", "met"))))
        print("-+-".join("-" * x for x in w))
        for r in rows:
            print(" | ".join(c.ljust(w[i]) for i, c in enumerate(r)))


if __name__ == "__main__":
    main()
