"""``urdf-lint format [PATHS]``: lay out xacro and URDF sources (:mod:`urdf_lint.formatting.layout`)
and prove that no robot changes.

1. Every ``.urdf``/``.xacro`` under the paths (``exclude`` and ``[format] exclude`` honoured;
   a file named explicitly is always formatted) is read (regular files of bounded size only)
   and laid out; the guard of :func:`urdf_lint.formatting.layout.check_same` runs on each result.
2. **The proof.** The models of the repository that read a file that would change (the
   include graph of :mod:`urdf_lint.discovery.discover`, plus the models whose includes only expansion
   resolves, kept when their recorded inputs meet a changed file; ``exclude`` and
   ``discover = false`` do not hide a model from the proof) are expanded in the
   sandboxed workers, as ``check`` and ``expand`` do, once as the files are and once with the
   new layouts in place of the files (``LintSettings.overlay``: nothing is written while it
   is proved). The two robots are compared as canonical XML (comments, layout whitespace and
   attribute order ignored; every other text kept exact). A model that differs leaves every
   changed file it reads alone, and the reason is printed; the models those files also feed
   are proved again without them, until nothing more is refused.
3. The rest is written atomically (:func:`urdf_lint.core.fsbound.rewrite`), only below the
   formatted paths; ``--check`` and ``--diff`` write nothing.

Exit codes as ``ruff format``: 0 formatted (or nothing to do), 1 with ``--check``/``--diff``
when a file would change, 2 on an error (a file that is not well-formed XML, a bad option).
"""
from __future__ import annotations

import dataclasses
import os
import sys
from dataclasses import dataclass

from urdf_lint.formatting.layout import FormatError, Refused, Style, format_source, read_document, _normal

SUFFIXES = (".urdf", ".xacro")


def add_parser(sub, raw, add_inputs) -> None:
    p = sub.add_parser("format", help="lay out xacro and URDF sources (never changes a robot)",
                       description="Format xacro and URDF files: one element per line, "
                                   "children indented, long tags wrapped; comments, text and "
                                   "${...} kept byte for byte. Every model that reads a "
                                   "changed file is expanded before and after and must be "
                                   "identical, else the file is left alone.")
    p.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                   help="files or folders to format (default: .)")
    p.add_argument("--check", action="store_true",
                   help="write nothing; exit 1 when a file would be reformatted")
    p.add_argument("--diff", action="store_true",
                   help="write nothing; print the changes as a unified diff (exit 1 when "
                        "there are any)")
    p.add_argument("--indent", metavar="N", help="spaces per level (default: 2; config key "
                   "'indent' under [tool.urdf-lint.format])")
    p.add_argument("--line-length", metavar="N", help="wrap a start tag's attributes one per "
                   "line past N characters (default: 100; config key 'line-length')")
    p.add_argument("--attribute-order", metavar="{keep,canonical}",
                   help="canonical: name first, then the URDF/xacro schema order (default: "
                        "keep; config key 'attribute-order')")
    p.add_argument("--isolated", action="store_true", help="ignore all config files")
    add_inputs(p)
    p.add_argument("--timeout", metavar="SECONDS",
                   help="time limit per model expansion of the proof (default: 30)")
    p.add_argument("--memory-mb", metavar="MIB",
                   help="memory limit per model expansion of the proof (default: 2048)")
    p.add_argument("-q", "--quiet", action="store_true", help="print only errors")


def style_of(cfg, args=None) -> Style:
    """The layout settings: ``[tool.urdf-lint.format]``, then the command line."""
    from urdf_lint.config.schema import FORMAT_KEYS, format_option
    opts = {k: FORMAT_KEYS[k].default for k in ("indent", "line-length", "attribute-order")}
    opts.update({k: v for k, v in cfg.format_options.items() if k in opts})
    for k in opts:
        given = getattr(args, k.replace("-", "_"), None) if args is not None else None
        if given is not None:
            opts[k] = format_option(k, given)
    return Style(indent=opts["indent"], line_length=opts["line-length"],
                 attribute_order=opts["attribute-order"])


@dataclass
class FileResult:
    """One file the formatter looked at: its bytes before and after, or why it is left alone."""
    path: str                   # real path
    shown: str                  # as messages show it
    old: bytes = b""
    new: bytes | None = None    # the new layout (None: unchanged, or left alone)
    error: str | None = None    # cannot be formatted (exit 2)
    refused: str | None = None  # left alone: why


def files_to_format(paths, cfg) -> list[str]:
    from urdf_lint.discovery.discover import _candidates
    excludes = list(cfg.exclude) + list(cfg.format_options.get("exclude", []))
    scoped = dataclasses.replace(cfg, exclude=excludes)
    return [f for f, _ in _candidates(paths, scoped)]


