"""``urdf-lint check``: discover -> expand -> model -> rules -> findings.

This module orchestrates; the work happens in :mod:`urdf_lint.lint` (inside workers).
"""
from __future__ import annotations

import functools
import os
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

from .config import Config
from .findings import SEVERITY_RANK, Finding, merge
from .packages import PackageResolver, iter_files


@dataclass
class ModelResult:
    entry: str
    args: dict
    status: str
    stats: dict
    deps: list
    findings: list            # raw dicts
    cached: bool = False

    @property
    def label(self) -> str:
        from .locations import display_path
        base = display_path(self.entry)
        if self.args:
            base += " [" + " ".join(f"{k}:={v}" for k, v in sorted(self.args.items())) + "]"
        return base


@dataclass
class CheckResult:
    findings: list = field(default_factory=list)     # merged Finding objects, after filtering
    models: list = field(default_factory=list)       # ModelResult of linted models
    skipped: list = field(default_factory=list)      # libraries etc.
    internal: list = field(default_factory=list)     # internal errors (exit 2)
    unused_files: list = field(default_factory=list)


def git_root(start: str) -> str | None:
    return _git_root(os.path.abspath(start))


@functools.lru_cache(maxsize=16)  # asked by config trust, roots and the cache: one git call
def _git_root(start: str) -> str | None:
    try:
        out = subprocess.run(["git", "rev-parse", "--show-toplevel"], cwd=start,
                             capture_output=True, text=True, timeout=5)
        if out.returncode == 0 and out.stdout.strip():
            return out.stdout.strip()
    except (OSError, subprocess.SubprocessError):
        pass
    return None


def repo_root(start: str) -> str:
    """The git work tree holding ``start``, or ``start`` itself outside git."""
    return git_root(start) or os.path.abspath(start)


def build_resolver(paths, cfg: Config, cli_packages: dict | None = None) -> PackageResolver:
    from .packages import discover_roots
    first = os.path.abspath(paths[0]) if paths else os.getcwd()
    start = first if os.path.isdir(first) else os.path.dirname(first)
    scan, extra_roots = discover_roots(paths or [start], git_root(start))
    explicit = dict(cfg.package_paths)
    explicit.update(cli_packages or {})
    return PackageResolver.build(scan, explicit=explicit, extra_roots=extra_roots)


def discover(paths, cfg: Config) -> list[dict]:
    """Every candidate model file under the paths, with the arg sets to expand it with."""
    configured = {m.path: m.arg_sets for m in cfg.models}
    jobs, seen = [], set()
    for p in paths:
        p = os.path.abspath(p)
        for f in iter_files(Path(p), suffixes=(".urdf", ".xacro")):
            f = os.path.realpath(f) if not os.path.islink(f) else os.path.abspath(f)
            # an exclude does not apply below a path that is itself excluded and named explicitly
            if f in seen or (cfg.is_excluded(f) and not cfg.is_excluded(p)):
                continue
            seen.add(f)
            kind = "urdf" if f.endswith(".urdf") else "xacro"
            if f in configured:
                for args in configured[f]:
                    jobs.append({"entry": f, "args": dict(args), "kind": kind, "explicit": True})
            else:
                jobs.append({"entry": f, "args": {}, "kind": kind, "explicit": p == f})
    # configured models inside the linted paths that the walk did not reach
    for f, arg_sets in configured.items():
        if f in seen or not any(_inside(f, os.path.abspath(p)) for p in paths):
            continue
        kind = "urdf" if f.endswith(".urdf") else "xacro"
        for args in arg_sets:
            jobs.append({"entry": f, "args": dict(args), "kind": kind, "explicit": True})
    return jobs


def _inside(f, p):
    return f == p or f.startswith(p.rstrip(os.sep) + os.sep)


def selected_codes(cfg: Config) -> list[str]:
    from .registry import load_rules
    return [c for c, r in load_rules().items() if cfg.is_selected(c, r.name)]


def settings_for(cfg: Config, resolver: PackageResolver, cache_dir: str | None) -> dict:
    from .config import DEFAULT_ENV_ALLOW
    from .registry import load_rules
    rules = load_rules()
    options = {}
    for code, r in rules.items():
        o = cfg.options_for(code, r.name)
        if o:
            unknown = set(o) - set(r.options)
            if unknown:
                from .config import ConfigError
                raise ConfigError(f"unknown option(s) for {code} {r.name}: "
                                  f"{', '.join(sorted(unknown))} (known: "
                                  f"{', '.join(sorted(r.options)) or 'none'})")
            options[code] = o
    return {"resolver": resolver.to_dict(), "selected": selected_codes(cfg), "options": options,
            "env_allow": sorted(set(DEFAULT_ENV_ALLOW) | set(cfg.env_allow)),
            "mesh_cache_dir": cache_dir}


