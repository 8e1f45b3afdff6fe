"""``urdf-lint hook``: pre-commit's entry; lints the models that the committed files affect
(``check`` of the whole repository, through the cache)."""
from __future__ import annotations

import dataclasses
import os
from typing import TYPE_CHECKING

from urdf_lint.cli.common import ConfigOptions, options_from
from urdf_lint.cli.parser import add_inputs, add_limits, add_output, add_selection
from urdf_lint.core.emit import say

if TYPE_CHECKING:  # pragma: no cover
    from argparse import Namespace

    from urdf_lint.cli.parser import Formatter, SubParsers


NAME = "hook"


def add_parser(sub: SubParsers, raw: Formatter) -> None:
    h = sub.add_parser("hook", help="pre-commit: lint the models that the given files affect",
                       formatter_class=raw,
                       description="Lint the models that the given (changed) files affect; "
                                   "the whole repository is linted through the cache.")
    h.add_argument("files", nargs="*", metavar="FILE",
                   help="changed files, as pre-commit passes them (default: none)")
    add_output(h)
    add_selection(h)
    add_inputs(h)
    add_limits(h)


def run(args: Namespace) -> int:
    """Lint the whole repository (cached) and report the models that the files affect."""
    from urdf_lint.cli.check import CheckOptions, check
    from urdf_lint.discovery.vcs import GitError, repo_root, staged_removals
    quiet = not args.verbose   # the findings only, unless -v
    config = dataclasses.replace(ConfigOptions.from_args(args), quiet=quiet)
    opts = dataclasses.replace(options_from(CheckOptions, args, config=config),
                               paths=[repo_root(os.getcwd())], quiet=quiet,
                               hook_summary=not args.quiet)   # said even when the hook passes
    # pre-commit passes only files that exist: add what the commit deletes or renames away
    try:
        removed = staged_removals(os.getcwd())
    except (GitError, OSError):
        removed = set()
    files = list(args.files) + sorted(removed)
    if not files:
        if opts.hook_summary:
            say("urdf-lint: no robot description file in this commit")
        return 0
    return check(dataclasses.replace(opts, files=files))
