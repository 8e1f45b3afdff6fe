"""Two different model files in the repository declare the same robot name.

Why: Tools that key on the robot name (Gazebo spawners, MoveIt configs, robot_state_publisher
namespaces, dashboards) then mix the two up; it is usually a copy-paste left-over. Arg sets of
one file may share a name, and so may a checked-in URDF generated from a xacro; different entry
files should not. This is a run-scope rule: it compares every model of the run.

How to fix: Give each model file its own robot name.
"""
CODE = "UL106"
NAME = "duplicate-robot-name"
SEVERITY = "info"
SCOPE = "run"
FAIL = """<robot name="visual">
  <link name="a"/>
</robot>
"""
FAIL_AT = [(1, 1)]
PASS = """<robot name="unique_name_for_this_example">
  <link name="a"/>
</robot>
"""
EXAMPLE_FILES = {"urdf/other.urdf": '<robot name="visual">\n  <link name="a"/>\n</robot>\n'}


from typing import TYPE_CHECKING, Any

from urdf_lint.engine.api import Report, display_path

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked


def check(run: Any, ctx: Any) -> "Checked":
    by_name: dict[str, dict[str, dict[str, Any]]] = {}
    generated = getattr(run, "generated", {})   # a generated URDF is the same robot as its xacro
    for m in run.models:
        if m.name and m.name_origin:
            key = generated.get(m.entry, m.entry)
            by_name.setdefault(m.name, {}).setdefault(key, {}).setdefault(m.entry, m)
    for name, groups in by_name.items():
        if len(groups) < 2:
            continue
        for key, members in groups.items():
            for m in members.values():
                rest = [display_path(e) for k, g in groups.items() if k != key for e in g]
                others = ", ".join(rest[:3]) + (f" and {len(rest) - 3} more" if len(rest) > 3 else "")
                yield Report(m.name_origin, f"robot name '{name}' is also used by {others}")
