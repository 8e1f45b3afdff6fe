"""How long ``urdf-lint format`` takes on the corpus (issue 27), repeats interleaved, medians:

    .venv/bin/python bench/bench_format.py [--corpus DIR] [--repeat N]

* engine:  the layout and its guard (read back, fixed point, suppression coverage) of every
           ``.urdf``/``.xacro`` of the corpus, in process, from bytes in memory;
* steady:  ``urdf-lint format --check`` on a formatted copy of the corpus, as a process (what a
           pre-commit hook or CI pays once the repository is formatted: nothing changes, so
           nothing needs proving);
* first:   ``urdf-lint format --check`` on an unformatted copy: the proof (each changed file
           proved from itself where xacro's rules allow, urdf_lint/formatting/inert.py; the
           models that read any other changed file expanded twice in the sandboxed workers).
"""
from __future__ import annotations

import argparse
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
DATA = ("*.stl", "*.STL", "*.dae", "*.DAE", "*.obj", "*.OBJ", "*.png", "*.jpg", "*.jpeg", "*.mtl")


def engine(blobs, cpu: list) -> float:
    from urdf_lint.formatting.layout import FormatError, Refused, format_source
    t0, c0 = time.perf_counter(), time.process_time()
    for path, data in blobs:
        try:
            format_source(data, path=path)
        except (FormatError, Refused):
            pass
    cpu.append(time.process_time() - c0)
    return time.perf_counter() - t0


def cli(folder: Path) -> float:
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, "-m", "urdf_lint", "format", "--check", "-q", str(folder)],
                       capture_output=True, text=True, cwd=folder)
    dt = time.perf_counter() - t0
    assert p.returncode in (0, 1, 2) and "Traceback" not in p.stderr, p.stderr
    return dt


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--corpus", default=str(REPO.parent / "shared" / "corpus"))
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--no-first", action="store_true", help="skip the run with the proof")
    a = ap.parse_args()
    corpus = Path(a.corpus)
    files = sorted(p for p in corpus.rglob("*") if p.suffix in (".urdf", ".xacro"))
    blobs = [(str(p), p.read_bytes()) for p in files]
    with tempfile.TemporaryDirectory(prefix="bench-format-") as tmp:
        raw, done = Path(tmp, "raw"), Path(tmp, "formatted")
        for d in (raw, done):
            shutil.copytree(corpus, d, ignore=shutil.ignore_patterns(*DATA))
        subprocess.run([sys.executable, "-m", "urdf_lint", "format", "-q", str(done)], cwd=done,
                       capture_output=True)
        times: dict = {"engine": [], "steady": [], "first": []}
        cpu: list = []
        for _ in range(a.repeat):   # interleaved: a busy machine slows every kind alike
            times["engine"].append(engine(blobs, cpu))
            times["steady"].append(cli(done))
            if not a.no_first:
                times["first"].append(cli(raw))
    print(f"{len(files)} files, {sum(len(b) for _, b in blobs) / 1e6:.1f} MB, "
          f"{a.repeat} interleaved repeats, median (min-max) seconds")
    for k, v in times.items():
        if v:
            print(f"  {k:<7} {statistics.median(v):6.2f}  ({min(v):.2f}-{max(v):.2f})")
    print(f"  engine CPU time {statistics.median(cpu):.2f} s (the machine's load aside)")


if __name__ == "__main__":
    main()
