"""The base of every output format of ``urdf-lint diff`` (as :mod:`urdf_lint.report.base` is
of ``check``'s), and the helpers the formats share."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from urdf_lint.core.escape import escape_markdown, escape_markdown_code

if TYPE_CHECKING:  # pragma: no cover
    from urdf_lint.core.locations import Origin


@dataclass
class DiffResult:
    """The outcome of ``urdf-lint diff``: the models a change affected, and what it did to each."""
    base: str
    head: str
    models: list[Any] = field(default_factory=list)      # ModelDiff, affected models only
    total_models: int = 0
    base_expanded: int = 0
    internal: list[str] = field(default_factory=list)
    snapshot_problems: list[Any] = field(default_factory=list)   # (model, why): --render failed
    no_recordings: str = ""     # why --render wrote no .rrd at all (rerun-sdk not installed)


@dataclass(frozen=True)
class DiffOptions:
    """How a diff report is written."""
    image_base_url: str | None = None   # markdown: where the --render pictures are served


class DiffFormatter:
    """Subclass, set ``name`` and ``help``, and override :meth:`render`: the whole report of
    one :class:`DiffResult` as text. Every name, value and message in
    it is the description's (untrusted): escape it for the format."""

    name = ""
    help = ""

    def __init__(self, options: DiffOptions | None = None):
        self.options = options or DiffOptions()

    def render(self, result: DiffResult) -> str:
        raise NotImplementedError


ICON = {"added": "+", "removed": "-", "renamed": "~", "changed": "*"}
MD_ICON = {"added": "🟢", "removed": "🔴", "renamed": "🔁", "changed": "✏️"}


def fmt(v: object) -> str:
    if v is None:
        return "—"
    if isinstance(v, tuple):
        return " ".join(fmt(x) for x in v)
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v)


def loc(o: "Origin | None", root: str | None = None) -> str:
    if o is None:
        return ""
    from urdf_lint.core.locations import display_path
    return f"{display_path(o.file, root)}:{o.line}"


def vloc(v: tuple[Any, ...], root: str | None = None) -> str:
    """``config/joint_limits.yaml:28``: where a changed value is written."""
    from urdf_lint.core.locations import display_path
    return f"{display_path(v[0], root)}:{v[1]}"


def chain(o: "Origin | None", root: str | None = None) -> str:
    return o.format_chain(root) if o is not None and o.chain else ""


def what(c: Any) -> str:
    return f"{c.kind} '{c.name}'" + (f" {c.field}" if c.field and c.change != "renamed" else "")


def moved(m: Any, n: int = 3) -> str:
    parts = [f"{link} {d * 1000:.3g} mm" + (f", {a:.3g} rad" if a > 1e-6 else "")
             for link, d, a in m.moved[:n]]
    more = len(m.moved) - n
    return ", ".join(parts) + (f" and {more} more" if more > 0 else "")


def finding(fk: tuple[str, str, str], at: tuple[int, int] | None = None) -> str:
    """``at``: its (line, col) in the revision that has it, when known."""
    code, file, msg = fk
    where = f"{file}:{at[0]}:{at[1]}" if at and at[0] else file
    return f"{code} {where}: {msg}"


def related(m: Any, fk: tuple[str, str, str]) -> str:
    """``robot element at urdf/arm.urdf.xacro:9``: the robot element an SRDF or YAML finding
    is about (``m`` its ModelDiff), or ""."""
    r = m.finding_related.get(fk)
    from urdf_lint.core.locations import related_label
    return f"{related_label(r[0])} at {r[0]}:{r[1]}" if r else ""


def value_source(m: Any, fk: tuple[str, str, str]) -> str:
    """``value from config/inertial.yaml:25``: the line a finding's value comes from (a YAML
    scalar, a property elsewhere; ``m`` its ModelDiff), as ``check`` says it, or ""."""
    v = m.finding_value_from.get(fk)
    return f"value from {v[0]}:{v[1]}" if v else ""


def md_escape(s: object) -> str:
    """Untrusted text (names, values, messages such as ``xacro.fatal``'s) as Markdown that
    renders as that text only: no HTML, link, image, mention, table break or line break
    (the shared helper, :mod:`urdf_lint.core.escape`)."""
    return escape_markdown(str(s).replace("\r", " ").replace("\n", " "))


def code(s: object) -> str:
    """A code span: shown literally (no link, HTML or mention is made inside one)."""
    s = str(s).replace("\r", " ").replace("\n", " ")
    s = s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    return f"`{escape_markdown_code(s)}`"


