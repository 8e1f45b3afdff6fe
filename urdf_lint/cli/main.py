"""Command line: urdf-lint check|hook|expand|rules|rule|render|diff|generate|format|mcp|clean|
doctor.

Exit codes: 0 clean, 1 findings at or above --fail-on, 2 usage or internal error, 130 Ctrl-C.
Heavy modules (xacro, trimesh, rerun) are imported only by the commands that need them.
Options that are also config keys (``--select``, ``--timeout``, ...) go through the config
schema (:mod:`urdf_lint.config.schema`), so a bad value on the command line gets the same message as
in a config file.
"""
from __future__ import annotations

import argparse
import difflib
import os
import re
import sys
from pathlib import Path

from urdf_lint.core.emit import say, tell
from urdf_lint.core.errors import UsageError


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


def plain(text: str) -> str:
    """Docstring text for a terminal: reST literals (````x````) become ```x```."""
    return re.sub(r"``(.+?)``", r"`\1`", text, flags=re.S)


def first_sentence(doc: str) -> str:
    """The first sentence of a rule's docstring, as plain text (an ellipsis is not an end)."""
    para = " ".join(plain(doc).strip().split("\n\n")[0].split())
    m = re.search(r"(?<!\.)\.(?!\.)\s+", para)
    return para if m is None else para[:m.start() + 1]


# -- the parser -------------------------------------------------------------------------------
class _Parser(argparse.ArgumentParser):
    """A command-line mistake is one line: what is wrong, the closest known flag or command,
    and where the usage is (like ruff; the whole usage buried the suggestion)."""

    def error(self, message):
        m = re.match(r"argument (\S+): invalid choice: '([^']*)' \(choose from (.*)\)", message)
        if m:
            choices = re.findall(r"'([^']*)'", m.group(3))
            close = difflib.get_close_matches(m.group(2), choices, n=1, cutoff=0.6)
            if close:
                message += f" (did you mean {close[0]}?)"
        m = re.match(r"unrecognized arguments: (.*)", message)
        if m:
            hints = []
            args = [a for a in m.group(1).split() if a.startswith("-")]
            for arg in args:
                close = difflib.get_close_matches(arg.split("=")[0], self.flags(), n=1,
                                                  cutoff=0.6)
                if close:
                    hints.append(f"did you mean {close[0]}?" if len(args) == 1
                                 else f"{arg}: did you mean {close[0]}?")
            if hints:
                message += " (" + "; ".join(hints) + ")"
        self.exit(2, f"{self.prog}: error: {message}; see '{self.prog} --help'\n")

    def flags(self) -> list:
        return [s for a in self._actions for s in a.option_strings]


def add_key_flags(p, group: str) -> None:
    """The flags of the config keys in ``group`` (each key's ``flag`` in the schema)."""
    from urdf_lint.config.schema import FLAG_KEYS
    for k in FLAG_KEYS:
        f = k.flag
        assert f is not None
        if f.group == group:
            p.add_argument(*f.flags, dest=f.dest or k.attr, metavar=k.metavar(),
                           action="append" if f.repeat else "store", help=k.cli_help())


def _add_selection(p):
    add_key_flags(p, "selection")
    p.add_argument("--exit-zero", action="store_true",
                   help="exit 0 even when there are findings (still 2 on errors)")


def _add_target(p):
    from urdf_lint.config.schema import KEYS
    f = KEYS["targets"].flag
    assert f is not None
    p.add_argument(*f.flags, action="append", metavar=f.metavar, dest=f.dest,
                   help=KEYS["targets"].cli_help())


def _add_inputs(p, config=True):
    p.add_argument("--package-path", action="append", metavar="NAME=DIR",
                   help="where package NAME is, for $(find NAME) and package://NAME; "
                        "repeatable (default: package.xml files under the paths and the "
                        "repository, AMENT_PREFIX_PATH, ROS_PACKAGE_PATH)")
    if config:
        p.add_argument("--config", metavar="FILE",
                       help="config file: pyproject.toml or urdf-lint.toml (default: the "
                            "nearest one above the first path)")
        add_key_flags(p, "jobs")
    _add_trust(p)


def _add_trust(p):
    """The keys a repository's own config may not set (urdf_lint/config/trust.py), and the switch
    that lets it."""
    from urdf_lint.config.trust import trust_config_help
    add_key_flags(p, "trust")
    p.add_argument("--trust-config", action="store_true", help=trust_config_help())


def _add_views(p):
    add_key_flags(p, "views")


def _add_limits(p):
    add_key_flags(p, "limits")
    add_key_flags(p, "cache")


def _add_output(p):
    from urdf_lint.report.registry import formats
    fmts = formats()
    add_key_flags(p, "output")
    p.epilog = "output formats:\n" + "\n".join(f"  {n:<9} {c.help}" for n, c in fmts.items())
    p.add_argument("--show-source", action="store_true",
                   help="show the source line of each finding under it (text format)")
    p.add_argument("--statistics", action="store_true",
                   help="print only the number of findings per rule")
    p.add_argument("--color", metavar="{auto,always,never}", default="auto",
                   help="colour the text output; auto colours a terminal unless NO_COLOR is "
                        "set, or anything when FORCE_COLOR is set (default: auto)")
    add_key_flags(p, "baseline")
    p.add_argument("--no-cache", action="store_true",
                   help="do not read or write the result cache (.urdf_lint_cache/)")
    v = p.add_mutually_exclusive_group()
    v.add_argument("-q", "--quiet", action="store_true",
                   help="print the findings and nothing else (no summary, notes or progress)")
    v.add_argument("-v", "--verbose", action="store_true",
                   help="also list the config, each model and every file it read, and files "
                        "no model uses")


def _add_fix(p):
    """``check --fix`` and friends (issue 14; :mod:`urdf_lint.fix.cli`)."""
    p.add_argument("--fix", action="store_true",
                   help="apply the safe fixes to the xacro sources, then report what remains "
                        "(default: off, nothing is written)")
    p.add_argument("--unsafe-fixes", action="store_true",
                   help="with --fix or --diff: also the fixes that change structure "
                        "(default: off)")
    p.add_argument("--diff", action="store_true",
                   help="print the fixes as a unified diff of the sources instead of writing "
                        "(as proposed: --fix also re-lints and rolls back the wrong ones)")
    p.add_argument("--add-suppressions", action="store_true",
                   help="write '<!-- urdf-lint: disable-next CODE -->' above each finding's "
                        "source line (adopt the linter in one commit; default: off)")
    p.add_argument("--exit-non-zero-on-fix", action="store_true",
                   help="with --fix: exit 1 when a file was changed (pre-commit; default: off)")


