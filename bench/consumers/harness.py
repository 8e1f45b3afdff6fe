"""The consumer harness (issue 38): every defect class as a mutant of a few clean bases, plus
the corpus, loaded by every consumer that runs here, each in a worker process of its own (some
segfault), and linted by urdf-lint under that consumer's target. Writes the verdicts, with the
consumer versions, to ``urdf_lint/engine/verdicts.json`` (shipped in the wheel: the rules' help
cites it) and prints the agreement per consumer.

    nice -n 10 .venv/bin/python bench/consumers/harness.py            # the full run
    .venv/bin/python bench/consumers/harness.py --fast --check        # the probe's mutants only,
                                                                      # compared with the file

Verdicts: ``.`` loads, ``R`` rejects (raises or returns failure), ``C`` crashes (the process
dies on a signal) or hangs (no answer within ``TIMEOUT_S``). Consumers and their targets:
:data:`CONSUMERS`; Gazebo through ``sdf_probe.cc`` (built here against Debian's
``libsdformat-dev``), Isaac through ``urdf-usd-converter`` in ``.venv-isaac`` (Python 3.12).
"""
from __future__ import annotations

import argparse
import json
import os
import re
import select
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
sys.path.insert(0, str(HERE))
import mutants  # noqa: E402

VERDICTS = REPO / "urdf_lint" / "engine" / "verdicts.json"
TIMEOUT_S = 60
MEMORY_BYTES = 4 << 30
# consumer -> the urdf-lint target measured against it
CONSUMERS = {"mujoco": "mujoco", "pinocchio": "pinocchio", "pybullet": "pybullet",
             "drake": "drake", "yourdfpy": "yourdfpy", "urdf_parser_py": "urdf_parser_py",
             "urdf_parser_py_0.0.4": "urdf_parser_py", "urchin": "urchin",
             "idyntree": "idyntree", "sdformat": "gazebo", "isaac": "isaac",
             "isaac_isolated": "isaac", "check_urdf": "ros"}
# recorded, not a source of severities: Debian 12's urdfdom 3.0.1 is older than what ROS 2
# ships (urdfdom 4 to 6 read URDF 1.1), and `ros` stands for KDL, robot_state_publisher,
# MoveIt and ros2_control as well (docs/consumers.md)
# urdf-usd-converter alone (`isaac`, 0.3.4) is recorded too, but the `isaac` target follows
# Isaac Sim's importer itself (`isaac_isolated`, isaacsim-asset-isolated 6.2.0.0, which runs
# the converter 0.3.2 after reading the file with ElementTree: it refuses a malformed XML
# declaration the converter alone reads)
INFORMATIONAL = {"check_urdf", "isaac"}
# the consumers the fast part (CI) runs: those that install from the package index into the
# project's venv with the consumers extra
PIP_CONSUMERS = ("mujoco", "pinocchio", "pybullet", "yourdfpy", "urdf_parser_py",
                 "urdf_parser_py_0.0.4", "urchin",
                 "idyntree")
# rules about the repository, not about loading: their severities are not the consumers'
REPOSITORY_CODES = {"UL002", "UL003", "UL004", "UL005", "UL008", "UL009", "UL010", "UL011",
                    "UL012", "UL106", "UL403", "UL901", "UL902", "UL903", "UL904"}
OLD_UPP = Path(sys.prefix) / "consumers" / "urdf-parser-py-0.0.4"   # pip install --target
# the consumers that need Python 3.12 and a venv of their own: (the venv, what it installs)
OWN_VENVS = {"isaac": (REPO / ".venv-isaac", "urdf-usd-converter==0.3.4"),
             "isaac_isolated": (REPO / ".venv-isaac-isolated", "isaacsim-asset-isolated==6.2.0.0")}
CORPUS = REPO.parent / "shared" / "corpus"
if not CORPUS.is_dir():
    CORPUS = Path("/work/shared/corpus")