def to_findings(raw: list, label: str, cfg: Config) -> list[Finding]:
    from .registry import load_rules
    rules = load_rules()
    out = []
    for d in raw:
        r = rules.get(d["code"])
        name = r.name if r else d["code"]
        sev, best = (r.severity if r else "error"), -1
        for pat, s in cfg.severity.items():   # the most specific override wins
            if (d["code"].startswith(pat) or pat == name) and len(pat) > best:
                sev, best = s, len(pat)
        out.append(Finding(code=d["code"], name=name, severity=sev, message=d["message"],
                           file=d["file"], line=d["line"], col=d["col"],
                           chain=tuple(tuple(c) for c in d.get("chain", ())), models=[label]))
    return out


def run_check(paths, cfg: Config, resolver: PackageResolver, jobs_n=None, cache=None,
              progress=None,
              affected_by: set | None = None, render_dir: str | None = None,
              render_rrd: bool = True) -> CheckResult:
    """Lint every model under ``paths``. With ``affected_by`` (changed files), report only the
    models whose inputs include one of them; files no model uses land in ``unused_files``."""
    from . import suppress

    jobs = discover(paths, cfg)
    settings = settings_for(cfg, resolver, cache.dir if cache else None)
    results: list[ModelResult] = []
    todo = []
    if render_dir:
        os.makedirs(render_dir, exist_ok=True)
        settings = dict(settings, render_dir=os.path.realpath(render_dir), render_rrd=render_rrd,
                        render_base=os.getcwd())
    for job in jobs:
        # snapshots need the model itself, so a render pass expands everything once
        hit = cache.get(job, settings) if cache and not render_dir else None
        if hit is not None:
            results.append(ModelResult(job["entry"], job["args"], hit["status"], hit["stats"],
                                       hit["deps"], hit["findings"], cached=True))
        else:
            todo.append(job)
    internal = []
    if todo:
        from .worker import run_jobs
        import xacro  # noqa: F401 - import once in the parent, shared by the forked workers
        from . import expand  # noqa: F401
        for n, (job, res) in enumerate(run_jobs(todo, settings, jobs_n=jobs_n, timeout=cfg.timeout,
                                                memory_mb=cfg.memory_mb), 1):
            internal.extend(res.get("internal", []))
            mr = ModelResult(job["entry"], job["args"], res["status"], res["stats"], res["deps"],
                             res["findings"])
            results.append(mr)
            if cache and not res.get("internal"):
                cache.put(job, settings, res)
            if progress:
                progress(n, len(todo))

    # a candidate that failed on its own but is included by a model is a library
    used = set()
    for r in results:
        if r.status == "model":
            used.update(r.deps[1:])
    out = CheckResult(internal=internal)
    for r in sorted(results, key=lambda r: (r.entry, sorted(r.args.items()))):
        if r.status in ("library", "not-robot") or (r.status == "failed" and r.entry in used
                                                    and not r.args):
            out.skipped.append(r)
        else:
            out.models.append(r)

    if affected_by is not None:
        from .changes import affected
        out.models, out.unused_files = affected(out.models, affected_by)
        out.unused_files = [f for f in out.unused_files if os.path.exists(f)]
    all_findings = []
    for r in out.models:
        all_findings.extend(to_findings(r.findings, r.label, cfg))
    if affected_by is None:
        all_findings.extend(to_findings(_duplicate_robot_names(out.models), "", cfg))
    merged = merge(all_findings)
    files = set()
    for r in out.models:
        files.update(d for d in r.deps if d.endswith((".xacro", ".urdf", ".xml")))
    from .packages import MAX_SOURCE_BYTES
    # the parent reads only what the workers could: inside the roots, regular, bounded
    directives = {f: suppress.parse_directives(f) for f in sorted(files)
                  if resolver.readable(f, MAX_SOURCE_BYTES)}
    selected = settings["selected"]
    kept, unused = suppress.apply(
        merged, directives, is_selected=lambda c: any(s.startswith(c) for s in selected))
    kept += to_findings(unused, "", cfg)
    final = []
    for f in kept:
        if not cfg.is_selected(f.code, f.name) or cfg.ignored_for_file(f.code, f.name, f.file):
            continue
        if f.code == "UL009":
            f.models = []
        final.append(f)
    out.findings = sorted(final, key=lambda f: (f.file, f.line, f.col, f.code))
    return out


def _duplicate_robot_names(models) -> list:
    """UL106: different entry files declaring the same robot name."""
    from .locations import display_path
    by_name: dict = {}
    for m in models:
        name = m.stats.get("name")
        if name and m.stats.get("name_loc"):
            by_name.setdefault(name, {}).setdefault(m.entry, m)
    out = []
    for name, entries in by_name.items():
        if len(entries) < 2:
            continue
        for entry, m in entries.items():
            rest = [display_path(e) for e in entries if e != entry]
            others = ", ".join(rest[:3]) + (f" and {len(rest) - 3} more" if len(rest) > 3 else "")
            f, line, col = m.stats["name_loc"]
            out.append({"code": "UL106", "file": f, "line": line, "col": col, "chain": [],
                        "message": f"robot name '{name}' is also used by {others}"})
    return out


def exit_code(result: CheckResult, fail_on: str) -> int:
    if result.internal:
        return 2
    if fail_on == "never":
        return 0
    threshold = SEVERITY_RANK[fail_on]
    return 1 if any(SEVERITY_RANK[f.severity] >= threshold for f in result.findings) else 0
