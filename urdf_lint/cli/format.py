"""``urdf-lint format [PATHS]``: its parser and its command; the run (layout, proof) is
:mod:`urdf_lint.run.format`."""
from __future__ import annotations

import os
import sys
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from urdf_lint.cli.common import ConfigOptions, load_cfg, options_from, parse_package_paths
from urdf_lint.cli.parser import add_inputs
from urdf_lint.core.escape import escape_text
from urdf_lint.run.format import Proof, files_to_format, format_files, prove, style_of

if TYPE_CHECKING:  # pragma: no cover
    import argparse
    from argparse import Namespace
    from collections.abc import Callable, Sequence

    from urdf_lint.cli.parser import Formatter, SubParsers
    from urdf_lint.config.schema import Config
    from urdf_lint.formatting.layout import Node
    from urdf_lint.run.format import FileResult

NAME = "format"


def add_parser(sub: SubParsers, raw: Formatter) -> None:
    p = sub.add_parser("format", help="lay out xacro and URDF sources (never changes a robot)",
                       description="Format xacro and URDF files: one element per line, "
                                   "children indented, long tags wrapped; comments, text and "
                                   "${...} kept byte for byte. A layout must expand to "
                                   "the same robot in every model that reads the file: "
                                   "proved from the file itself by xacro's rules, or by "
                                   "expanding those models before and after; else the file "
                                   "is left alone.")
    p.add_argument("paths", nargs="*", default=["."], metavar="PATH",
                   help="files or folders to format (default: .)")
    p.add_argument("--check", action="store_true",
                   help="write nothing; exit 1 when a file would be reformatted")
    p.add_argument("--diff", action="store_true",
                   help="write nothing; print the changes as a unified diff (exit 1 when "
                        "there are any)")
    _add_style_flags(p)
    p.add_argument("--isolated", action="store_true", help="ignore all config files")
    add_inputs(p)
    p.add_argument("--timeout", metavar="SECONDS",
                   help="time limit per model expansion of the proof (default: 30)")
    p.add_argument("--memory-mb", metavar="MIB",
                   help="memory limit per model expansion of the proof (default: 2048)")
    p.add_argument("-q", "--quiet", action="store_true", help="print only errors")


def _add_style_flags(p: argparse.ArgumentParser) -> None:
    """One flag per layout key of ``[tool.urdf-lint.format]`` (``--line-length``), from its
    schema entry: its help, choices and default."""
    from urdf_lint.config.schema import FORMAT_KEYS
    from urdf_lint.run.format import STYLE_KEYS
    for name in STYLE_KEYS:
        key = FORMAT_KEYS[name]
        choices = getattr(key.type, "choices", None)
        metavar = "{" + ",".join(choices) + "}" if choices else "N"
        p.add_argument(f"--{name}", metavar=metavar,
                       help=f"{key.help} (default: {key.default_text}; config key '{name}' "
                            "under [tool.urdf-lint.format])")


@dataclass(frozen=True)
class FormatOptions:
    """What ``format`` was asked to do (the formatter reads these by name)."""
    config: ConfigOptions = field(default_factory=ConfigOptions)
    paths: list[str] = field(default_factory=lambda: ["."])
    package_path: list[str] | None = None
    check: bool = False
    diff: bool = False
    quiet: bool = False
    indent: str | None = None
    line_length: str | None = None
    attribute_order: str | None = None
    self_closing: str | None = None


def run(args: Namespace) -> int:
    opts = options_from(FormatOptions, args, config=ConfigOptions.from_args(args))
    return cmd_format(opts, lambda o, paths: load_cfg(o.config, paths), parse_package_paths)