# -- workers -----------------------------------------------------------------------------------
def _command(consumer: str, build: Path) -> tuple[list[str], dict] | str:
    """The worker's command line and environment, or why it cannot run."""
    env = dict(os.environ)
    if consumer == "sdformat":
        exe = build / "sdf_probe"
        if not exe.exists():
            return "libsdformat-dev is not installed (apt-get install libsdformat-dev)"
        return [str(exe)], env
    if consumer in OWN_VENVS:
        venv, package = OWN_VENVS[consumer]
        py = venv / "bin" / "python"
        if not py.exists():
            return (f"{venv.name} is missing (python3.12 -m venv {venv.name}; "
                    f"{venv.name}/bin/pip install {package})")
        return [str(py), str(HERE / "worker.py"), consumer], env
    if consumer == "urdf_parser_py_0.0.4":
        if not OLD_UPP.is_dir():
            return f"urdf-parser-py 0.0.4 is not installed in {OLD_UPP}"
        env["PYTHONPATH"] = str(OLD_UPP)
        # the ROS package's urdfdom-py, installed in the venv, is shadowed by the target dir
        return [sys.executable, "-s", str(HERE / "worker.py"), consumer], env
    return [sys.executable, str(HERE / "worker.py"), consumer], env


def build_probe(build: Path) -> str | None:
    """Compile sdf_probe.cc against the installed sdformat (pkg-config); None on success."""
    for pc in ("sdformat14", "sdformat13", "sdformat12"):
        flags = subprocess.run(["pkg-config", "--cflags", "--libs", pc], capture_output=True,
                               text=True)
        if flags.returncode == 0:
            p = subprocess.run(["g++", "-std=c++17", "-O1", str(HERE / "sdf_probe.cc"), "-o",
                                str(build / "sdf_probe"), *flags.stdout.split()],
                               capture_output=True, text=True)
            return None if p.returncode == 0 else p.stderr[-500:]
    return "no sdformat found by pkg-config (apt-get install libsdformat-dev)"


def _limits() -> None:
    """A consumer that loops on a kinematic loop takes memory without bound: 4 GB at most."""
    import resource
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_BYTES, MEMORY_BYTES))


class Worker:
    def __init__(self, consumer: str, build: Path):
        self.consumer, self.build = consumer, build
        self.proc: subprocess.Popen | None = None
        self.version: str | None = None
        self.unavailable: str | None = None

    def start(self) -> bool:
        cmd = _command(self.consumer, self.build)
        if isinstance(cmd, str):
            self.unavailable = cmd
            return False
        argv, env = cmd
        self.proc = subprocess.Popen(argv, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.DEVNULL, text=True, env=env,
                                     cwd=self.build, start_new_session=True,
                                     preexec_fn=_limits)
        first = self._line(TIMEOUT_S * 3)
        if not first:
            self.unavailable = "the worker died while importing the consumer"
            return False
        head = json.loads(first)
        if "unavailable" in head:
            self.unavailable = head["unavailable"]
            return False
        self.version = head["version"]
        return True

    def _line(self, timeout: float) -> str | None:
        assert self.proc is not None and self.proc.stdout is not None
        ready, _, _ = select.select([self.proc.stdout], [], [], timeout)
        if not ready:
            return None
        return self.proc.stdout.readline()      # "" when the process died

    def stop(self) -> None:
        if self.proc is not None and self.proc.poll() is None:
            os.killpg(self.proc.pid, 9)
            self.proc.wait()
        self.proc = None

    def load(self, path: Path) -> dict:
        if self.proc is None and not self.start():
            return {"v": "?", "msg": self.unavailable}
        assert self.proc is not None and self.proc.stdin is not None
        try:
            self.proc.stdin.write(str(path) + "\n")
            self.proc.stdin.flush()
        except BrokenPipeError:
            pass
        line = self._line(TIMEOUT_S)
        if line:
            return json.loads(line)
        if line is None:
            self.stop()
            return {"v": "C", "msg": f"no answer in {TIMEOUT_S}s (hangs)"}
        rc = self.proc.wait()
        self.proc = None
        return {"v": "C", "msg": f"the process died (signal {-rc})" if rc < 0 else
                f"the process exited with status {rc}"}


