"""Inline suppression in XML comments of the xacro/URDF *source*.

``<!-- urdf-lint: disable-next UL204 -->``  the next element, and all a macro call there makes
``<!-- urdf-lint: disable UL3 -->`` ... ``<!-- urdf-lint: enable UL3 -->``  a range of lines
``<!-- urdf-lint: disable-file UL101 -->``  the whole file

No codes means every code. Codes match by prefix (``UL3`` = all joint-limit rules) or name.
A directive that suppresses nothing is reported as ``UL009 unused-suppression``; an unknown
directive (``disabel-next``) or code (``UL999``) as ``UL010 invalid-suppression``.
"""
from __future__ import annotations

import bisect
import re
import xml.parsers.expat
from dataclasses import dataclass, field
from typing import Any, Callable, Iterable, Iterator

from urdf_lint.core.locations import Origin
from urdf_lint.discovery.packages import MAX_SOURCE_BYTES as MAX_BYTES   # the parent's cap on any XML source
from urdf_lint.config.policy import code_matches

_DIRECTIVE = re.compile(r"<!--\s*urdf[-_]lint\s*:\s*([A-Za-z_-]*)(.*?)-->", re.S)
KINDS = ("disable-next", "disable-file", "disable", "enable")


@dataclass
class Directive:
    """An inline ``urdf-lint: disable...`` comment: its kind, codes and the lines it covers."""
    kind: str
    codes: list[str]
    file: str
    line: int
    col: int
    span: Any = ()            # ((start_line, start_col), end_line) for disable-next / ranges
    used: bool = False
    problems: list[str] = field(default_factory=list)   # what is wrong with the comment itself

    def matches_code(self, code: str, name: str) -> bool:
        return not self.codes or any(code_matches(c, code, name) for c in self.codes)


def _element_spans(data: bytes) -> list[list[Any]]:
    spans: list[list[Any]] = []
    stack: list[int] = []
    p = xml.parsers.expat.ParserCreate()

    def start(name: str, attrs: Any) -> None:
        stack.append(len(spans))
        spans.append([(p.CurrentLineNumber, p.CurrentColumnNumber + 1), None])

    def end(name: str) -> None:
        spans[stack.pop()][1] = p.CurrentLineNumber
    p.StartElementHandler = start
    p.EndElementHandler = end
    try:
        p.Parse(data, True)
    except Exception:
        pass
    return spans


SOURCE_SUFFIXES = (".xacro", ".urdf", ".xml")   # the files suppression comments are read from


def _read_source(path: str) -> bytes | None:
    """The bytes of a regular file of bounded size (never a device, FIFO or folder), or None
    when it holds no urdf-lint comment at all."""
    from urdf_lint.core.hashing import read_regular
    data = read_regular(path, MAX_BYTES)   # (an unsaved editor buffer: urdf_lint/core/overlay.py)
    return data if data is not None and (b"urdf-lint" in data or b"urdf_lint" in data) else None


_marked: dict[Any, bool] = {}   # (path, size, mtime) -> holds the words: a shared include is read once


def with_directives(deps: Iterable[str]) -> list[str]:
    """The source files among ``deps`` that may hold a suppression comment (worker side: a
    file without the words ``urdf-lint``/``urdf_lint`` holds none)."""
    import os
    out = []
    for d in deps:
        if not d.endswith(SOURCE_SUFFIXES):
            continue
        from urdf_lint.core import overlay
        if overlay.get(d) is not None:
            if _read_source(d) is not None:
                out.append(d)
            continue
        try:
            st = os.stat(d)
        except OSError:
            continue
        key = (d, st.st_size, st.st_mtime_ns)
        if key not in _marked:
            _marked[key] = _read_source(d) is not None
        if _marked[key]:
            out.append(d)
    return out


_HEAD = re.compile(r"<!--\s*urdf[-_]lint\s*:\s*([A-Za-z_-]*)")


