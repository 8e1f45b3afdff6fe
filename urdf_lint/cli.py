"""Command line: ``urdf-lint check|expand|rules|rule|render|clean``.

Exit codes: 0 clean, 1 findings at or above --fail-on, 2 usage or internal error.
Heavy modules (xacro, trimesh, rerun) are imported only by the commands that need them.
"""
from __future__ import annotations

import argparse
import os
import sys


class UsageError(Exception):
    pass


def _parse_package_paths(items):
    out = {}
    for it in items or []:
        name, sep, d = it.partition("=")
        if not sep or not name or not d:
            raise UsageError(f"--package-path expects NAME=DIR, got {it!r}")
        out[name] = os.path.abspath(d)
    return out


def _parse_mappings(items):
    args, rest = {}, []
    for it in items:
        if ":=" in it:
            k, _, v = it.partition(":=")
            args[k] = v
        else:
            rest.append(it)
    return args, rest


def _codes(s):
    return [c.strip() for c in s.split(",") if c.strip()] if s else []


def build_parser():
    p = argparse.ArgumentParser(prog="urdf-lint", description=__doc__.splitlines()[0])
    p.add_argument("--version", action="store_true", help="print the version and exit")
    sub = p.add_subparsers(dest="command")

    c = sub.add_parser("check", help="find, expand and lint every robot model under PATHS")
    c.add_argument("paths", nargs="*", default=["."])
    c.add_argument("--format", choices=["text", "json", "sarif", "github", "junit"])
    c.add_argument("--output", "-o", help="write the report to this file")
    c.add_argument("--select", help="comma-separated codes or prefixes (replaces config)")
    c.add_argument("--extend-select", help="codes or prefixes to add")
    c.add_argument("--ignore", help="codes or prefixes to ignore")
    c.add_argument("--fail-on", choices=["error", "warning", "info", "never"])
    c.add_argument("--package-path", action="append", metavar="NAME=DIR")
    c.add_argument("--config", help="config file (pyproject.toml or urdf-lint.toml)")
    c.add_argument("--isolated", action="store_true", help="ignore all config files")
    c.add_argument("-j", "--jobs", type=int, help="parallel workers (default: CPU count)")
    c.add_argument("--no-cache", action="store_true", help="do not read or write the cache")
    c.add_argument("--statistics", action="store_true", help="print counts per rule")
    c.add_argument("--render", metavar="DIR", help="also write snapshots (.rrd, .png) to DIR")
    c.add_argument("--changed-since", metavar="REF",
                   help="only the models affected by files changed since a git ref")
    c.add_argument("--baseline", metavar="FILE",
                   help="ignore findings recorded in FILE (create it with --write-baseline)")
    c.add_argument("--write-baseline", metavar="FILE", help="record current findings to FILE")
    c.add_argument("--timeout", type=float, help="per-model time limit in seconds")
    c.add_argument("--memory-mb", type=int, help="per-model memory limit in MiB")
    c.add_argument("--env-allow", action="append", metavar="VAR",
                   help="an environment variable $(env)/$(optenv) may read (repeatable)")
    c.add_argument("--cache-dir", metavar="DIR", help="where to keep the result cache")
    c.add_argument("--trust-config", action="store_true",
                   help="let the repository's config set env-allow, package-paths outside "
                        "it, cache-dir, jobs and looser limits")
    c.add_argument("--quiet", "-q", action="store_true", help="no summary line when clean")

    h = sub.add_parser("hook", help="pre-commit: lint the models that the given files affect")
    h.add_argument("files", nargs="*")
    h.add_argument("--format", choices=["text", "json", "sarif", "github", "junit"])
    h.add_argument("--select")
    h.add_argument("--extend-select")
    h.add_argument("--ignore")
    h.add_argument("--fail-on", choices=["error", "warning", "info", "never"])
    h.add_argument("--package-path", action="append", metavar="NAME=DIR")
    h.add_argument("--config")
    h.add_argument("-j", "--jobs", type=int)
    h.add_argument("--no-cache", action="store_true")
    h.add_argument("--trust-config", action="store_true")

    e = sub.add_parser("expand", help="expand one xacro file to URDF (no ROS needed)")
    e.add_argument("file")
    e.add_argument("mappings", nargs="*", metavar="name:=value")
    e.add_argument("-o", "--output")
    e.add_argument("--package-path", action="append", metavar="NAME=DIR")
    e.add_argument("--env-allow", action="append", metavar="VAR")
    e.add_argument("--trust-config", action="store_true")

    sub.add_parser("rules", help="list the rule catalogue")
    r = sub.add_parser("rule", help="explain one rule")
    r.add_argument("code")

    rd = sub.add_parser("render", help="write .rrd recordings and PNG snapshots")
    rd.add_argument("paths", nargs="*", default=["."])
    rd.add_argument("--out", default="snapshots")
    rd.add_argument("--package-path", action="append", metavar="NAME=DIR")
    rd.add_argument("--config")
    rd.add_argument("--no-rrd", action="store_true", help="PNG only")
    rd.add_argument("-j", "--jobs", type=int)
    rd.add_argument("--trust-config", action="store_true")

    sub.add_parser("doctor", help="show which protections the worker sandbox has here")

    cl = sub.add_parser("clean", help="remove the cache")
    cl.add_argument("paths", nargs="*", default=["."])
    return p


