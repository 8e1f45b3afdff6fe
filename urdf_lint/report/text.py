"""``text`` (default): ``path:line:col: CODE message [name]``, then the macro call chain and the
models that share the finding, each on an indented line; ``--show-source`` adds a code frame."""
from __future__ import annotations

from urdf_lint.core.locations import display_path
from urdf_lint.core.escape import escape_text
from urdf_lint.report.base import (BOLD, DIM, RESET, BaseFormatter, Finding, Outcome,
                                   chain_text, fold, fold_instances, location, message,
                                   refused_text, targets_tag, value_from_text, related_text)


class TextFormatter(BaseFormatter):
    name = "text"
    help = "one finding per block: location, message, call chain, models"

    def start(self, result: Outcome) -> None:
        self._current: str | None = None
        self._lines: dict[str, list[str]] = {}

    def handle(self, f: Finding) -> None:
        w = self.stream.write
        path = escape_text(display_path(f.file))
        if self.options.color and path != self._current:
            if self._current is not None:
                w("\n")
            w(f"{BOLD}{path}{RESET}\n")
            self._current = path
        code = self.paint(f.code, self.severity_color(f.severity))
        name = self.paint(f"[{f.name}]", DIM) + targets_tag(f)
        w(f"{location(f)}: {code} {escape_text(message(f))} {name}\n")
        if f.detail and not f.instances:
            w(f"    {escape_text(f.detail)}\n")
        if self.options.show_source:
            w(self.code_frame(f))
        for line in (chain_text(f), value_from_text(f), related_text(f), fold_instances(f)):
            if line:
                w(f"    {line}\n")
        if self.options.show_models and len(f.models) > 1:
            w(f"    in {len(f.models)} models: {fold(f.models)}\n")
        why = refused_text(f)
        if why:
            w(f"    {why}\n")

    def finish(self, result: Outcome) -> None:
        if not self.options.quiet:
            self.stream.write(self.summary_line(result) + "\n")

    def code_frame(self, f: Finding, context: int = 1) -> str:
        """The source line of a finding with a caret under its column, and ``context`` lines
        around it (like ruff's ``--show-source``)."""
        lines = self._source(f.file)
        if not lines or not 1 <= f.line <= len(lines):
            return ""
        first, last = max(1, f.line - context), min(len(lines), f.line + context)
        width = len(str(last))
        out = [f"{'':>{width}} |"]
        for n in range(first, last + 1):
            # the source is the description's: one visible line (tabs kept for the caret)
            text = "\t".join(escape_text(part) for part in lines[n - 1].split("\t"))
            out.append(f"{n:>{width}} | {text}".rstrip())
            if n == f.line:
                prefix = "".join(c if c == "\t" else " " for c in text[:max(0, f.col - 1)])
                out.append(f"{'':>{width}} | {prefix}{self.paint('^', self.severity_color(f.severity))}")
        out.append(f"{'':>{width}} |")
        return "".join(f"  {ln}\n" for ln in out)

    def _source(self, path: str) -> list[str]:
        if path not in self._lines:
            from urdf_lint.core import fsbound
            try:   # what a worker could read: inside the roots, a regular file, bounded
                self._lines[path] = fsbound.read_text(
                    path, self.options.roots, errors="replace").splitlines()
            except OSError:
                self._lines[path] = []
        return self._lines[path]
