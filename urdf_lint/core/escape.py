"""One escaping helper for every output format, so that nothing a description names (file,
link, joint, macro names; messages quoting them) can forge output.

* :func:`escape_text` makes a string one visible line: control characters (C0, DEL, C1),
  newlines, ANSI escape sequences, Unicode line/paragraph separators and bidirectional
  overrides become ``\\xNN`` / ``\\uNNNN``. Used by the text and github formats and by every
  diagnostic written to stderr, so a link name carrying ``\\n::error file=...::`` cannot start
  a GitHub workflow command in a CI log.
* :func:`escape_xml` also drops what XML 1.0 cannot hold, then escapes ``&<>"``: JUnit stays
  well-formed whatever the names are.
* :func:`escape_markdown` also escapes HTML and every Markdown construct, and defuses what
  GitHub links by itself (@mentions, #references, bare URLs): ``summary.md`` and
  ``urdf-lint diff --format markdown`` (a pull-request comment). :func:`escape_html` is the
  same for text inside the HTML such a comment may hold.

JSON and SARIF need none of this: ``json.dump`` escapes control characters itself.
"""
from __future__ import annotations

import re

# C0 controls, DEL, C1 controls, line/paragraph separators, bidi embeddings/overrides/isolates,
# byte-order mark and non-characters that XML cannot carry
_UNSAFE = re.compile("[\x00-\x1f\x7f-\x9f\u2028\u2029\u202a-\u202e\u2066-\u2069\ufeff\ufffe\uffff"
                     "\ud800-\udfff]")


def _visible(m: re.Match[str]) -> str:
    c = ord(m.group(0))
    return f"\\x{c:02x}" if c < 0x100 else f"\\u{c:04x}"


def escape_text(s: object) -> str:
    """One line of plain text, every unsafe character shown as an escape."""
    s = str(s)
    return _UNSAFE.sub(_visible, s) if _UNSAFE.search(s) else s


_XML = str.maketrans({"&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;"})


def escape_xml(s: object) -> str:
    """One line of text or attribute content for XML 1.0 (always well-formed)."""
    return escape_text(s).translate(_XML)


# what GitHub links in rendered text itself, after Markdown: @mentions, #123 references,
# bare URLs and e-mail addresses. A word joiner (U+2060, invisible) after the @ or # and inside
# "://" and "www." breaks each pattern while the visible text stays the same
_GITHUB_LINKS = re.compile(r"([@#])|(:)(?=//)|(?<![\w.])(www)(?=\.)", re.I)
_JOINER = "\u2060"


def _defuse(s: str) -> str:
    return _GITHUB_LINKS.sub(lambda m: m.group(0) + _JOINER, s)


def escape_html(s: object) -> str:
    """Text inside HTML that GitHub renders (a ``<summary>``): one line, ``&<>"`` as entities,
    no mention, reference or autolink."""
    s = escape_text(s).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;") \
        .replace('"', "&quot;")
    return _defuse(s)


# every ASCII character that starts Markdown syntax inline: code, emphasis, links and images,
# tables, strikethrough, math, headings (CommonMark lets any of them be backslash-escaped)
_MD = re.compile(r"([\\`*_\[\]()!|~$#])")
_BLOCK_START = re.compile(r"^([-+=]|\d+(?=[.)]))")


def escape_markdown(s: object) -> str:
    """Untrusted text placed in Markdown (a pull-request comment, ``summary.md``): it renders
    as the same visible text and nothing else: no HTML, no link or image, no code span,
    emphasis, strikethrough or math, no table cell break, no list or heading at the start,
    no @mention, #reference or autolinked URL."""
    s = escape_html(s).replace(_JOINER, "")
    s = _MD.sub(r"\\\1", s)
    s = _BLOCK_START.sub(lambda m: "\\" + m.group(0) if not m.group(0)[0].isdigit()
                         else m.group(0) + "\\", s)
    return _defuse(s)


def escape_markdown_code(s: object) -> str:
    """Text for inside a Markdown code span in a table cell: one line, no backtick to end the
    span early, no ``|`` to end the cell."""
    return escape_text(s).replace("`", "'").replace("|", "\\|")