def _load_cfg(args, paths):
    from .config import find_config, load_config, validate_codes
    from .registry import codes_to_names
    known = codes_to_names()
    if getattr(args, "isolated", False):
        cfg = load_config(None)
    else:
        path = args.config or find_config(paths[0] if paths else ".")
        cfg = load_config(path, known)
    _trust(cfg, args, paths)
    if getattr(args, "select", None):
        cfg.select = _codes(args.select)
    if getattr(args, "extend_select", None):
        cfg.extend_select += _codes(args.extend_select)
    if getattr(args, "ignore", None):
        cfg.ignore += _codes(args.ignore)
    if getattr(args, "fail_on", None):
        cfg.fail_on = args.fail_on
    if getattr(args, "timeout", None):
        cfg.timeout = args.timeout
    _cli_settings(cfg, args)
    validate_codes(cfg, known)
    return cfg


def _trust(cfg, args, paths):
    """The repository's config may not loosen the guarantees (see urdf_lint/trust.py)."""
    from .check import repo_root
    from . import trust
    first = os.path.abspath(paths[0] if paths else ".")
    start = first if os.path.isdir(first) else os.path.dirname(first)
    for n in trust.apply(cfg, repo_root(start), trusted=getattr(args, "trust_config", False)):
        sys.stderr.write(f"urdf-lint: {n}\n")


def _cli_settings(cfg, args):
    """What the user set on the command line wins, clamped like the rest."""
    from . import trust
    if getattr(args, "env_allow", None):
        cfg.env_allow = list(cfg.env_allow) + list(args.env_allow)
    if getattr(args, "memory_mb", None):
        cfg.memory_mb = args.memory_mb
    if getattr(args, "cache_dir", None):
        cfg.cache_dir = os.path.abspath(args.cache_dir)
    if getattr(args, "jobs", None):
        cfg.jobs = args.jobs
    trust.clamp(cfg)


def cmd_check(args) -> int:
    from .check import build_resolver, exit_code, run_check
    from . import report
    for p in args.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    cfg = _load_cfg(args, args.paths)
    resolver = build_resolver(args.paths, cfg, _parse_package_paths(args.package_path))
    cache = None
    if not args.no_cache:
        from .cache import Cache
        cache = Cache.for_paths(args.paths, cfg)
        if cache.refused:  # said why on stderr; nothing (mesh facts included) goes there
            cache = None
    affected_by = None
    if args.changed_since:
        from .changes import GitError, changed_files
        try:
            affected_by = changed_files(args.changed_since, args.paths[0] if os.path.isdir(args.paths[0])
                                        else os.path.dirname(os.path.abspath(args.paths[0])))
        except (GitError, OSError) as e:
            raise UsageError(f"--changed-since {args.changed_since}: {e}") from None
    if getattr(args, "files", None) is not None:
        affected_by = {os.path.abspath(f) for f in args.files}
    progress = None
    if sys.stderr.isatty() and not os.environ.get("CI"):
        def progress(n, total):
            sys.stderr.write(f"\rlinting {n}/{total} models" + (" " * 10))
            if n == total:
                sys.stderr.write("\r" + " " * 40 + "\r")
            sys.stderr.flush()
    render_dir = getattr(args, "render", None)
    _refuse_symlinked_out(render_dir)
    result = run_check(args.paths, cfg, resolver, jobs_n=cfg.jobs, cache=cache,
                       progress=progress, affected_by=affected_by, render_dir=render_dir)
    if args.write_baseline:
        from .baseline import write_baseline
        write_baseline(args.write_baseline, result.findings)
    if args.baseline:
        from .baseline import filter_baseline
        result.findings = filter_baseline(args.baseline, result.findings)
    fmt = args.format or cfg.format or ("github" if os.environ.get("GITHUB_ACTIONS") else "text")
    if args.output:
        with open(args.output + ".tmp", "w", encoding="utf-8") as f:
            report.write(result, fmt, f, statistics=args.statistics, color=False)
        os.replace(args.output + ".tmp", args.output)
    elif not (args.quiet and not result.findings):
        report.write(result, fmt, sys.stdout, statistics=args.statistics)
    for f in result.unused_files:
        from .locations import display_path
        if f.endswith((".xacro", ".urdf", ".yaml", ".yml", ".stl", ".dae", ".obj")):
            sys.stderr.write(f"note: {_safe_text(display_path(f))} is not used by any model\n")
    for msg in result.internal:
        sys.stderr.write(f"urdf-lint: internal error (please report): {_safe_lines(msg)}\n")
    if render_dir:
        _report_snapshots(result, render_dir)
    return exit_code(result, cfg.fail_on)


