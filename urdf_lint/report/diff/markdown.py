"""``markdown``: the diff as GitHub-flavoured markdown for a job summary or a pull-request
comment (always under 60,000 characters; with --image-base-url, the --render pictures)."""
from __future__ import annotations

from typing import Any

from urdf_lint.core.escape import escape_html
from urdf_lint.report.diff.base import (MD_ICON, DiffFormatter, DiffResult, chain, code, fmt, loc,
                                        md_escape, moved, related, vloc)

MARKDOWN_LIMIT = 60_000   # characters of a job summary


class MarkdownDiff(DiffFormatter):
    name = "markdown"
    help = "for a pull-request comment or a job summary (GitHub-flavoured, under 60,000 characters)"

    def render(self, result: DiffResult) -> str:
        return to_markdown(result, self.options.image_base_url)


def to_markdown(r: DiffResult, image_base_url: str | None = None,
                limit: int = MARKDOWN_LIMIT) -> str:
    head = ["## urdf-lint: what this change does to the robots",
            "",
            f"{code(r.base)} → {code(r.head)}: **{len(r.models)}** of {r.total_models} "
            f"model(s) affected ({r.base_expanded} expanded at the base).",
            ""]
    if not r.models:
        return "\n".join(head + ["No robot model is affected by this change.", ""])
    table = ["| model | status | changes | moved | findings |", "|---|---|---|---|---|"]
    for m in r.models:
        fi, ff = len(m.findings_introduced), len(m.findings_fixed)
        table.append(f"| {code(m.model)} | {m.status} | {len(m.changes)} | "
                     f"{md_escape(moved(m)) if m.moved else '—'} | "
                     f"{'+' + str(fi) if fi else '0'} new / {ff} fixed |")
    sections = []
    for m in r.models:
        rows = [f"<details><summary><b>{escape_html(m.model)}</b>: {m.status}, "
                f"{len(m.changes)} change(s)</summary>", ""]
        if m.error:
            rows += [f"> {md_escape(m.error)}", ""]
        if image_base_url:
            stem = m.picture   # the name the pictures were written under
            base = image_base_url.rstrip("/")
            rows += ["| before | after | difference |", "|---|---|---|",
                     f"| ![before]({base}/{stem}.before.png) | ![after]({base}/{stem}.after.png)"
                     f" | ![diff]({base}/{stem}.diff.png) |", ""]
        elif m.snapshot:   # --render without a place to show them: name them (the artifact)
            files = [code(m.snapshot[k].replace("\\", "/").rsplit("/", 1)[-1])
                     for k in ("before", "after", "diff") if m.snapshot.get(k)]
            said = m.snapshot.get("caption")
            rows += [f"Pictures (in the review's artifact): {', '.join(files)}"
                     + (f" ({md_escape(said)})" if said else ""), ""]
        if m.changes:
            rows += ["| | element | field | before | after | source |", "|---|---|---|---|---|---|"]
            for c in m.changes:
                o = c.head or c.base
                src = (code(vloc(c.value_from)) + " <sub>value from; used at "
                       + md_escape(loc(o)) + "</sub>") if c.value_from else \
                    code(loc(o)) + (f" <sub>{md_escape(chain(o))}</sub>" if chain(o) else "")
                rows.append(f"| {MD_ICON[c.change]} | {c.kind} {code(c.name)} | "
                            f"{md_escape(c.field or c.change)} | {md_escape(fmt(c.before))} | "
                            f"{md_escape(fmt(c.after))} | {src} |")
            rows.append("")
        if m.moved:
            rows += [f"Links moved at the zero configuration: {md_escape(moved(m, 10))}.", ""]
        for title, items in (("New findings", m.findings_introduced),
                             ("Fixed findings", m.findings_fixed)):
            if items:
                rows += [f"**{title}**", ""]
                rows += [f"- {s} {code(fk[0])} {code(_at(fk[1], m.finding_lines.get(fk)))}: "
                         f"{md_escape(fk[2])}" + _notes(m, fk) for fk, s in items]
                rows.append("")
        rows += ["</details>", ""]
        sections.append(rows)
    text = "\n".join(head + table + [""] + [ln for s in sections for ln in s])
    if len(text) <= limit:
        return text
    # too big for a comment: keep the summary table, then as many sections as fit
    out = "\n".join(head + table + [""])
    note = ("\n_The details of {n} more model(s) are in the JSON report "
            "(`urdf-lint diff --format json`)._\n")
    kept = 0
    for s in sections:
        chunk = "\n".join(s) + "\n"
        if len(out) + len(chunk) + len(note) + 20 > limit:
            break
        out += chunk
        kept += 1
    if kept < len(sections):
        out += note.format(n=len(sections) - kept)
    if len(out) > limit:  # even the table is too long: summarise it
        out = "\n".join(head) + f"\n{len(r.models)} models changed; see the JSON report.\n"
    return out


def _notes(m: Any, fk: tuple[str, str, str]) -> str:
    """Where a finding's value comes from (a YAML line, as ``check`` says it) and the robot
    element it is about (``m`` its ModelDiff)."""
    v = m.finding_value_from.get(fk)
    src = f" <sub>value from {code(f'{v[0]}:{v[1]}')}</sub>" if v else ""
    return src + (f" <sub>{md_escape(related(m, fk))}</sub>" if related(m, fk) else "")


def _at(file: str, at: tuple[int, int] | None) -> str:
    return f"{file}:{at[0]}" if at and at[0] else file
