"""Command line: ``urdf-lint check|expand|rules|rule|render|clean``.

Exit codes: 0 clean, 1 findings at or above --fail-on, 2 usage or internal error.
Heavy modules (xacro, trimesh, rerun) are imported only by the commands that need them.
"""
from __future__ import annotations

import argparse
import os
import sys


from .errors import UsageError


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

    e = sub.add_parser("expand", help="expand one xacro file to URDF (no ROS needed)")
    e.add_argument("file")
    e.add_argument("mappings", nargs="*", metavar="name:=value")
    e.add_argument("-o", "--output")
    e.add_argument("--package-path", action="append", metavar="NAME=DIR")

    rl = sub.add_parser("rules", help="list the rule catalogue")
    rl.add_argument("--format", choices=["text", "markdown"], default="text",
                    help="text: one line per rule; markdown: the full rules page (default: text)")
    r = sub.add_parser("rule", help="explain one rule")
    r.add_argument("code")

    rd = sub.add_parser("render", help="write .rrd recordings and PNG snapshots")
    rd.add_argument("paths", nargs="*", default=["."])
    rd.add_argument("--out", default="snapshots")
    rd.add_argument("--package-path", action="append", metavar="NAME=DIR")
    rd.add_argument("--config")
    rd.add_argument("--no-rrd", action="store_true", help="PNG only")
    rd.add_argument("-j", "--jobs", type=int)

    df = sub.add_parser("diff", help="what a change did to the robots: a semantic diff of "
                        "every affected model between two git revisions")
    df.add_argument("base", help="the base revision (e.g. origin/main)")
    df.add_argument("head", nargs="?", help="the head revision (default: the working tree)")
    df.add_argument("--path", action="append", dest="paths", metavar="PATH",
                    help="limit to models under PATH (default: the whole repository)")
    df.add_argument("--format", choices=["text", "json", "markdown"], default="text",
                    help="output format (default: text)")
    df.add_argument("--output", "-o", help="write the report to this file")
    df.add_argument("--image-base-url", help="where snapshot images will be served from "
                    "(markdown only)")
    df.add_argument("--fail-on", choices=["error", "warning", "info", "never"],
                    help="exit 1 when the change introduces findings at or above this "
                    "severity (default: error)")
    df.add_argument("--package-path", action="append", metavar="NAME=DIR")
    df.add_argument("-j", "--jobs", type=int, help="parallel workers (default: CPU count)")
    df.add_argument("--no-cache", action="store_true", help="do not read or write the cache")
    df.add_argument("--render", metavar="DIR", help="write before/after/difference PNGs with "
                    "identical framing and one .rrd holding both revisions per affected model")
    df.add_argument("--no-rrd", action="store_true", help="with --render: PNGs only")
    g = sub.add_parser("generate", help="rewrite every generated URDF (the 'output' of a "
                       "models entry, or a .urdf whose header names its xacro) that is stale")
    g.add_argument("paths", nargs="*", default=["."])
    g.add_argument("--check", action="store_true",
                   help="only report stale outputs (exit 1), write nothing")
    g.add_argument("--package-path", action="append", metavar="NAME=DIR")
    g.add_argument("--config")
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
    validate_codes(cfg, known)
    return cfg


def _through_models(args, cfg):
    """``check FILE`` / ``render FILE`` on fragments or macro libraries: (the repository root
    to lint, the files whose models to report), or None when every path is a model or a folder.
    The models that include such a file are linted instead of the file on its own."""
    from .discovery import build_resolver, discover_models, repository_root
    from .jobs import Status
    from .lint import classify_xacro
    if not args.paths or not all(os.path.isfile(p) for p in args.paths):
        return None
    files = [os.path.realpath(p) for p in args.paths]
    configured = {m.path for m in cfg.models}
    cand = [f for f in files if f.endswith(".xacro") and f not in configured]
    if not cand:
        return None
    root = repository_root(args.paths)
    resolver = build_resolver([root], cfg, _parse_package_paths(args.package_path))
    graph = discover_models([root], cfg, resolver).graph
    redirect = [f for f in cand if graph.includers(f) or classify_xacro(f) is Status.LIBRARY]
    if not redirect:
        return None
    from .locations import display_path
    for f in redirect:
        by = graph.includers(f)
        if by:
            sys.stderr.write(f"note: {display_path(f)} is included by "
                             f"{', '.join(display_path(g) for g in by[:5])}"
                             f"{' ...' if len(by) > 5 else ''}: linting the models that "
                             "include it\n")
    return root, set(files)