def _fix_mode(args) -> bool:
    """Whether ``check`` writes or proposes fixes; the flags that need each other are checked."""
    fix, diff = getattr(args, "fix", False), getattr(args, "diff", False)
    adds = getattr(args, "add_suppressions", False)
    if getattr(args, "unsafe_fixes", False) and not (fix or diff):
        raise UsageError("--unsafe-fixes needs --fix or --diff")
    if getattr(args, "exit_non_zero_on_fix", False) and not fix:
        raise UsageError("--exit-non-zero-on-fix needs --fix")
    if adds and (fix or diff):
        raise UsageError("--add-suppressions cannot be combined with --fix or --diff")
    return bool(fix or diff or adds)


SUBPARSERS: dict = {}


def _cmd_check(sub, raw):
    c = sub.add_parser("check", help="find, expand and lint every robot model under PATHS",
                       formatter_class=raw,
                       description="Find, expand and lint every robot model under PATHS.")
    c.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                   help="files or folders to lint (default: .)")
    _add_output(c)
    c.add_argument("-o", "--output", metavar="FILE",
                   help="write the report to FILE, atomically (default: standard output)")
    _add_selection(c)
    _add_inputs(c)
    c.add_argument("--isolated", action="store_true", help="ignore all config files")
    c.add_argument("--render", metavar="DIR",
                   help="also write snapshots (.rrd, .png) to DIR (default: no snapshots)")
    _add_views(c)
    c.add_argument("--changed-since", metavar="REF",
                   help="only the models affected by files changed since a git ref, e.g. "
                        "origin/main (default: every model)")
    c.add_argument("--write-baseline", metavar="FILE",
                   help="record the current findings in FILE and exit 0 (default: off)")
    _add_limits(c)
    _add_fix(c)


def _cmd_hook(sub, raw):
    h = sub.add_parser("hook", help="pre-commit: lint the models that the given files affect",
                       formatter_class=raw,
                       description="Lint the models that the given (changed) files affect; "
                                   "the whole repository is linted through the cache.")
    h.add_argument("files", nargs="*", metavar="FILE",
                   help="changed files, as pre-commit passes them (default: none)")
    _add_output(h)
    _add_selection(h)
    _add_inputs(h)
    _add_limits(h)


def _cmd_expand(sub, raw):
    e = sub.add_parser("expand", help="expand one xacro file to URDF (no ROS needed)",
                       description="Expand one xacro file to URDF, byte-identical to xacro 2.1.1.")
    e.add_argument("file", help="the .xacro file")
    e.add_argument("mappings", nargs="*", metavar="name:=value",
                   help="xacro args (default: the args' defaults)")
    e.add_argument("-o", "--output", metavar="FILE",
                   help="write the URDF to FILE, atomically (default: standard output)")
    _add_inputs(e, config=False)
    add_key_flags(e, "limits")


def _cmd_rules(sub, raw):
    rl = sub.add_parser("rules", help="list the rule catalogue", description="List the rule catalogue.")
    rl.add_argument("--format", choices=["text", "markdown"], default="text",
                    help="text: one line per rule; markdown: the full rules page (default: text)")


def _cmd_rule(sub, raw):
    r = sub.add_parser("rule", help="explain one rule", description="Explain one rule.")
    r.add_argument("code", help="a rule code (UL302) or name (limit-order)")


def _cmd_render(sub, raw):
    rd = sub.add_parser("render", help="write .rrd recordings and PNG snapshots",
                        description="Write a .rrd recording and a PNG snapshot per model.")
    rd.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                    help="files or folders (default: .)")
    rd.add_argument("--out", default="snapshots", metavar="DIR",
                    help="output folder (default: snapshots)")
    _add_inputs(rd)
    _add_limits(rd)
    rd.add_argument("--no-rrd", action="store_true", help="PNG only, no rerun recording")
    _add_views(rd)
    _add_target(rd)


def _cmd_diff(sub, raw):
    df = sub.add_parser("diff", help="what a change did to the robots: a semantic diff of "
                        "every affected model between two git revisions", formatter_class=raw,
                        description="Compare every model a change affects between two git "
                                    "revisions: links, joints, limits, inertials, geometry, "
                                    "poses and findings, at their xacro lines.")
    df.add_argument("base", help="the base revision (e.g. origin/main)")
    df.add_argument("head", nargs="?", help="the head revision (default: the working tree)")
    df.add_argument("--path", action="append", dest="paths", metavar="PATH",
                    help="limit to models under PATH (default: the whole repository)")
    from urdf_lint.report import diff as diff_formats
    fmts = diff_formats.formats()
    df.add_argument("--format", choices=list(fmts), default="text", metavar="FORMAT",
                    help="output format: " + ", ".join(fmts) + " (see below; default: text)")
    df.epilog = "output formats:\n" + "\n".join(f"  {n:<9} {c.help}" for n, c in fmts.items())
    df.add_argument("-o", "--output", metavar="FILE",
                    help="write the report to FILE, atomically (default: standard output)")
    df.add_argument("--image-base-url", metavar="URL",
                    help="where the --render images will be served from, for the markdown "
                         "(default: none, no images in the markdown)")
    df.add_argument("--fail-on", choices=["error", "warning", "info", "never"],
                    help="exit 1 when the change introduces findings at or above this "
                         "severity (default: error)")
    _add_target(df)
    df.add_argument("--package-path", action="append", metavar="NAME=DIR",
                    help="where a package lives (default: found from package.xml files)")
    df.add_argument("-j", "--jobs", metavar="N",
                    help="parallel workers (default: from the work, at most the CPU count)")
    df.add_argument("--no-cache", action="store_true", help="do not read or write the cache")
    df.add_argument("--render", metavar="DIR", help="write before/after/difference PNGs with "
                    "identical framing and one .rrd holding both revisions per affected model "
                    "(default: no snapshots)")
    df.add_argument("--no-rrd", action="store_true", help="with --render: PNGs only")
    _add_views(df)
    df.add_argument("--trust-config", action="store_true",
                    help="let each revision's config set env-allow, package-paths outside the "
                         "repository, cache-dir, jobs and looser limits (default: off)")


