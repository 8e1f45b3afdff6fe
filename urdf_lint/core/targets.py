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
behaviour (and which version of it) each entry encodes; the measured facts are in the rules
page and in ``tests/test_consumers.py``.
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
    "python": "the Python parsers (urdf_parser_py, urchin, yourdfpy)",
}
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


def resolve(table: dict[str, str] | None, default: str,
            selected: Iterable[str]) -> tuple[str | None, tuple[str, ...]]:
    """(effective severity or None when no selected target keeps the finding, the selected
    targets whose own entry raises it above ``default``)."""
    table = table or {}
    best, by = None, []
    for t in selected:
        s = table.get(t, table.get("*", default))
        if s == OFF:
            continue
        if best is None or SEVERITY_RANK[s] > SEVERITY_RANK[best]:
            best, by = s, [t]
        elif s == best:
            by.append(t)
    if best is None:
        return None, ()
    base = table.get("*", default)       # what a target the table does not name gets
    if base == OFF or SEVERITY_RANK[best] > SEVERITY_RANK[base]:
        return best, tuple(t for t in by if t in table)
    return best, ()


def applies(table: dict[str, str] | None, default: str, selected: Iterable[str]) -> bool:
    """Can a finding with this table be kept under the selected targets?"""
    return resolve(table, default, selected)[0] is not None


def column(table: dict[str, str] | None, default: str) -> dict[str, str]:
    """Every target's severity (or ``off``) under ``table``: the rules page's row."""
    table = table or {}
    return {t: table.get(t, table.get("*", default)) for t in NAMES}
