"""``concise``: exactly one line per finding, ``path:line:col: CODE message [name]``, with the
macro call chain folded into the line, for editors' problem matchers and grep."""
from __future__ import annotations

from .base import DIM, BaseFormatter, chain_text, location, message, targets_tag
from .escape import escape_text


class ConciseFormatter(BaseFormatter):
    name = "concise"
    help = "one line per finding (path:line:col: CODE message), for editors and grep"

    def handle(self, f):
        code = self.paint(f.code, self.severity_color(f.severity))
        ch = chain_text(f)
        tail = f" ({ch})" if ch else ""
        name = self.paint(f"[{f.name}]", DIM) + targets_tag(f)
        self.stream.write(f"{location(f)}: {code} {escape_text(message(f))} {name}{tail}\n")

    def finish(self, result):
        if not self.options.quiet:
            self.stream.write(self.summary_line(result) + "\n")