def format_files(files, style: Style, paths) -> list[FileResult]:
    """Read and lay out each file (not written)."""
    from urdf_lint.core.hashing import read_regular
    from urdf_lint.core.locations import display_path
    from urdf_lint.discovery.packages import MAX_SOURCE_BYTES
    from urdf_lint.fix.sourceedit import inside
    real_paths = [os.path.realpath(p) for p in paths]
    out = []
    for f in files:
        real = os.path.realpath(f)
        res = FileResult(real, display_path(f))
        out.append(res)
        if not inside(real, real_paths, resolved=True):
            res.refused = "it resolves outside the formatted paths (a symlink?)"
            continue
        data = read_regular(real, MAX_SOURCE_BYTES)
        if data is None:
            res.error = (f"{res.shown}:1:1: not a regular file of at most "
                         f"{MAX_SOURCE_BYTES >> 20} MiB; not formatted")
            continue
        res.old = data
        try:
            new = format_source(data, style, real)
        except FormatError as e:
            res.error = f"{res.shown}:{e.line}:{e.col}: {e.message}"
            continue
        except Refused as e:
            res.refused = e.reason
            continue
        if new != data:
            res.new = new
    return out


# -- the proof ------------------------------------------------------------------------------------
def canonical_robot(xml: str) -> list:
    """An expanded robot as canonical nodes: comments and layout whitespace dropped,
    attributes sorted, all other text exact."""
    return _normal([n for n in read_document(xml.encode("utf-8")) if n[0] == "el"], False,
                   comments=False)


def first_difference(a: list, b: list, path: str = "") -> str:
    """Where two canonical robots first differ, as ``<joint 'j1'>``."""
    for x, y in zip(a, b, strict=False):
        if x == y:
            continue
        if x[0] == y[0] == "el" and x[1] == y[1] and x[2] == y[2]:
            return first_difference(x[3], y[3], _describe(x))
        return _describe(x if x[0] == "el" else y) if (x[0] == "el" or y[0] == "el") \
            else f"the text in {path or 'the document'}"
    return f"the number of children of {path or 'the document'}"


def _describe(node) -> str:
    name = dict(node[2]).get("name")
    return f"<{node[1]}{' ' + repr(name) if name else ''}>"


def _outcome(report):
    """(canonical robot or None, the failure or None) of an expansion."""
    from urdf_lint.core.jobs import Status
    xml = report.kept_model.xml if report.kept_model is not None else None
    if report.status is Status.FAILED or xml is None or report.internal:
        why = next(iter(report.problems), None)
        text = f"{why.code} {why.message}" if why is not None else "expansion failed"
        return None, text
    try:
        return canonical_robot(xml), None
    except FormatError as e:
        return None, e.message


def prove(changed: dict, paths, cfg, package_paths, jobs_n=None) -> tuple[dict, int]:
    """({real path: why it must be left alone}, how many models were compared) for the new
    layouts ``changed`` ({real path: bytes})."""
    from urdf_lint.config.schema import DEFAULT_ENV_ALLOW
    from urdf_lint.discovery.discover import build_resolver, discover_models, repository_root
    from urdf_lint.core.jobs import LintJob, LintSettings
    from urdf_lint.discovery.packages import inside
    from urdf_lint.runner.worker import run_jobs
    if not changed:
        return {}, 0
    root = repository_root(paths)
    scan = [root] + [p for p in paths if not inside(os.path.realpath(p), os.path.realpath(root))]
    resolver = build_resolver(scan, cfg, package_paths)
    # every model that may read a changed file, also those the config leaves out of linting
    every = dataclasses.replace(cfg, exclude=[], discover=True)
    disc = discover_models(scan, every, resolver)
    graph = disc.graph

    def reach(entry):
        seen, todo = {entry}, [entry]
        while todo:
            for g in graph.includes.get(todo.pop(), ()):
                if g not in seen:
                    seen.add(g)
                    todo.append(g)
        return seen
    jobs = {}
    for job in disc.jobs:
        if job.kind != "xacro":   # a .urdf model is the file itself: the guard compared it
            continue
        if reach(job.entry) & changed.keys() or graph.unresolved_below(job.entry):
            key = (job.entry, tuple(sorted(job.args.items())))
            jobs[key] = LintJob(job.entry, dict(job.args), "expand", explicit=True)
    env_allow = tuple(sorted(set(DEFAULT_ENV_ALLOW) | set(cfg.env_allow)))
    base = LintSettings(resolver=resolver.to_dict(), env_allow=env_allow)

    def expand(keys, overlay):
        settings = dataclasses.replace(base, overlay=dict(overlay))
        by_job = {id(jobs[k]): k for k in keys}
        return {by_job[id(j)]: r for j, r in run_jobs([jobs[k] for k in keys], settings,
                                                      jobs_n=jobs_n, timeout=cfg.timeout,
                                                      memory_mb=cfg.memory_mb)}
    before = expand(list(jobs), {})
    deps = {k: {os.path.realpath(d) for d in r.deps} for k, r in before.items()}
    overlay = dict(changed)
    refused: dict = {}
    pending = [k for k in jobs if deps[k] & overlay.keys()]
    compared = len(pending)
    while pending:
        after = expand(pending, overlay)
        removed: set = set()
        for k in pending:
            deps[k] |= {os.path.realpath(d) for d in after[k].deps}
            (a, why_a), (b, why_b) = _outcome(before[k]), _outcome(after[k])
            if a is not None and b is not None:
                if a == b:
                    continue
                why = f"{first_difference(a, b)} differs"
            elif a is None and b is None:
                if why_a == why_b:
                    continue   # it does not expand either way: the guard is the proof
                why = f"the expansion fails differently ({why_b})"
            else:
                why = f"the expansion {'fails' if b is None else 'succeeds'} once formatted" + \
                    (f" ({why_b})" if why_b else "")
            label = before[k].label
            for f in sorted(deps[k] & overlay.keys()):
                refused.setdefault(f, f"formatting would change the robot {label}: {why}")
                removed.add(f)
        for f in removed:
            overlay.pop(f, None)
        pending = [k for k in jobs if deps[k] & removed and deps[k] & overlay.keys()]
    return refused, compared


