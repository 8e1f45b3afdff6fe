"""A `<xacro:if>` or `<xacro:unless>` whose value is a constant that never expands its body
(`value="false"`, `value="0"`, `value="${False}"`; `<xacro:unless value="true">`): no arg
can reach what is inside.

Why: A block switched off by a literal is dead code: it is never linted, never rendered and
never built, yet it reads as part of the robot (a sensor, a transmission, a gripper mount).
Its errors stay hidden until someone flips the literal, and branch coverage
(`urdf-lint check --coverage`, docs/coverage.md) reports it as unreachable, not as a branch
no value was found for.

How to fix: Delete the block, or make it depend on an arg (`<xacro:arg name="with_camera"
default="false"/>` and `value="$(arg with_camera)"`) so that it can be selected, and linted.
"""
CODE = "UL014"
NAME = "unreachable-branch"
SEVERITY = "info"
ORIGIN = "expansion"
FAIL = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="a"/>
  <xacro:if value="false">
    <link name="camera"/>
  </xacro:if>
</robot>
"""
FAIL_AT = [(3, 3)]
PASS = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="camera" default="false"/>
  <link name="a"/>
  <xacro:if value="$(arg camera)">
    <link name="camera"/>
  </xacro:if>
</robot>
"""
