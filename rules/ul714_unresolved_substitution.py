"""A joint name in a controller YAML is built by a launch substitution (`$(var tf_prefix)joint1`) whose value urdf-lint does not know: those names were not checked.

Why: the prefix is filled in by the launch file (`ParameterFile(..., allow_substs=True)`), so
the names cannot be checked against the robot without it. When the model has a xacro arg of the
same name (a `[[tool.urdf-lint.models]]` entry with `args = {tf_prefix = "left_"}`), the name is
resolved with it and checked by UL710-UL712 instead. One information finding per file, at its
first such name.

Consumers: ros and gazebo.

How to fix: Nothing is wrong. To have the names checked, lint the model with the prefix as a
xacro arg of the same name.
"""
CODE = "UL714"
NAME = "unresolved-substitution"
SEVERITY = "info"
TARGETS = {"*": "off", "ros": "info", "gazebo": "info"}
from urdf_lint.rules._config import example_robot, forward_controller_example
FAIL = example_robot(("joint1", "base", "l1"))
PASS = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="tf_prefix" default=""/>
  <link name="base"/><link name="l1"/>
  <joint name="$(arg tf_prefix)joint1" type="revolute"><parent link="base"/><child link="l1"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
</robot>
"""
EXAMPLE_FILES = {"config/r_controllers.yaml": forward_controller_example("$(var tf_prefix)joint1")}
EXAMPLE_AT = "config/r_controllers.yaml"
FAIL_AT = [(9, 9)]
from typing import TYPE_CHECKING, Any
from urdf_lint.engine.api import Report

if TYPE_CHECKING:
    from urdf_lint.engine.api import Checked, Context, Model
from urdf_lint.rules._config import named_joints, resolve_name


def check(model: "Model", ctx: "Context") -> "Checked":
    first: dict[Any, Any] = {}
    count: dict[Any, int] = {}
    for doc, node, raw, _ in named_joints(ctx):
        _, left = resolve_name(ctx, raw)
        if left:
            first.setdefault(doc.path, (doc, node, raw))
            count[doc.path] = count.get(doc.path, 0) + 1
    for path, (doc, node, raw) in first.items():
        n = count[path]
        yield Report(doc.key_at(node) if not isinstance(node.value, str) else doc.at(node),
                     f"{n} joint name{'s' if n > 1 else ''} in this file "
                     f"{'are' if n > 1 else 'is'} built by a launch substitution ('{raw}'): "
                     "not checked against the robot (no xacro arg gives the value)")
