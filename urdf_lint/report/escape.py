"""One escaping helper for every output format, so that nothing a description names (file,
link, joint, macro names; messages quoting them) can forge output.

* :func:`escape_text` makes a string one visible line: control characters (C0, DEL, C1),
  newlines, ANSI escape sequences, Unicode line/paragraph separators and bidirectional
  overrides become ``\\xNN`` / ``\\uNNNN``. Used by the text and github formats and by every
  diagnostic written to stderr, so a link name carrying ``\\n::error file=...::`` cannot start
  a GitHub workflow command in a CI log.
* :func:`escape_xml` also drops what XML 1.0 cannot hold, then escapes ``&<>"``: JUnit stays
  well-formed whatever the names are.
* :func:`escape_markdown` also escapes HTML and Markdown syntax (for ``summary.md``).

JSON and SARIF need none of this: ``json.dump`` escapes control characters itself.
"""
from __future__ import annotations

import re

# C0 controls, DEL, C1 controls, line/paragraph separators, bidi embeddings/overrides/isolates,
# byte-order mark and non-characters that XML cannot carry
_UNSAFE = re.compile("[\x00-\x1f\x7f-\x9f\u2028\u2029\u202a-\u202e\u2066-\u2069\ufeff\ufffe\uffff"
                     "\ud800-\udfff]")


def _visible(m) -> str:
    c = ord(m.group(0))
    return f"\\x{c:02x}" if c < 0x100 else f"\\u{c:04x}"


def escape_text(s) -> str:
    """One line of plain text, every unsafe character shown as an escape."""
    s = str(s)
    return _UNSAFE.sub(_visible, s) if _UNSAFE.search(s) else s


_XML = str.maketrans({"&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;"})


def escape_xml(s) -> str:
    """One line of text or attribute content for XML 1.0 (always well-formed)."""
    return escape_text(s).translate(_XML)


_MD = re.compile(r"([\\`*\[\]|])")


def escape_markdown(s) -> str:
    """Inline Markdown text: no HTML, no links or images, no code spans, no table breaks
    (``_`` is left alone: paths are full of it and it only ever makes emphasis)."""
    s = escape_text(s).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    return _MD.sub(r"\\\1", s)


def escape_markdown_code(s) -> str:
    """Text for inside a Markdown code span in a table cell: one line, no backtick to end the
    span early, no ``|`` to end the cell."""
    return escape_text(s).replace("`", "'").replace("|", "\\|")
