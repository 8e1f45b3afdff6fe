"""urdf-lint's own messages on the standard streams, each escaped by the one escaper
(:mod:`urdf_lint.core.escape`), so that no name in them can forge a line."""
from __future__ import annotations

import errno
import sys
from typing import Iterable, TextIO

# a write to standard output that fails for want of room (``> /dev/full``, a full disk or
# quota, a file size limit): the run cannot say what it found. Only a write fails so; an I/O
# error (EIO: a terminal hung up) counts only where the failing call was a write to standard
# output (``certain``), since a read can fail with it too
OUTPUT_ERRNOS = frozenset((errno.ENOSPC, errno.EDQUOT, errno.EFBIG))


def say(text: object, stream: TextIO | None = None) -> None:
    """One message of urdf-lint's own on stderr (or ``stream``) as ONE visible line: every
    command's messages go through here (or through an output format), so a file, link or
    package name in them cannot start another line, forge a CI workflow command (``::error``)
    or send a terminal escape (the one escaper: :mod:`urdf_lint.core.escape`)."""
    from urdf_lint.core.escape import escape_text
    (stream or sys.stderr).write(escape_text(text) + "\n")


def tell(text: object) -> None:
    """:func:`say` on standard output (what a command prints as its result)."""
    say(text, sys.stdout)


def reader_left() -> None:
    """Standard output's reader has gone (``urdf-lint check . | head``): what is still to be
    printed goes nowhere, without an error, and the command keeps the exit status of what it
    found (a pipeline with ``pipefail`` must not pass a run with errors because its reader
    left early)."""
    from urdf_lint.core.fsbound import null_onto
    null_onto(sys.stdout.fileno(), write=True)


def drop_stdout(e: OSError) -> str:
    """Standard output could not be written (:data:`OUTPUT_ERRNOS`): what is still to be
    printed goes nowhere (:func:`reader_left`, so the interpreter's last flush does not fail
    again) and the error that says so, without "please report": the run did nothing wrong, and
    its exit status is 2 (the report is lost)."""
    reader_left()
    return f"cannot write to standard output: {e.strerror or e}"


def lost_stdout(e: OSError) -> int:
    """Say that standard output could not be written (:func:`drop_stdout`); the exit status."""
    say(f"urdf-lint: error: {drop_stdout(e)}")
    return 2


def stdout_failed(e: BaseException, certain: bool = False) -> bool:
    """Whether ``e`` is a failed write to standard output of :func:`drop_stdout`'s kind (an
    error of a file urdf-lint opened names that file); ``certain``: the failing call was such
    a write (then an I/O error counts too)."""
    return isinstance(e, OSError) and not isinstance(e, BrokenPipeError) \
        and e.filename is None \
        and (e.errno in OUTPUT_ERRNOS or certain and e.errno == errno.EIO)


def safe_lines(s: object) -> str:
    """Text from a model or a traceback, each line escaped for the terminal and every line
    after the first indented, so that none can start a CI workflow command."""
    from urdf_lint.core.escape import escape_text
    return "\n    ".join(escape_text(line) for line in str(s).split("\n"))


def report_internal(messages: Iterable[str]) -> bool:
    """Each internal error on stderr (they make the exit code 2); whether there was one."""
    for msg in messages:
        sys.stderr.write(f"urdf-lint: internal error (please report): {safe_lines(msg)}\n")
    return bool(messages)