def _cmd_generate(sub, raw):
    g = sub.add_parser("generate", help="rewrite every stale generated URDF (the 'output' of a "
                       "models entry, or a .urdf whose header names its xacro)",
                       description="Rewrite every generated URDF that no longer equals what its "
                                   "xacro expands to (atomically); exit 1 when one was stale.")
    g.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                   help="files or folders (default: .)")
    g.add_argument("--check", action="store_true",
                   help="only report stale outputs (exit 1), write nothing")
    _add_inputs(g)


def _cmd_format(sub, raw):
    from urdf_lint.formatting.run import add_parser
    add_parser(sub, raw, _add_inputs)


def _cmd_mcp(sub, raw):
    from urdf_lint.cli.mcp import add_parser
    add_parser(sub, raw)


def _cmd_doctor(sub, raw):
    sub.add_parser("doctor", help="show which protections the worker sandbox has here",
                   description="Show which OS protections the workers get on this machine "
                               "(Landlock, seccomp, parent-death signal) and which are missing.")


def _cmd_clean(sub, raw):
    cl = sub.add_parser("clean", help="remove the cache", description="Remove the result cache.")
    cl.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                    help="find the cache from here (default: .)")


def _cmd_server(sub, raw):
    sub.add_parser("server", help="a language server for editors (LSP over stdio; needs the "
                   "'server' extra)",
                   description="Run the urdf-lint language server on stdin/stdout: diagnostics "
                               "from the real expansion, fixes, navigation, hover, completion. "
                               "Editors start it; see the README for the set-up.")


# the subcommands in the order of `urdf-lint --help`; each builds its own parser
_COMMAND_PARSERS = {
    "check": _cmd_check,
    "hook": _cmd_hook,
    "expand": _cmd_expand,
    "rules": _cmd_rules,
    "rule": _cmd_rule,
    "render": _cmd_render,
    "diff": _cmd_diff,
    "generate": _cmd_generate,
    "format": _cmd_format,
    "mcp": _cmd_mcp,
    "doctor": _cmd_doctor,
    "clean": _cmd_clean,
    "server": _cmd_server,
}


def build_parser(only: str | None = None):
    """The command-line parser; with ``only`` (a known command) just that subcommand's parser
    is built: building all of them imports the format registry and the config schema, which
    ``urdf-lint expand`` does not need (it stays under 0.15 s)."""
    p = _Parser(prog="urdf-lint", description="Expand xacro without ROS, lint robot "
                "descriptions at their xacro source lines, and render review snapshots.")
    p.add_argument("--version", action="store_true", help="print the version and exit")
    sub = p.add_subparsers(dest="command", parser_class=_Parser, metavar="COMMAND")
    raw = argparse.RawDescriptionHelpFormatter   # keeps the epilog's table of formats
    for name, add in _COMMAND_PARSERS.items():
        if only is None or name == only:
            add(sub, raw)
    SUBPARSERS.clear()
    SUBPARSERS.update(sub.choices)
    return p


def _command_of(argv) -> str | None:
    """The subcommand named on the command line (the first word that is not an option), when
    it is a known one; None otherwise (then the whole parser is built, for help and hints)."""
    for a in argv:
        if a == "--":
            return None
        if not a.startswith("-"):
            return a if a in _COMMAND_PARSERS else None
    return None


# -- config -----------------------------------------------------------------------------------
def _load_cfg(args, paths):
    from urdf_lint.config.schema import find_config, load_config, validate_codes
    from urdf_lint.engine.registry import codes_to_names
    known = codes_to_names()
    if getattr(args, "isolated", False):
        cfg = load_config(None)
    else:
        path = getattr(args, "config", None) or find_config(paths[0] if paths else ".")
        cfg = load_config(path, known)
    _trust(cfg, args, paths)
    _apply_cli(cfg, args)
    validate_codes(cfg, known)
    return cfg


def _cli_values(args) -> dict:
    """Schema key -> what the user typed for its flag (None: not given)."""
    from urdf_lint.config.schema import FLAG_KEYS
    return {k.name: getattr(args, (k.flag.dest if k.flag else "") or k.attr, None)
            for k in FLAG_KEYS}


def _apply_cli(cfg, args):
    """What the user set on the command line wins (through the schema), clamped like the rest."""
    from urdf_lint.config.schema import apply_cli
    from urdf_lint.config import trust
    apply_cli(cfg, _cli_values(args))
    trust.clamp(cfg)


def _trust(cfg, args, paths):
    """The repository's config may not loosen the guarantees (see urdf_lint/config/trust.py)."""
    from urdf_lint.discovery.discover import start_dir
    from urdf_lint.discovery.vcs import repo_root
    from urdf_lint.config import trust
    given = {k for k, v in _cli_values(args).items() if v}
    for n in cfg.notes + trust.apply(cfg, repo_root(start_dir(paths)),
                                     trusted=getattr(args, "trust_config", False), given=given):
        if not getattr(args, "quiet", False):
            say(f"urdf-lint: {n}")


def _safe_text(s) -> str:
    from urdf_lint.core.escape import escape_text
    return escape_text(str(s))


def _write_base(target, paths) -> str:
    from urdf_lint.cli.output import write_base
    return write_base(target, paths)


def _refuse_symlinked_out(d, paths=()):
    """Snapshots are written where the user said, never through a link a repository planted:
    no component of the folder from the repository down (the folder itself included) may be
    a symlink."""
    if not d:
        return
    from urdf_lint.core import fsbound
    base = _write_base(d, paths)
    try:
        if os.path.abspath(d) != os.path.abspath(base):
            fsbound.check_no_symlink(d, base)
            fsbound.make_dirs(d, base)
        elif os.path.islink(d.rstrip(os.sep) or d):
            raise fsbound.BoundaryError(d, "is a symlink; refusing to write through it")
    except OSError as e:
        raise UsageError(f"output folder {_safe_text(d)}: "
                         f"{_safe_text(getattr(e, 'why', None) or e.strerror or e)}") from None


