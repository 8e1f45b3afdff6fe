"""A `<mimic joint=...>` names an unknown joint, the joint itself, or mimic joints form a cycle (a
mimics b mimics a).

Why: Such a model has no well-defined joint positions; parsers and controllers refuse it
(urchin and Drake reject an unknown mimicked joint; MuJoCo 4.0.0, Pinocchio 4.1.0 and PyBullet
3.2.7 load it and ignore the relation: a warning for them, measured with MuJoCo 4.0.0, Pinocchio 4.1.0, PyBullet 3.2.7).

How to fix: Point the mimic at an existing, different joint and break the cycle.

Fix: safe, when the name has a single close "did you mean" candidate (other than the joint itself), for an unknown mimicked joint: `--fix`
writes it where the name is written.
"""
CODE = "UL308"
NAME = "mimic"
SEVERITY = "error"
FAIL = """<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="continuous"><parent link="a"/><child link="b"/><mimic joint="j2"/></joint>
  <joint name="j2" type="continuous"><parent link="a"/><child link="c"/><mimic joint="j1"/></joint>
</robot>
"""
FAIL_AT = [(3, 73)]
PASS = """<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="continuous"><parent link="a"/><child link="b"/></joint>
  <joint name="j2" type="continuous"><parent link="a"/><child link="c"/><mimic joint="j1" multiplier="-1"/></joint>
</robot>
"""
from typing import TYPE_CHECKING
from urdf_lint.engine.api import Report, did_you_mean, reference_fixes

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model


# consumers that load an unknown mimicked joint and ignore the relation (docstring)
IGNORED: dict[str, str] = {}   # issue 38: the joint moves on its own, a different robot: an error


def check(model: "Model", ctx: "Context") -> "Checked":
    follows = {}
    for j in model.top_joints():
        m = j.find("mimic")
        if m is None:
            continue
        target = m.get("joint")
        name = j.get("name")
        if not target:
            yield Report(m, f"joint '{name}': <mimic> has no joint attribute")
        elif target == name:
            yield Report(m, f"joint '{name}' mimics itself")
        elif target not in model.joints:
            others = [n for n in model.joints if n != name]
            fix = reference_fixes([(m, "joint", target)], others).get((m, "joint"))
            yield Report(m, (f"joint '{name}' mimics unknown joint '{target}'"
                             + did_you_mean(target, others)), fix=fix, targets=IGNORED)
        else:
            follows[name] = (target, m)
    reported = set()
    for start in follows:
        seen, cur = [], start
        while cur in follows and cur not in seen:
            seen.append(cur)
            cur = follows[cur][0]
        if cur in seen:
            cycle = seen[seen.index(cur):]
            key = frozenset(cycle)
            if key not in reported:
                reported.add(key)
                yield Report(follows[cycle[0]][1], ("mimic cycle: " + " -> ".join(cycle + [cycle[0]])))