def _report_snapshots(result, out_dir):
    from .render import write_summary
    from .locations import display_path
    written = 0
    for m in result.models:
        snap = m.stats.get("snapshot") or {}
        for k in ("png", "rrd"):
            if snap.get(k):
                written += 1
        for prob in snap.get("problems", []):
            sys.stderr.write(f"urdf-lint: snapshot of {_safe_text(m.label)}: {_safe_text(prob)}\n")
        if m.status != "model":
            sys.stderr.write(f"urdf-lint: no snapshot of {_safe_text(m.label)}: it did not expand "
                             "(see 'urdf-lint check')\n")
    summary = write_summary(result, out_dir)
    sys.stderr.write(f"snapshots: {written} files for {len(result.models)} model(s) in "
                     f"{display_path(out_dir)}/ (summary: {display_path(summary)})\n")


def cmd_hook(args) -> int:
    """Lint the whole repository (cached) and report the models that the files affect."""
    from .check import repo_root
    root = repo_root(os.getcwd())
    ns = argparse.Namespace(paths=[root], output=None, statistics=False, render=None,
                            changed_since=None, baseline=None, write_baseline=None, timeout=None,
                            quiet=True, isolated=False, **vars(args))
    ns.command = "check"
    if not args.files:
        return 0
    return cmd_check(ns)


def cmd_expand(args) -> int:
    from .config import load_config
    from .check import build_resolver
    from .config import DEFAULT_ENV_ALLOW
    from .locations import display_path
    if not os.path.isfile(args.file):
        raise UsageError(f"no such file: {args.file}")
    mappings, rest = _parse_mappings(args.mappings)
    if rest:
        raise UsageError(f"expected name:=value, got {' '.join(rest)}")
    from .config import find_config
    cfg = load_config(find_config(args.file))
    _trust(cfg, args, [args.file])
    _cli_settings(cfg, args)
    resolver = build_resolver([args.file], cfg, _parse_package_paths(args.package_path))
    # expanded in a worker like `check`: time and memory limits, scrubbed environment, sandbox
    from .worker import run_jobs
    import xacro  # noqa: F401 - imported once in the parent, shared by the forked worker
    from . import expand  # noqa: F401
    job = {"entry": os.path.abspath(args.file), "args": mappings, "kind": "expand",
           "explicit": True, "display_name": args.file}
    settings = {"resolver": resolver.to_dict(), "selected": [], "options": {},
                "env_allow": sorted(set(DEFAULT_ENV_ALLOW) | set(cfg.env_allow)),
                "mesh_cache_dir": None}
    res = {}
    for _, res in run_jobs([job], settings, jobs_n=1, timeout=cfg.timeout,
                           memory_mb=cfg.memory_mb):
        pass
    for msg in res.get("internal") or []:
        sys.stderr.write(f"urdf-lint: internal error (please report): {_safe_lines(msg)}\n")
        return 2
    for n in res.get("notes") or []:
        sys.stderr.write(f"{_safe_text(display_path(n['file']))}:{n['line']}:{n['col']}: {n['code']} "
                         f"{_safe_text(n['message'])}\n")
    error = res.get("error") or (res.get("findings") or [None])[0]
    if error or res.get("xml") is None:
        e = error or {"file": job["entry"], "line": 1, "col": 1, "code": "UL002",
                      "message": "expansion failed"}
        sys.stderr.write(f"{_safe_text(display_path(e['file']))}:{e['line']}:{e['col']}: {e['code']} "
                         f"{_safe_text(e['message'])}\n")
        return 1
    xml = res["xml"]
    if args.output:
        d = os.path.dirname(os.path.abspath(args.output))
        os.makedirs(d, exist_ok=True)
        tmp = args.output + ".tmp"
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(xml)
        os.replace(tmp, args.output)
    else:
        sys.stdout.write(xml)
    return 0


