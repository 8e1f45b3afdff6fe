"""Output of ``urdf-lint diff``: text for the terminal, JSON for tools, and GitHub-flavoured
markdown for a job summary or a pull-request comment (always under 60,000 characters)."""
from __future__ import annotations

import json
import os

from urdf_lint.core.escape import escape_html, escape_markdown, escape_markdown_code, escape_text
from urdf_lint.review.run import MARKDOWN_LIMIT, DiffResult

_ICON = {"added": "+", "removed": "-", "renamed": "~", "changed": "*"}
_MD_ICON = {"added": "🟢", "removed": "🔴", "renamed": "🔁", "changed": "✏️"}


def _fmt(v) -> str:
    if v is None:
        return "—"
    if isinstance(v, tuple):
        return " ".join(_fmt(x) for x in v)
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v)


def _loc(o, root=None) -> str:
    if o is None:
        return ""
    from urdf_lint.core.locations import display_path
    return f"{display_path(o.file, root)}:{o.line}"


def _vloc(v, root=None) -> str:
    """``config/joint_limits.yaml:28``: where a changed value is written."""
    from urdf_lint.core.locations import display_path
    return f"{display_path(v[0], root)}:{v[1]}"


def _chain(o, root=None) -> str:
    return o.format_chain(root) if o is not None and o.chain else ""


def _what(c) -> str:
    return f"{c.kind} '{c.name}'" + (f" {c.field}" if c.field and c.change != "renamed" else "")


def _moved(m, n=3) -> str:
    parts = [f"{link} {d * 1000:.3g} mm" + (f", {a:.3g} rad" if a > 1e-6 else "")
             for link, d, a in m.moved[:n]]
    more = len(m.moved) - n
    return ", ".join(parts) + (f" and {more} more" if more > 0 else "")


def _finding(fk) -> str:
    code, file, msg = fk
    return f"{code} {file}: {msg}"


def to_text(r: DiffResult) -> str:
    out = [f"urdf-lint diff {r.base}..{r.head}: {len(r.models)} model(s) affected of "
           f"{r.total_models}, {r.base_expanded} expanded at {r.base}"]
    for m in r.models:
        out.append("")
        out.append(f"{m.model}: {m.status}" + (f" ({m.error})" if m.error else ""))
        for c in m.changes:
            where = _loc(c.head or c.base)
            line = f"  {_ICON[c.change]} {_what(c)}"
            if c.change in ("changed", "renamed"):
                line += f": {_fmt(c.before)} -> {_fmt(c.after)}"
            out.append(line + (f"  [{where}]" if where else ""))
            ch = _chain(c.head or c.base)
            if ch:
                out.append(f"      {ch}")
            if c.value_from:
                out.append(f"      value from {_vloc(c.value_from)}")
        if m.moved:
            out.append(f"  moved at zero configuration: {_moved(m, 5)}")
        for fk, sev in m.findings_introduced:
            out.append(f"  introduced {sev}: {_finding(fk)}")
        for fk, sev in m.findings_fixed:
            out.append(f"  fixed {sev}: {_finding(fk)}")
    # names, values and messages are the description's: each line one visible line
    return "\n".join(escape_text(line) for line in out) + "\n"


def to_json(r: DiffResult) -> str:
    from urdf_lint.core.locations import display_path

    def rel(p):
        return display_path(p)
    models: list[dict] = []
    doc = {"version": 1, "base": r.base, "head": r.head, "models_total": r.total_models,
           "base_expanded": r.base_expanded, "models": models}
    for m in r.models:
        models.append({
            "model": m.model, "status": m.status, "error": m.error, "picture": m.picture,
            "changes": [c.to_dict(rel) for c in m.changes],
            "moved": [{"link": link, "distance": d, "angle": a} for link, d, a in m.moved],
            "findings_introduced": [{"code": fk[0], "file": fk[1], "message": fk[2],
                                     "severity": s} for fk, s in m.findings_introduced],
            "findings_fixed": [{"code": fk[0], "file": fk[1], "message": fk[2], "severity": s}
                               for fk, s in m.findings_fixed]})
    return json.dumps(doc, indent=2) + "\n"


def md_escape(s) -> str:
    """Untrusted text (names, values, messages such as ``xacro.fatal``'s) as Markdown that
    renders as that text only: no HTML, link, image, mention, table break or line break
    (the shared helper, :mod:`urdf_lint.core.escape`)."""
    return escape_markdown(str(s).replace("\r", " ").replace("\n", " "))


def _code(s) -> str:
    """A code span: shown literally (no link, HTML or mention is made inside one)."""
    s = str(s).replace("\r", " ").replace("\n", " ")
    s = s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    return f"`{escape_markdown_code(s)}`"


def to_markdown(r: DiffResult, image_base_url: str | None = None,
                limit: int = MARKDOWN_LIMIT) -> str:
    head = ["## urdf-lint: what this change does to the robots",
            "",
            f"{_code(r.base)} → {_code(r.head)}: **{len(r.models)}** of {r.total_models} "
            f"model(s) affected ({r.base_expanded} expanded at the base).",
            ""]
    if not r.models:
        return "\n".join(head + ["No robot model is affected by this change.", ""])
    table = ["| model | status | changes | moved | findings |", "|---|---|---|---|---|"]
    for m in r.models:
        fi, ff = len(m.findings_introduced), len(m.findings_fixed)
        table.append(f"| {_code(m.model)} | {m.status} | {len(m.changes)} | "
                     f"{md_escape(_moved(m)) if m.moved else '—'} | "
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
        if m.changes:
            rows += ["| | element | field | before | after | source |", "|---|---|---|---|---|---|"]
            for c in m.changes:
                o = c.head or c.base
                src = (_code(_vloc(c.value_from)) + " <sub>value from; used at "
                       + md_escape(_loc(o)) + "</sub>") if c.value_from else \
                    _code(_loc(o)) + (f" <sub>{md_escape(_chain(o))}</sub>" if _chain(o) else "")
                rows.append(f"| {_MD_ICON[c.change]} | {c.kind} {_code(c.name)} | "
                            f"{md_escape(c.field or c.change)} | {md_escape(_fmt(c.before))} | "
                            f"{md_escape(_fmt(c.after))} | {src} |")
            rows.append("")
        if m.moved:
            rows += [f"Links moved at the zero configuration: {md_escape(_moved(m, 10))}.", ""]
        for title, items in (("New findings", m.findings_introduced),
                             ("Fixed findings", m.findings_fixed)):
            if items:
                rows += [f"**{title}**", ""]
                rows += [f"- {s} {_code(fk[0])} {_code(fk[1])}: {md_escape(fk[2])}"
                         for fk, s in items]
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


FORMATS = {"text": to_text, "json": to_json, "markdown": to_markdown}


def write(r: DiffResult, fmt: str, stream, **kw) -> None:
    fn = FORMATS[fmt]
    stream.write(fn(r, **kw) if fmt == "markdown" else fn(r))


def write_file(r: DiffResult, fmt: str, path: str, base: str | None = None, **kw) -> None:
    """The report in ``path``, atomically, written below ``base`` (by default its folder)."""
    from urdf_lint.core import fsbound
    with fsbound.open_write(path, base or os.path.dirname(os.path.abspath(path))) as f:
        write(r, fmt, f, **kw)
