"""xacro could not expand the file: an undefined property or macro, a bad macro parameter, a
failing expression or a bad directive.

Why: Without an expansion there is no robot to check, and the xacro build step fails the same
way. The location is the innermost element xacro was evaluating; the message names the macro
chain.

How to fix: Define the missing name, fix the expression, or pass the parameter.
"""
CODE = "UL002"
NAME = "xacro-error"
SEVERITY = "error"
ORIGIN = "expansion"
FAIL = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="${undefined_name}"/>
</robot>
"""
FAIL_AT = [(2, 3)]
PASS = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="n" value="base"/>
  <link name="${n}"/>
</robot>
"""