def _safe_text(s) -> str:
    from .report.escape import escape_text
    return escape_text(str(s))


def _safe_lines(s) -> str:
    return "\n".join(_safe_text(line) for line in str(s).split("\n"))


def cmd_rules(args) -> int:
    from .registry import load_rules
    for code, r in load_rules().items():
        print(f"{code}  {r.name:<28} {r.severity:<8} {r.summary}")
    return 0


def cmd_rule(args) -> int:
    from .registry import find_rule
    r = find_rule(args.code)
    if r is None:
        raise UsageError(f"unknown rule {args.code!r} (see 'urdf-lint rules')")
    print(f"{r.code} {r.name} (default severity: {r.severity})\n")
    print(r.doc)
    if r.options:
        print("\nOptions (set under [tool.urdf-lint.rule-options." + r.code + "]):")
        for k, v in r.options.items():
            print(f"  {k} = {v!r}")
    print("\nFails:\n" + r.fail.strip())
    print("\nPasses:\n" + r.passing.strip())
    return 0


def _refuse_symlinked_out(d):
    """Snapshots are written where the user said, never through a link a repository planted."""
    if d and os.path.islink(d.rstrip(os.sep) or d):
        raise UsageError(f"output folder {d} is a symlink; refusing to write through it")


def cmd_render(args) -> int:
    from .check import build_resolver, run_check
    for p in args.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    _refuse_symlinked_out(args.out)
    cfg = _load_cfg(args, args.paths)
    resolver = build_resolver(args.paths, cfg, _parse_package_paths(args.package_path))
    result = run_check(args.paths, cfg, resolver, jobs_n=cfg.jobs,
                       render_dir=args.out, render_rrd=not args.no_rrd)
    _report_snapshots(result, args.out)
    for m in result.models:
        snap = m.stats.get("snapshot") or {}
        for k in ("png", "rrd"):
            if snap.get(k):
                from .locations import display_path
                print(display_path(snap[k]))
    for msg in result.internal:
        sys.stderr.write(f"urdf-lint: internal error (please report): {_safe_lines(msg)}\n")
    return 2 if result.internal else 0


def cmd_clean(args) -> int:
    from .cache import Cache
    from .config import load_config
    removed = Cache.for_paths(args.paths, load_config(None)).clear()
    print(f"removed {removed}" if removed else "no cache to remove")
    return 0


def cmd_doctor(args) -> int:
    from . import __version__
    from .sandbox import protections
    print(f"urdf-lint {__version__} on {sys.platform}, Python {sys.version.split()[0]}")
    for name, (ok, why) in protections().items():
        print(f"  {'on ' if ok else 'OFF'}  {name:<12} {why}")
    return 0


COMMANDS = {"doctor": cmd_doctor, "check": cmd_check, "hook": cmd_hook, "expand": cmd_expand, "rules": cmd_rules, "rule": cmd_rule,
            "render": cmd_render, "clean": cmd_clean}


def main(argv=None) -> int:
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:
        return 2 if e.code else 0
    if args.version:
        from . import __version__
        from .sandbox import summary_line
        print(f"urdf-lint {__version__}\n{summary_line()}")
        return 0
    if not args.command:
        parser.print_help()
        return 2
    from .config import ConfigError
    import signal

    def _terminate(signum, frame):  # SIGTERM is handled like Ctrl-C: workers are stopped
        raise KeyboardInterrupt
    try:
        signal.signal(signal.SIGTERM, _terminate)
    except ValueError:  # pragma: no cover - not the main thread
        pass
    try:
        return COMMANDS[args.command](args)
    except (UsageError, ConfigError) as e:
        sys.stderr.write(f"urdf-lint: error: {e}\n")
        return 2
    except KeyboardInterrupt:
        sys.stderr.write("urdf-lint: interrupted\n")
        return 2
    except BrokenPipeError:
        return 0
    except Exception as e:  # noqa: BLE001
        import traceback
        sys.stderr.write(f"urdf-lint: internal error (please report): {type(e).__name__}: {e}\n")
        if os.environ.get("URDF_LINT_DEBUG"):
            traceback.print_exc()
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