def _comments(text: str) -> Iterator[tuple[int, int, str, str]]:
    """(start, end, kind, rest) of every ``<!-- urdf-lint: KIND REST -->`` in ``text``, what
    ``_DIRECTIVE.finditer`` yields, in one linear pass: each comment's end is the first
    ``-->`` after its kind, found once (the pattern's lazy search for it from every unclosed
    opening made a file of unclosed comments quadratic), and once no ``-->`` follows, no
    later opening can close either."""
    pos = 0
    while (m := _HEAD.search(text, pos)) is not None:
        close = text.find("-->", m.end(1))
        if close >= 0:
            kind, rest = m.group(1), text[m.end(1):close]
        else:   # only a '-->' ending the kind itself ('disable-->'): the pattern backtracks
            close = text.find("-->", m.start(1))
            if close < 0:
                return
            kind, rest = text[m.start(1):close], ""
        yield m.start(), close + 3, kind, rest
        pos = close + 3


class _Lines:
    """Line and column of increasing offsets in ``text``, counted incrementally (linear in
    the text however many offsets are asked for)."""

    def __init__(self, text: str):
        self.text, self.pos, self.line, self.line_start = text, 0, 1, 0

    def at(self, offset: int) -> tuple[int, int]:
        assert offset >= self.pos
        n = self.text.count("\n", self.pos, offset)
        if n:
            self.line += n
            self.line_start = self.text.rfind("\n", self.pos, offset) + 1
        self.pos = offset
        return self.line, offset - self.line_start + 1


MAX_HINTS = 200   # "did you mean" for this many unknown words of a file (each costs ~0.5 ms)


def parse_directives(path: str) -> list[Directive]:
    data = _read_source(path)
    if data is None:
        return []
    return directives_in(data, path)


def coverage(data: bytes, path: str = "") -> list[tuple[int, str, frozenset[int]]]:
    """(line, "kind codes", the ordinals of the elements it covers) for every directive in
    ``data``: what ``urdf-lint format`` must keep when it moves lines."""
    spans = _element_spans(data)
    out = []
    for d in directives_in(data, path):
        if d.kind in KINDS:
            what = f"{d.kind} {' '.join(d.codes)}".strip()
            out.append((d.line, what, frozenset(i for i, s in enumerate(spans)
                                                if _covers(d, path, *s[0]))))
    return out


def directives_in(data: bytes, path: str) -> list[Directive]:
    """The directives in the bytes of the source ``path``."""
    text = data.decode("utf-8", "replace")
    out = []
    spans: list[list[Any]] | None = None
    starts: list[Any] = []
    open_ranges: dict[Any, Any] = {}
    nlines = text.count("\n") + 1
    lines = _Lines(text)
    hints: dict[Any, Any] = {}
    for start, end, kind, rest in _comments(text):
        codes = [c for c in re.split(r"[\s,]+", rest.strip()) if c]
        line, col = lines.at(start)
        end_line, end_col = lines.at(end)
        d = Directive(kind, codes, path, line, col)
        if kind not in KINDS:
            d.problems.append(f"unknown suppression directive '{kind or rest.strip()}'"
                              + _hint(kind, KINDS, hints) + "; it suppresses nothing")
            d.used = True   # reported as invalid, not also as unused
            out.append(d)
            continue
        d.problems.extend(_code_problems(codes, hints))
        if kind == "disable-next":
            if spans is None:
                spans = _element_spans(data)
                starts = [s[0] for s in spans]   # in document order
            i = bisect.bisect_left(starts, (end_line, end_col))
            nxt = spans[i] if i < len(spans) else None
            d.span = (nxt[0], nxt[1] or nxt[0][0]) if nxt else ((line, col), line)
        elif kind == "disable":
            d.span = ((line, col), nlines)
            for c in (codes or ["*"]):
                open_ranges[c] = d
        elif kind == "enable":
            for c in (codes or list(open_ranges)):
                r = open_ranges.pop(c, None)
                if r is not None:
                    r.span = (r.span[0], line)
            continue  # enable itself suppresses nothing
        out.append(d)
    return out


def _did_you_mean(word: str, candidates: Iterable[str]) -> str:
    from urdf_lint.engine.api import did_you_mean
    return did_you_mean(word, candidates)