# -- inputs ------------------------------------------------------------------------------------
def _urdf_lint(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "urdf_lint", *args], capture_output=True,
                          text=True, cwd=cwd or REPO)


def _packages() -> dict[str, Path]:
    out = {}
    for pxml in CORPUS.rglob("package.xml"):
        m = re.search(r"<name>\s*([^<\s]+)\s*</name>", pxml.read_text(errors="replace"))
        if m:
            out[m.group(1)] = pxml.parent
    return out


def _absolute_uris(text: str, pkgs: dict[str, Path], folder: Path) -> str:
    """package:// and file:// URIs and relative paths as absolute file paths (MuJoCo and
    PyBullet resolve no packages)."""
    def sub(m):
        uri = m.group(2)
        if uri.startswith("package://"):
            name, _, rest = uri[10:].partition("/")
            if name in pkgs:
                uri = str(pkgs[name] / rest)
        elif uri.startswith("file://"):
            uri = uri[7:]
        elif not uri.startswith("/"):
            uri = str(folder / uri)
        return f'{m.group(1)}"{uri}"'
    return re.sub(r'(filename=)"([^"]*)"', sub, text)


def _not_generated(text: str) -> str:
    """The expansion without xacro's "autogenerated" banner: beside its source, urdf-lint would
    take it for the source's generated output and report on the source instead."""
    return re.sub(r"<!--[^>]*?autogenerated by xacro[\s\S]*?-->", "", text, count=1)


def expand(entry: str, args: dict) -> str | None:
    src = CORPUS / entry
    if not src.name.endswith(".xacro") and ".xacro" not in src.name:
        text = src.read_text(errors="replace")
    else:
        p = _urdf_lint("expand", str(src), *(f"{k}:={v.replace('{CORPUS}', str(CORPUS))}"
                                             for k, v in args.items()))
        if p.returncode != 0:
            return None
        text = p.stdout
    return text


