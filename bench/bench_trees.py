"""A cold and a warm ``urdf-lint check`` of the corpus, for several source trees, interleaved:

    .venv/bin/python bench/bench_trees.py REV [REV ...] [--repeat N] [--corpus DIR]

Each REV (a commit, branch or tag of this repository) is checked out with ``git worktree`` into
a temporary folder and run as ``python -P -m urdf_lint`` with that folder first on the path
(``-P``: the working directory is not; ``urdf_lint/rules`` is linked to the tree's ``rules/``,
which the installed package maps), so every tree uses this virtualenv's dependencies and only
the code differs. This working tree is compared too, as ``HEAD+work``.

* cold: ``check CORPUS --no-cache``;
* warm: ``check CORPUS --cache-dir DIR`` with a cache each tree filled before the first repeat.

The order of the trees rotates from repeat to repeat; the table shows each tree's median and
minimum and the median's ratio to the first REV. (Issue 21's "no measurable cost" was shown
with it: the security branches against the commit they started from.)
"""
from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
PY = str(REPO / ".venv" / "bin" / "python")


def _tree(rev: str, into: Path) -> Path:
    dst = into / rev.replace("/", "_")
    subprocess.run(["git", "worktree", "add", "-q", "--detach", str(dst), rev], cwd=REPO,
                   check=True)
    (dst / "urdf_lint" / "rules").symlink_to("../rules")
    return dst


def _run(tree: Path, corpus: str, args: list) -> float:
    env = dict(os.environ, PYTHONPATH=str(tree))
    env.pop("GITHUB_ACTIONS", None)
    t0 = time.perf_counter()
    p = subprocess.run([PY, "-P", "-m", "urdf_lint", "check", corpus, "-q", "--format", "json",
                        *args], env=env, cwd=tempfile.gettempdir(), capture_output=True)
    dt = time.perf_counter() - t0
    if p.returncode not in (0, 1):
        raise SystemExit(f"{tree}: exit {p.returncode}\n{p.stderr.decode()[-800:]}")
    return dt


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("revs", nargs="+")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--corpus", default=str(REPO.parent / "shared" / "corpus"))
    a = ap.parse_args()
    work = Path(tempfile.mkdtemp(prefix="bench-trees-"))
    trees: dict[str, Path] = {}
    try:
        for rev in a.revs:
            trees[rev] = _tree(rev, work)
        trees["HEAD+work"] = REPO
        caches = {name: tempfile.mkdtemp(dir=work, prefix="cache-") for name in trees}
        for name, tree in trees.items():
            _run(tree, a.corpus, ["--cache-dir", caches[name]])
        times: dict = {(n, k): [] for n in trees for k in ("cold", "warm")}
        names = list(trees)
        for i in range(a.repeat):
            for name in names[i % len(names):] + names[:i % len(names)]:
                times[(name, "cold")].append(_run(trees[name], a.corpus, ["--no-cache"]))
                times[(name, "warm")].append(
                    _run(trees[name], a.corpus, ["--cache-dir", caches[name]]))
        for kind in ("cold", "warm"):
            base = statistics.median(times[(names[0], kind)])
            for name in names:
                t = times[(name, kind)]
                print(f"{kind:5} {name:24} median {statistics.median(t):.3f} s  "
                      f"min {min(t):.3f} s  ratio {statistics.median(t) / base:.3f}")
    finally:
        for tree in trees.values():
            if tree != REPO:
                subprocess.run(["git", "worktree", "remove", "--force", str(tree)], cwd=REPO,
                               capture_output=True)
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