def cmd_format(args: FormatOptions,
               load_cfg: Callable[[FormatOptions, list[str]], Config],
               parse_package_paths: Callable[[list[str] | None], dict[str, str]]) -> int:
    from urdf_lint.core.errors import UsageError
    from urdf_lint.discovery.discover import repository_root
    for p in args.paths:
        if not os.path.exists(p):
            raise UsageError(f"no such file or directory: {p}")
    repo = repository_root(args.paths)
    paths, status = _inside_repository(args.paths, repo)
    if not paths:
        return status
    cfg = load_cfg(args, paths)
    style = style_of(cfg, args)
    docs: dict[bytes, list[Node]] = {}
    results = format_files(files_to_format(paths, cfg), style, paths, docs, repo)
    changed = {r.path: r.new for r in results if r.new is not None}
    proof = Proof()
    if changed:
        proof = prove(changed, paths, cfg, parse_package_paths(args.package_path),
                      cfg.jobs, old={r.path: r.old for r in results if r.new is not None},
                      docs=docs)
        for r in results:
            if r.path in proof.refused:
                r.refused, r.new = proof.refused[r.path], None
    status = max(status, _say_problems(results))
    todo = [r for r in results if r.new is not None]
    if args.diff:
        from urdf_lint.run.fix import unified_diff
        sys.stdout.write(unified_diff({r.path: r.new for r in todo if r.new is not None},
                                      {r.path: r.old for r in todo}))
    elif args.check:
        from urdf_lint.core.emit import tell
        for r in todo:
            tell(f"Would reformat: {escape_text(r.shown)}")
    else:
        status = max(status, _write(todo, paths, repo))
        todo = [r for r in todo if r.new is not None]
    if not args.quiet:
        _say_summary(results, todo, args, proof if changed else None)
    if status:
        return status
    return 1 if todo and (args.check or args.diff) else 0


def _inside_repository(paths: Sequence[str], repo: str) -> tuple[list[str], int]:
    """(the named paths to format, 2 when one was refused else 0): a named path that is a
    symlink (or in the repository through one) resolving outside the repository is refused
    with one located error and nothing of it is read or written."""
    from urdf_lint.core.emit import say
    from urdf_lint.core.fsbound import named_root
    from urdf_lint.core.locations import display_path
    keep = [p for p in paths if named_root(p, repo) is not None]
    for p in paths:
        if p not in keep:
            say(f"error: {escape_text(display_path(os.path.abspath(p)))}:1:1: resolves outside "
                "the repository (a symlink to elsewhere); not formatted")
    return keep, 2 if len(keep) < len(paths) else 0


def _say_problems(results: Sequence[FileResult]) -> int:
    """Say each file that could not be formatted or was left alone; 2 for an error or an
    internal problem, else 0."""
    from urdf_lint.core.emit import say
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


def _write(todo: Sequence[FileResult], paths: Sequence[str], repo: str) -> int:
    """Write the new layouts, only below the formatted paths, atomically (the boundary's
    rewrite: a file saved since it was read is skipped, exit 1); 2 when one cannot be
    written, else 0."""
    from urdf_lint.core import fsbound
    from urdf_lint.core.emit import say
    status = 0
    for r in todo:
        try:
            fsbound.rewrite(r.path, r.new or b"", paths, old=r.old, repo=repo)
        except fsbound.ChangedError:
            say(f"{escape_text(r.shown)}: skipped: it changed while urdf-lint formatted it; "
                "the newer content is kept (run format again)")
            r.refused, r.new = "changed while formatting", None
            status = max(status, 1)
        except OSError as e:
            say(f"error: {escape_text(r.shown)}: cannot write: "
                f"{getattr(e, 'why', None) or e.strerror or e}")
            status = 2
    return status


def _say_summary(results: Sequence[FileResult], todo: Sequence[FileResult], args: FormatOptions,
                 proof: Proof | None) -> None:
    from urdf_lint.core.emit import say
    left = sum(1 for r in results if r.refused)
    same = sum(1 for r in results if r.new is None and not r.refused and not r.error)
    verb = "would be reformatted" if args.check or args.diff else "reformatted"
    say(f"{len(todo)} file(s) {verb}, {same} file(s) left unchanged"
        + (f", {left} file(s) left alone" if left else "")
        + (f" ({proof.by_file} proved from the file itself, {proof.compared} model(s) "
           "expanded before and after)" if proof is not None else ""))
