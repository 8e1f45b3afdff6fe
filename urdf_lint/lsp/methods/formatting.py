"""``textDocument/formatting``: ``urdf-lint format``'s layout of the document as the editor
has it (:mod:`urdf_lint.formatting.layout`), under the same guard and the same proof
(:func:`urdf_lint.run.format.prove`: from the file itself where xacro's rules make it one,
else by expanding every model that reads it, before and after, in the server's warm pool of
sandboxed workers, with the unsaved buffers read in place of the files). A layout that is
not proved is not offered: the editor is told why (:class:`Refused`). The style is the
repository's ``[tool.urdf-lint.format]`` (the editor's tab size is not used: the repository's
config is what ``format`` and CI use), ``self-closing = "auto"`` keeping the file's own
``<a />`` or ``<a/>``. Edits are offered only for a file ``check --fix`` may write (inside
the workspace folder, never through a symlink leading out of it)."""
from __future__ import annotations

import difflib
import re
from typing import Any, Iterator

from lsprotocol import types

from urdf_lint.lsp.methods import Refused
from urdf_lint.lsp.services import Services
from urdf_lint.lsp.state import Workspace
from urdf_lint.lsp.text import Doc
from urdf_lint.lsp.uris import uri_path

SUFFIXES = (".urdf", ".xacro")


def handle(sv: Services, params: types.DocumentFormattingParams
           ) -> list[types.TextEdit] | None:
    """Run in the lint thread (:func:`urdf_lint.lsp.server.in_lint_thread`): the proof may
    use the warm pool."""
    return edits(sv.ws, uri_path(params.text_document.uri), None)


def edits(ws: Workspace | None, path: str, rng: types.Range | None) -> list[types.TextEdit] | None:
    """The text edits that lay out ``path`` (only the changed lines touching ``rng`` when
    given), proved; [] when it is laid out already; None for a file format does not lay out."""
    from urdf_lint.formatting.layout import FormatError, Refused as Unsafe, check_same, \
        format_source
    from urdf_lint.run.format import style_of
    if ws is None or not path.endswith(SUFFIXES):
        return None
    if not ws.writable(path):
        raise Refused("not formatted: the file is outside the workspace folder (format writes "
                      "only below the paths it is given)")
    data = ws.buffers[path] if path in ws.buffers else ws.read(path)
    style = style_of(ws.cfg)
    docs: dict[bytes, Any] = {}
    try:
        new = format_source(data, style, path, docs)
    except FormatError as e:
        raise Refused(f"not formatted: line {e.line}: {e.message}") from None
    except Unsafe as e:
        raise Refused(f"not formatted: {e.reason}") from None
    if rng is not None and new != data:
        new = _within(data, new, rng)
        why = check_same(data, new, style, path) if new != data else None
        if why is not None:
            raise Refused(f"not formatted: the lines asked for alone: {why}")
    if new == data:
        return []
    _prove(ws, path, data, new, docs)
    return _text_edits(data, new)


def _prove(ws: Workspace, path: str, old: bytes, new: bytes, docs: dict[bytes, Any]) -> None:
    """Format's proof for the new layout of ``path`` (raises :class:`Refused` when it fails)."""
    from urdf_lint.run.format import prove
    held = dict(ws.buffers)   # (before: the buffers as they are; after: with the new layout)
    with ws.lock:   # (the warm pool serves one run at a time)
        proof = prove({path: new}, [ws.root], ws.cfg, None, old={path: old}, docs=docs,
                      held=held, runner=ws.pool.run if ws.pool is not None else None)
    if path in proof.refused:
        raise Refused(f"not formatted: {proof.refused[path]}")


def _hunks(old: bytes, new: bytes) -> Iterator[tuple[int, int, list[bytes]]]:
    """(old line from, old line to, new lines) of each change, by lines: a run of changed
    lines is cut where the old and the new lines hold the same markup so far (the layout
    moves only whitespace, and closes an empty element), so that each old line's elements
    are one change."""
    a, b = old.splitlines(keepends=True), new.splitlines(keepends=True)
    for op, i1, i2, j1, j2 in difflib.SequenceMatcher(None, a, b, autojunk=False).get_opcodes():
        if op == "equal":
            continue
        x, y = i1, j1
        sa = sb = b""
        while x < i2 or y < j2:
            # the next line of the side that holds less so far (the old one on a tie)
            if x < i2 and (y >= j2 or len(_markup(sa)) <= len(_markup(sb))):
                sa += a[x]
                x += 1
            else:
                sb += b[y]
                y += 1
            if x < i2 and y < j2 and _markup(sa) == _markup(sb):
                yield i1, x, b[j1:y]
                i1, j1, sa, sb = x, y, b"", b""
        yield i1, i2, b[j1:j2]


_SPACE = re.compile(rb"\s+")
_EMPTY = re.compile(rb"></[^>]*>")


def _markup(text: bytes) -> bytes:
    """The markup of ``text`` as the layout keeps it: no whitespace, ``<a></a>`` as ``<a/>``."""
    return _EMPTY.sub(b"/>", _SPACE.sub(b"", text))


def _within(old: bytes, new: bytes, rng: types.Range) -> bytes:
    """``old`` with only the changes of ``new`` that touch the lines of ``rng``."""
    a = old.splitlines(keepends=True)
    out: list[bytes] = []
    at = 0
    first, last = rng.start.line, rng.end.line
    for i1, i2, lines in _hunks(old, new):
        if i1 <= last and (i2 > first or i1 == i2 and i1 >= first):
            out.extend(a[at:i1])
            out.extend(lines)
            at = i2
    out.extend(a[at:])
    return b"".join(out)


def _text_edits(old: bytes, new: bytes) -> list[types.TextEdit]:
    doc = Doc(old)
    starts = [0]
    for line in old.splitlines(keepends=True):
        starts.append(starts[-1] + len(line))
    return [types.TextEdit(range=types.Range(doc.offset_position(starts[i1]),
                                             doc.offset_position(starts[i2])),
                           new_text=b"".join(lines).decode("utf-8", "replace"))
            for i1, i2, lines in _hunks(old, new)]