# -- the command ---------------------------------------------------------------------------------
def cmd_format(args, load_cfg, parse_package_paths) -> int:
    from urdf_lint.core.errors import UsageError
    for p in args.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    cfg = load_cfg(args, args.paths)
    style = style_of(cfg, args)
    results = format_files(files_to_format(args.paths, cfg), style, args.paths)
    changed = {r.path: r.new for r in results if r.new is not None}
    compared = 0
    if changed:
        refused, compared = prove(changed, args.paths, cfg,
                                  parse_package_paths(args.package_path), cfg.jobs)
        for r in results:
            if r.path in refused:
                r.refused, r.new = refused[r.path], None
    status = _say_problems(results)
    todo = [r for r in results if r.new is not None]
    if args.diff:
        from urdf_lint.fix.run import unified_diff
        sys.stdout.write(unified_diff({r.path: r.new for r in todo},
                                      {r.path: r.old for r in todo}))
    else:
        status = max(status, _check_or_write(todo, args))
    if not args.quiet:
        _say_summary(results, todo, args, compared)
    if status:
        return status
    return 1 if todo and (args.check or args.diff) else 0


def _say_problems(results) -> int:
    """Say each file that could not be formatted or was left alone; 2 for an error or an
    internal problem, else 0."""
    from urdf_lint.core.emit import say
    from urdf_lint.core.escape import escape_text
    status = 0
    for r in results:
        if r.error:
            say(f"error: {escape_text(r.error)}")
            status = 2
        elif r.refused:
            say(f"{escape_text(r.shown)}: left alone: {escape_text(r.refused)}")
            if r.refused.startswith("internal"):
                status = 2
    return status


def _check_or_write(todo, args) -> int:
    """The names of the files to format (``--check``), or the files written in place; 2 when
    one cannot be written, else 0."""
    from urdf_lint.core.emit import say
    from urdf_lint.core.escape import escape_text
    status = 0
    if args.check:
        from urdf_lint.core.emit import tell
        for r in todo:
            tell(f"Would reformat: {escape_text(r.shown)}")
    else:
        from urdf_lint.core import fsbound
        for r in todo:
            try:   # only below the formatted paths, atomically (the boundary)
                fsbound.rewrite(r.path, r.new or b"", args.paths)
            except OSError as e:
                say(f"error: {escape_text(r.shown)}: cannot write: "
                    f"{getattr(e, 'why', None) or e.strerror or e}")
                status = 2
    return status


def _say_summary(results, todo, args, compared) -> None:
    from urdf_lint.core.emit import say
    left = sum(1 for r in results if r.refused)
    same = sum(1 for r in results if r.new is None and not r.refused and not r.error)
    verb = "would be reformatted" if args.check or args.diff else "reformatted"
    say(f"{len(todo)} file(s) {verb}, {same} file(s) left unchanged"
        + (f", {left} file(s) left alone" if left else "")
        + (f" ({compared} model(s) expanded before and after)" if compared else ""))