class _Out:
    """Where the CLI's own messages go: stderr, filtered by -q / -v."""

    def __init__(self, args):
        self.quiet = getattr(args, "quiet", False)
        self.verbose = getattr(args, "verbose", False)

    def note(self, text):
        if not self.quiet:
            say(text)

    def info(self, text):
        if self.verbose:
            say(text)


def _color_mode(args) -> str:
    mode = getattr(args, "color", "auto") or "auto"
    if mode not in ("auto", "always", "never"):
        from urdf_lint.config.schema import did_you_mean
        raise UsageError(f"--color: invalid value {mode!r} (expected auto, always or never"
                         f"{did_you_mean(mode, ('auto', 'always', 'never'))})")
    return mode


# -- commands ---------------------------------------------------------------------------------

MODEL_SUFFIXES = (".urdf", ".xacro")


def _through_models(args, cfg):
    """Files that are not models themselves, linted through the models that use them, as the
    hook does: a fragment or macro library that models include, and any other file (a YAML
    file, a mesh, a texture: ``check $(git diff --name-only)``). Returns (the repository root
    to lint, the files whose models to report, the files the user named), or None when every
    path is a model or a folder. Folders named beside such files are linted whole (their
    model files join the files to report)."""
    from urdf_lint.discovery.discover import build_resolver, discover_models, repository_root
    from urdf_lint.core.jobs import Status
    from urdf_lint.engine.lint import classify_xacro
    files = [os.path.realpath(p) for p in args.paths if os.path.isfile(p)]
    configured = {m.path for m in cfg.models}
    inputs = [f for f in files if not f.endswith(MODEL_SUFFIXES) and f not in configured]
    cand = [f for f in files if f.endswith(".xacro") and f not in configured]
    if not inputs and not cand:
        return None
    root = repository_root(args.paths)
    redirect = list(inputs)
    by: dict = {}
    if cand:
        resolver = build_resolver([root], cfg, _parse_package_paths(args.package_path))
        graph = discover_models([root], cfg, resolver).graph
        by = {f: graph.includers(f) for f in cand}
        redirect += [f for f in cand if by[f] or classify_xacro(f) is Status.LIBRARY]
    if not redirect:
        return None
    from urdf_lint.core.locations import display_path
    from urdf_lint.discovery.packages import iter_files
    for f in cand:
        if by.get(f) and not getattr(args, "quiet", False):
            inc = by[f]
            say(f"note: {_safe_text(display_path(f))} is included by "
                f"{', '.join(_safe_text(display_path(g)) for g in inc[:5])}"
                f"{' ...' if len(inc) > 5 else ''}: linting the models that include it")
    report = set(files)
    for d in args.paths:
        if os.path.isdir(d):
            report.update(os.path.realpath(f) for f in iter_files(Path(d), MODEL_SUFFIXES))
    return root, report, set(files)


def _no_models_warning(paths, result, out) -> None:
    """A folder the user named that holds no robot model: said, like ruff's "No Python files
    found" (the run still exits 0: nothing failed)."""
    entries = [os.path.realpath(m.entry) for m in [*result.models, *result.skipped]]
    for p in paths:
        if not os.path.isdir(p):
            continue
        top = os.path.realpath(p)
        if not any(e == top or e.startswith(top.rstrip(os.sep) + os.sep) for e in entries):
            out.note(f"warning: no robot models found in {_safe_text(p)} (no .urdf file and no "
                     ".xacro file that expands to a robot)")


def cmd_check(args) -> int:
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.core.locations import display_path
    from urdf_lint.run.pipeline import exit_code, run_check
    out = _Out(args)
    color_mode = _color_mode(args)
    for p in args.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    cfg = _load_cfg(args, args.paths)
    out.info(f"config: {display_path(cfg.path) if cfg.path else 'none (defaults)'}")
    affected_by = None
    named: set = set()
    given = list(args.paths)
    if getattr(args, "files", None) is None and not args.changed_since:
        redirect = _through_models(args, cfg)
        if redirect is not None:
            args.paths, affected_by, named = [redirect[0]], redirect[1], redirect[2]
    resolver = build_resolver(args.paths, cfg, _parse_package_paths(args.package_path))
    cache = None
    if not args.no_cache:
        from urdf_lint.run.cache import Cache
        cache = Cache.for_paths(args.paths, cfg)
        if cache.refused:  # said why on stderr; nothing (mesh facts included) goes there
            cache = None
    if args.changed_since:
        affected_by = _changed_since(args.changed_since, args.paths[0])
    if getattr(args, "files", None) is not None:
        affected_by = {os.path.abspath(f) for f in args.files}
    progress = None
    if sys.stderr.isatty() and not os.environ.get("CI") and not out.quiet:
        def progress(n, total):
            sys.stderr.write(f"\rlinting {n}/{total} models" + (" " * 10))
            if n == total:
                sys.stderr.write("\r" + " " * 40 + "\r")
            sys.stderr.flush()
    render_dir = getattr(args, "render", None)
    _refuse_symlinked_out(render_dir, args.paths)
    if _fix_mode(args):
        if named:
            raise UsageError(
                "--fix/--diff/--add-suppressions on a file that models include: run it on "
                f"the folder ({_safe_text(display_path(args.paths[0]))}), so that every fix "
                "is checked against every model that uses the file")
        from urdf_lint.fix.cli import check_fix
        return check_fix(args, cfg, resolver, affected_by, render_dir, out, color_mode)
    if render_dir:
        _clear_stale(render_dir, args.paths)
    result = run_check(args.paths, cfg, resolver, jobs_n=cfg.jobs, cache=cache,
                       progress=progress, affected_by=affected_by, render_dir=render_dir)
    from urdf_lint.fix.fixes import inside_paths   # a fix offered in JSON / SARIF edits only linted files
    result.findings = inside_paths(result.findings, args.paths)
    if result.reused:
        out.info("nothing changed since the last identical run: showing its result")
    if out.verbose:
        _list_models(result, out)
    from urdf_lint.core.emit import report_internal
    report_internal(result.internal)
    if args.write_baseline:
        from urdf_lint.engine.baseline import write_baseline
        n = write_baseline(args.write_baseline, result.findings,
                           _write_base(args.write_baseline, args.paths))
        files = len({f.file for f in result.findings})
        out.note(f"urdf-lint: wrote {n} finding(s) in {files} file(s) to "
                 f"{display_path(os.path.abspath(args.write_baseline))}; "
                 f"lint with --baseline {args.write_baseline} to report only new ones")
        if render_dir:
            _report_snapshots(result, render_dir, out)
        return 2 if result.internal else 0
    from urdf_lint.cli.output import write_findings
    write_findings(args, cfg, result, out, color_mode, resolver.roots)
    if getattr(args, "hook_summary", False):
        _hook_summary(result, args.files)
    _note_unused(result, out, named)
    if getattr(args, "files", None) is None and not args.changed_since:
        _no_models_warning(given, result, out)
    _note_variants(result, cfg, resolver, out)
    if render_dir:
        _report_snapshots(result, render_dir, out)
    if args.exit_zero:
        return 2 if result.internal else 0
    return exit_code(result, cfg.fail_on)