def cmd_check(args) -> int:
    from .discovery import build_resolver, start_dir
    from .pipeline import exit_code, run_check
    from . import report
    for p in args.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    cfg = _load_cfg(args, args.paths)
    affected_by = None
    if getattr(args, "files", None) is None and not args.changed_since:
        redirect = _through_models(args, cfg)
        if redirect is not None:
            args.paths, affected_by = [redirect[0]], redirect[1]
    resolver = build_resolver(args.paths, cfg, _parse_package_paths(args.package_path))
    cache = None
    if not args.no_cache:
        from .cache import Cache
        cache = Cache.for_paths(args.paths, cfg)
    if args.changed_since:
        from .vcs import GitError, changed_files
        try:
            affected_by = changed_files(args.changed_since, start_dir(args.paths))
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
    result = run_check(args.paths, cfg, resolver, jobs_n=args.jobs or cfg.jobs, cache=cache,
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
    _note_unused(result)
    for msg in result.internal:
        sys.stderr.write(f"urdf-lint: internal error (please report): {msg}\n")
    if render_dir:
        _report_snapshots(result, render_dir)
    return exit_code(result, cfg.fail_on)


def _note_unused(result):
    from .locations import display_path
    for f in result.gone:
        if f.endswith((".xacro", ".urdf")):
            sys.stderr.write(f"note: {display_path(f)} was deleted and no remaining model "
                             "reads it; if it was a model, it is gone\n")
    for f in result.unused_files:
        if f.endswith((".xacro", ".urdf", ".yaml", ".yml", ".stl", ".dae", ".obj")):
            sys.stderr.write(f"note: {display_path(f)} is not used by any model\n")


def _report_snapshots(result, out_dir):
    from .render import write_summary
    from .locations import display_path
    written = 0
    for m in result.models:
        snap = m.snapshot or {}
        for k in ("png", "rrd"):
            if snap.get(k):
                written += 1
        for prob in snap.get("problems", []):
            sys.stderr.write(f"urdf-lint: snapshot of {m.label}: {prob}\n")
        if m.status != "model":
            sys.stderr.write(f"urdf-lint: no snapshot of {m.label}: it did not expand "
                             "(see 'urdf-lint check')\n")
    summary = write_summary(result, out_dir)
    sys.stderr.write(f"snapshots: {written} files for {len(result.models)} model(s) in "
                     f"{display_path(out_dir)}/ (summary: {display_path(summary)})\n")


def cmd_hook(args) -> int:
    """Lint the whole repository (cached) and report the models that the files affect."""
    from .vcs import repo_root
    root = repo_root(os.getcwd())
    ns = argparse.Namespace(paths=[root], output=None, statistics=False, render=None,
                            changed_since=None, baseline=None, write_baseline=None, timeout=None,
                            quiet=True, isolated=False, **vars(args))
    ns.command = "check"
    # pre-commit passes only files that exist: add what the commit deletes or renames away
    from .vcs import GitError, staged_removals
    try:
        removed = staged_removals(os.getcwd())
    except (GitError, OSError):
        removed = set()
    ns.files = list(args.files) + sorted(removed)
    if not ns.files:
        return 0
    return cmd_check(ns)


def cmd_expand(args) -> int:
    from .config import load_config
    from .discovery import build_resolver
    from .expansion import expand_file
    from .config import DEFAULT_ENV_ALLOW
    from .locations import display_path
    if not os.path.isfile(args.file):
        raise UsageError(f"no such file: {args.file}")
    mappings, rest = _parse_mappings(args.mappings)
    if rest:
        raise UsageError(f"expected name:=value, got {' '.join(rest)}")
    from .config import find_config
    cfg = load_config(find_config(args.file))
    resolver = build_resolver([args.file], cfg, _parse_package_paths(args.package_path))
    res = expand_file(args.file, mappings, resolver,
                      env_allow=tuple(DEFAULT_ENV_ALLOW) + tuple(cfg.env_allow),
                      display_name=args.file)
    for n in res.notes:
        sys.stderr.write(f"{display_path(n.file)}:{n.line}:{n.col}: {n.code} {n.message}\n")
    if res.error:
        e = res.error
        sys.stderr.write(f"{display_path(e.file)}:{e.line}:{e.col}: {e.code} {e.message}\n")
        return 1
    if args.output:
        d = os.path.dirname(os.path.abspath(args.output))
        os.makedirs(d, exist_ok=True)
        tmp = args.output + ".tmp"
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(res.xml)
        os.replace(tmp, args.output)
    else:
        sys.stdout.write(res.xml)
    return 0


def cmd_rules(args) -> int:
    from .registry import load_rules
    if getattr(args, "format", "text") == "markdown":
        from .rulesdoc import markdown
        sys.stdout.write(markdown(load_rules()))
        return 0
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


def cmd_render(args) -> int:
    from .discovery import build_resolver
    from .pipeline import run_check
    for p in args.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    cfg = _load_cfg(args, args.paths)
    redirect = _through_models(args, cfg)
    affected_by = None
    if redirect is not None:
        args.paths, affected_by = [redirect[0]], redirect[1]
    resolver = build_resolver(args.paths, cfg, _parse_package_paths(args.package_path))
    result = run_check(args.paths, cfg, resolver, jobs_n=args.jobs or cfg.jobs,
                       render_dir=args.out, render_rrd=not args.no_rrd, affected_by=affected_by)
    _note_unused(result)
    _report_snapshots(result, args.out)
    for m in result.models:
        snap = m.snapshot or {}
        for k in ("png", "rrd"):
            if snap.get(k):
                from .locations import display_path
                print(display_path(snap[k]))
    for msg in result.internal:
        sys.stderr.write(f"urdf-lint: internal error (please report): {msg}\n")
    if result.internal:
        return 2
    # a requested model that could not be snapshotted is a failure, not a blank image
    missed = [m for m in result.models if m.status != "model" or not (m.snapshot or {}).get("png")]
    return 1 if missed else 0


def cmd_diff(args) -> int:
    from . import review, review_report
    paths = args.paths or ["."]
    for p in paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    args.config, args.isolated = None, False
    try:
        result = review.run_diff(args.base, args.head, paths, lambda ps: _load_cfg(args, ps),
                                 _parse_package_paths(args.package_path), jobs_n=args.jobs,
                                 use_cache=not args.no_cache, render_dir=args.render,
                                 rrd=not args.no_rrd)
    except review.ReviewError as e:
        raise UsageError(str(e)) from None
    kw = {"image_base_url": args.image_base_url} if args.format == "markdown" else {}
    if args.output:
        review_report.write_file(result, args.format, args.output, **kw)
    else:
        review_report.write(result, args.format, sys.stdout, **kw)
    for msg in result.internal:
        sys.stderr.write(f"urdf-lint: internal error (please report): {msg}\n")
    return review.exit_code(result, args.fail_on or "error")


def cmd_generate(args) -> int:
    """Regenerate stale outputs in place (atomically); exit 1 when a file was (or, with
    --check, would be) rewritten or a xacro did not expand, like a formatter hook."""
    from .config import DEFAULT_ENV_ALLOW
    from .discovery import build_resolver, discover_models
    from .expansion import expand_file
    from .generated import header_source, stale_at, write_output
    from .locations import display_path
    for p in args.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    cfg = _load_cfg(args, args.paths)
    resolver = build_resolver(args.paths, cfg, _parse_package_paths(args.package_path))
    status = 0
    for job in discover_models(args.paths, cfg, resolver).jobs:
        if not job.output:
            continue
        named = header_source(job.output) if os.path.exists(job.output) else None
        shown = os.path.relpath(job.entry)   # what the header names (xacro opens this path)
        res = expand_file(job.entry, job.args, resolver,
                          env_allow=tuple(DEFAULT_ENV_ALLOW) + tuple(cfg.env_allow),
                          display_name=shown)
        if res.error is not None:
            e = res.error
            sys.stderr.write(f"{display_path(e.file)}:{e.line}:{e.col}: {e.code} {e.message}\n")
            status = 1
            continue
        if stale_at(job.output, res.xml) is None:
            continue
        status = 1
        if named and res.xml:   # keep the header's own name for the source: no churn
            head, rest = res.xml[:1024], res.xml[1024:]
            res.xml = head.replace(f"from {shown} ", f"from {named} ", 1) + rest
        if args.check:
            print(f"would regenerate {display_path(job.output)} from {display_path(job.entry)}")
        else:
            write_output(job.output, res.xml)
            print(f"regenerated {display_path(job.output)} from {display_path(job.entry)}")
    return status


def cmd_clean(args) -> int:
    from .cache import Cache
    from .config import load_config
    removed = Cache.for_paths(args.paths, load_config(None)).clear()
    print(f"removed {removed}" if removed else "no cache to remove")
    return 0


COMMANDS = {"check": cmd_check, "hook": cmd_hook, "expand": cmd_expand, "rules": cmd_rules, "rule": cmd_rule,
            "render": cmd_render, "diff": cmd_diff, "generate": cmd_generate, "clean": cmd_clean}


def main(argv=None) -> int:
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:
        return 2 if e.code else 0
    if args.version:
        from . import __version__
        print(f"urdf-lint {__version__}")
        return 0
    if not args.command:
        parser.print_help()
        return 2
    from .config import ConfigError
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
