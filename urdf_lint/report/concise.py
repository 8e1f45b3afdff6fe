"""``concise``: exactly one line per finding, ``path:line:col: CODE message [name]``, with the
macro call chain folded into the line, for editors' problem matchers and grep."""
from __future__ import annotations

from urdf_lint.report.base import (DIM, BaseFormatter, Finding, Outcome, chain_text,
                                   fold_instances, location, message, targets_tag,
                                   value_from_text, related_text)
from urdf_lint.core.escape import escape_text


class ConciseFormatter(BaseFormatter):
    name = "concise"
    help = "one line per finding (path:line:col: CODE message), for editors and grep"

    def handle(self, f: Finding) -> None:
        code = self.paint(f.code, self.severity_color(f.severity))
        parts = [p for p in (f.detail if not f.instances else "", chain_text(f),
                             value_from_text(f), related_text(f), fold_instances(f)) if p]
        tail = f" ({'; '.join(escape_text(p) for p in parts)})" if parts else ""
        name = self.paint(f"[{f.name}]", DIM) + targets_tag(f)
        self.stream.write(f"{location(f)}: {code} {escape_text(message(f))} {name}{tail}\n")

    def finish(self, result: Outcome) -> None:
        if not self.options.quiet:
            self.stream.write(self.summary_line(result) + "\n")
