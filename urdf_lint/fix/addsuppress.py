"""``urdf-lint check --add-suppressions``: a ``<!-- urdf-lint: disable-next CODES -->`` line
above the source line of every current finding (like ruff's ``--add-noqa``), to adopt the
linter on a large repository in one commit.

The comment takes the indentation and the line ending of the line it precedes; the findings of
one line share one comment. Nothing is written above an XML declaration, into a file that is
not XML (a YAML file), or for an unused suppression (UL009: remove that comment instead).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Iterable

from urdf_lint.core import fsbound
from urdf_lint.core.codes import RuleName
from urdf_lint.core.edits import Edit
from urdf_lint.fix.scope import inside
from urdf_lint.fix.sourceedit import apply_edits, line_offset

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.core.findings import Problem

# the rules raised here, by name (urdf_lint.core.codes: no rule module is imported)
unused_suppression = RuleName("ul009_unused_suppression")


def suppression_edits(findings: Iterable["Problem"]
                      ) -> tuple[dict[str, list[Edit]], list["Problem"]]:
    """({file: [Edit]}, [findings left alone])."""
    by_line: dict[tuple[str, int], list["Problem"]] = {}
    skipped: list["Problem"] = []
    for f in findings:
        if f.code == unused_suppression.CODE or not f.file.endswith((".xacro", ".urdf", ".xml")):
            skipped.append(f)
            continue
        by_line.setdefault((f.file, f.line), []).append(f)
    edits: dict[str, list[Edit]] = {}
    cache: dict[str, bytes] = {}
    for (file, line), fs in sorted(by_line.items()):
        if file not in cache:
            try:
                cache[file] = fsbound.read_bytes(file)
            except OSError:
                skipped.extend(fs)
                continue
        data = cache[file]
        start = line_offset(data, line)
        if start is None:
            skipped.extend(fs)
            continue
        end = data.find(b"\n", start)
        text = data[start:end if end >= 0 else len(data)]
        if b"<?xml" in text or b"<!DOCTYPE" in text:
            skipped.extend(fs)
            continue
        indent = text[:len(text) - len(text.lstrip(b" \t"))].decode("utf-8")
        eol = "\r\n" if text.endswith(b"\r") else "\n"
        codes = ", ".join(dict.fromkeys(sorted(f.code for f in fs)))
        edits.setdefault(file, []).append(
            Edit(file, start, start, f"{indent}<!-- urdf-lint: disable-next {codes} -->{eol}"))
    return edits, skipped


def add_suppressions(findings: Iterable["Problem"], paths: list[str] | None = None
                     ) -> tuple[int, list[str], list["Problem"]]:
    """Write the comments; (comments written, files changed, findings left alone). With
    ``paths``, files outside them (another package, an installed one) are left alone."""
    mine: list["Problem"] = []
    outside: list["Problem"] = []
    for f in findings:
        (mine if paths is None or inside(f.file, paths) else outside).append(f)
    findings = mine
    edits, skipped = suppression_edits(findings)
    skipped += outside
    written = 0
    from urdf_lint.discovery.discover import repository_root
    repo = repository_root(paths) if paths is not None else None
    for file, es in sorted(edits.items()):
        data = fsbound.read_bytes(file)
        fsbound.rewrite(file, apply_edits(data, es), paths if paths is not None else [file],
                        old=data, repo=repo)
        written += len(es)
    return written, sorted(edits), skipped