def _changed_since(ref, first_path):
    from urdf_lint.discovery.vcs import GitError, changed_files
    cwd = first_path if os.path.isdir(first_path) else os.path.dirname(os.path.abspath(first_path))
    try:
        return changed_files(ref, cwd)
    except (GitError, OSError) as e:
        lines = [ln.strip() for ln in str(e).splitlines() if ln.strip()]
        text = " ".join(lines).lower()
        if "not a git repository" in text:
            why = f"{os.path.abspath(cwd)} is not inside a git repository"
        elif "unknown revision" in text or "bad revision" in text or "ambiguous argument" in text:
            why = f"no commit, branch or tag named {ref!r} (try e.g. origin/main or HEAD~1)"
        elif isinstance(e, OSError):
            why = f"cannot run git: {e.strerror or e}"
        else:
            why = re.sub(r"^(fatal|error): ", "", lines[0]) if lines else "git failed"
        raise UsageError(f"--changed-since {ref}: {why}") from None


def _list_models(result, out):
    from urdf_lint.core.locations import display_path
    for m in result.models:
        state = "cached" if m.cached else m.status
        reads = [d for d in m.deps if d != m.entry]
        out.info(f"model: {_safe_text(m.label)} ({state}, {len(reads)} other file(s) read)")
        for d in reads:
            out.info(f"    {_safe_text(display_path(d))}")
    for m in result.skipped:
        out.info(f"skipped: {_safe_text(display_path(m.entry))} ({m.status})")


def _note_variants(result, cfg, resolver, out) -> None:
    """One info line: the models linted with args left at defaults that select variants, and
    how to lint the variants (``[[models]] args``)."""
    from urdf_lint.core.locations import display_path
    from urdf_lint.run.pipeline import variant_args
    found = variant_args(result.models, cfg, resolver)
    if not found:
        return
    entry, names = next(iter(found.items()))
    shown = ", ".join(names[:4]) + (" ..." if len(names) > 4 else "")
    more = f" and {len(found) - 1} more model(s)" if len(found) > 1 else ""
    out.note(f"note: {_safe_text(display_path(entry))}{more} linted with args at their defaults "
             f"that select variants ({_safe_text(shown)}); to lint the variants, list them: "
             f"[[tool.urdf-lint.models]] path = \"{_safe_text(display_path(entry))}\" "
             f"args = [{{{_safe_text(names[0])} = \"...\"}}, ...]")


def _note_unused(result, out, named=()):
    """Deleted files no remaining model reads (always said), unused files (under -v, or always
    when the user named the file)."""
    from urdf_lint.core.locations import display_path
    for f in getattr(result, "gone", ()):
        if f.endswith((".xacro", ".urdf")):
            out.note(f"note: {_safe_text(display_path(f))} was deleted and no remaining model "
                     "reads it; if it was a model, it is gone")
    named = {os.path.realpath(f) for f in named}
    for f in result.unused_files:
        if os.path.realpath(f) in named:   # the user named it: always said
            out.note(f"note: {_safe_text(display_path(f))} is not used by any model")
        elif f.endswith((".xacro", ".urdf", ".yaml", ".yml", ".stl", ".dae", ".obj")):
            out.info(f"note: {_safe_text(display_path(f))} is not used by any model")


def _clear_stale(out_dir, paths):
    from urdf_lint.render.snapshot import clear_stale
    try:
        clear_stale(out_dir, _write_base(out_dir, paths))
    except OSError as e:
        raise UsageError(f"cannot clear {_safe_text(out_dir)}: "
                         f"{_safe_text(getattr(e, 'why', None) or e.strerror or e)}") from None


def _report_snapshots(result, out_dir, out=None) -> int:
    """Caption and finish the snapshots with the run's final findings, write summary.md and
    the manifest, and say (one located line each) which requested snapshot could not be
    made; returns how many could not."""
    from urdf_lint.render.snapshot import finish_snapshots, write_manifest, write_summary
    from urdf_lint.core.locations import display_path
    from urdf_lint.render.recording import NO_RERUN
    finish_snapshots(result.models, result.findings, out_dir)
    written, missed, files = 0, 0, []
    no_rerun = False
    for m in result.models:
        snap = m.snapshot or {}
        if f"rrd: {NO_RERUN}" in snap.get("problems", ()):   # optional: said once, below
            snap["problems"] = [p for p in snap["problems"] if p != f"rrd: {NO_RERUN}"]
            no_rerun = True
        for k in ("png", "rrd"):
            if snap.get(k):
                written += 1
                files.append(snap[k])
        if m.status != "model":
            say(f"{m.label}: no snapshot: the model did not expand (see 'urdf-lint check')")
            missed += 1
        elif snap.get("problems") or not snap.get("png"):
            why = "; ".join(snap.get("problems") or ["no picture was drawn"])
            say(f"{_safe_text(m.label)}: snapshot incomplete: {_safe_text(why)}")
            missed += 1
    if no_rerun:
        _no_recordings_note(NO_RERUN)
    summary = write_summary(result, out_dir)
    write_manifest(out_dir, files + [summary])
    msg = (f"snapshots: {written} files for {len(result.models)} model(s) in "
           f"{display_path(out_dir)}/ (summary: {display_path(summary)})")
    if out is not None:
        out.note(msg)
    else:
        say(msg)
    return missed


