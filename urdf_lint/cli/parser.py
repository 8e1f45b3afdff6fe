"""The command line's parser: its one-line errors, and the flags several commands share.

A flag that sets a config key comes from the key's ``flag`` in the schema
(:data:`urdf_lint.config.schema.SCHEMA`): :func:`add_key_flags` adds every key of a group, so a
new key with a flag is on every command that takes its group, with nothing to add here.
"""
from __future__ import annotations

import argparse
import os
import re
import sys
from typing import TYPE_CHECKING, Any, NoReturn

from urdf_lint.core.suggest import close_matches

if TYPE_CHECKING:  # pragma: no cover
    # what main.build_parser hands each command's add_parser(sub, raw)
    SubParsers = argparse._SubParsersAction["Parser"]
    Formatter = type[argparse.HelpFormatter]


def columns() -> int:
    """``shutil.get_terminal_size().columns``: ``COLUMNS``, else the width of the terminal on
    standard output, else 80; without importing shutil, which argparse's formatter does for
    it (~3 ms with the compression modules shutil loads: every run builds a parser, which
    makes a formatter per argument, and few print help)."""
    try:
        width = int(os.environ.get("COLUMNS", "0"))
    except ValueError:
        width = 0
    if width <= 0:
        try:
            width = os.get_terminal_size(sys.__stdout__.fileno()).columns  # type: ignore[union-attr]
        except (AttributeError, ValueError, OSError):
            width = 0
    return width if width > 0 else 80


class HelpFormatter(argparse.HelpFormatter):
    """argparse's formatter, its width from :func:`columns`."""

    def __init__(self, prog: str, indent_increment: int = 2, max_help_position: int = 24,
                 width: int | None = None) -> None:
        super().__init__(prog, indent_increment, max_help_position,
                         columns() - 2 if width is None else width)


class RawDescriptionHelpFormatter(argparse.RawDescriptionHelpFormatter, HelpFormatter):
    """:class:`HelpFormatter` keeping the description's and epilog's lines (a table)."""


class Parser(argparse.ArgumentParser):
    """A command-line mistake is one line: what is wrong, the closest known flag or command,
    and where the usage is (like ruff; the whole usage buried the suggestion)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("formatter_class", HelpFormatter)
        super().__init__(*args, **kwargs)

    def error(self, message: str) -> NoReturn:
        m = re.match(r"argument (\S+): invalid choice: '([^']*)' \(choose from (.*)\)", message)
        if m:
            choices = re.findall(r"'([^']*)'", m.group(3))
            close = close_matches(m.group(2), choices, n=1, cutoff=0.6)
            if close:
                message += f" (did you mean {close[0]}?)"
        m = re.match(r"unrecognized arguments: (.*)", message)
        if m:
            hints = []
            args = [a for a in m.group(1).split() if a.startswith("-")]
            for arg in args:
                close = close_matches(arg.split("=")[0], self.flags(), n=1,
                                                  cutoff=0.6)
                if close:
                    hints.append(f"did you mean {close[0]}?" if len(args) == 1
                                 else f"{arg}: did you mean {close[0]}?")
            if hints:
                message += " (" + "; ".join(hints) + ")"
        self.exit(2, f"{self.prog}: error: {message}; see '{self.prog} --help'\n")

    def flags(self) -> list[str]:
        return [s for a in self._actions for s in a.option_strings]

    def print_help(self, file: Any = None) -> None:
        """The help on standard output; a write that fails (``--help > /dev/full``) is the
        one error every command gives for it (argparse's own printing ignores it, exit 0)."""
        (file or sys.stdout).write(self.format_help())


def add_key_flags(p: argparse.ArgumentParser, group: str) -> None:
    """The flags of the config keys in ``group`` (each key's ``flag`` in the schema)."""
    from urdf_lint.config.schema import FLAG_KEYS
    for k in FLAG_KEYS:
        f = k.flag
        assert f is not None
        if f.group == group:
            p.add_argument(*f.flags, dest=f.dest or k.attr, metavar=k.metavar(),
                           action="append" if f.repeat else "store", help=k.cli_help())


def add_selection(p: argparse.ArgumentParser) -> None:
    add_key_flags(p, "selection")
    p.add_argument("--exit-zero", action="store_true",
                   help="exit 0 even when there are findings (still 2 on errors)")


def add_target(p: argparse.ArgumentParser) -> None:
    from urdf_lint.config.schema import KEYS
    f = KEYS["targets"].flag
    assert f is not None
    p.add_argument(*f.flags, action="append", metavar=f.metavar, dest=f.dest,
                   help=KEYS["targets"].cli_help())


def add_inputs(p: argparse.ArgumentParser, config: bool = True) -> None:
    p.add_argument("--package-path", action="append", metavar="NAME=DIR",
                   help="where package NAME is, for $(find NAME) and package://NAME; "
                        "repeatable (default: package.xml files under the paths and the "
                        "repository, AMENT_PREFIX_PATH, ROS_PACKAGE_PATH)")
    if config:
        p.add_argument("--config", metavar="FILE",
                       help="config file: pyproject.toml or urdf-lint.toml (default: the "
                            "nearest one above the first path)")
        add_key_flags(p, "jobs")
    add_trust(p)


def add_trust(p: argparse.ArgumentParser) -> None:
    """The keys a repository's own config may not set (urdf_lint/config/trust.py), and the switch
    that lets it."""
    from urdf_lint.config.schema import trust_config_help
    add_key_flags(p, "trust")
    p.add_argument("--trust-config", action="store_true", help=trust_config_help())


def add_views(p: argparse.ArgumentParser) -> None:
    add_key_flags(p, "views")


def add_limits(p: argparse.ArgumentParser) -> None:
    add_key_flags(p, "limits")
    add_key_flags(p, "cache")


def add_output(p: argparse.ArgumentParser) -> None:
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


def add_fix(p: argparse.ArgumentParser) -> None:
    """``check --fix`` and friends (issue 14; :mod:`urdf_lint.cli.fix`)."""
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
