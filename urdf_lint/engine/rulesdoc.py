"""Rule documentation: the fixed sections of a rule's docstring, and the rules page.

A rule's docstring is, in this order (ruff's rule docs have the same parts):

* what it finds: the first paragraph (its first sentence is the one-line summary);
* ``Why:`` why it matters;
* ``How to fix:`` what to change;
* ``Fix:`` (when ``--fix`` can fix it) whether the fix is safe or unsafe, and what it edits;
* ``Options:`` each option in ``OPTIONS`` with its default and meaning (only when it has any).

The example is the rule's ``FAIL`` and ``PASS`` source (``FAIL_AT`` pins where it reports).
``urdf-lint rules --format markdown`` renders the catalogue as one page.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

SECTIONS = ("why", "how to fix", "fix", "options")
_PREFIX = {"why": "Why:", "how to fix": "How to fix:", "fix": "Fix:", "options": "Options:"}


class DocError(ValueError):
    pass


def sections(doc: str) -> dict[str, str]:
    """{"what", "why", "how to fix", "options"} of a rule docstring (paragraphs joined into
    one line each); raises DocError when the sections are missing or out of order."""
    paras = [" ".join(p.split()) for p in doc.strip().split("\n\n") if p.strip()]
    if not paras:
        raise DocError("empty docstring")
    out = {"what": paras[0]}
    current = "what"
    order = []
    for p in paras[1:]:
        head = next((k for k, pre in _PREFIX.items() if p.startswith(pre)), None)
        if head is None:
            out[current] += "\n\n" + p          # a further paragraph of the same section
            continue
        if head in out:
            raise DocError(f"section {_PREFIX[head]!r} appears twice")
        out[head] = p[len(_PREFIX[head]):].strip()
        order.append(head)
        current = head
    for need in ("why", "how to fix"):
        if need not in out:
            raise DocError(f"missing section {_PREFIX[need]!r}")
    if order != sorted(order, key=SECTIONS.index):
        raise DocError(f"sections out of order: {order} (expected {list(SECTIONS)})")
    return out


def _anchor(code: str, r: Any) -> str:
    """The link to a rule's section on the one-page catalogue."""
    return f"#{code.lower()}-{r.name}"


def targets_table(rules: dict[str, Any], link: Callable[[str, Any], str] = _anchor,
                  heading: str = "##") -> list[str]:
    """The severity of each rule per consumer target (config ``targets``), for the rules whose
    ``TARGETS`` set one; ``off``: the rule does not apply to that target. ``link`` makes a
    rule's link (its section on the one page, or its own page)."""
    from urdf_lint.core.targets import KNOWN, NAMES, column
    short = {"error": "error", "warning": "warn", "info": "info", "off": "off"}
    out = [f"{heading} Consumer targets", "",
           "With `targets = [...]` (or `--target`), a finding takes the highest severity any "
           "selected target gives it (a `severity` override still wins), and names the target "
           "that raised it. Targets:", ""]
    out += [f"* `{t}`: {what}" for t, what in KNOWN.items()]
    out += ["", "Rules that differ between targets (every other rule has its default "
            "severity for all of them; a rule may also set one finding's severities itself, "
            "as its section says):", "",
            "| Code | " + " | ".join(NAMES) + " |", "|---" * (len(NAMES) + 1) + "|"]
    for code, r in rules.items():
        if r.targets:
            col = column(r.targets, r.severity)
            out.append(f"| [{code}]({link(code, r)}) | "
                       + " | ".join(short[col[t]] for t in NAMES) + " |")
    return out


def summary_table(rules: dict[str, Any], link: Callable[[str, Any], str] = _anchor) -> list[str]:
    """One row per rule: its code (a link), name, default severity and one-line summary."""
    lines = ["| Code | Name | Severity | Summary |", "|---|---|---|---|"]
    for code, r in rules.items():
        summary = r.summary.replace("|", "\\|")
        lines.append(f"| [{code}]({link(code, r)}) | `{r.name}` | {r.severity} | {summary} |")
    return lines


def rule_body(code: str, r: Any) -> list[str]:
    """A rule's documentation below its heading: its facts, the docstring's sections, the
    example."""
    s = sections(r.doc)
    facts = [f"Default severity: **{r.severity}**"]
    if r.targets:
        facts.append("per target: " + ", ".join(f"{t} {s}" for t, s in r.targets.items()))
    if r.scope == "run":
        facts.append("checks the whole run (all models together)")
    if r.origin != "rule":
        facts.append(f"reported by the {r.origin}")
    if "meshes" in r.needs:
        facts.append("loads mesh files")
    lines = ["; ".join(facts) + ".", "", s["what"], "",
             "**Why.** " + s["why"], "", "**How to fix.** " + s["how to fix"]]
    if "fix" in s:
        lines += ["", "**Fix** (`urdf-lint check --fix`). " + s["fix"]]
    if r.options:
        lines += ["", "**Options** (under `[tool.urdf-lint.rule-options." + code + "]`). "
                  + s.get("options", "")]
    at = ", ".join(f"line {ln}, col {c}" for ln, c in r.fail_at)
    if r.example_at:   # a rule about a configuration file: the file is the example
        lines += ["", f"**Example.** `{r.example_at}`, reported" + (f" at {at}" if at else "")
                  + ":", "", "```", r.example_files[r.example_at].rstrip("\n"), "```", "",
                  "against the robot:", "", "```xml", r.fail.rstrip("\n"), "```", "",
                  "Passes with:", "", "```xml", r.passing.rstrip("\n"), "```"]
        lines += [x for k, v in r.pass_files.items()
                  for x in ("", f"and `{k}`:", "", "```", v.rstrip("\n"), "```")]
        return lines
    lines += ["", "**Example.** Reported" + (f" at {at}" if at else "") + ":", "",
              "```xml", r.fail.rstrip("\n"), "```", "", "Passes:", "",
              "```xml", r.passing.rstrip("\n"), "```"]
    return lines


def markdown(rules: dict[str, Any]) -> str:
    """The rules page: a table of every rule, the severities per consumer target, then one
    section per rule."""
    lines = ["# urdf-lint rules", "",
             "Generated by `urdf-lint rules --format markdown`. Select or ignore rules by code, "
             "prefix (`UL3`) or name.", ""]
    lines += summary_table(rules) + [""] + targets_table(rules)
    for code, r in rules.items():
        lines += ["", f"## {code} {r.name}", ""] + rule_body(code, r)
    return "\n".join(lines) + "\n"