def _no_recordings_note(why) -> None:
    """The .rrd recordings are optional (rerun-sdk, the ``render`` extra): without them the
    pictures are still made and the run does not fail; said once (``render`` and
    ``diff --render`` alike)."""
    say(f"note: no .rrd recordings: {_safe_text(why)}; the PNG pictures are written "
        "(--no-rrd: no recordings, no note)")


def cmd_hook(args) -> int:
    """Lint the whole repository (cached) and report the models that the files affect."""
    from urdf_lint.discovery.vcs import repo_root
    root = repo_root(os.getcwd())
    ns = argparse.Namespace(paths=[root], output=None, render=None, changed_since=None,
                            write_baseline=None, isolated=False, **vars(args))
    ns.quiet = True if not args.verbose else False
    ns.hook_summary = not args.quiet   # the one line said even when the hook passes
    ns.command = "check"
    # pre-commit passes only files that exist: add what the commit deletes or renames away
    from urdf_lint.discovery.vcs import GitError, staged_removals
    try:
        removed = staged_removals(os.getcwd())
    except (GitError, OSError):
        removed = set()
    ns.files = list(args.files) + sorted(removed)
    if not ns.files:
        if ns.hook_summary:
            say("urdf-lint: no robot description file in this commit")
        return 0
    return cmd_check(ns)


def _hook_summary(result, files) -> None:
    """``hook``: one line on every run, passed or failed, with the warnings and infos that do
    not fail it (pre-commit shows it with ``verbose: true``, set in .pre-commit-hooks.yaml)."""
    from collections import Counter
    named = {os.path.realpath(f) for f in files}
    sev = Counter(f.severity for f in result.findings)
    mine = sum(1 for f in result.findings if os.path.realpath(f.file) in named)
    n = len(result.models)
    line = (f"urdf-lint: {n} model(s) affected by {len(files)} file(s): {sev['error']} error(s), "
            f"{sev['warning']} warning(s), {sev['info']} info")
    if result.findings:
        line += f" ({mine} in the committed files)"
    say(line)


def cmd_expand(args) -> int:
    if not os.path.isfile(args.file):
        raise UsageError(f"no such file: {args.file}")
    from urdf_lint.runner.worker import prestart
    prestart()   # (done already by main(); here for callers of cmd_expand)
    from urdf_lint.config.schema import find_config, load_config
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.core.jobs import LintJob, Status
    from urdf_lint.core.locations import display_path
    mappings, rest = _parse_mappings(args.mappings)
    if rest:
        raise UsageError(f"expected name:=value, got {' '.join(rest)}")
    cfg = load_config(find_config(args.file))
    _trust(cfg, args, [args.file])
    _apply_cli(cfg, args)
    resolver = build_resolver([args.file], cfg, _parse_package_paths(args.package_path))
    # expanded in a worker like `check`: time and memory limits, scrubbed environment, sandbox
    job = LintJob(os.path.abspath(args.file), mappings, "expand", explicit=True,
                  display_name=args.file)
    res = _expand_in_workers([job], resolver, cfg)[0]
    from urdf_lint.core.emit import report_internal
    if report_internal(res.internal):
        return 2
    for n in res.problems:
        say(f"{_safe_text(display_path(n.file))}:{n.line}:{n.col}: {n.code} "
            f"{_safe_text(n.message)}")
    xml = res.kept_model.xml if res.kept_model is not None else None
    if res.status is Status.FAILED or xml is None:
        if not res.problems:
            from urdf_lint.rules import ul002_xacro_error
            say(f"{display_path(job.entry)}:1:1: {ul002_xacro_error.CODE} expansion failed")
        return 1
    if args.output:
        from urdf_lint.core import fsbound
        try:
            fsbound.write_text(args.output, xml, _write_base(args.output, [args.file]),
                               make_dirs=True)
        except OSError as e:
            raise UsageError(f"cannot write {_safe_text(args.output)}: "
                             f"{_safe_text(getattr(e, 'why', None) or e.strerror or e)}") from None
    else:
        sys.stdout.write(xml)
    return 0


def cmd_rules(args) -> int:
    from urdf_lint.engine.registry import load_rules
    if getattr(args, "format", "text") == "markdown":
        from urdf_lint.engine.rulesdoc import markdown
        sys.stdout.write(markdown(load_rules()))
        return 0
    for code, r in load_rules().items():
        print(f"{code}  {r.name:<28} {r.severity:<8} {first_sentence(r.doc)}")
    return 0


def cmd_rule(args) -> int:
    from urdf_lint.engine.registry import find_rule
    r = find_rule(args.code)
    if r is None:
        from urdf_lint.config.schema import did_you_mean
        from urdf_lint.engine.registry import load_rules
        rules = load_rules()
        hint = did_you_mean(args.code, list(rules) + [x.name for x in rules.values()])
        raise UsageError(f"unknown rule {args.code!r}{hint} (see 'urdf-lint rules')")
    print(f"{r.code} {r.name} (default severity: {r.severity})\n")
    if r.targets:
        print("Per consumer target (config 'targets'): "
              + ", ".join(f"{t} {s}" for t, s in r.targets.items()) + "\n")
    print(plain(r.doc))
    if r.options:
        print("\nOptions (set under [tool.urdf-lint.rule-options." + r.code + "]):")
        for k, v in r.options.items():
            print(f"  {k} = {v!r}")
    print("\nFails:\n" + r.fail.strip())
    print("\nPasses:\n" + r.passing.strip())
    return 0


