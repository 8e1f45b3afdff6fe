"""Command line: urdf-lint check|hook|expand|rules|rule|render|diff|generate|format|mcp|clean|
doctor|server.

Each command is one module of this package (``urdf_lint/cli/<command>.py``) with
``add_parser(sub, raw)`` and ``run(args) -> int``; :data:`COMMANDS` lists them in the order of
``urdf-lint --help``, and only the named command's module is imported. A command turns its
parsed arguments into typed options (dataclasses) before anything below the CLI sees them.

Exit codes: 0 clean, 1 findings at or above --fail-on, 2 usage or internal error, 130 Ctrl-C.
Heavy modules (xacro, trimesh, rerun) are imported only by the commands that need them.
Options that are also config keys (``--select``, ``--timeout``, ...) come from the config
schema (:mod:`urdf_lint.config.schema`), so a bad value on the command line gets the same
message as in a config file.
"""
from __future__ import annotations

import argparse
import importlib
import os
import sys
from typing import TYPE_CHECKING

from urdf_lint.cli.parser import Parser, RawDescriptionHelpFormatter
from urdf_lint.core.emit import say
from urdf_lint.core.errors import UsageError

if TYPE_CHECKING:  # pragma: no cover
    from argparse import Namespace
    from collections.abc import Callable, Sequence
    from types import ModuleType
    from typing import Any, NoReturn

# the subcommands in the order of `urdf-lint --help`: each is the module urdf_lint.cli.<name>


COMMANDS = ("check", "hook", "expand", "rules", "rule", "render", "diff", "generate", "format",
            "mcp", "doctor", "clean", "server", "preview")
LONG_LIVED = ("mcp", "server", "preview")   # the others end with their run
SUBPARSERS: dict[str, argparse.ArgumentParser] = {}


def command_module(name: str) -> ModuleType:
    return importlib.import_module(f"urdf_lint.cli.{name}")


def _runner(name: str) -> Callable[[Namespace], int]:
    mod = command_module(name)
    run: Callable[[Namespace], int] = (getattr(mod, "run", None)
                                                or getattr(mod, f"cmd_{name}"))
    return run


def build_parser(only: str | None = None) -> Parser:
    """The command-line parser; with ``only`` (a known command) just that subcommand's parser
    is built: building all of them imports the format registry and the config schema, which
    ``urdf-lint expand`` does not need (it stays under 0.15 s)."""
    p = Parser(prog="urdf-lint", description="Expand xacro without ROS, lint robot "
               "descriptions at their xacro source lines, and render review snapshots.")
    p.add_argument("--version", action="store_true", help="print the version and exit")
    sub = p.add_subparsers(dest="command", parser_class=Parser, metavar="COMMAND")
    raw = RawDescriptionHelpFormatter   # keeps the epilog's table of formats
    for name in COMMANDS:
        if only is None or name == only:
            command_module(name).add_parser(sub, raw)
    SUBPARSERS.clear()
    SUBPARSERS.update(sub.choices)
    return p


def _command_of(argv: Sequence[str]) -> str | None:
    """The subcommand named on the command line (the first word that is not an option), when
    it is a known one; None otherwise (then the whole parser is built, for help and hints)."""
    for a in argv:
        if a == "--":
            return None
        if not a.startswith("-"):
            return a if a in COMMANDS else None
    return None


def main(argv: Sequence[str] | None = None) -> int:
    from urdf_lint.core import lazy
    lazy.enable()   # modules few runs use load on first use (PyYAML, Pillow): in this process only
    try:
        return _main(argv)
    except KeyboardInterrupt:
        sys.stderr.write("\nurdf-lint: interrupted\n")
        return 130
    except OSError as e:    # `--version > /dev/full` (a command's own is handled by guarded)
        from urdf_lint.core.emit import lost_stdout, reader_left, stdout_failed
        if isinstance(e, BrokenPipeError):    # `--help | head -1`
            reader_left()
            return 0
        if not stdout_failed(e):
            raise
        return lost_stdout(e)


def entry() -> None:
    """The ``urdf-lint`` command (and ``python -m urdf_lint``): :func:`main`, then leave."""
    # numpy's BLAS starts a thread per core when loaded (~15 ms); the matrices urdf-lint
    # multiplies are 3x3 (a command setting, unless the user chose: not for library users)
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    try:
        code = main()
    except SystemExit as e:   # argparse's --help and usage errors: their output is flushed too
        if not (e.code is None or isinstance(e.code, int)):
            raise
        code = e.code or 0
    exit_now(code)


def exit_now(code: int) -> None:
    """End the process without tearing the interpreter down: freeing every module and object
    one by one takes ~20 ms after a run (a tenth of ``urdf-lint expand``), and the OS frees
    them anyway. Exit handlers still run and the output streams are flushed (when standard
    output cannot take what is left, a full disk, the error says so and the status is 2);
    when a thread that is not a daemon is still running, exit the usual way (it is waited
    for)."""
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
        except OSError as e:
            from urdf_lint.core.emit import lost_stdout, stdout_failed
            if stream is sys.stdout and stdout_failed(e, certain=True):
                code = lost_stdout(e)
            # else: the reader is gone (`| head`): nothing more to say
        except ValueError:   # (closed)
            pass
    os._exit(code)


def _hook_arguments(argv: list[str]) -> tuple[list[str], list[str]]:
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


def _main(argv: Sequence[str] | None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    command = _command_of(argv)
    if command not in LONG_LIVED:
        import urdf_lint.runner
        urdf_lint.runner.ONE_SHOT = True
    hook_files: list[str] = []
    if command == "hook":
        argv, hook_files = _hook_arguments(argv)
    if command in ("expand", "generate") and "-h" not in argv and "--help" not in argv:
        # the worker imports the expansion while the parent parses, reads the config and
        # finds the packages (a run that stops early stops it too)
        from urdf_lint.run.worker import prestart
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
    return guarded(_runner(args.command), args)


def guarded(command: Callable[..., int], *args: Any) -> int:
    """Run one command (``command(*args)``, its exit status) as ``urdf-lint`` does: SIGTERM
    handled like Ctrl-C, a usage or config error is one line and 2, any other exception an
    internal error and 2 (the command line, and each call of the MCP server's tools)."""
    from urdf_lint.config.schema import ConfigError   # (a BaselineError is a UsageError)
    import signal

    # SIGTERM is handled like Ctrl-C: workers are stopped
    def _terminate(signum: int, frame: object) -> NoReturn:
        raise KeyboardInterrupt
    try:
        signal.signal(signal.SIGTERM, _terminate)
    except ValueError:  # pragma: no cover - not the main thread
        pass
    try:
        return command(*args)
    except (UsageError, ConfigError) as e:
        say(f"urdf-lint: error: {e}")
        return 2
    except KeyboardInterrupt:
        raise
    except BrokenPipeError:   # a reader that left early (`| head`): not an error of the run
        from urdf_lint.core.emit import reader_left
        reader_left()
        return 0
    except Exception as e:  # noqa: BLE001
        from urdf_lint.core.emit import lost_stdout, stdout_failed
        if isinstance(e, OSError) and stdout_failed(e):   # `> /dev/full`: not an internal error
            return lost_stdout(e)
        import traceback
        say(f"urdf-lint: internal error (please report): {type(e).__name__}: {e}")
        if os.environ.get("URDF_LINT_DEBUG"):
            traceback.print_exc()
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
