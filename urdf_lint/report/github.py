"""``github``: GitHub Actions workflow commands (``::error file=...``), annotations on the pull
request; chosen automatically when ``GITHUB_ACTIONS`` is set."""
from __future__ import annotations

from urdf_lint.core.locations import display_path
from urdf_lint.report.base import (Finding, BaseFormatter, chain_text, fold_instances, message,
                                   related_text, value_from_text)
from urdf_lint.core.escape import escape_text

_LEVEL = {"error": "error", "warning": "warning", "info": "notice"}


def _gh_escape(s: str, prop: bool = False) -> str:
    # one visible line first: a name carrying "\n::error ..." cannot start a workflow command
    s = escape_text(s).replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")
    if prop:
        s = s.replace(":", "%3A").replace(",", "%2C")
    return s


class GithubFormatter(BaseFormatter):
    name = "github"
    help = "GitHub Actions annotations (default when GITHUB_ACTIONS is set)"

    def handle(self, f: Finding) -> None:
        msg = message(f)
        for extra in (f.detail if not f.instances else "", chain_text(f), value_from_text(f),
                      related_text(f), fold_instances(f)):
            if extra:
                msg += f" ({extra})"
        self.stream.write(f"::{_LEVEL[f.severity]} file={_gh_escape(display_path(f.file), True)},"
                          f"line={f.line},col={f.col},title={_gh_escape(f.code + ' ' + f.name, True)}"
                          f"::{_gh_escape(msg)}\n")
