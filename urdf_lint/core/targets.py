"""Consumer targets: the programs a description is written for, and what a finding means to each.

A robot description is loaded by programs that disagree on what they accept: MuJoCo refuses a
moving body without mass, Drake a second transmission of the same name, the Python parsers an
undeclared namespace prefix, while urdfdom and the rest of ROS load all three. The config key
``targets`` (``--target``; default ``["ros"]``) names the consumers a repository cares about,
and a rule declares, per target, whether it applies and at which severity:

* ``TARGETS = {"mujoco": "error", "gazebo": "warning"}`` in the rule module: targets not
  listed get the rule's ``SEVERITY``; ``"*"`` sets the severity of every unlisted target;
  ``"off"`` means the rule does not apply to that target (its findings are dropped when no
  selected target keeps them);
* a rule may also yield a table of its own for one finding (a dict after the message), which
  replaces the module's table for that finding.

The effective severity of a finding is the highest among the selected targets; the targets that
give it (where their entry raises it above the rule's own severity) are named on the finding
(:attr:`urdf_lint.core.findings.Problem.severity_from`: text ``[mujoco]``, JSON ``severity_from``).
A ``severity`` override in the config still wins. Each rule's docstring says which consumer
behaviour (and which version of it) each entry encodes; the measured verdicts ship in
``urdf_lint/engine/verdicts.json`` (written by ``bench/consumers/harness.py``, issue 38).

Targets name programs. ``python`` is a group: selecting it selects ``yourdfpy``,
``urdf_parser_py`` and ``urchin``, which disagree (urdf_parser_py and urchin reject malformed
XML that yourdfpy loads); a table entry for ``python`` is what each of the three gets unless the
table names it. iDynTree is a target of its own (``idyntree``), not part of ``ros``.
"""
from __future__ import annotations

from typing import Iterable

from urdf_lint.core.findings import SEVERITIES, SEVERITY_RANK

# name -> what it stands for (the rules page and --help show this)
KNOWN: dict[str, str] = {
    "ros": "urdfdom (check_urdf), KDL, robot_state_publisher, MoveIt, ros2_control",
    "gazebo": "Gazebo's URDF to SDF conversion (sdformat)",
    "mujoco": "MuJoCo's URDF compiler",
    "drake": "Drake's URDF parser",
    "pinocchio": "Pinocchio (model, geometry and dynamics)",
    "pybullet": "PyBullet's loadURDF",
    "isaac": "Isaac Sim's URDF importer",
    "python": "the Python parsers: yourdfpy, urdf_parser_py and urchin together",
    "yourdfpy": "yourdfpy (URDF.load with meshes)",
    "urdf_parser_py": "urdf_parser_py (ROS's urdfdom-py, and the older urdf-parser-py)",
    "urchin": "urchin (URDF.load with meshes)",
    "idyntree": "iDynTree's ModelLoader",
}
# a target that stands for several programs: selecting it selects each
GROUPS: dict[str, tuple[str, ...]] = {"python": ("yourdfpy", "urdf_parser_py", "urchin")}
GROUP_OF = {m: g for g, ms in GROUPS.items() for m in ms}
NAMES = tuple(KNOWN)
OFF = "off"
LEVELS = SEVERITIES + (OFF,)


def check_table(table: object, where: str) -> dict[str, str]:
    """A rule's table, validated: known targets (or ``*``) to a severity or ``off``."""
    if not isinstance(table, dict):
        raise RuntimeError(f"{where}: TARGETS must be a dict of target -> severity")
    for k, v in table.items():
        if k != "*" and k not in KNOWN:
            raise RuntimeError(f"{where}: unknown target {k!r} in TARGETS (known: "
                               f"{', '.join(NAMES)})")
        if v not in LEVELS:
            raise RuntimeError(f"{where}: TARGETS[{k!r}] must be one of {LEVELS}, not {v!r}")
    return dict(table)


def expand(selected: Iterable[str]) -> tuple[str, ...]:
    """The selected targets with each group replaced by its members (order kept, no repeats)."""
    return tuple(dict.fromkeys(m for _, m in _members(selected)))


def _members(selected: Iterable[str]) -> list[tuple[str, str]]:
    """(the name as selected, one program it stands for) for every selected target."""
    return [(t, m) for t in selected for m in GROUPS.get(t, (t,))]


def entry(table: dict[str, str], target: str, default: str) -> str:
    """One target's severity under ``table``: its own entry, else its group's, else ``*``."""
    if target in table:
        return table[target]
    g = GROUP_OF.get(target)
    if g is not None and g in table:
        return table[g]
    if target in GROUPS:      # a group's column: the highest of its members
        sevs = [entry(table, m, default) for m in GROUPS[target]]
        kept = [x for x in sevs if x != OFF]
        return max(kept, key=SEVERITY_RANK.__getitem__) if kept else OFF
    return table.get("*", default)


def resolve(table: dict[str, str] | None, default: str,
            selected: Iterable[str]) -> tuple[str | None, tuple[str, ...]]:
    """(effective severity or None when no selected target keeps the finding, the selected
    targets whose own entry raises it above ``default``)."""
    table = table or {}
    best: str | None = None
    by: list[tuple[str, str]] = []      # (as selected, program)
    seen: set[str] = set()
    for name, t in _members(selected):
        if t in seen:
            continue
        seen.add(t)
        s = entry(table, t, default)
        if s == OFF:
            continue
        if best is None or SEVERITY_RANK[s] > SEVERITY_RANK[best]:
            best, by = s, [(name, t)]
        elif s == best:
            by.append((name, t))
    if best is None:
        return None, ()
    base = table.get("*", default)       # what a target the table does not name gets
    if base == OFF or SEVERITY_RANK[best] > SEVERITY_RANK[base]:
        # named as selected: a group's members raise it under the group's name
        return best, tuple(dict.fromkeys(n for n, t in by if t in table or GROUP_OF.get(t) in table))
    return best, ()


def applies(table: dict[str, str] | None, default: str, selected: Iterable[str]) -> bool:
    """Can a finding with this table be kept under the selected targets?"""
    return resolve(table, default, selected)[0] is not None


def column(table: dict[str, str] | None, default: str) -> dict[str, str]:
    """Every target's severity (or ``off``) under ``table``: the rules page's row."""
    table = table or {}
    return {t: entry(table, t, default) for t in NAMES}