def _hint(word: str, candidates: Iterable[str], hints: dict[Any, Any]) -> str:
    """:func:`_did_you_mean`, once per word and for at most :data:`MAX_HINTS` words."""
    key = ("hint", word)
    if key not in hints:
        hints[key] = _did_you_mean(word, candidates) if hints.get("hinted", 0) < MAX_HINTS else ""
        hints["hinted"] = hints.get("hinted", 0) + 1
    hint: str = hints[key]
    return hint


def _code_problems(codes: Iterable[str], hints: dict[Any, Any] | None = None) -> list[str]:
    """Messages for codes that name no rule, no code prefix and no rule name (each code judged
    once per ``hints``, the memo of one file's scan)."""
    memo = {} if hints is None else hints
    out = []
    for c in codes:
        key = ("code", c)
        if key not in memo:
            memo[key] = _code_problem(c, memo)
        if memo[key]:
            out.append(memo[key])
    return out


def _code_problem(c: str, hints: dict[Any, Any]) -> str | None:
    from urdf_lint.engine.registry import catalogue
    rules = catalogue()
    names = {r.name for r in rules.values()}
    if c.upper() == "ALL" or c in names or any(k.startswith(c) for k in rules):
        return None
    return (f"unknown code '{c}' in a suppression comment"
            + _hint(c, list(rules) + sorted(names), hints) + "; it suppresses nothing")


def _covers(d: Directive, file: str, line: int, col: int) -> bool:
    if file != d.file:
        return False
    if d.kind == "disable-file":
        return True
    (sl, sc), el = d.span
    return (line, col) >= (sl, sc) and line <= el


def apply(findings: Iterable[Any], directives_by_file: dict[str, list[Directive]],
          report_unused: bool = True, is_selected: Callable[[str], bool] = lambda code: True
          ) -> tuple[list[Any], list[tuple[Origin, str]], list[tuple[Origin, str]]]:
    """Drop suppressed findings; return ``(kept, unused, invalid)``, the last two as
    ``(Origin, message)`` pairs: each directive that suppressed nothing, and each unknown
    directive or code (unless a suppression covers it). The run pipeline reports them as
    ``UL009 unused-suppression`` and ``UL010 invalid-suppression``."""
    directives = [d for ds in directives_by_file.values() for d in ds]
    if not directives:
        return list(findings), [], []
    from urdf_lint.core.findings import Problem
    from urdf_lint.core.codes import RuleName
    from urdf_lint.engine.registry import catalogue
    invalid_suppression = RuleName("ul010_invalid_suppression")
    name = catalogue()[invalid_suppression.CODE].name
    invalid = [Problem.at(invalid_suppression.CODE, p, (d.file, d.line, d.col)).replace(name=name)
               for d in directives for p in d.problems]
    directives = [d for d in directives if d.kind in KINDS]
    kept: list[Any] = []
    invalid_kept: list[Any] = []
    invalid_ids = {id(f) for f in invalid}
    for f in list(findings) + invalid:
        locs = [(f.file, f.line, f.col)] + [(c[0], c[1], c[2]) for c in f.chain]
        hit = False
        for d in directives:
            if d.matches_code(f.code, f.name) and any(_covers(d, *loc) for loc in locs):
                d.used = True
                hit = True
        if not hit:
            (invalid_kept if id(f) in invalid_ids else kept).append(f)
    unused = []
    if report_unused:
        for d in directives:
            # a directive for codes that were not run this time cannot be judged unused; nor
            # one whose codes are all unknown (reported as invalid instead)
            if d.codes and len(d.problems) == len(d.codes):
                continue
            if not d.used and (not d.codes or any(is_selected(c) for c in d.codes)):
                what = ", ".join(d.codes) if d.codes else "all codes"
                unused.append((Origin(d.file, d.line, d.col),
                               f"unused suppression '{d.kind} {what}': "
                               "nothing was reported here; remove the comment"))
    return kept, unused, [(f.origin, f.message) for f in invalid_kept]