def cmd_render(args) -> int:
    from urdf_lint.discovery.discover import build_resolver
    from urdf_lint.run.pipeline import run_check
    for p in args.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    _refuse_symlinked_out(args.out, args.paths)
    cfg = _load_cfg(args, args.paths)
    given = list(args.paths)
    redirect = _through_models(args, cfg)
    affected_by, named = None, set()
    if redirect is not None:
        args.paths, affected_by, named = [redirect[0]], redirect[1], redirect[2]
    resolver = build_resolver(args.paths, cfg, _parse_package_paths(args.package_path))
    _clear_stale(args.out, args.paths)
    result = run_check(args.paths, cfg, resolver, jobs_n=cfg.jobs,
                       render_dir=args.out, render_rrd=not args.no_rrd, affected_by=affected_by)
    if cfg.baseline:   # the pictures and summary.md count what 'check' would report
        from urdf_lint.engine.baseline import filter_baseline
        result.findings = filter_baseline(cfg.baseline, result.findings, _Out(args).note)
    _note_unused(result, _Out(args), named)
    _no_models_warning(given, result, _Out(args))
    missed = _report_snapshots(result, args.out)
    for m in result.models:
        snap = m.snapshot or {}
        for k in ("png", "rrd"):
            if snap.get(k):
                from urdf_lint.core.locations import display_path
                tell(display_path(snap[k]))
    from urdf_lint.core.emit import report_internal
    if report_internal(result.internal):
        return 2
    # a requested model that could not be snapshotted is a failure, not a blank image
    return 1 if missed else 0


def cmd_diff(args) -> int:
    from urdf_lint.report import diff as diff_report
    from urdf_lint.review import run as review
    paths = args.paths or ["."]
    for p in paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    # the config comes from each revision's own tree; the CLI adds only these keys
    cfg_args = argparse.Namespace(fail_on=args.fail_on, jobs=args.jobs, targets=args.targets,
                                  trust_config=args.trust_config, views=args.views,
                                  forward_axis=args.forward_axis)
    _refuse_symlinked_out(args.render, paths)
    cfgs = []

    def load(ps):
        cfgs.append(_load_cfg(cfg_args, ps))
        return cfgs[-1]
    try:
        result = review.run_diff(args.base, args.head, paths, load,
                                 _parse_package_paths(args.package_path), jobs_n=None,
                                 use_cache=not args.no_cache, render_dir=args.render,
                                 rrd=not args.no_rrd)
    except review.ReviewError as e:
        raise UsageError(str(e)) from None
    options = diff_report.DiffOptions(image_base_url=args.image_base_url)
    if args.output:
        try:
            diff_report.write_file(result, args.format, args.output,
                                   _write_base(args.output, paths), options)
        except OSError as e:
            raise UsageError(f"cannot write {_safe_text(args.output)}: "
                             f"{_safe_text(getattr(e, 'why', None) or e.strerror or e)}") from None
    else:
        diff_report.write(result, args.format, sys.stdout, options)
    for model, why in result.snapshot_problems:
        say(f"{_safe_text(model)}: snapshot incomplete: {_safe_text(why)}")
    if result.no_recordings:
        _no_recordings_note(result.no_recordings)
    from urdf_lint.core.emit import report_internal
    report_internal(result.internal)
    return review.exit_code(result, cfgs[0].fail_on if cfgs else (args.fail_on or "error"))


def cmd_doctor(args) -> int:
    from urdf_lint import __version__
    from urdf_lint.runner.sandbox import protections
    print(f"urdf-lint {__version__} on {sys.platform}, Python {sys.version.split()[0]}")
    for name, (ok, why) in protections().items():
        print(f"  {'on ' if ok else 'OFF'}  {name:<12} {why}")
    return 0


def cmd_generate(args) -> int:
    """Regenerate stale outputs in place (atomically); exit 1 when a file was (or, with
    --check, would be) rewritten or a xacro did not expand, like a formatter hook. Each xacro
    is expanded in a sandboxed worker with the run's limits, like ``check`` and ``expand``:
    the worker returns the XML, the parent compares and writes it (inside the repository
    only, anywhere the user trusts with --trust-config)."""
    import dataclasses

    from urdf_lint.config import trust
    from urdf_lint.discovery.discover import build_resolver, discover_models, start_dir
    from urdf_lint.core.emit import report_internal
    from urdf_lint.discovery.generated import header_source, stale_at, write_output
    from urdf_lint.core.jobs import Status
    from urdf_lint.core.locations import display_path
    from urdf_lint.discovery.vcs import repo_root
    for p in args.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    cfg = _load_cfg(args, args.paths)
    resolver = build_resolver(args.paths, cfg, _parse_package_paths(args.package_path))
    # (what the header names: xacro opens this path)
    jobs = [dataclasses.replace(job, kind="expand", display_name=os.path.relpath(job.entry))
            for job in discover_models(args.paths, cfg, resolver).jobs if job.output]
    status = 0
    stale = failed = 0
    for job, res in zip(jobs, _expand_in_workers(jobs, resolver, cfg), strict=True):
        assert job.output is not None and job.display_name is not None
        if report_internal(res.internal):
            status = 2
            continue
        shown = job.display_name
        xml = res.kept_model.xml if res.kept_model is not None else None
        if res.status is Status.FAILED or xml is None:
            for e in res.problems[-1:]:   # (before it: the expansion's notes)
                say(f"{_safe_text(display_path(e.file))}:{e.line}:{e.col}: {e.code} "
                    f"{_safe_text(e.message)}")
            status = max(status, 1)
            failed += 1
            continue
        if stale_at(job.output, xml) is None:
            continue
        status = max(status, 1)
        stale += 1
        named = header_source(job.output, resolver.roots) if os.path.exists(job.output) else None
        if named and xml:   # keep the header's own name for the source: no churn
            head, rest = xml[:1024], xml[1024:]
            xml = head.replace(f"from {shown} ", f"from {named} ", 1) + rest
        if args.check:
            tell(f"would regenerate {_safe_text(display_path(job.output))} from "
                 f"{_safe_text(display_path(job.entry))}")
        else:
            try:   # inside the repository only (anywhere the user trusts with --trust-config)
                write_output(job.output, xml, _write_base(job.output, args.paths)
                             if getattr(args, "trust_config", False) else
                             trust.config_root(cfg, repo_root(start_dir(args.paths))))
            except OSError as e:
                say(f"urdf-lint: error: cannot write {display_path(job.output)}: "
                    f"{getattr(e, 'why', None) or e.strerror or e}")
                status = 2
                continue
            tell(f"regenerated {_safe_text(display_path(job.output))} from "
                 f"{_safe_text(display_path(job.entry))}")
    tell(_generate_summary(len(jobs), stale, failed, args.check))
    return status


