"""A `$(arg name)` has no default and no value was given.

Why: xacro refuses to expand the model, so it cannot be checked; anyone building it must know
the arg.

How to fix: Give the arg a default (`<xacro:arg name="x" default="..."/>`), or list the model
with its args in the config (`[[tool.urdf-lint.models]] path = ... args = {x = "..."}`).
"""
CODE = "UL005"
NAME = "missing-arg"
SEVERITY = "error"
ORIGIN = "expansion"
FAIL = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="$(arg base_name)"/>
</robot>
"""
FAIL_AT = [(2, 3)]
PASS = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="base_name" default="base_link"/>
  <link name="$(arg base_name)"/>
</robot>
"""