def prepare(work: Path, fast: bool, with_corpus: bool) -> dict[str, dict]:
    """Write every input under ``work``; returns id -> {path, kind, class, base, codes, lint}.

    A consumer loads ``path``, with its mesh URIs made absolute; urdf-lint lints ``lint``, the
    same model with its URIs as written, placed beside its source in a copy of the corpus
    (``work.parent / "corpus"``), so that its packages and relative paths resolve inside the
    linted roots as they do for a user."""
    items: dict[str, dict] = {}
    copy = work.parent / "corpus"
    pkgs = _packages() if CORPUS.is_dir() else {}
    if not fast and CORPUS.is_dir():
        shutil.copytree(CORPUS, copy, ignore=shutil.ignore_patterns(".git"))
        pkgs = {k: copy / v.relative_to(CORPUS) for k, v in pkgs.items()}
    bases = {"probe": mutants.PROBE}
    raw: dict[str, str] = {"probe": mutants.PROBE}
    if not fast and CORPUS.is_dir():
        for entry, args in mutants.BASE_ENTRIES:
            text = expand(entry, args)
            if text is not None:
                raw[entry] = text
                bases[entry] = _absolute_uris(text, pkgs, (copy / entry).parent)

    def lint_copy(base: str, ident: str, text: str, folder: Path) -> Path:
        text = _not_generated(text)
        if base == "probe" or not base:
            return folder / "r.urdf"
        src = (copy / base).parent
        for f, data in mutants.MESH_FILES.items():
            (src / f).write_bytes(data)
        (src / f"_harness_{ident}.urdf").write_text(text)
        return src / f"_harness_{ident}.urdf"
    n = 0
    for base, text in bases.items():
        for name, codes in mutants.all_classes().items():
            m = mutants.mutate(text, name)
            if m is None:
                continue
            d = work / f"m{n:04d}"
            d.mkdir(parents=True)
            for f, data in mutants.MESH_FILES.items():
                (d / f).write_bytes(data)
            (d / "r.urdf").write_text(m)
            mine = mutants.mutate(raw[base], name) if base != "probe" else m
            items[d.name] = {"path": d / "r.urdf", "kind": "mutant", "class": name,
                             "base": base, "codes": list(codes),
                             "lint": lint_copy(base, d.name, mine or m, d)}
            n += 1
        d = work / f"m{n:04d}"
        d.mkdir(parents=True)
        (d / "r.urdf").write_text(text)
        items[d.name] = {"path": d / "r.urdf", "kind": "base", "class": "clean base",
                         "base": base, "codes": [],
                         "lint": lint_copy(base, d.name, raw[base], d)}
        n += 1
    if with_corpus and CORPUS.is_dir():
        entries = json.loads((CORPUS / "entries.json").read_text())
        for i, e in enumerate(entries):
            text = expand(e["file"], e["args"])
            d = work / f"c{i:04d}"
            d.mkdir(parents=True)
            label = e["file"] + ("" if not e["args"] else " " + " ".join(
                f"{k}:={v}" for k, v in sorted(e["args"].items()) if "{CORPUS}" not in v))
            if text is None:
                continue
            (d / "r.urdf").write_text(_absolute_uris(text, pkgs, (copy / e["file"]).parent))
            src = (copy / e["file"]).parent / f"_harness_{d.name}.urdf"
            src.write_text(_not_generated(text))
            items[d.name] = {"path": d / "r.urdf", "kind": "corpus", "class": label,
                             "base": "", "codes": [], "lint": src,
                             "not_a_robot": "<link" not in text}
    return items


# -- lint under each target --------------------------------------------------------------------
def lint(work: Path, items: dict, targets: set[str]) -> dict[str, dict[str, list]]:
    """id -> target -> [(code, severity)] of the loading rules, from one run per target over
    ``work`` and the corpus copy beside it (whose own files' findings are left aside)."""
    out: dict[str, dict[str, list]] = {i: {} for i in items}
    which = {str(Path(it.get("lint", it["path"])).resolve()): i for i, it in items.items()}
    roots = [str(work)] + ([str(work.parent / "corpus")] if (work.parent / "corpus").is_dir()
                           else [])
    for t in sorted(targets):
        p = _urdf_lint("check", *roots, "--no-cache", "--format", "json", "--fail-on",
                       "never", "--select", "ALL", "--target", t, cwd=work.parent)
        if p.returncode != 0:
            raise SystemExit(f"urdf-lint --target {t} failed: {p.stderr[-2000:]}")
        for i in items:
            out[i][t] = []
        for f in json.loads(p.stdout)["findings"]:
            i = which.get(str((work.parent / f["file"]).resolve()))
            if i is not None and f["code"] not in REPOSITORY_CODES:
                out[i][t].append((f["code"], f["severity"]))
    return out


def agrees(verdict: str, findings: list, codes: list) -> tuple[bool, str]:
    """Does urdf-lint under the consumer's target say what the consumer did?"""
    errors = sorted({c for c, s in findings if s == "error"})
    if verdict in ("R", "C", "W"):
        return bool(errors), "" if errors else "the consumer %s, urdf-lint has no error" % (
            {"R": "rejects", "C": "crashes", "W": "loads a different robot"}[verdict])
    if errors:
        return False, "the consumer loads it, urdf-lint errors: " + ", ".join(errors)
    return True, ""