def _generate_summary(outputs, stale, failed, check) -> str:
    """``generate``: one line, also when everything was up to date."""
    if not outputs:
        return ("urdf-lint generate: no generated URDF found (a models entry with 'output', or a "
                ".urdf whose header names its xacro)")
    done = "would be regenerated" if check else "regenerated"
    parts = [f"{stale} {done}" if stale else "all up to date" if not failed else ""]
    if failed:
        parts.append(f"{failed} xacro(s) did not expand")
    return (f"urdf-lint generate: {outputs} generated URDF(s) checked, "
            + ", ".join(p for p in parts if p) + ".")


def cmd_format(args) -> int:
    from urdf_lint.formatting.run import cmd_format as run
    return run(args, _load_cfg, _parse_package_paths)


def cmd_mcp(args) -> int:
    from urdf_lint.cli.mcp import cmd_mcp as run
    return run(args)


def _expand_in_workers(jobs: list, resolver, cfg) -> list:
    """The ModelReport of each ``expand`` job, in the jobs' order: expanded in sandboxed
    workers (time and memory limits, scrubbed environment, Landlock, seccomp) with the run's
    one snapshot of the roots; the XML comes back as data (``kept_model.xml``)."""
    from urdf_lint.config.schema import DEFAULT_ENV_ALLOW
    from urdf_lint.core.jobs import LintSettings
    from urdf_lint.runner.worker import run_jobs
    settings = LintSettings(resolver=resolver.to_dict(),
                            env_allow=tuple(sorted(set(DEFAULT_ENV_ALLOW) | set(cfg.env_allow))))
    done = {id(job): res for job, res in run_jobs(jobs, settings, jobs_n=cfg.jobs,
                                                  timeout=cfg.timeout, memory_mb=cfg.memory_mb)}
    return [done[id(job)] for job in jobs]


def cmd_clean(args) -> int:
    from urdf_lint.run.cache import Cache
    from urdf_lint.config.schema import load_config
    removed = Cache.for_paths(args.paths, load_config(None)).clear()
    tell(f"removed {removed}" if removed else "no cache to remove")
    return 0


def cmd_server(args) -> int:
    try:
        from urdf_lint.lsp.server import main as serve
    except ImportError as e:
        raise UsageError(f"the language server needs the 'server' extra ({e.name} is not "
                         "installed): pip install 'urdf-lint[server]'") from None
    return serve()


COMMANDS = {"check": cmd_check, "hook": cmd_hook, "expand": cmd_expand, "rules": cmd_rules, "rule": cmd_rule,
            "render": cmd_render, "diff": cmd_diff, "generate": cmd_generate, "format": cmd_format,
            "mcp": cmd_mcp, "clean": cmd_clean,
            "doctor": cmd_doctor, "server": cmd_server}


def main(argv=None) -> int:
    try:
        return _main(argv)
    except KeyboardInterrupt:
        sys.stderr.write("\nurdf-lint: interrupted\n")
        return 130


def entry() -> None:
    """The ``urdf-lint`` command (and ``python -m urdf_lint``): :func:`main`, then leave."""
    # numpy's BLAS starts a thread per core when loaded (~15 ms); the matrices urdf-lint
    # multiplies are 3x3 (a command setting, unless the user chose: not for library users)
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    exit_now(main())


def exit_now(code: int) -> None:
    """End the process without tearing the interpreter down: freeing every module and object
    one by one takes ~20 ms after a run (a tenth of ``urdf-lint expand``), and the OS frees
    them anyway. Exit handlers still run and the output streams are flushed; when a thread
    that is not a daemon is still running, exit the usual way (it is waited for)."""
    threading = sys.modules.get("threading")
    if threading is not None and any(
            t.is_alive() and not t.daemon and t is not threading.main_thread()
            for t in threading.enumerate()):
        sys.exit(code)
    import atexit
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):   # the reader is gone (`| head`): nothing more to say
            pass
    os._exit(code)


def _hook_arguments(argv) -> tuple[list, list]:
    """``urdf-lint hook``: (the arguments to parse, the file names). pre-commit appends the
    names of the commit's files to the hook's arguments, and a committed file may be named
    like an option (``--env-allow=TOKEN,x.yaml``). Everything after the first ``--`` is a file
    name, and so is, before it, an argument starting with ``-`` that names an existing path
    (pre-commit passes only existing files): neither is ever parsed as an option."""
    i = argv.index("hook")
    rest, files = argv[i + 1:], []
    if "--" in rest:
        k = rest.index("--")
        rest, files = rest[:k], rest[k + 1:]
    taken = [a for a in rest if a.startswith("-") and len(a) > 1 and os.path.lexists(a)]
    for a in taken:
        say(f"urdf-lint: note: {a} is a file, not an option (end the hook's args with --)")
    return argv[:i + 1] + [a for a in rest if a not in taken], taken + files


def _main(argv) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    command = _command_of(argv)
    hook_files: list = []
    if command == "hook":
        argv, hook_files = _hook_arguments(argv)
    if command in ("expand", "generate") and "-h" not in argv and "--help" not in argv:
        # the worker imports the expansion while the parent parses, reads the config and
        # finds the packages (a run that stops early stops it too)
        from urdf_lint.runner.worker import prestart
        prestart()
    parser = build_parser(command)
    try:
        args, extra = parser.parse_known_args(argv)
        if extra:
            (SUBPARSERS.get(args.command) or parser).error(
                f"unrecognized arguments: {' '.join(extra)}")
    except SystemExit as e:
        return 2 if e.code else 0
    if command == "hook":
        args.files = list(args.files) + hook_files
    if args.version:
        from urdf_lint import __version__
        from urdf_lint.runner.sandbox import summary_line
        print(f"urdf-lint {__version__}\n{summary_line()}")
        return 0
    if not args.command:
        parser.print_help()
        return 2
    from urdf_lint.config.schema import ConfigError   # (a BaselineError is a UsageError)
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
        say(f"urdf-lint: error: {e}")
        return 2
    except KeyboardInterrupt:
        raise
    except BrokenPipeError:
        return 0
    except Exception as e:  # noqa: BLE001
        import traceback
        say(f"urdf-lint: internal error (please report): {type(e).__name__}: {e}")
        if os.environ.get("URDF_LINT_DEBUG"):
            traceback.print_exc()
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
