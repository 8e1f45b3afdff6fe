"""``text``: the diff for a terminal, one visible line per change."""
from __future__ import annotations

from urdf_lint.core.escape import escape_text
from urdf_lint.report.diff.base import (ICON, DiffFormatter, DiffResult, chain, finding, fmt, loc,
                                        moved, related, value_source, vloc, what)


class TextDiff(DiffFormatter):
    name = "text"
    help = "for a terminal: one line per change, at its xacro line (default)"

    def render(self, result: DiffResult) -> str:
        return to_text(result)


def to_text(r: DiffResult) -> str:
    out = [f"urdf-lint diff {r.base}..{r.head}: {len(r.models)} model(s) affected of "
           f"{r.total_models}, {r.base_expanded} expanded at {r.base}"]
    for m in r.models:
        out.append("")
        out.append(f"{m.model}: {m.status}" + (f" ({m.error})" if m.error else ""))
        for c in m.changes:
            where = loc(c.head or c.base)
            line = f"  {ICON[c.change]} {what(c)}"
            if c.change in ("changed", "renamed"):
                line += f": {fmt(c.before)} -> {fmt(c.after)}"
            out.append(line + (f"  [{where}]" if where else ""))
            ch = chain(c.head or c.base)
            if ch:
                out.append(f"      {ch}")
            if c.value_from:
                out.append(f"      value from {vloc(c.value_from)}")
        if m.moved:
            out.append(f"  moved at zero configuration: {moved(m, 5)}")
        for word, items in (("introduced", m.findings_introduced), ("fixed", m.findings_fixed)):
            for fk, sev in items:
                out.append(f"  {word} {sev}: {finding(fk, m.finding_lines.get(fk))}")
                for extra in (value_source(m, fk), related(m, fk)):
                    if extra:
                        out.append(f"      {extra}")
    # names, values and messages are the description's: each line one visible line
    return "\n".join(escape_text(line) for line in out) + "\n"