def run(fast: bool, with_corpus: bool, consumers: list[str], keep: Path | None = None,
        lint_only: bool = False) -> dict:
    """Prepare the inputs, load them in each consumer, lint them. With ``keep`` the inputs and
    the verdicts stay in that folder, and ``lint_only`` reuses them (after a rule changed)."""
    work = keep or Path(tempfile.mkdtemp(prefix="ul-consumers-"))
    build = work / "_build"
    saved = work / "verdicts-raw.json"
    if lint_only:
        raw = json.loads(saved.read_text())
        items = {i: dict(it, path=Path(it["path"])) for i, it in raw["items"].items()}
        findings = lint(work / "in", items, {v["target"] for v in raw["info"].values()
                                             if "version" in v})
        return summarise(items, raw["results"], findings, raw["info"])
    if keep is not None and work.exists():
        shutil.rmtree(work)
    build.mkdir(parents=True)
    try:
        probe_error = build_probe(build) if "sdformat" in consumers else None
        items = prepare(work / "in", fast, with_corpus)
        results: dict[str, dict] = {i: {} for i in items}
        info: dict[str, dict] = {}
        for c in consumers:
            t0 = time.time()
            w = Worker(c, build)
            if c == "sdformat" and probe_error:
                w.unavailable = probe_error
            elif not w.start():
                pass
            if w.unavailable:
                info[c] = {"target": CONSUMERS[c], "unavailable": w.unavailable}
                print(f"{c}: unavailable: {w.unavailable}", file=sys.stderr)
                continue
            bases = {it["base"]: i for i, it in items.items() if it["kind"] == "base"}
            order = sorted(items, key=lambda i: items[i]["kind"] != "base")   # bases first
            for i in order:
                it = items[i]
                r = results[i][c] = w.load(it["path"])
                base = results.get(bases.get(it["base"], ""), {}).get(c, {})
                if r["v"] == "." and "links" in r and "links" in base and \
                        it["class"] not in mutants.LUMPS and \
                        r["links"] < base["links"]:
                    r.update(v="W", msg=f"loads {r['links']} links of the base's "
                                        f"{base['links']}: links dropped")
                if r["v"] == "." and it["kind"] != "corpus" and (
                        it["class"] in mutants.CHANGES_ROBOT or
                        c in mutants.CHANGES_ROBOT_FOR.get(it["class"], ())):
                    r.update(v="W", msg="loads; the class drops or contradicts part of the "
                                        "robot (mutants.CHANGES_ROBOT)")
                elif r["v"] == "." and it["kind"] == "corpus":
                    text = Path(it["path"]).read_text()
                    why = mutants.different_robot(text, c)
                    made = mutants.bodies(text)
                    if why:
                        r.update(v="W", msg="loads; " + why)
                    elif "links" in r and made is not None and r["links"] < made:
                        r.update(v="W", msg=f"loads {r['links']} links of the {made} the "
                                            "model's joints make: links dropped")
            info[c] = {"target": CONSUMERS[c], "version": w.version}
            w.stop()
            print(f"{c} {w.version}: {len(items)} models in {time.time() - t0:.0f}s",
                  file=sys.stderr)
        if keep is not None:
            saved.write_text(json.dumps({"items": items, "results": results, "info": info},
                                        default=str))
        targets = {info[c]["target"] for c in info if "version" in info[c]}
        findings = lint(work / "in", items, targets)
        return summarise(items, results, findings, info)
    finally:
        if keep is None:
            shutil.rmtree(work, ignore_errors=True)


