"""xacro warned while expanding (an unknown attribute on a directive, a redefined global symbol, a
glob include that matched nothing, a deprecated form).

Why: xacro prints these and carries on, so they are easy to miss in a build log, and the next
xacro release may turn them into errors.

How to fix: Fix the cause named in the message.
"""
CODE = "UL008"
NAME = "xacro-warning"
SEVERITY = "warning"
ORIGIN = "expansion"
FAIL = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="len" value="2" />
  <link name="a"/>
</robot>
"""
FAIL_AT = [(2, 3)]
PASS = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="length" value="2" />
  <link name="a"/>
</robot>
"""