def summarise(items, results, findings, info) -> dict:
    mutants_out: dict[str, dict] = {}
    corpus_out: dict[str, dict] = {}
    agreement: dict[str, dict] = {}
    disagreements: list[dict] = []
    for i, it in items.items():
        for c, r in results[i].items():
            t = info[c]["target"]
            if (c, it["class"]) in mutants.NOT_MEASURED or r["v"] == "?" or \
                    it.get("not_a_robot"):
                continue          # a macro library expanded alone is no robot to load
            if c == "sdformat" and it["kind"] == "corpus" and \
                    "mesh" in (mutants.different_robot(Path(it["path"]).read_text(), "isaac") or ""):
                continue          # sdf_probe opens no mesh file: a missing one is not measured
            ok, why = agrees(r["v"], findings[i].get(t, []), it["codes"])
            part = "corpus" if it["kind"] == "corpus" else "mutants"
            a = agreement.setdefault(c, {"mutants": [0, 0], "corpus": [0, 0]})[part]
            a[1] += 1
            a[0] += ok
            if not ok:
                disagreements.append({"consumer": c, "kind": part, "model": it["class"],
                                      "base": it["base"], "why": why, "msg": r["msg"]})
            if it["kind"] == "corpus":
                corpus_out.setdefault(it["class"], {})[c] = r["v"]
            else:
                row = mutants_out.setdefault(it["class"], {"codes": it["codes"],
                                                           "verdicts": {}})
                msg = re.sub(r"/\S*/in/[mc]\d+/", "", r["msg"])         # no scratch paths
                msg = re.sub(r"/\S*/corpus/", "corpus/", msg)[:200]
                row["verdicts"].setdefault(c, {})[it["base"]] = \
                    {"v": r["v"], "msg": msg} if r["v"] != "." else {"v": "."}
    return {"consumers": info, "mutants": mutants_out, "corpus": corpus_out,
            "agreement": {c: {k: f"{a[0]}/{a[1]}" for k, a in v.items()}
                          for c, v in agreement.items()},
            "disagreements": disagreements}


def merge_verdicts(old: dict, new: dict) -> dict:
    """The recorded verdicts ``old`` with the consumers measured in ``new`` replaced (their
    versions, and their verdict on every mutant and corpus model ``new`` has)."""
    out = json.loads(json.dumps(old))
    for c, v in new["consumers"].items():   # the date of each re-measured consumer
        out["consumers"][c] = dict(v, measured=new["measured"])
    for name, row in new["mutants"].items():
        mine = out["mutants"].setdefault(name, {"codes": row["codes"], "verdicts": {}})
        mine["codes"] = row["codes"]
        mine["verdicts"].update(row["verdicts"])
    for name, row in new["corpus"].items():
        out["corpus"].setdefault(name, {}).update(row)
    return out   # ("measured": the date of the last full run)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--fast", action="store_true",
                    help="the probe's mutants only, the pip consumers only (CI's part)")
    ap.add_argument("--no-corpus", action="store_true")
    ap.add_argument("--consumers", help="comma-separated (default: all, or the pip ones with "
                                        "--fast)")
    ap.add_argument("--write", action="store_true", help=f"write {VERDICTS.relative_to(REPO)}")
    ap.add_argument("--report", metavar="FILE", help="write the whole result (with the "
                                                     "disagreements) as JSON to FILE")
    ap.add_argument("--keep", metavar="DIR", help="keep the inputs and the verdicts in DIR")
    ap.add_argument("--lint-only", action="store_true",
                    help="with --keep: reuse the verdicts kept there, lint again")
    a = ap.parse_args(argv)
    consumers = a.consumers.split(",") if a.consumers else list(
        PIP_CONSUMERS if a.fast else CONSUMERS)
    res = run(a.fast, not (a.fast or a.no_corpus), consumers,
              Path(a.keep).resolve() if a.keep else None, a.lint_only)
    if a.report:
        Path(a.report).write_text(json.dumps(res, indent=1, default=str))
    for c, v in res["agreement"].items():
        print(f"{c:22} mutants {v['mutants']:>9}   corpus {v['corpus']:>9}")
    if a.write:
        keep = {k: res[k] for k in ("consumers", "mutants", "corpus")}
        keep["measured"] = time.strftime("%Y-%m-%d")
        if a.consumers:   # some consumers measured again: the others' verdicts are kept
            keep = merge_verdicts(json.loads(VERDICTS.read_text()), keep)
        VERDICTS.write_text(json.dumps(keep, indent=1, sort_keys=True) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
